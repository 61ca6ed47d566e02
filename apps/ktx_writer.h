// apps/ktx_writer.h — KTX 1 files of float RGBA levels, as an engine loads them (`footprint bake`).
//
// KTX 1 (Khronos, "KTX File Format Specification" 1.1) is a GL texture's glTexImage2D calls as a
// file. What encode_ktx() writes, every number little-endian:
//   identifier            «KTX 11»\r\n\x1A\n
//   endianness            0x04030201
//   glType, glTypeSize    GL_HALF_FLOAT (0x140B), 2   or  GL_FLOAT (0x1406), 4
//   glFormat              GL_RGBA (0x1908)
//   glInternalFormat      GL_RGBA16F (0x881A)         or  GL_RGBA32F (0x8814)
//   glBaseInternalFormat  GL_RGBA
//   pixelWidth, Height    level 0's; pixelDepth 0
//   numberOfArrayElements 0 (not an array texture)
//   numberOfFaces         1, or 6 for a cube map (faces +X −X +Y −Y +Z −Z, GL's order)
//   numberOfMipmapLevels  the levels given (level 0 first, each max(1, ⌊W/2^l⌋) × max(1, ⌊H/2^l⌋))
//   key/value data        each pair as the spec says: its byte size, the key and the value as
//                         NUL-terminated UTF-8, padded to 4 bytes
//   per level             imageSize, then the level's texels; imageSize is the whole level's bytes,
//                         but one FACE's for a cube map (the spec's rule for non-array cube maps)
// Texels are 4 channels of 2 or 4 bytes, so every row, face and level is a multiple of 4 bytes and
// the spec's row, cube and MIP paddings are all empty (Filament's KtxBundle assumes they are).
//
// Rows are written in the order given, first row first. The images given are footprint's, top row
// first (t = 0 at the top, docs/method.md): the file's first row is the image's top row, which the
// key "KTXorientation" = "S=r,T=d" states for a 2D texture (bake_command.h adds it). A cube map's
// faces are written as GL's cube map rule reads them (first row at GL's t = 0), which is
// footprint's face orientation (envmap/env_layout.h): nothing is flipped.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/result.h"
#include "image/image.h"

namespace footprint {

enum class KtxPixelType {
    half_float,  // GL_RGBA16F: what an engine samples; ±65504, 11 significant bits
    float32,     // GL_RGBA32F
};

struct KtxTexture {
    KtxPixelType type = KtxPixelType::half_float;
    // levels[l][face]: 4-channel images, level 0 first; one face per level, or six for a cube map
    // (+X −X +Y −Y +Z −Z, square).
    std::vector<std::vector<Image>> levels;
    std::vector<std::pair<std::string, std::string>> key_values;  // written in this order
};

// The bytes of the KTX 1 file holding `texture`. Errors name the level, face and texel: levels
// of the wrong size or channel count, and for half_float a value that half floats cannot hold
// (beyond ±65504, or not finite) — never written as infinity.
Result<std::string> encode_ktx(const KtxTexture& texture);

}  // namespace footprint
