#include "shading/blinn_phong.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace footprint {
namespace {

// The formulas are evaluated in double: they are a handful of operations, and double keeps
// products of tiny or huge float inputs (|d|⁴, det K) from underflowing or overflowing.
constexpr double kInfinity = std::numeric_limits<double>::infinity();

double clamp01(double x) {
    return std::clamp(x, 0.0, 1.0);
}

// K clamped to be positive semi-definite: negative variances to 0, |k12| ≤ sqrt(k11 k22).
struct Sym2d {
    double xx = 0, xy = 0, yy = 0;
};
Sym2d psd_clamp(const Sym2& k) {
    const double xx = std::max(0.0, double(k.xx)), yy = std::max(0.0, double(k.yy));
    const double bound = std::sqrt(xx * yy);
    return {xx, std::clamp(double(k.xy), -bound, bound), yy};
}

// λ_max of a PSD K (spec §2.7 / §5.5): ½(k11 + k22 + hypot(k11 − k22, 2 k12)).
double max_eigenvalue(const Sym2d& k) {
    return 0.5 * (k.xx + k.yy + std::hypot(k.xx - k.yy, 2 * k.xy));
}

// dᵀK⁻¹d for d ≠ 0. Where K is singular (or indefinite from rounding) it is the limit of K + εI,
// ε → 0⁺, for the PSD part of K: +∞ as soon as d has a component along a direction of zero
// variance, so that direction is mirror-sharp.
double inverse_quadratic_form(const Sym2& k, double dx, double dy) {
    const double xx = k.xx, xy = k.xy, yy = k.yy;
    const double det = xx * yy - xy * xy;
    if (det > 0 && xx > 0) {  // positive definite: the adjugate form dᵀ adj(K) d / det K
        const double adj = yy * dx * dx - 2 * xy * dx * dy + xx * dy * dy;
        return std::max(adj, 0.0) / det;
    }
    // Rank ≤ 1: keep the major eigenpair (robust form of spec §2.7), drop the other (≤ 0).
    const double w = std::hypot(xx - yy, 2 * xy);
    const double lambda1 = 0.5 * (xx + yy + w);
    if (!(lambda1 > 0)) return kInfinity;  // K = 0 (or negative): zero variance everywhere
    double rx = xx >= yy ? xx - yy + w : 2 * xy;
    double ry = xx >= yy ? 2 * xy : yy - xx + w;
    const double len = std::hypot(rx, ry);
    if (len > 0) {
        rx /= len;
        ry /= len;
    } else {
        rx = 1;
        ry = 0;
    }
    const double along = rx * dx + ry * dy, across = -ry * dx + rx * dy;
    if (across != 0) return kInfinity;
    return along * along / lambda1;
}

// cos²a' = cos²a / (term + cos²a) for term ≥ 0 (possibly +∞) and cos²a ∈ [0, 1]: 0 where both
// vanish (ĥ on the horizon).
double modified_cos2(double cos2, double term) {
    const double den = term + cos2;
    return den > 0 ? cos2 / den : 0.0;
}

double dot3(const std::array<float, 3>& a, const std::array<float, 3>& b) {
    return double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
}

// (cos²a')^{m/2}, m ≥ 0; 0^0 = 1.
double lobe(double cos2_prime, double m) {
    return std::pow(cos2_prime, 0.5 * m);
}

}  // namespace

float blinn_phong(float cos_a, float shininess) {
    if (!(cos_a > 0)) return 0;
    return static_cast<float>(std::pow(std::min(double(cos_a), 1.0), std::max(0.0f, shininess)));
}

float modified_cos2_paper(float cos2_a, Vec2 d, const Sym2& k_b) {
    const double dx = d.x, dy = d.y;
    const double q = dx * dx + dy * dy;  // |d|²
    if (q == 0) return 1;                // 0/0 term defined as 0
    // σ²(d̂) = d̂ᵀK d̂ = |Bᵀd|²/|d|²; the term |d|⁴/|Bᵀd|² = |d|²/σ²(d̂).
    const double var =
        (double(k_b.xx) * dx * dx + 2 * double(k_b.xy) * dx * dy + double(k_b.yy) * dy * dy) / q;
    const double term = var > 0 ? q / var : kInfinity;
    return static_cast<float>(modified_cos2(clamp01(cos2_a), term));
}

float modified_cos2_isotropic(float cos2_a, float l1) {
    const double c2 = clamp01(cos2_a);
    if (c2 >= 1) return 1;  // d = 0
    const double num = double(l1) * l1 * c2;
    return static_cast<float>(num / ((1 - c2) + num));  // denominator ≥ 1 − c2 > 0
}

float modified_cos2_gaussian(float cos2_a, Vec2 d, const Sym2& k_rel) {
    if (d.x == 0 && d.y == 0) return 1;  // 0/0 term defined as 0
    return static_cast<float>(
        modified_cos2(clamp01(cos2_a), inverse_quadratic_form(k_rel, d.x, d.y)));
}

float rough_blinn_phong(float cos_a, Vec2 d, const Sym2& k_b, float shininess) {
    if (!(cos_a > 0)) return 0;
    const double c = std::min(double(cos_a), 1.0), c2 = c * c;
    const double m = std::max(0.0f, shininess);
    const Sym2d k = psd_clamp(k_b);
    // K_rel = I + m K_b; det K_rel = 1 + m tr K_b + m² det K_b ≥ 1 (no cancellation).
    const double det_rel = 1 + m * (k.xx + k.yy) + m * m * std::max(0.0, k.xx * k.yy - k.xy * k.xy);
    // dᵀ adj(K_rel) d = |d|² + m dᵀ adj(K_b) d.
    const double dx = d.x, dy = d.y;
    const double adj_b = std::max(0.0, k.yy * dx * dx - 2 * k.xy * dx * dy + k.xx * dy * dy);
    const double term = (dx * dx + dy * dy + m * adj_b) / det_rel;
    return static_cast<float>(lobe(modified_cos2(c2, term), m) / std::sqrt(det_rel));
}

HalfVectorGeometry half_vector_geometry(const std::array<float, 3>& n,
                                        const std::array<float, 3>& e1,
                                        const std::array<float, 3>& e2,
                                        const std::array<float, 3>& h) {
    return {static_cast<float>(dot3(n, h)),
            {static_cast<float>(-dot3(h, e1)), static_cast<float>(-dot3(h, e2))}};
}

float specular(RoughShadingModel model, const std::array<float, 3>& n,
               const std::array<float, 3>& e1, const std::array<float, 3>& e2,
               const std::array<float, 3>& h, const Sym2& k_b, float shininess) {
    const HalfVectorGeometry g = half_vector_geometry(n, e1, e2, h);
    if (!(g.cos_a > 0)) return 0;
    const double m = std::max(0.0f, shininess);
    const double c = std::min(double(g.cos_a), 1.0);
    const float cos2 = static_cast<float>(c * c);
    switch (model) {
        case RoughShadingModel::plain:
            return blinn_phong(g.cos_a, shininess);
        case RoughShadingModel::paper: {
            const Sym2d k = psd_clamp(k_b);
            const Sym2 k_rel{static_cast<float>(1 + m * k.xx), static_cast<float>(m * k.xy),
                             static_cast<float>(1 + m * k.yy)};
            const double trace = 2 + m * (k.xx + k.yy);
            return static_cast<float>(lobe(modified_cos2_paper(cos2, g.d, k_rel), m) * 2 / trace);
        }
        case RoughShadingModel::isotropic: {
            const double l1_squared = 1 + m * max_eigenvalue(psd_clamp(k_b));
            const float l1 = static_cast<float>(std::sqrt(l1_squared));
            return static_cast<float>(lobe(modified_cos2_isotropic(cos2, l1), m) / l1_squared);
        }
        case RoughShadingModel::gaussian:
            return rough_blinn_phong(g.cos_a, g.d, k_b, shininess);
    }
    return 0;
}

}  // namespace footprint
