#include "shading/microfacet.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "shading/fresnel.h"

namespace footprint {
namespace {

// As in blinn_phong.cpp, the formulas are evaluated in double: det M, z⁴ and the products of tiny
// or huge float inputs neither underflow nor overflow there.
constexpr double kPi = std::numbers::pi;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kLargestFloat = std::numeric_limits<float>::max();

struct Sym2d {
    double xx = 0, xy = 0, yy = 0;
    double determinant() const { return xx * yy - xy * xy; }
};
struct Local {  // (ω·e1, ω·e2, ω·n̂)
    double x = 0, y = 0, z = 0;
};

double dot3(const std::array<float, 3>& a, const std::array<float, 3>& b) {
    return double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
}

Local to_local(const std::array<float, 3>& w) {
    return {w[0], w[1], w[2]};
}

// A float result: NaN (never expected) to 0, beyond the float range to the largest float.
float to_float(double r) {
    return r >= 0 ? static_cast<float>(std::min(r, kLargestFloat)) : 0.0f;
}

double clamp_alpha(float alpha) {
    return alpha >= kMinMicrofacetAlpha ? std::min(double(alpha), 1.0) : kMinMicrofacetAlpha;
}

// M = α² I + 2 K_b with K_b clamped to be PSD: negative (or NaN) variances to 0, |k12| ≤ √(k11
// k22).
Sym2d roughness_matrix(float alpha, const Sym2& k) {
    const double xx = std::max(0.0, double(k.xx)), yy = std::max(0.0, double(k.yy));
    const double bound = std::sqrt(xx * yy);
    const double xy = std::isnan(k.xy) ? 0.0 : std::clamp(double(k.xy), -bound, bound);
    const double a2 = clamp_alpha(alpha) * clamp_alpha(alpha);
    return {a2 + 2 * xx, 2 * xy, a2 + 2 * yy};
}

Sym2d to_double(const Sym2& m) {
    return {m.xx, m.xy, m.yy};
}

bool positive_definite(const Sym2d& m) {
    return std::isfinite(m.xx) && std::isfinite(m.xy) && std::isfinite(m.yy) && m.xx > 0 &&
           m.determinant() > 0;
}

// D(ĥ) for the local coordinates of ĥ (normalised here) and a positive definite M (the top of
// microfacet.h): Q = tᵀM⁻¹t by the adjugate, Beckmann exp(−Q/z²)/(π √det M z⁴), GGX
// 1/(π √det M (z² + Q)²) [W07 eq. 33 for M = α² I].
double distribution(MicrofacetModel model, Local h, const Sym2d& m) {
    const double length = std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z);
    if (!(h.z > 0) || !(length > 0) || !positive_definite(m)) return 0;
    const double x = h.x / length, y = h.y / length, z = h.z / length;
    const double det = m.determinant();
    const double q = std::max(0.0, m.yy * x * x - 2 * m.xy * x * y + m.xx * y * y) / det;
    const double z2 = z * z;
    switch (model) {
        case MicrofacetModel::beckmann:
            return std::exp(-q / z2) / (kPi * std::sqrt(det) * z2 * z2);
        case MicrofacetModel::ggx: {
            const double den = z2 + q;
            return 1 / (kPi * std::sqrt(det) * den * den);
        }
    }
    return 0;
}

// Smith's Λ(ω) with q = α_ω² tan²θ = tᵀM t / z² (the roughness of ω's azimuth [H14]).
double lambda(MicrofacetModel model, Local w, const Sym2d& m) {
    if (!(w.z > 0) || !positive_definite(m)) return kInfinity;
    const double q =
        std::max(0.0, m.xx * w.x * w.x + 2 * m.xy * w.x * w.y + m.yy * w.y * w.y) / (w.z * w.z);
    if (!(q > 0)) return 0;  // along n̂: nothing masks
    if (!(q < kInfinity)) return kInfinity;
    switch (model) {
        case MicrofacetModel::beckmann: {
            // (e^{−a²}/(a√π) − erfc a)/2: the difference cancels for large a, where Λ < 1e-5
            // anyway and the double rounding stays far below that; max() keeps it ≥ 0.
            const double a = 1 / std::sqrt(q);
            return std::max(0.0, 0.5 * (std::exp(-a * a) / (a * std::sqrt(kPi)) - std::erfc(a)));
        }
        case MicrofacetModel::ggx:
            return q / (2 * (1 + std::sqrt(1 + q)));  // (√(1 + q) − 1)/2 without cancellation
    }
    return 0;
}

double masking_shadowing(MicrofacetModel model, Local l, Local v, const Sym2d& m) {
    if (!(l.z > 0) || !(v.z > 0)) return 0;
    return 1 / (1 + lambda(model, l, m) + lambda(model, v, m));  // 1/∞ = 0
}

}  // namespace

Sym2 microfacet_roughness_matrix(float alpha, const Sym2& k_b) {
    const Sym2d m = roughness_matrix(alpha, k_b);
    return {static_cast<float>(m.xx), static_cast<float>(m.xy), static_cast<float>(m.yy)};
}

float microfacet_distribution(MicrofacetModel model, const std::array<float, 3>& h, const Sym2& m) {
    return to_float(distribution(model, to_local(h), to_double(m)));
}

float smith_lambda(MicrofacetModel model, const std::array<float, 3>& w, const Sym2& m) {
    return to_float(lambda(model, to_local(w), to_double(m)));
}

float smith_masking_shadowing(MicrofacetModel model, const std::array<float, 3>& l,
                              const std::array<float, 3>& v, const Sym2& m) {
    return to_float(masking_shadowing(model, to_local(l), to_local(v), to_double(m)));
}

MicrofacetTerms microfacet_terms(MicrofacetModel model, const std::array<float, 3>& n,
                                 const std::array<float, 3>& e1, const std::array<float, 3>& e2,
                                 const std::array<float, 3>& l, const std::array<float, 3>& v,
                                 const Sym2& k_b, float alpha) {
    const double cos_l = dot3(n, l), cos_v = dot3(n, v);
    if (!(cos_l > 0) || !(cos_v > 0)) return {};
    // ĥ = normalize(l̂ + v̂): never zero with both above the horizon.
    std::array<float, 3> h;
    for (int i = 0; i < 3; ++i) h[i] = l[i] + v[i];
    const Local l_local{dot3(l, e1), dot3(l, e2), cos_l}, v_local{dot3(v, e1), dot3(v, e2), cos_v};
    const Local h_local{dot3(h, e1), dot3(h, e2), dot3(h, n)};  // normalised by distribution()
    const double h_length = std::sqrt(dot3(h, h));
    const double cos_vh = dot3(v, h) / h_length;  // = l̂·ĥ
    const Sym2d m = roughness_matrix(alpha, k_b);
    const double d = distribution(model, h_local, m);
    const double g = masking_shadowing(model, l_local, v_local, m);
    return {to_float(d * g / (4 * cos_v)), schlick_fresnel(0, static_cast<float>(cos_vh))};
}

float MicrofacetTerms::times(float f0) const {
    const float f = std::clamp(f0, 0.0f, 1.0f);
    return dg * (f + (1 - f) * schlick);
}

float microfacet_highlight(MicrofacetModel model, const std::array<float, 3>& n,
                           const std::array<float, 3>& e1, const std::array<float, 3>& e2,
                           const std::array<float, 3>& l, const std::array<float, 3>& v,
                           const Sym2& k_b, float alpha, float f0) {
    return microfacet_terms(model, n, e1, e2, l, v, k_b, alpha).times(f0);
}

}  // namespace footprint
