#include "shading/blinn_phong.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>

#include "math/footprint_ellipse.h"
#include "shading/test_extreme_values.h"

namespace footprint {
namespace {

// Relative rounding of the float results of formulas evaluated in double (a few ulps).
constexpr float kFloatRel = 4e-6f;
// Monte Carlo variance of 200 000 samples: the standard error is sqrt(2/N) = 0.32 %; 2 % as
// check.py's [B1].
constexpr double kMonteCarloRel = 0.02;
// [B7]: the spec states 0.129 % of the peak for check.py's K_b, which this (converged) quadrature
// reproduces (0.1288 %); the other anisotropic K_b tested reach 0.141 %, hence 0.15 %.
constexpr double kConvolutionTolerance = 0.0015;
// [B6]: the comparison "a' < a" is decided by rounding where σ² is this close to 1.
constexpr double kB6Margin = 1e-4;

constexpr float kPi = 3.14159265358979f;

// Spec §5.2: the stored upper factor B = [[d1, d2], [0, d3]], B Bᵀ = K.
struct Upper {
    double d1 = 0, d2 = 0, d3 = 0;
};
Upper upper_factor(const Sym2& k) {
    if (k.yy > 1e-30f) {
        const double d3 = std::sqrt(double(k.yy));
        return {std::sqrt(std::max(0.0, double(k.xx) * k.yy - double(k.xy) * k.xy) / k.yy),
                k.xy / d3, d3};
    }
    return {std::sqrt(std::max(0.0, double(k.xx))), 0, 0};
}

// Random SPD matrix with eigenvalues in [lo, hi] (check.py's rand_spd2).
Sym2 random_spd(std::mt19937& rng, float lo, float hi) {
    std::uniform_real_distribution<float> angle(0, kPi), ev(lo, hi);
    return make_footprint_ellipse(std::sqrt(ev(rng)), std::sqrt(ev(rng)), angle(rng)).from_axes();
}

// d = sin a · (cos θ, sin θ) for a random angle a ∈ [lo, hi] and direction θ.
Vec2 random_d(std::mt19937& rng, float lo, float hi) {
    std::uniform_real_distribution<float> a(lo, hi), th(0, 2 * kPi);
    const float s = std::sin(a(rng)), t = th(rng);
    return {s * std::cos(t), s * std::sin(t)};
}

float cos2_of(Vec2 d) {
    return 1 - dot(d, d);
}

TEST(BlinnPhong, PlainLobe) {
    EXPECT_FLOAT_EQ(blinn_phong(1, 50), 1);
    EXPECT_NEAR(blinn_phong(0.9f, 20), std::pow(0.9f, 20.0f), kFloatRel);
    EXPECT_EQ(blinn_phong(0, 20), 0);
    EXPECT_EQ(blinn_phong(-0.5f, 20), 0);
    EXPECT_EQ(blinn_phong(1.0000001f, 1000), 1);  // rounding above 1 counts as 1
}

TEST(BlinnPhong, B1UsesBTransposeDNotDd) {
    // Spec §7 [B1]: K = 0.04·[[1, .8], [.8, 1]], d ∥ e1. B = [[.12, .16], [0, .2]].
    const Sym2 k{0.04f, 0.032f, 0.04f};
    const Upper b = upper_factor(k);
    EXPECT_NEAR(b.d1, 0.12, 1e-7);
    EXPECT_NEAR(b.d2, 0.16, 1e-7);
    EXPECT_NEAR(b.d3, 0.20, 1e-7);
    const Vec2 d{0.3f, 0};
    const double q = double(d.x) * d.x;
    const double bt_d_x = b.d1 * d.x, bt_d_y = b.d2 * d.x;  // Bᵀd
    const double bt2 = bt_d_x * bt_d_x + bt_d_y * bt_d_y;
    const double dd2 = (b.d1 * d.x) * (b.d1 * d.x);  // |Dd|², the paper's print (D = B)
    EXPECT_NEAR(bt2 / q, 0.0400, 1e-6);              // the variance in direction d
    EXPECT_NEAR(dd2 / q, 0.0144, 1e-6);              // what |Dd| would claim

    // The sample variance of N(0, K) along d̂ is the former.
    std::mt19937 rng(1);
    std::normal_distribution<double> normal;
    double sum = 0, sum2 = 0;
    constexpr int kSamples = 200000;
    for (int i = 0; i < kSamples; ++i) {
        const double z1 = normal(rng), z2 = normal(rng);
        const double x = b.d1 * z1 + b.d2 * z2;  // first component of B z
        sum += x;
        sum2 += x * x;
    }
    const double var = sum2 / kSamples - (sum / kSamples) * (sum / kSamples);
    EXPECT_NEAR(var / 0.04, 1.0, kMonteCarloRel);

    // modified_cos2_paper uses |Bᵀd|: cos²a' = cos²a / (|d|⁴/|Bᵀd|² + cos²a).
    const double c2 = 1 - q;
    const double corrected = c2 / (q * q / bt2 + c2);  // 0.2880
    const double printed = c2 / (q * q / dd2 + c2);    // 0.1271
    const float got = modified_cos2_paper(float(c2), d, k);
    EXPECT_NEAR(got, corrected, kFloatRel * corrected);
    EXPECT_GT(std::fabs(got - printed), 0.15);
}

TEST(BlinnPhong, B2TanScalesByDirectionalSigma) {
    // tan a' = tan a / σ(d̂), σ²(d̂) = d̂ᵀK d̂.
    std::mt19937 rng(2);
    for (int i = 0; i < 1000; ++i) {
        const Sym2 k = random_spd(rng, 1e-3f, 0.5f);
        const Vec2 d = random_d(rng, 0.01f, 1.4f);
        const double c2 = cos2_of(d);
        const double sigma2 = k.quadratic_form(d) / dot(d, d);
        const double tan_a = std::sqrt((1 - c2) / c2);
        const double c2p = modified_cos2_paper(float(c2), d, k);
        const double tan_ap = std::sqrt(1 / c2p - 1);
        EXPECT_NEAR(tan_ap, tan_a / std::sqrt(sigma2), 1e-4 * std::max(1.0, tan_ap));
    }
}

TEST(BlinnPhong, B4LimitsMeanDNotDInverse) {
    std::mt19937 rng(4);
    for (int i = 0; i < 200; ++i) {
        const Sym2 k0 = random_spd(rng, 0.05f, 3.0f);
        const Vec2 d = random_d(rng, 0.05f, 1.4f);
        const float c2 = cos2_of(d);
        // K_b → 0: mirror-sharp highlight; K_b → ∞: flat (cos a' → 1).
        EXPECT_LT(modified_cos2_paper(c2, d, 1e-12f * k0), 1e-6f);
        EXPECT_GT(modified_cos2_paper(c2, d, 1e12f * k0), 1 - 1e-6f);
        EXPECT_LT(modified_cos2_gaussian(c2, d, 1e-12f * k0), 1e-6f);
        EXPECT_GT(modified_cos2_gaussian(c2, d, 1e12f * k0), 1 - 1e-6f);
    }
    // With D⁻¹ (K⁻¹) substituted, D → 0 would give a flat highlight: the reverse limit.
    const Vec2 d{0.3f, -0.4f};
    const Sym2 tiny_inverse{1e12f, 0, 1e12f};  // K⁻¹ for K = 1e−12 I
    EXPECT_GT(modified_cos2_paper(cos2_of(d), d, tiny_inverse), 1 - 1e-6f);
}

TEST(BlinnPhong, B6AngleShrinksIffVarianceExceedsOne) {
    std::mt19937 rng(6);
    int checked = 0;
    for (int i = 0; i < 2000; ++i) {
        const Sym2 k = random_spd(rng, 0.05f, 3.0f);
        const Vec2 d = random_d(rng, 0.05f, 1.4f);
        const float c2 = cos2_of(d);
        const double sigma2 = k.quadratic_form(d) / dot(d, d);
        // The Gaussian form's analogue: a' < a iff dᵀK⁻¹d < |d|².
        const double inv_form =
            Sym2{k.yy, -k.xy, k.xx}.quadratic_form(d) / k.determinant() / dot(d, d);
        if (std::fabs(sigma2 - 1) < kB6Margin || std::fabs(inv_form - 1) < kB6Margin) continue;
        ++checked;
        EXPECT_EQ(modified_cos2_paper(c2, d, k) > c2, sigma2 > 1) << "sigma2 " << sigma2;
        EXPECT_EQ(modified_cos2_gaussian(c2, d, k) > c2, inv_form < 1) << "inv " << inv_form;
    }
    EXPECT_GT(checked, 1900);
}

TEST(BlinnPhong, B3IsotropicFormEqualsPaperForm) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> l(0.05f, 4.0f);
    for (int i = 0; i < 1000; ++i) {
        const float l1 = l(rng);
        const Vec2 d = random_d(rng, 0.01f, 1.5f);
        const float c2 = cos2_of(d);
        const Sym2 k{l1 * l1, 0, l1 * l1};
        const float iso = modified_cos2_isotropic(c2, l1);
        EXPECT_NEAR(modified_cos2_paper(c2, d, k), iso, kFloatRel * iso);
        EXPECT_NEAR(modified_cos2_gaussian(c2, d, k), iso, kFloatRel * iso);
    }
    // The spec's example: l1 = .37, a = .6.
    const float c2 = std::cos(0.6f) * std::cos(0.6f), l2 = 0.37f * 0.37f;
    EXPECT_NEAR(modified_cos2_isotropic(c2, 0.37f), l2 * c2 / (1 - c2 + l2 * c2), kFloatRel);
}

TEST(BlinnPhong, B5PaperFormIsWiderThanGaussianForm) {
    // |d|⁴/dᵀKd ≤ dᵀK⁻¹d (Cauchy–Schwarz), so the paper's cos²a' ≥ the Gaussian one; equal on
    // the principal axes and for isotropic K.
    std::mt19937 rng(5);
    for (int i = 0; i < 1000; ++i) {
        const Sym2 k = random_spd(rng, 1e-3f, 0.5f);
        const Vec2 d = random_d(rng, 0.01f, 1.5f);
        const float c2 = cos2_of(d);
        const float paper = modified_cos2_paper(c2, d, k);
        EXPECT_GE(paper, modified_cos2_gaussian(c2, d, k) * (1 - kFloatRel));
        // d along a principal axis.
        const FootprintEllipse e = make_footprint_ellipse(k);
        for (const Vec2 axis : {e.major_axis, e.minor_axis()}) {
            const Vec2 da = length(d) * axis;
            const float pa = modified_cos2_paper(c2, da, k);
            // The axes carry the float rounding of the eigen-decomposition (2e−5 relative).
            EXPECT_NEAR(modified_cos2_gaussian(c2, da, k), pa, 1e-4f * pa);
        }
    }
}

TEST(BlinnPhong, ZeroOffsetGivesCosOne) {
    const Vec2 zero{0, 0};
    for (const Sym2& k : {Sym2{}, Sym2{1e-3f, 0, 0}, Sym2{0.04f, 0.032f, 0.04f}, Sym2{1, 0, 1}}) {
        EXPECT_EQ(modified_cos2_paper(1, zero, k), 1);
        EXPECT_EQ(modified_cos2_gaussian(1, zero, k), 1);
    }
    EXPECT_EQ(modified_cos2_isotropic(1, 0), 1);
    EXPECT_EQ(modified_cos2_isotropic(1, 2), 1);
    // At the peak the energy-consistent lobe is 1/sqrt(det(I + m K_b)).
    const Sym2 kb{4e-3f, 1.5e-3f, 1.5e-3f};
    const double m = 400;
    const double det = (1 + m * kb.xx) * (1 + m * kb.yy) - m * m * kb.xy * kb.xy;
    EXPECT_NEAR(rough_blinn_phong(1, zero, kb, 400), 1 / std::sqrt(det), kFloatRel);
    EXPECT_EQ(rough_blinn_phong(1, zero, Sym2{}, 400), 1);
}

TEST(BlinnPhong, SingularRoughness) {
    const Vec2 d{0.3f, 0}, d_off{0.3f, 0.1f};
    const float c2 = cos2_of(d), c2_off = cos2_of(d_off);
    // K = 0: every direction is mirror-sharp.
    EXPECT_EQ(modified_cos2_paper(c2, d, Sym2{}), 0);
    EXPECT_EQ(modified_cos2_gaussian(c2, d, Sym2{}), 0);
    EXPECT_EQ(modified_cos2_isotropic(c2, 0), 0);
    // Rank 1, variance .04 along e1 only: on the axis paper = Gaussian = tan a / 0.2; off it the
    // Gaussian form is sharp, the paper form still sees the variance along d̂.
    const Sym2 k1{0.04f, 0, 0};
    const float expected = float(c2 / (dot(d, d) / 0.04 + c2));
    EXPECT_NEAR(modified_cos2_paper(c2, d, k1), expected, kFloatRel * expected);
    EXPECT_NEAR(modified_cos2_gaussian(c2, d, k1), expected, kFloatRel * expected);
    EXPECT_EQ(modified_cos2_gaussian(c2_off, d_off, k1), 0);
    EXPECT_GT(modified_cos2_paper(c2_off, d_off, k1), 0);
    EXPECT_EQ(modified_cos2_paper(c2, Vec2{0, 0.3f}, k1), 0);
    // A rotated rank-1 K (rounding makes it slightly definite or indefinite): finite, in [0, 1].
    const Sym2 k_rot = outer(Vec2{0.6f, 0.8f}, 0.04f);
    const float g = modified_cos2_gaussian(c2, 0.3f * Vec2{0.6f, 0.8f}, k_rot);
    EXPECT_TRUE(g >= 0 && g <= 1);
    // The recommended form is never singular: I + m K_b has eigenvalues ≥ 1.
    const float r = rough_blinn_phong(std::sqrt(c2_off), d_off, k1, 400);
    EXPECT_GT(r, 0);
    EXPECT_LE(r, 1);
}

// The plain lobe as a function of the slope u of ĥ: (cos a)^m = (1 + |u|²)^{−m/2}.
double slope_lobe(double ux, double uy, double m) {
    return std::exp(-0.5 * m * std::log1p(ux * ux + uy * uy));
}

// (lobe ∗ N(0, K_b))(s) = E[lobe(s − t)], t = B z, z ~ N(0, I) — the set-up of check.py's [B7]
// (small-slope regime: slopes add). Trapezoid rule in z over [−8, 8]² (the Gaussian tail beyond
// is < 1e−14); the integrand is smooth on a scale ≳ 0.3 in z, so a step of 0.05 is exact to
// far below the tolerance.
double convolved_lobe(double sx, double sy, const Upper& b, double m) {
    constexpr double kStep = 0.05, kRange = 8;
    const int n = int(std::lround(kRange / kStep));
    double sum = 0;
    for (int i = -n; i <= n; ++i) {
        const double z1 = i * kStep;
        for (int j = -n; j <= n; ++j) {
            const double z2 = j * kStep;
            const double w = std::exp(-0.5 * (z1 * z1 + z2 * z2));
            // t = B z with B = [[d1, d2], [0, d3]].
            sum += w * slope_lobe(sx - (b.d1 * z1 + b.d2 * z2), sy - b.d3 * z2, m);
        }
    }
    return sum * kStep * kStep / (2 * M_PI);
}

TEST(BlinnPhong, B7RoughLobeIsConvolutionWithSlopeDistribution) {
    constexpr float m = 400;
    const Sym2 kbs[] = {
        {4e-3f, 1.5e-3f, 1.5e-3f},  // check.py's
        {1e-3f, -6e-4f, 5e-3f},
        make_footprint_ellipse(0.08f, 0.015f, 0.5f).matrix,  // strongly anisotropic, rotated
    };
    const std::array<float, 2> slopes[] = {{0, 0},         {0.05f, 0},      {0, 0.04f},
                                           {0.06f, 0.05f}, {-0.08f, 0.03f}, {0.12f, -0.02f}};
    for (const Sym2& kb : kbs) {
        const Upper b = upper_factor(kb);
        const double peak = convolved_lobe(0, 0, b, m);
        double worst = 0;
        for (const auto& s : slopes) {
            // ĥ with slope s relative to n̂: cos²a = 1/(1 + |s|²), d = s cos a (|d| = sin a).
            const double c = 1 / std::sqrt(1 + double(s[0]) * s[0] + double(s[1]) * s[1]);
            const Vec2 d{float(s[0] * c), float(s[1] * c)};
            const double predicted = rough_blinn_phong(float(c), d, kb, m);
            const double truth = convolved_lobe(s[0], s[1], b, m);
            worst = std::max(worst, std::fabs(predicted - truth) / peak);
            EXPECT_NEAR(predicted, truth, kConvolutionTolerance * peak)
                << "K_b " << kb.xx << " " << kb.xy << " " << kb.yy << " s " << s[0] << " " << s[1];
        }
        std::printf("[B7] K_b = (%g, %g, %g): worst deviation %.4f %% of the peak\n", kb.xx, kb.xy,
                    kb.yy, 100 * worst);
    }
}

TEST(BlinnPhong, DispatcherAgreesWithPlainLobeForSmoothSurface) {
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(-1, 1);
    const std::array<float, 3> n{0, 0, 1}, e1{1, 0, 0}, e2{0, 1, 0};
    for (int i = 0; i < 500; ++i) {
        std::array<float, 3> h{u(rng), u(rng), u(rng) + 1.2f};
        const float len = std::hypot(h[0], h[1], h[2]);
        for (float& x : h) x /= len;
        const float plain = specular(RoughShadingModel::plain, n, e1, e2, h, Sym2{}, 60);
        EXPECT_NEAR(plain, blinn_phong(h[2], 60), kFloatRel);
        for (const RoughShadingModel model :
             {RoughShadingModel::paper, RoughShadingModel::isotropic,
              RoughShadingModel::gaussian}) {
            // |d|² + cos²a = 1 holds to float rounding, amplified m/2 = 30 times by the power.
            EXPECT_NEAR(specular(model, n, e1, e2, h, Sym2{}, 60), plain, 1e-5f);
        }
        // For isotropic K_b the three rough models coincide.
        const Sym2 iso{2e-3f, 0, 2e-3f};
        const float g = specular(RoughShadingModel::gaussian, n, e1, e2, h, iso, 60);
        EXPECT_NEAR(specular(RoughShadingModel::paper, n, e1, e2, h, iso, 60), g, 1e-5f);
        EXPECT_NEAR(specular(RoughShadingModel::isotropic, n, e1, e2, h, iso, 60), g, 1e-5f);
        const HalfVectorGeometry geo = half_vector_geometry(n, e1, e2, h);
        const Sym2 aniso{4e-3f, 1.5e-3f, 1.5e-3f};
        EXPECT_EQ(specular(RoughShadingModel::gaussian, n, e1, e2, h, aniso, 60),
                  rough_blinn_phong(geo.cos_a, geo.d, aniso, 60));
    }
    // ĥ below the horizon: no highlight.
    const std::array<float, 3> below{0.6f, 0, -0.8f};
    for (const RoughShadingModel model :
         {RoughShadingModel::plain, RoughShadingModel::paper, RoughShadingModel::isotropic,
          RoughShadingModel::gaussian}) {
        EXPECT_EQ(specular(model, n, e1, e2, below, Sym2{0.1f, 0, 0.1f}, 60), 0);
    }
}

TEST(BlinnPhong, HalfVectorGeometry) {
    // d = −(ĥ·e1, ĥ·e2), the tangential part of n̂ − ĥ.
    const std::array<float, 3> n{0, 0, 1}, e1{1, 0, 0}, e2{0, 1, 0}, h{0.6f, 0, 0.8f};
    const HalfVectorGeometry g = half_vector_geometry(n, e1, e2, h);
    EXPECT_FLOAT_EQ(g.cos_a, 0.8f);
    EXPECT_FLOAT_EQ(g.d.x, -0.6f);
    EXPECT_FLOAT_EQ(g.d.y, 0);
}

TEST(BlinnPhong, NaNFreeOnRandomAndDegenerateInput) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-1, 1);
    auto pick = [&](float x) { return test::extreme_scale(rng, x); };
    for (int i = 0; i < 100000; ++i) {
        Sym2 k;
        switch (rng() % 5) {
            case 0:
                k = Sym2{};
                break;
            case 1:
                k = outer(Vec2{u(rng), u(rng)}, std::fabs(pick(u(rng))));
                break;  // rank 1
            case 2:
                k = Sym2{pick(u(rng)), pick(u(rng)), pick(u(rng))};
                break;  // even indefinite
            case 3:
                k = Sym2{std::fabs(pick(1)), 0, 0};
                break;
            default:
                k = random_spd(rng, 0, 2);
                break;
        }
        const Vec2 d{pick(u(rng)), pick(u(rng))};
        const float c2 = pick(u(rng)) + 0.5f;  // also outside [0, 1]
        const float m = std::fabs(pick(1000 * u(rng)));
        const float values[] = {
            modified_cos2_paper(c2, d, k),
            modified_cos2_gaussian(c2, d, k),
            modified_cos2_isotropic(c2, pick(u(rng))),
            rough_blinn_phong(c2, d, k, m),
            blinn_phong(c2, m),
        };
        for (const float v : values) {
            ASSERT_TRUE(v >= 0 && v <= 1) << v << " k " << k.xx << " " << k.xy << " " << k.yy
                                          << " d " << d.x << " " << d.y << " c2 " << c2;
        }
        std::array<float, 3> h{u(rng), u(rng), u(rng)};
        const std::array<float, 3> n{0, 0, 1}, e1{1, 0, 0}, e2{0, 1, 0};
        if (rng() % 8 == 0) h = n;
        for (const RoughShadingModel model :
             {RoughShadingModel::plain, RoughShadingModel::paper, RoughShadingModel::isotropic,
              RoughShadingModel::gaussian}) {
            const float v = specular(model, n, e1, e2, h, k, m);
            ASSERT_TRUE(std::isfinite(v) && v >= 0) << v;
        }
    }
}

}  // namespace
}  // namespace footprint
