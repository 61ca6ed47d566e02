// apps/filament_ktx_reader.h — test support: a KTX file as Filament's image::KtxBundle reads it
// (bake_filament_test.cpp). A header of standard types only, so that the test's footprint headers
// and Filament's (whose <math/vec3.h> shares footprint's math/vec3.h's name) meet in no file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace footprint::test {

struct FilamentKtx {
    std::uint32_t gl_type = 0, gl_format = 0, gl_internal_format = 0;
    std::uint32_t width = 0, height = 0, levels = 0, array_length = 0;
    bool cubemap = false;
    std::string orientation;   // the "KTXorientation" value; empty if none
    std::string slope_offset;  // the "footprint:slope_offset" value; empty if none
    // blobs[level][face]: the bytes getBlob() gives, which Filament uploads.
    std::vector<std::vector<std::vector<std::uint8_t>>> blobs;
};

// `bytes` (a KTX file) through image::KtxBundle's constructor and getters.
FilamentKtx read_with_filament(const std::string& bytes);

}  // namespace footprint::test
