#include "bump/roughness.h"

#include <algorithm>
#include <cmath>

namespace footprint {

RoughnessFactor roughness_factor(const Sym2& k) {
    RoughnessFactor b;
    if (!k.is_finite()) return b;
    // ε: k22 below this (relative to the trace) is rank-deficient for float purposes.
    constexpr float kRelativeEpsilon = 1e-12f;
    const float scale = std::max(0.0f, k.xx) + std::max(0.0f, k.yy);
    if (k.yy > kRelativeEpsilon * scale && k.yy > 0) {
        b.d3 = std::sqrt(k.yy);
        const float bound = std::sqrt(std::max(0.0f, k.xx));
        b.d2 = std::clamp(k.xy / b.d3, -bound, bound);
        b.d1 = std::sqrt(std::max(0.0f, k.xx * k.yy - k.xy * k.xy) / k.yy);
    } else {
        b.d1 = std::sqrt(std::max(0.0f, k.xx));
    }
    return b;
}

float isotropic_roughness(const Sym2& k) {
    if (!k.is_finite()) return 0;
    const float w = std::sqrt((k.xx - k.yy) * (k.xx - k.yy) + 4 * k.xy * k.xy);
    return std::sqrt(std::max(0.0f, 0.5f * (k.xx + k.yy + w)));
}

Sym2 clamp_to_psd(const Sym2& k) {
    if (!k.is_finite()) return {};
    if (k.xx >= 0 && k.yy >= 0 && k.determinant() >= 0) return k;
    // Eigen-decompose (spec §2.7's robust axes) and drop the negative part.
    const float w = std::sqrt((k.xx - k.yy) * (k.xx - k.yy) + 4 * k.xy * k.xy);
    const float major = std::max(0.0f, 0.5f * (k.xx + k.yy + w));
    const float minor = std::max(0.0f, 0.5f * (k.xx + k.yy - w));
    Vec2 r = k.xx >= k.yy ? Vec2{k.xx - k.yy + w, 2 * k.xy} : Vec2{2 * k.xy, k.yy - k.xx + w};
    const float len = std::sqrt(dot(r, r));
    r = len > 0 ? r / len : Vec2{1, 0};
    return outer(r, major) + outer(Vec2{-r.y, r.x}, minor);
}

}  // namespace footprint
