#include "bump/roughness.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace footprint {
namespace {

// B Bᵀ against K, relative to tr K: float rounding of a few operations (d2 = k12/d3 and the square
// roots) on matrices whose entries span 1e−6…1e3 of the trace.
constexpr float kFactorTolerance = 2e-5f;

TEST(Roughness, FactorOfAMillionRandomCovariancesIsFiniteAndExact) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1, 1);
    std::uniform_int_distribution<int> kind(0, 3);
    for (int i = 0; i < 1000000; ++i) {
        Sym2 k;
        const float scale = std::exp2(u(rng) * 20);
        switch (kind(rng)) {
            case 0: {  // full rank: A Aᵀ
                const Vec2 a{u(rng), u(rng)}, b{u(rng), u(rng)};
                k = scale * footprint_matrix(a, b);
                break;
            }
            case 1:  // rank 1 (brushed / corrugated): v vᵀ, where the paper's d1 goes NaN ([R1z])
                k = outer(Vec2{u(rng), u(rng)}, scale);
                break;
            case 2:  // c = k22 = 0
                k = {scale * std::fabs(u(rng)), 0, 0};
                break;
            default:  // rank 1 along y only, and zero
                k = i % 2 ? Sym2{0, 0, scale * std::fabs(u(rng))} : Sym2{};
        }
        const RoughnessFactor b = roughness_factor(k);
        ASSERT_TRUE(std::isfinite(b.d1) && std::isfinite(b.d2) && std::isfinite(b.d3)) << i;
        const Sym2 r = b.covariance();
        const float tol = kFactorTolerance * std::max(k.trace(), 1e-30f);
        ASSERT_NEAR(r.xx, k.xx, tol) << i;
        ASSERT_NEAR(r.xy, k.xy, tol) << i;
        ASSERT_NEAR(r.yy, k.yy, tol) << i;
        ASSERT_GE(b.d1, 0.0f);
        ASSERT_GE(b.d3, 0.0f);
    }
}

TEST(Roughness, SpecExamples) {
    // k22 > 0: d3 = √k22, d2 = k12/d3, d1 = √(det/k22).
    const RoughnessFactor b = roughness_factor(Sym2{4, 2, 4});
    EXPECT_FLOAT_EQ(b.d3, 2);
    EXPECT_FLOAT_EQ(b.d2, 1);
    EXPECT_FLOAT_EQ(b.d1, std::sqrt(3.0f));
    // k22 = 0: B = [[√k11, 0], [0, 0]] (spec §4's table).
    const RoughnessFactor c = roughness_factor(Sym2{9, 0, 0});
    EXPECT_FLOAT_EQ(c.d1, 3);
    EXPECT_EQ(c.d2, 0);
    EXPECT_EQ(c.d3, 0);
    // NaN in, zeros out.
    const RoughnessFactor n = roughness_factor(Sym2{NAN, 0, 1});
    EXPECT_EQ(n.d1, 0);
}

TEST(Roughness, IsotropicL1BoundsEveryDirection) {
    // l1 = √λ_max, and the standard deviation √(ŝᵀKŝ) ≤ l1 in every direction ([R4]).
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> u(-1, 1);
    for (int i = 0; i < 10000; ++i) {
        const Sym2 k = footprint_matrix(Vec2{u(rng), u(rng)}, Vec2{u(rng), u(rng)});
        const float l1 = isotropic_roughness(k);
        EXPECT_NEAR(l1, make_footprint_ellipse(k).major_radius, 1e-5f);
        for (int a = 0; a < 16; ++a) {
            const float t = float(a) * 0.19635f;
            EXPECT_LE(std::sqrt(k.quadratic_form(Vec2{std::cos(t), std::sin(t)})),
                      l1 * (1 + 1e-5f) + 1e-7f);
        }
    }
}

TEST(Roughness, ClampToPsd) {
    const Sym2 psd{2, 1, 1};
    const Sym2 same = clamp_to_psd(psd);
    EXPECT_EQ(same.xx, 2);
    EXPECT_EQ(same.xy, 1);
    // [[1, 2], [2, 1]] has eigenvalues 3 and −1: keep 3 along (1, 1)/√2.
    const Sym2 c = clamp_to_psd(Sym2{1, 2, 1});
    EXPECT_NEAR(c.xx, 1.5f, 1e-6f);
    EXPECT_NEAR(c.xy, 1.5f, 1e-6f);
    EXPECT_NEAR(c.yy, 1.5f, 1e-6f);
    EXPECT_GE(clamp_to_psd(Sym2{-1e-9f, 0, 0}).xx, 0.0f);
    EXPECT_EQ(clamp_to_psd(Sym2{NAN, 0, 0}).xx, 0.0f);
}

}  // namespace
}  // namespace footprint
