#include "shading/fresnel.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace footprint {

namespace {

// Bounds beyond ±kEdge count as infinite: φ(10) ≈ 8e-23, far below float.
constexpr double kEdge = 10;

// The incomplete moments of the standard normal density φ from z0 on, k = 0 … 7:
//   to_z1[k] = ∫_{z0}^{z1} z^k φ,   to_infinity[k] = ∫_{z0}^{∞} z^k φ (k ≤ 2),
// by T_0 = Φ(b) − Φ(a), T_1 = φ(a) − φ(b), T_k = (k − 1) T_{k−2} + a^{k−1} φ(a) − b^{k−1} φ(b):
// one erfc and one exp per bound.
struct NormalMoments {
    double to_z1[8], to_infinity[3], below_z0;  // below_z0 = Φ(z0)
};

NormalMoments normal_moments(double z0, double z1) {
    if (z0 <= -kEdge && z1 >= kEdge) {
        // The whole line (the common case: no slope turns c past 0 or 1): E[z^k] = (k − 1)!!.
        return {{1, 0, 1, 0, 3, 0, 15, 0}, {1, 0, 1}, 0};
    }
    z0 = std::clamp(z0, -kEdge, kEdge), z1 = std::clamp(z1, -kEdge, kEdge);
    const double inv_sqrt_2pi = 1 / std::sqrt(2 * std::numbers::pi);
    const double phi0 = std::exp(-0.5 * z0 * z0) * inv_sqrt_2pi;
    const double phi1 = std::exp(-0.5 * z1 * z1) * inv_sqrt_2pi;
    const double cdf0 = 0.5 * std::erfc(-z0 / std::numbers::sqrt2);
    const double cdf1 = 0.5 * std::erfc(-z1 / std::numbers::sqrt2);
    NormalMoments t;
    t.below_z0 = cdf0;
    t.to_z1[0] = cdf1 - cdf0, t.to_z1[1] = phi0 - phi1;
    t.to_infinity[0] = 1 - cdf0, t.to_infinity[1] = phi0;
    double edge0 = phi0, edge1 = phi1;  // z^{k−1} φ(z) at both bounds
    for (int k = 2; k < 8; ++k) {
        edge0 *= z0, edge1 *= z1;
        t.to_z1[k] = (k - 1) * t.to_z1[k - 2] + edge0 - edge1;
        if (k < 3) t.to_infinity[k] = (k - 1) * t.to_infinity[k - 2] + edge0;
    }
    return t;
}

}  // namespace

float schlick_fresnel(float f0, float cos_theta) {
    const float c = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
    const float c2 = c * c;
    return f0 + (1.0f - f0) * c2 * c2 * c;
}

FresnelOverSlopes fresnel_over_slopes(float f0, float cos_mean, Vec2 dcos_dslope, const Sym2& k) {
    FresnelOverSlopes out;
    out.covariance = k;
    const float variance = k.quadratic_form(dcos_dslope);  // σ_c²
    if (!(variance > 0) || !std::isfinite(variance)) {
        out.mean = schlick_fresnel(f0, cos_mean);
        out.schlick = schlick_fresnel(0, cos_mean);
        return out;
    }
    // E[z^m F; c ≥ 0], m = 0, 1, 2, with c = c̄ + σz: F0 where c > 1 (z > z1), and on [0, 1]
    // F0 + (1 − F0)(a − σz)⁵ with a = 1 − c̄, a quintic in z: Σ_j q_j z^j, q_j = C(5, j) a^{5−j}
    // (−σ)^j.
    const double sigma = std::sqrt(double(variance)), a = 1.0 - cos_mean;
    const NormalMoments t = normal_moments(-cos_mean / sigma, (1.0 - cos_mean) / sigma);
    constexpr double kBinomial[6] = {1, 5, 10, 10, 5, 1};
    double q[6], a_power = 1, s_power = 1;
    for (int j = 5; j >= 0; --j) q[j] = a_power, a_power *= a;  // a^{5−j}
    for (int j = 0; j <= 5; ++j) q[j] *= kBinomial[j] * s_power, s_power *= -sigma;
    double moments[3], quintic[3];
    for (int m = 0; m < 3; ++m) {
        quintic[m] = 0;
        for (int j = 0; j <= 5; ++j) quintic[m] += q[j] * t.to_z1[m + j];
        moments[m] = f0 * t.to_infinity[m] + (1.0 - f0) * quintic[m];
    }
    out.facing_away = static_cast<float>(t.below_z0);
    out.schlick = static_cast<float>(quintic[0]);
    const float f = static_cast<float>(moments[0]), zf = static_cast<float>(moments[1]),
                z2f = static_cast<float>(moments[2]);
    out.mean = f;
    if (!(f > 0)) return out;
    // K u, the slopes' covariance with c (up to σ_c).
    const Vec2 ku{k.xx * dcos_dslope.x + k.xy * dcos_dslope.y,
                  k.xy * dcos_dslope.x + k.yy * dcos_dslope.y};
    const float mean_z = zf / f;
    const float variance_z = std::max(0.0f, z2f / f - mean_z * mean_z);
    out.mean_slope_shift = (mean_z / static_cast<float>(sigma)) * ku;
    const float narrowing = (1 - variance_z) / variance;
    out.covariance = Sym2{k.xx - narrowing * ku.x * ku.x, k.xy - narrowing * ku.x * ku.y,
                          k.yy - narrowing * ku.y * ku.y};
    return out;
}

float mean_fresnel(const FresnelOverSlopes& over, float f0) {
    return f0 * (1 - over.facing_away) + (1 - f0) * over.schlick;
}

}  // namespace footprint
