// math/fast_log2.h — log2 for level-of-detail selection, inline and without a libm call.
//
// Texture lookups at random positions are bound by memory latency, and the lod computation sits on
// the path from the derivatives to the first texel address. This log2 splits x = 2^e·m with
// m ∈ [√½, √2) and evaluates log2 m = (2/ln 2)·atanh(t), t = (m − 1)/(m + 1), |t| ≤ 0.1716, by its
// series to t⁷: the truncation error is below 5e−8, i.e. float rounding. Powers of two are exact.
// x must be a positive, finite, normal float (callers clamp: lods start at sizes ≥ 1e−30).
#pragma once

#include <bit>
#include <cstdint>

namespace footprint {

inline float fast_log2(float x) {
    std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
    int exponent = static_cast<int>((bits >> 23) & 0xffu) - 127;
    float m = std::bit_cast<float>((bits & 0x007fffffu) | 0x3f800000u);  // [1, 2)
    if (m > 1.41421356f) {
        m *= 0.5f;
        exponent += 1;
    }
    const float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
    // 2/ln2 · (t + t³/3 + t⁵/5 + t⁷/7)
    const float series =
        t * (2.88539008f + t2 * (0.961796694f + t2 * (0.577078016f + t2 * 0.412198583f)));
    return static_cast<float>(exponent) + series;
}

}  // namespace footprint
