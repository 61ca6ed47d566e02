#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "gpu/gpu_test_device.h"

int main(int argc, char** argv) {
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
