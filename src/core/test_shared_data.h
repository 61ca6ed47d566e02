// core/test_shared_data.h — test support: where the shared real-data set lives.
//
// Tests that read real files (HDR environments, meshes, normal maps) look in the folder
// FOOTPRINT_SHARED_DATA names, else in the one the build was configured with
// (FOOTPRINT_SHARED_DATA_DIR = <repository>/../shared/data), and GTEST_SKIP() with a message when
// a file is absent: the data set is not part of the repository.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

namespace footprint::test {

inline std::filesystem::path shared_data_dir() {
    if (const char* env = std::getenv("FOOTPRINT_SHARED_DATA"); env && *env) return env;
#ifdef FOOTPRINT_SHARED_DATA_DIR
    return FOOTPRINT_SHARED_DATA_DIR;
#else
    return "../shared/data";
#endif
}

// The GTEST_SKIP() message of a test whose shared data is absent.
inline std::string missing_shared_data(const std::filesystem::path& where) {
    return "shared data not found at " + where.string() +
           " (set FOOTPRINT_SHARED_DATA to the shared/data folder)";
}

}  // namespace footprint::test
