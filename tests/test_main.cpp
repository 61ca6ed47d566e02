#include <gtest/gtest.h>

#include <stdlib.h>  // mkdtemp

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "gpu/gpu_test_device.h"

namespace {

// The texture system writes the pyramids it builds to $XDG_CACHE_HOME/footprint by default
// (texture_system.h): tests, and the commands they run, write them to a folder of their own, never
// to the user's, removed at the end. A test process started with FOOTPRINT_TEST_KEEP_XDG_CACHE set
// (a child a test starts) keeps the one it was given.
struct TestCacheHome {
    std::filesystem::path dir;
    TestCacheHome() {
        if (std::getenv("FOOTPRINT_TEST_KEEP_XDG_CACHE") != nullptr) return;
        std::string name =
            (std::filesystem::temp_directory_path() / "footprint-tests-XXXXXX").string();
        if (::mkdtemp(name.data()) == nullptr) return;
        dir = name;
        // Mesa keeps its compiled shaders under XDG_CACHE_HOME too: they stay where they were, or
        // every test process would compile the GPU path's shaders again (minutes on llvmpipe).
        if (std::getenv("MESA_SHADER_CACHE_DIR") == nullptr) {
            const char* xdg = std::getenv("XDG_CACHE_HOME");
            const char* home = std::getenv("HOME");
            if (xdg != nullptr && xdg[0] == '/')
                ::setenv("MESA_SHADER_CACHE_DIR", (std::string(xdg) + "/mesa_shader_cache").c_str(),
                         1);
            else if (home != nullptr)
                ::setenv("MESA_SHADER_CACHE_DIR",
                         (std::string(home) + "/.cache/mesa_shader_cache").c_str(), 1);
        }
        ::setenv("XDG_CACHE_HOME", name.c_str(), 1);
    }
    ~TestCacheHome() {
        std::error_code ignored;
        if (!dir.empty()) std::filesystem::remove_all(dir, ignored);
    }
};

}  // namespace

int main(int argc, char** argv) {
    const TestCacheHome cache_home;
    ::testing::InitGoogleTest(&argc, argv);
    const int result = RUN_ALL_TESTS();
#ifdef FOOTPRINT_SANITIZED
    // LeakSanitizer's tracer faults while it suspends the threads of Mesa's llvmpipe ("Tracer
    // caught signal 11 … LeakSanitizer has encountered a fatal error", in a test that passed), at
    // exit and when called earlier alike, in about one GPU test process in ten. A process that
    // made a GPU device therefore ends without the leak check; every other test process (ctest
    // runs each suite in its own, and the GPU tests are suites of their own) keeps it
    // (docs/testing.md).
    if (footprint::test::gpu_device_created) {
        std::fflush(nullptr);
        std::_Exit(result);
    }
#endif
    return result;
}
