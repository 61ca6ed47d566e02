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

#include <type_traits>

#include "math/lanes.h"

namespace footprint {

// For one lane (float) or four (Float4, math/lanes.h): each lane is the float result bit for bit.
template <class F>
inline F fast_log2(F x) {
    static_assert(std::is_same_v<F, float> || std::is_same_v<F, Float4>);
    using I = IntOf<F>;
    const I bits = bits_of(x);
    const I exponent = (shift_right<23>(bits) & I(0xff)) - I(127);
    const F m = float_from_bits((bits & I(0x007fffff)) | I(0x3f800000));  // [1, 2)
    const MaskOf<F> high = m > F(1.41421356f);
    const F reduced = select(high, m * F(0.5f), m);
    const I e = select(high, exponent + I(1), exponent);
    const F t = (reduced - F(1.0f)) / (reduced + F(1.0f)), t2 = t * t;
    // 2/ln2 · (t + t³/3 + t⁵/5 + t⁷/7)
    const F series = t * (F(2.88539008f) +
                          t2 * (F(0.961796694f) + t2 * (F(0.577078016f) + t2 * F(0.412198583f))));
    return to_float(e) + series;
}

}  // namespace footprint
