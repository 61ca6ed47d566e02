// image/color.h — the sRGB transfer function (IEC 61966-2-1), exact piecewise form.
// Everything inside footprint is linear light; files in sRGB are decoded on input and encoded on
// output. Alpha is never encoded.
#pragma once

#include <cmath>

namespace footprint {

inline float srgb_to_linear(float v) {
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

inline float linear_to_srgb(float v) {
    if (!(v > 0.0f)) return 0.0f;  // also maps NaN to 0
    if (v >= 1.0f) return 1.0f;
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

}  // namespace footprint
