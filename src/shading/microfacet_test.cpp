// Tests of shading/microfacet.h against brute force: quadrature over the hemisphere (the
// normalisation, Smith's Λ against D, the albedo), the numerical convolution of the slope
// distributions with N(0, K_b), and the textbook isotropic formulas.
#include "shading/microfacet.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "math/footprint_ellipse.h"
#include "shading/fresnel.h"
#include "shading/test_extreme_values.h"

namespace footprint {
namespace {

constexpr double kPi = std::numbers::pi;

// The hemisphere quadrature below (midpoint in ψ, θ = atan(c tan ψ), trapezoid in φ; 256 × 128
// nodes) integrates D cos θ_h and G1 D max(0, v̂·ĥ) to within 1.3e-5 of their exact values (the
// worst: the anisotropic GGX lobe, 2.4 times longer than the round lobe the grid is made for); the
// float results of D and Λ add ~1e-7.
constexpr double kQuadrature = 3e-5;
// The albedo's integrand ends in a kink where l̂ crosses the horizon; against a brute force over
// l̂ (8 M nodes, textbook GGX) it agreed to 1e-4 (0.5915 at α = 0.6 facing the light).
constexpr double kAlbedoQuadrature = 1e-3;
// Beckmann widened against the numerical convolution of two Gaussians: the trapezoid rule on a
// Gaussian integrand is exact to far below this at a step of a third of its scale, so what is left
// is the float rounding of D (measured ≤ 3e-8 of the peak).
constexpr double kBeckmannConvolution = 1e-6;
// GGX widened by the moment match (M = α² I + 2 K_b) against its true convolution with N(0, K_b):
// measured 24.3 % of the peak at worst (isotropic σ²/α² = 0.7, at the peak; microfacet.h lists the
// figures), hence 25 %. A lobe widened by K_b instead of 2 K_b would be twice as high as the truth
// at σ²/α² = 8.
constexpr double kGgxMomentMatch = 0.25;
// Float rounding of the highlight's inputs and of the result, a few ulps amplified by the lobe's
// steepness (Q/z² ≤ 20 here; reciprocity measured ≤ 2e-6).
constexpr double kFloatRel = 2e-5;

// Highlights far in a lobe's tail are float denormals (< 1e-38), whose relative rounding is coarse.
constexpr double kDenormal = 1e-38;
// A frame turned in the tangent plane: e1, e2 and K_b are rounded to float after the rotation, and
// the lobe amplifies their rounding by its steepness (measured ≤ 8e-6 relative).
constexpr double kTurnedFrame = 5e-5;

using Array3 = std::array<float, 3>;

Array3 to_array(double x, double y, double z) {
    return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
}

// ∫ f(x, y, z) dω over the upper hemisphere (z = cos θ): θ = atan(c tan ψ) packs the nodes where a
// lobe of slope scale c lives, midpoint rule in ψ ∈ [0, π/2), trapezoid rule in φ (periodic:
// spectrally accurate); dω = sin θ dθ dφ with dθ/dψ = c sec²ψ / (1 + c² tan²ψ).
template <class F>
double hemisphere_integral(double c, int n_psi, int n_phi, F f) {
    const double d_psi = 0.5 * kPi / n_psi, d_phi = 2 * kPi / n_phi;
    double sum = 0;
    for (int i = 0; i < n_psi; ++i) {
        const double psi = (i + 0.5) * d_psi, t = c * std::tan(psi);
        const double theta = std::atan(t);
        const double dtheta = c / (std::cos(psi) * std::cos(psi) * (1 + t * t));
        const double sin_theta = std::sin(theta), cos_theta = std::cos(theta);
        for (int j = 0; j < n_phi; ++j) {
            const double phi = j * d_phi;
            sum += f(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta) * sin_theta *
                   dtheta;
        }
    }
    return sum * d_psi * d_phi;
}

// The roughness matrices tested: isotropic and anisotropic, rotated, and a widened one.
struct RoughnessCase {
    const char* name;
    float alpha;
    Sym2 k_b;
};
const RoughnessCase kCases[] = {
    {"alpha 0.05", 0.05f, {}},
    {"alpha 0.3", 0.3f, {}},
    {"alpha 1", 1.0f, {}},
    {"alpha 0.1 + anisotropic K_b", 0.1f, make_footprint_ellipse(0.2f, 0.05f, 0.6f).matrix},
    {"alpha 0.4 + rank-1 K_b", 0.4f, outer(Vec2{0.6f, -0.8f}, 0.09f)},
};

// The scale of the lobe's slopes for hemisphere_integral(): √λ_min(M).
double slope_scale(const Sym2& m) {
    return make_footprint_ellipse(m).minor_radius;
}

TEST(Microfacet, DistributionIsNormalisedOverTheHemisphere) {
    for (const MicrofacetModel model : {MicrofacetModel::beckmann, MicrofacetModel::ggx}) {
        for (const RoughnessCase& c : kCases) {
            const Sym2 m = microfacet_roughness_matrix(c.alpha, c.k_b);
            // ∫ D(ĥ) cos θ_h dω_h = 1 (the projected microfacet area is the macro-surface's).
            const double integral =
                hemisphere_integral(slope_scale(m), 256, 128, [&](double x, double y, double z) {
                    return microfacet_distribution(model, to_array(x, y, z), m) * z;
                });
            EXPECT_NEAR(integral, 1.0, kQuadrature)
                << (model == MicrofacetModel::ggx ? "ggx " : "beckmann ") << c.name;
        }
    }
}

// Smith's Λ is the one that belongs to D: the visible normals' projected area is the macro
// surface's, ∫ G1(v̂) max(0, v̂·ĥ) D(ĥ) dω_h = cos θ_v with G1 = 1/(1 + Λ(v̂)) ([H14]'s "weak white
// furnace test"). It checks the projected roughness α_ω² = t̂ᵀM t̂ of anisotropic M too.
TEST(Microfacet, SmithLambdaMatchesTheDistribution) {
    const double thetas[] = {0.0, 0.8, 1.3, 1.5};
    for (const MicrofacetModel model : {MicrofacetModel::beckmann, MicrofacetModel::ggx}) {
        for (const RoughnessCase& c : kCases) {
            const Sym2 m = microfacet_roughness_matrix(c.alpha, c.k_b);
            for (const double theta : thetas) {
                for (const double phi : {0.3, 2.0}) {
                    const double vx = std::sin(theta) * std::cos(phi);
                    const double vy = std::sin(theta) * std::sin(phi), vz = std::cos(theta);
                    const double g1 =
                        1 / (1 + double(smith_lambda(model, to_array(vx, vy, vz), m)));
                    const double integral = hemisphere_integral(
                        slope_scale(m), 256, 128, [&](double x, double y, double z) {
                            const double cos_vh = std::max(0.0, vx * x + vy * y + vz * z);
                            return cos_vh * microfacet_distribution(model, to_array(x, y, z), m);
                        });
                    EXPECT_NEAR(g1 * integral, vz, kQuadrature)
                        << (model == MicrofacetModel::ggx ? "ggx " : "beckmann ") << c.name
                        << " theta " << theta << " phi " << phi;
                }
            }
        }
    }
}

// The textbook isotropic formulas (K_b = 0), written as [W07] writes them, against the functions:
//   Beckmann  D = exp(−tan²θ/α²)/(π α² cos⁴θ),   Λ = (erf(a) − 1)/2 + e^{−a²}/(2a√π), a = 1/(α tan
//   θ) GGX       D = α²/(π cos⁴θ (α² + tan²θ)²),     Λ = (−1 + √(1 + α² tan²θ))/2
double textbook_d(MicrofacetModel model, double alpha, double theta) {
    const double a2 = alpha * alpha, t2 = std::tan(theta) * std::tan(theta);
    const double c4 = std::pow(std::cos(theta), 4);
    if (model == MicrofacetModel::beckmann) return std::exp(-t2 / a2) / (kPi * a2 * c4);
    return a2 / (kPi * c4 * (a2 + t2) * (a2 + t2));
}
double textbook_lambda(MicrofacetModel model, double alpha, double theta) {
    if (theta == 0) return 0;
    if (model == MicrofacetModel::ggx) {
        const double at = alpha * std::tan(theta);
        return (-1 + std::sqrt(1 + at * at)) / 2;
    }
    const double a = 1 / (alpha * std::tan(theta));
    return (std::erf(a) - 1) / 2 + std::exp(-a * a) / (2 * a * std::sqrt(kPi));
}

TEST(Microfacet, WithoutRoughnessTheTextbookFormulas) {
    // By hand: at θ = 0 both peaks are 1/(π α²); GGX α = 0.5 at θ = 30°: α² = 1/4, tan² = 1/3,
    // cos⁴ = 9/16, D = (1/4)/(π · 9/16 · (7/12)²) = 576/(441 π) = 0.415752.
    const Sym2 m05 = microfacet_roughness_matrix(0.5f, {});
    EXPECT_NEAR(microfacet_distribution(MicrofacetModel::ggx, {0, 0, 1}, m05), 1 / (kPi * 0.25),
                kFloatRel);
    EXPECT_NEAR(microfacet_distribution(MicrofacetModel::beckmann, {0, 0, 1}, m05),
                1 / (kPi * 0.25), kFloatRel);
    const float s30 = 0.5f, c30 = std::sqrt(3.0f) / 2;
    EXPECT_NEAR(microfacet_distribution(MicrofacetModel::ggx, {s30, 0, c30}, m05),
                576 / (441 * kPi), kFloatRel);

    const double alphas[] = {0.05, 0.2, 0.5, 1.0};
    const double thetas[] = {0.0, 0.05, 0.2, 0.5, 1.0, 1.4};
    for (const MicrofacetModel model : {MicrofacetModel::beckmann, MicrofacetModel::ggx}) {
        for (const double alpha : alphas) {
            const Sym2 m = microfacet_roughness_matrix(static_cast<float>(alpha), {});
            for (const double theta : thetas) {
                for (const double phi : {0.0, 1.0, 4.0}) {  // isotropic: no azimuth dependence
                    const Array3 w = to_array(std::sin(theta) * std::cos(phi),
                                              std::sin(theta) * std::sin(phi), std::cos(theta));
                    const double d = textbook_d(model, alpha, theta);
                    EXPECT_NEAR(microfacet_distribution(model, w, m), d, kFloatRel * d + 1e-30)
                        << alpha << " " << theta;
                    const double lambda = textbook_lambda(model, alpha, theta);
                    // erf − 1 cancels in the textbook form where Λ is tiny: 1e-15 absolute.
                    EXPECT_NEAR(smith_lambda(model, w, m), lambda, kFloatRel * lambda + 1e-12)
                        << alpha << " " << theta;
                }
            }
        }
    }

    // The whole highlight, mirror configuration: v̂ at 45°, l̂ its reflection, ĥ = n̂.
    // f_r cos_l = D(0) G2 F / (4 cos_v) with D(0) = 1/(π α²), G2 = 1/(1 + 2 Λ(45°)),
    // F = 0.04 + 0.96 (1 − cos 45°)⁵.
    const Array3 n{0, 0, 1}, e1{1, 0, 0}, e2{0, 1, 0};
    const float r = std::sqrt(0.5f);
    const Array3 v{r, 0, r}, l{-r, 0, r};
    for (const MicrofacetModel model : {MicrofacetModel::beckmann, MicrofacetModel::ggx}) {
        const double alpha = 0.3;
        const double g2 = 1 / (1 + 2 * textbook_lambda(model, alpha, kPi / 4));
        const double f = 0.04 + 0.96 * std::pow(1 - std::sqrt(0.5), 5);
        const double expected = g2 * f / (kPi * alpha * alpha * 4 * std::sqrt(0.5));
        EXPECT_NEAR(microfacet_highlight(model, n, e1, e2, l, v, {}, 0.3f, 0.04f), expected,
                    kFloatRel * expected);
        // A coloured F0 (gold's, per channel) from one evaluation of the terms.
        const MicrofacetTerms terms = microfacet_terms(model, n, e1, e2, l, v, {}, 0.3f);
        for (const double f0 : {1.0, 0.78, 0.34}) {
            const double fc = f0 + (1 - f0) * std::pow(1 - std::sqrt(0.5), 5);
            const double want = g2 * fc / (kPi * alpha * alpha * 4 * std::sqrt(0.5));
            EXPECT_NEAR(terms.times(static_cast<float>(f0)), want, kFloatRel * want) << f0;
        }
    }
    // Off the mirror direction: v̂ at 60° along e1, l̂ at 30° along e2; everything by the textbook
    // in double, ĥ's angle from its components.
    const double vx = std::sin(kPi / 3), vz = std::cos(kPi / 3), ly = 0.5, lz = std::sqrt(0.75);
    const double hx = vx, hy = ly, hz = vz + lz, hl = std::sqrt(hx * hx + hy * hy + hz * hz);
    const double theta_h = std::acos(hz / hl), cos_vh = (vx * hx + vz * hz) / hl;
    for (const MicrofacetModel model : {MicrofacetModel::beckmann, MicrofacetModel::ggx}) {
        const double alpha = 0.6;
        const double d = textbook_d(model, alpha, theta_h);
        const double g2 = 1 / (1 + textbook_lambda(model, alpha, kPi / 3) +
                               textbook_lambda(model, alpha, kPi / 6));
        const double f = schlick_fresnel(0.5f, static_cast<float>(cos_vh));
        const double expected = d * g2 * f / (4 * vz);
        const float got = microfacet_highlight(model, n, e1, e2, to_array(0, ly, lz),
                                               to_array(vx, 0, vz), {}, 0.6f, 0.5f);
        EXPECT_NEAR(got, expected, kFloatRel * expected);
    }
}

// P22 of the widened lobe at the slope s: D(ĥ(s)) cos⁴θ_h, ĥ(s) = (s, 1)/√(1 + |s|²).
double widened_p22(MicrofacetModel model, const Sym2& m, double sx, double sy) {
    const double z = 1 / std::sqrt(1 + sx * sx + sy * sy);
    return microfacet_distribution(model, to_array(sx * z, sy * z, z), m) * std::pow(z, 4);
}

// The unfiltered slope distributions, from the textbook (independent of the code under test).
double base_p22(MicrofacetModel model, double alpha, double sx, double sy) {
    const double a2 = alpha * alpha, r2 = (sx * sx + sy * sy) / a2;
    if (model == MicrofacetModel::beckmann) return std::exp(-r2) / (kPi * a2);
    return 1 / (kPi * a2 * (1 + r2) * (1 + r2));
}

// (P22 ∗ N(0, K_b))(s) by the trapezoid rule over t ∈ ±7 marginal standard deviations (the
// Gaussian beyond is < 1e-11) with a step of a third of the smaller of α and √λ_min(K_b): the
// integrand is smooth on that scale, and the trapezoid rule converges exponentially (GGX's
// spectrum decays as e^{−α|k|}: ~1e-8 at this step).
double convolved_p22(MicrofacetModel model, double alpha, const Sym2& k, double sx, double sy) {
    const double det = double(k.xx) * k.yy - double(k.xy) * k.xy;
    const double step = std::min(alpha, double(make_footprint_ellipse(k).minor_radius)) / 3;
    const int nx = int(std::ceil(7 * std::sqrt(double(k.xx)) / step));
    const int ny = int(std::ceil(7 * std::sqrt(double(k.yy)) / step));
    double sum = 0;
    for (int i = -nx; i <= nx; ++i) {
        const double tx = i * step;
        for (int j = -ny; j <= ny; ++j) {
            const double ty = j * step;
            const double q = (k.yy * tx * tx - 2 * k.xy * tx * ty + k.xx * ty * ty) / det;
            sum += std::exp(-0.5 * q) * base_p22(model, alpha, sx - tx, sy - ty);
        }
    }
    return sum * step * step / (2 * kPi * std::sqrt(det));
}

struct ConvolutionCase {
    float alpha;
    Sym2 k_b;
};

// The largest |widened − convolved| over slopes along three azimuths out to 3 lobe widths,
// relative to the convolved peak.
double worst_deviation(MicrofacetModel model, const ConvolutionCase& c) {
    const Sym2 m = microfacet_roughness_matrix(c.alpha, c.k_b);
    const double peak = convolved_p22(model, c.alpha, c.k_b, 0, 0);
    const double width = make_footprint_ellipse(m).major_radius;
    double worst = 0;
    worst = std::fabs(widened_p22(model, m, 0, 0) - peak) / peak;
    for (const double phi : {0.0, 1.0, 2.0}) {
        for (const double r : {0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0}) {
            const double sx = r * width * std::cos(phi), sy = r * width * std::sin(phi);
            const double truth = convolved_p22(model, c.alpha, c.k_b, sx, sy);
            worst = std::max(worst, std::fabs(widened_p22(model, m, sx, sy) - truth) / peak);
        }
    }
    return worst;
}

// Beckmann: the slopes are Gaussian, Σ = α²/2 I, and Σ + K_b is the exact convolution [OB10].
TEST(Microfacet, BeckmannWidenedIsTheConvolutionWithTheSlopes) {
    const ConvolutionCase cases[] = {
        {0.2f, {0.004f, 0, 0.004f}},
        {0.1f, make_footprint_ellipse(0.15f, 0.04f, 0.5f).matrix},
        {0.3f, {0.02f, -0.012f, 0.03f}},
    };
    for (const ConvolutionCase& c : cases) {
        const double worst = worst_deviation(MicrofacetModel::beckmann, c);
        EXPECT_LT(worst, kBeckmannConvolution) << c.alpha;
    }
}

// GGX: the moment match against the true convolution (the figures of microfacet.h).
TEST(Microfacet, GgxWidenedIsCloseToTheConvolutionWithTheSlopes) {
    const ConvolutionCase cases[] = {
        {0.1f, {0.00125f, 0, 0.00125f}},                            // σ²/α² = 0.125
        {0.2f, {0.028f, 0, 0.028f}},                                // 0.7: the worst
        {0.05f, {0.02f, 0, 0.02f}},                                 // 8: GGX's tails
        {0.2f, make_footprint_ellipse(0.28f, 0.1f, 0.5f).matrix},   // σ²/α² = 2 and 0.25
        {0.3f, make_footprint_ellipse(0.2f, 0.08f, -1.1f).matrix},  // 0.44 and 0.07
    };
    for (const ConvolutionCase& c : cases) {
        const double worst = worst_deviation(MicrofacetModel::ggx, c);
        std::printf(
            "[GGX moment match] alpha %.2f, K_b = (%g, %g, %g): worst deviation %.1f %% of "
            "the peak\n",
            c.alpha, c.k_b.xx, c.k_b.xy, c.k_b.yy, 100 * worst);
        EXPECT_LT(worst, kGgxMomentMatch) << c.alpha;
    }
}

// The directional albedo ∫ f_r cos_l dω_l with F = 1 is at most 1 (energy conservation), and close
// to 1 for a narrow lobe away from grazing. Single scattering loses energy: G2 < 1, and (GGX's long
// tails) facets that reflect below the horizon — GGX facing the light keeps 88 % at α = 0.3, 59 %
// at α = 0.6 and 31 % at α = 1 (Beckmann: 99.97 %, 86 %, 46 %). Integrated over ĥ:
// dω_l = 4 (v̂·ĥ) dω_h, l̂ = 2(v̂·ĥ)ĥ − v̂.
double albedo(MicrofacetModel model, float alpha, const Sym2& k_b, double theta_v) {
    const Array3 n{0, 0, 1}, e1{1, 0, 0}, e2{0, 1, 0};
    const double vx = std::sin(theta_v), vz = std::cos(theta_v);
    const Array3 v = to_array(vx, 0, vz);
    const Sym2 m = microfacet_roughness_matrix(alpha, k_b);
    return hemisphere_integral(slope_scale(m), 160, 96, [&](double x, double y, double z) {
        const double cos_vh = vx * x + vz * z;
        if (cos_vh <= 0) return 0.0;
        const Array3 l = to_array(2 * cos_vh * x - vx, 2 * cos_vh * y, 2 * cos_vh * z - vz);
        return microfacet_highlight(model, n, e1, e2, l, v, k_b, alpha, 1) * 4 * cos_vh;
    });
}

TEST(Microfacet, DirectionalAlbedoIsAtMostOne) {
    for (const MicrofacetModel model : {MicrofacetModel::beckmann, MicrofacetModel::ggx}) {
        std::printf("albedo facing the light, %-8s:",
                    model == MicrofacetModel::ggx ? "GGX" : "Beckmann");
        for (const float alpha : {0.1f, 0.3f, 0.6f, 1.0f}) {
            for (const double theta_v : {0.0, 0.8, 1.4}) {
                const double a = albedo(model, alpha, {}, theta_v);
                if (theta_v == 0) std::printf("  alpha %.1f %.4f", alpha, a);
                EXPECT_LE(a, 1 + kAlbedoQuadrature) << alpha << " " << theta_v;
                EXPECT_GT(a, 0.25) << alpha << " " << theta_v;
                if (alpha <= 0.1f && theta_v < 1) {
                    EXPECT_GT(a, 0.98) << alpha << " " << theta_v;
                }
            }
            // Widened by the slopes: still ≤ 1.
            const double widened = albedo(model, alpha, {0.01f, 0.004f, 0.02f}, 0.8);
            EXPECT_LE(widened, 1 + kAlbedoQuadrature) << alpha;
        }
        std::printf("\n");
    }
}

// A unit vector from two uniforms, in the upper hemisphere of z.
Array3 random_upper(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    const double z = 0.02 + 0.98 * u(rng), phi = 2 * kPi * u(rng), s = std::sqrt(1 - z * z);
    return to_array(s * std::cos(phi), s * std::sin(phi), z);
}

TEST(Microfacet, ReciprocalAndRotationInvariant) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1);
    const Array3 n{0, 0, 1}, e1{1, 0, 0}, e2{0, 1, 0};
    for (int i = 0; i < 2000; ++i) {
        const MicrofacetModel model = i % 2 ? MicrofacetModel::ggx : MicrofacetModel::beckmann;
        const Array3 l = random_upper(rng), v = random_upper(rng);
        const Sym2 k = make_footprint_ellipse(0.2f * u(rng), 0.1f * u(rng), 3 * u(rng)).matrix;
        const float alpha = 0.05f + 0.95f * u(rng), f0 = u(rng);
        // f_r(l̂, v̂) = f_r(v̂, l̂): highlight(l̂, v̂)·cos_v = highlight(v̂, l̂)·cos_l = D G2 F / 4.
        const double lv = double(microfacet_highlight(model, n, e1, e2, l, v, k, alpha, f0)) * v[2];
        const double vl = double(microfacet_highlight(model, n, e1, e2, v, l, k, alpha, f0)) * l[2];
        EXPECT_NEAR(lv, vl, kFloatRel * std::max(lv, vl) + kDenormal);
        // The frame turned by β in the tangent plane, and K_b with it: the same highlight.
        const float beta = 6 * u(rng), c = std::cos(beta), s = std::sin(beta);
        const Array3 f1{c, s, 0}, f2{-s, c, 0};
        // K in the new frame: Rᵀ K R, R's columns the new axes in the old frame.
        const Sym2 k_turned{k.xx * c * c + 2 * k.xy * c * s + k.yy * s * s,
                            (k.yy - k.xx) * c * s + k.xy * (c * c - s * s),
                            k.xx * s * s - 2 * k.xy * c * s + k.yy * c * c};
        const double turned =
            double(microfacet_highlight(model, n, f1, f2, l, v, k_turned, alpha, f0)) * v[2];
        EXPECT_NEAR(turned, lv, kTurnedFrame * std::max(lv, turned) + kDenormal) << i;
    }
}

TEST(Microfacet, DegenerateInput) {
    const Array3 n{0, 0, 1}, e1{1, 0, 0}, e2{0, 1, 0};
    const Array3 up{0.6f, 0, 0.8f}, other{-0.6f, 0, 0.8f}, below{0.6f, 0, -0.8f};
    const Array3 horizon{1, 0, 0};
    for (const MicrofacetModel model : {MicrofacetModel::beckmann, MicrofacetModel::ggx}) {
        // l̂ or v̂ at or below the horizon: no highlight.
        EXPECT_EQ(microfacet_highlight(model, n, e1, e2, below, up, {}, 0.3f, 1), 0);
        EXPECT_EQ(microfacet_highlight(model, n, e1, e2, up, below, {}, 0.3f, 1), 0);
        EXPECT_EQ(microfacet_highlight(model, n, e1, e2, horizon, up, {}, 0.3f, 1), 0);
        // α clamped: 0 and NaN act as the minimum, 7 as 1.
        const float at_min =
            microfacet_highlight(model, n, e1, e2, other, up, {}, kMinMicrofacetAlpha, 1);
        EXPECT_EQ(microfacet_highlight(model, n, e1, e2, other, up, {}, 0, 1), at_min);
        EXPECT_EQ(microfacet_highlight(model, n, e1, e2, other, up, {}, NAN, 1), at_min);
        EXPECT_EQ(microfacet_highlight(model, n, e1, e2, other, up, {}, 7, 1),
                  microfacet_highlight(model, n, e1, e2, other, up, {}, 1, 1));
        // The peak at the smallest α is finite.
        const float peak =
            microfacet_highlight(model, n, e1, e2, other, up, {}, kMinMicrofacetAlpha, 1);
        EXPECT_TRUE(std::isfinite(peak) && peak > 1e4f) << peak;
        // K_b clamped to PSD: an indefinite one acts as its clamp, negative variances as 0.
        EXPECT_EQ(microfacet_highlight(model, n, e1, e2, other, up, {-1, 0, -1}, 0.3f, 1),
                  microfacet_highlight(model, n, e1, e2, other, up, {}, 0.3f, 1));
        EXPECT_EQ(
            microfacet_highlight(model, n, e1, e2, other, up, {0.01f, 0.5f, 0.04f}, 0.3f, 1),
            microfacet_highlight(model, n, e1, e2, other, up, {0.01f, 0.02f, 0.04f}, 0.3f, 1));
        // D and Λ at or below the horizon, and along n̂.
        const Sym2 m = microfacet_roughness_matrix(0.3f, {});
        EXPECT_EQ(microfacet_distribution(model, below, m), 0);
        EXPECT_EQ(smith_lambda(model, n, m), 0);
        EXPECT_EQ(smith_masking_shadowing(model, below, up, m), 0);
        EXPECT_EQ(microfacet_distribution(model, up, Sym2{}), 0);  // M not positive definite
    }
    // Random and extreme input: finite and ≥ 0.
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-1, 1);
    auto pick = [&](float x) { return test::extreme_scale(rng, x); };
    for (int i = 0; i < 20000; ++i) {
        const MicrofacetModel model = i % 2 ? MicrofacetModel::ggx : MicrofacetModel::beckmann;
        const Sym2 k{pick(u(rng)), pick(u(rng)), pick(u(rng))};
        const Array3 l{pick(u(rng)), pick(u(rng)), pick(u(rng))};
        const Array3 v{pick(u(rng)), pick(u(rng)), pick(u(rng))};
        const float value =
            microfacet_highlight(model, n, e1, e2, l, v, k, pick(u(rng)), pick(u(rng)));
        ASSERT_TRUE(std::isfinite(value) && value >= 0)
            << value << " k " << k.xx << " " << k.xy << " " << k.yy;
    }
}

}  // namespace
}  // namespace footprint
