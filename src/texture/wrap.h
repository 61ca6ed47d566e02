// texture/wrap.h — what happens to texel addresses outside the texture.
//
//   repeat  the texture tiles the plane (period W)
//   clamp   coordinates clamp to the edge texel (GL CLAMP_TO_EDGE; never GL_CLAMP's border colour)
//   mirror  the texture is reflected at each edge, period 2W, as GL MIRRORED_REPEAT:
//           texel indices ... 1 0 | 0 1 2 ... W−1 | W−1 W−2 ...
// Chosen per axis. Texel coordinates follow spec §1: texel i of a level covers [i−½, i+½) in
// that level's texel units, its centre at i; s ∈ [0,1] maps to X = s·W − ½.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

namespace footprint {

enum class WrapMode { repeat, clamp, mirror };

// Maps any integer texel index into [0, n).
inline int wrap_index(int i, int n, WrapMode mode) {
    switch (mode) {
        case WrapMode::repeat: {
            const int r = i % n;
            return r < 0 ? r + n : r;
        }
        case WrapMode::clamp:
            return std::clamp(i, 0, n - 1);
        case WrapMode::mirror: {
            const int period = 2 * n;
            int r = i % period;
            if (r < 0) r += period;
            return r < n ? r : period - 1 - r;
        }
    }
    return 0;
}

// Brings a normalised coordinate into a range where texel arithmetic cannot overflow an int,
// without changing which texels it addresses: repeat → [0,1), mirror → [0,2), clamp → [−1,2].
// Non-finite input is the caller's problem (lookups test for it first).
inline float reduce_coordinate(float s, WrapMode mode) {
    switch (mode) {
        case WrapMode::repeat:
            return s - std::floor(s);
        case WrapMode::mirror:
            return s - 2.0f * std::floor(0.5f * s);
        case WrapMode::clamp:
            return std::clamp(s, -1.0f, 2.0f);
    }
    return s;
}

std::optional<WrapMode> parse_wrap_mode(std::string_view name);  // "repeat" | "clamp" | "mirror"
const char* to_string(WrapMode mode);
// OpenImageIO's "wrapmodes" attribute of a texture file (maketx's): "periodic,clamp" for s, t.
// parse_wrap_mode() reads its names too ("periodic" is repeat).
std::string oiio_wrap_modes(WrapMode s, WrapMode t);
// Reads such an attribute ("periodic,clamp", or one mode for both axes): (s, t), each nullopt where
// it names no mode footprint has. "black", which footprint does not have, is read as clamp.
struct WrapModes {
    std::optional<WrapMode> s, t;
};
WrapModes parse_oiio_wrap_modes(std::string_view modes);

}  // namespace footprint
