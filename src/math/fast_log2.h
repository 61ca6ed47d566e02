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

#include "math/float4.h"

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

// The same for four x at once (math/float4.h): each lane is fast_log2(x) bit for bit.
inline Float4 fast_log2(Float4 x) {
    const Int4 bits = bits_of(x);
    const Int4 exponent = (shift_right<23>(bits) & Int4(0xff)) - Int4(127);
    const Float4 m = float_from_bits((bits & Int4(0x007fffff)) | Int4(0x3f800000));  // [1, 2)
    const Mask4 high = m > Float4(1.41421356f);
    const Float4 reduced = select(high, m * Float4(0.5f), m);
    const Int4 e = select(high, exponent + Int4(1), exponent);
    const Float4 t = (reduced - Float4(1.0f)) / (reduced + Float4(1.0f)), t2 = t * t;
    const Float4 series =
        t * (Float4(2.88539008f) +
             t2 * (Float4(0.961796694f) + t2 * (Float4(0.577078016f) + t2 * Float4(0.412198583f))));
    return to_float(e) + series;
}

}  // namespace footprint
