#include "ktx_writer.h"

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace footprint {

namespace {

constexpr std::uint8_t kIdentifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31,
                                          0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::uint32_t kEndianness = 0x04030201;
constexpr std::uint32_t kGlHalfFloat = 0x140B, kGlFloat = 0x1406;
constexpr std::uint32_t kGlRgba = 0x1908;
constexpr std::uint32_t kGlRgba16f = 0x881A, kGlRgba32f = 0x8814;
constexpr float kHalfMax = 65504.0f;

// Little-endian, byte by byte: the file is the same on any host.
void put_u32(std::string& out, std::uint32_t value) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xFF));
}
void put_u16(std::string& out, std::uint16_t value) {
    out.push_back(static_cast<char>(value & 0xFF));
    out.push_back(static_cast<char>(value >> 8));
}
void pad_to_4(std::string& out) {
    while (out.size() % 4 != 0) out.push_back('\0');
}

std::string where(std::size_t level, std::size_t face, std::size_t faces) {
    std::string text = "level " + std::to_string(level);
    if (faces > 1) {
        static const char* kNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
        text += std::string(" face ") + kNames[face];
    }
    return text;
}

}  // namespace

Result<std::string> encode_ktx(const KtxTexture& texture) {
    if (texture.levels.empty() || texture.levels[0].empty()) return Error{"no levels to write"};
    const std::size_t faces = texture.levels[0].size();
    if (faces != 1 && faces != 6)
        return Error{std::to_string(faces) + " faces: a KTX texture has 1, or 6 (a cube map)"};
    const int width = texture.levels[0][0].width, height = texture.levels[0][0].height;
    const bool half = texture.type == KtxPixelType::half_float;
    const std::size_t bytes_per_value = half ? 2 : 4;

    std::string out(reinterpret_cast<const char*>(kIdentifier), sizeof kIdentifier);
    put_u32(out, kEndianness);
    put_u32(out, half ? kGlHalfFloat : kGlFloat);
    put_u32(out, static_cast<std::uint32_t>(bytes_per_value));
    put_u32(out, kGlRgba);
    put_u32(out, half ? kGlRgba16f : kGlRgba32f);
    put_u32(out, kGlRgba);
    put_u32(out, static_cast<std::uint32_t>(width));
    put_u32(out, static_cast<std::uint32_t>(height));
    put_u32(out, 0);  // pixelDepth: a 2D texture
    put_u32(out, 0);  // numberOfArrayElements: not an array
    put_u32(out, static_cast<std::uint32_t>(faces));
    put_u32(out, static_cast<std::uint32_t>(texture.levels.size()));

    std::string key_values;
    for (const auto& [key, value] : texture.key_values) {
        put_u32(key_values, static_cast<std::uint32_t>(key.size() + 1 + value.size() + 1));
        key_values += key;
        key_values.push_back('\0');
        key_values += value;
        key_values.push_back('\0');
        pad_to_4(key_values);
    }
    put_u32(out, static_cast<std::uint32_t>(key_values.size()));
    out += key_values;

    for (std::size_t l = 0; l < texture.levels.size(); ++l) {
        const std::vector<Image>& level = texture.levels[l];
        const int w = std::max(1, width >> l), h = std::max(1, height >> l);
        if (level.size() != faces)
            return Error{"level " + std::to_string(l) + " has " + std::to_string(level.size()) +
                         " faces, level 0 has " + std::to_string(faces)};
        const std::size_t face_bytes = static_cast<std::size_t>(w) * h * 4 * bytes_per_value;
        // The spec's imageSize: one face's bytes for a non-array cube map, else the level's.
        put_u32(out, static_cast<std::uint32_t>(faces == 6 ? face_bytes : face_bytes * faces));
        for (std::size_t f = 0; f < faces; ++f) {
            const Image& image = level[f];
            if (image.width != w || image.height != h || image.channels != 4)
                return Error{where(l, f, faces) + " is " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + " with " +
                             std::to_string(image.channels) + " channels; expected " +
                             std::to_string(w) + "x" + std::to_string(h) + " RGBA"};
            for (std::size_t i = 0; i < image.pixels.size(); ++i) {
                const float v = image.pixels[i];
                if (!half) {
                    std::uint32_t bits;
                    std::memcpy(&bits, &v, 4);
                    put_u32(out, bits);
                    continue;
                }
                if (!(std::abs(v) <= kHalfMax)) {
                    const std::size_t texel = i / 4;
                    return Error{where(l, f, faces) + " texel (" + std::to_string(texel % w) +
                                 ", " + std::to_string(texel / w) + ") channel " +
                                 std::to_string(i % 4) + " is " + std::to_string(v) +
                                 ", beyond half floats' range (±65504)"};
                }
                put_u16(out, Imath::half(v).bits());  // rounded to nearest, ties to even
            }
            // Rows, faces and levels are multiples of 4 bytes (4 channels of 2 or 4 bytes): the
            // spec's cubePadding and mipPadding are empty.
        }
    }
    return out;
}

}  // namespace footprint
