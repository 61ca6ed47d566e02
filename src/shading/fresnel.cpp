#include "shading/fresnel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace footprint {

namespace {

// T_k = ∫_a^b z^k φ(z) dz for k = 0 … 7 (φ the standard normal density; a, b may be ±∞), by
// T_0 = Φ(b) − Φ(a), T_1 = φ(a) − φ(b), T_k = (k − 1) T_{k−2} + a^{k−1} φ(a) − b^{k−1} φ(b).
std::array<double, 8> normal_moments(double a, double b) {
    auto phi = [](double z) {
        return std::isfinite(z) ? std::exp(-0.5 * z * z) / std::sqrt(2 * std::numbers::pi) : 0.0;
    };
    auto cdf = [](double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); };
    // z^{k−1} φ(z), 0 at ±∞.
    auto edge = [&](double z, int power) {
        return std::isfinite(z) ? std::pow(z, power) * phi(z) : 0.0;
    };
    std::array<double, 8> t{};
    t[0] = cdf(b) - cdf(a);
    t[1] = phi(a) - phi(b);
    for (int k = 2; k < 8; ++k) t[k] = (k - 1) * t[k - 2] + edge(a, k - 1) - edge(b, k - 1);
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
        return out;
    }
    // E[z^m F], m = 0, 1, 2, with c = c̄ + σz: F = 1 where c < 0 (z < z0), F0 where c > 1 (z > z1),
    // and between them F0 + (1 − F0)(1 − c̄ − σz)⁵, a quintic in z whose terms integrate exactly.
    const double sigma = std::sqrt(double(variance)), a = 1.0 - cos_mean;
    const double z0 = -cos_mean / sigma, z1 = (1.0 - cos_mean) / sigma;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const std::array<double, 8> below = normal_moments(-kInf, z0), inside = normal_moments(z0, z1),
                                above = normal_moments(z1, kInf);
    constexpr double kBinomial[6] = {1, 5, 10, 10, 5, 1};
    double moments[3];
    for (int m = 0; m < 3; ++m) {
        double quintic = 0;
        for (int j = 0; j <= 5; ++j) {
            quintic += kBinomial[j] * std::pow(a, 5 - j) * std::pow(-sigma, j) * inside[m + j];
        }
        moments[m] = f0 * (above[m] + inside[m]) + (1.0 - f0) * quintic;
    }
    out.facing_away = static_cast<float>(below[0]);
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

}  // namespace footprint
