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

#include "math/float4.h"

namespace footprint {

inline float fast_atan2(float y, float x) {
    constexpr float kHalfPi = 1.57079632679f, kPi = 3.14159265359f;
    const float ax = std::fabs(x), ay = std::fabs(y);
    const float big = std::max(ax, ay), small = std::min(ax, ay);
    const float a = big > 0 ? small / big : 0.0f, s = a * a;
    float r =
        a *
        (0.999999344f +
         s * (-0.333298594f +
              s * (0.199465662f +
                   s * (-0.139086291f +
                        s * (0.0964219496f +
                             s * (-0.0559122972f + s * (0.0218629353f + s * -0.00405456079f)))))));
    if (ay > ax) r = kHalfPi - r;
    if (std::signbit(x)) r = kPi - r;
    if (std::isnan(x) || std::isnan(y)) return x + y;
    return std::copysign(r, y);
}

// The same for four (y, x) at once (math/float4.h): each lane is fast_atan2(y, x) bit for bit
// (a NaN lane may carry another NaN).
inline Float4 fast_atan2(Float4 y, Float4 x) {
    const Float4 ax = abs(x), ay = abs(y);
    const Float4 big = max_like_std(ax, ay), small = min_like_std(ax, ay);
    const Float4 a = select(big > Float4(0.0f), small / big, Float4(0.0f)), s = a * a;
    Float4 r =
        a *
        (Float4(0.999999344f) +
         s * (Float4(-0.333298594f) +
              s * (Float4(0.199465662f) +
                   s * (Float4(-0.139086291f) +
                        s * (Float4(0.0964219496f) +
                             s * (Float4(-0.0559122972f) +
                                  s * (Float4(0.0218629353f) + s * Float4(-0.00405456079f))))))));
    r = select(ay > ax, Float4(1.57079632679f) - r, r);
    r = select(sign_bit(x), Float4(3.14159265359f) - r, r);
    return select(is_not_nan(x) & is_not_nan(y), copysign(r, y), x + y);
}

}  // namespace footprint
