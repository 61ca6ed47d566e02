// math/fast_atan2.h — atan2 for environment-map coordinates, inline and without a libm call.
//
// A lat-long lookup takes two atan2 per direction (longitude and colatitude) and glibc's atan2f
// costs more than the rest of the footprint. This one reduces to a = min(|x|,|y|)/max(|x|,|y|) ∈
// [0, 1] and evaluates atan a by an odd degree-15 polynomial fitted minimax on [0, 1] (Lawson's
// weighted least squares): |error| ≤ 6e−8 rad, float rounding. Quadrants and signs follow
// std::atan2, including signed zeros (atan2(±0, x < 0) = ±π, atan2(±0, +0) = ±0); NaN in, NaN out.
#pragma once

#include <algorithm>
#include <cmath>

#include <type_traits>

#include "math/lanes.h"

namespace footprint {

// For one lane (float) or four (Float4, math/lanes.h): each lane is the float result bit for bit
// (a NaN lane may carry another NaN).
template <class F>
inline F fast_atan2(F y, F x) {
    static_assert(std::is_same_v<F, float> || std::is_same_v<F, Float4>);
    using std::abs;
    const F ax = abs(x), ay = abs(y);
    const F big = max_like_std(ax, ay), small = min_like_std(ax, ay);
    const F a = select(big > F(0.0f), small / big, F(0.0f)), s = a * a;
    F r = a * (F(0.999999344f) +
               s * (F(-0.333298594f) +
                    s * (F(0.199465662f) +
                         s * (F(-0.139086291f) +
                              s * (F(0.0964219496f) +
                                   s * (F(-0.0559122972f) +
                                        s * (F(0.0218629353f) + s * F(-0.00405456079f))))))));
    r = select(ay > ax, F(1.57079632679f) - r, r);
    r = select(sign_bit(x), F(3.14159265359f) - r, r);
    return select(MaskOf<F>(is_not_nan(x) & is_not_nan(y)), copysign(r, y), x + y);
}

}  // namespace footprint
