// Tests of shading/fresnel.h against brute force: Monte Carlo over Gaussian slopes.
#include "shading/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace footprint {
namespace {

// E[F·(c ≥ 0)], P(c < 0), and the mean slope − b̄ and covariance of the slopes facing the eye
// weighted by F, by Monte Carlo: b − b̄ ~ N(0, K) with K = L Lᵀ, c = c̄ + uᵀ(b − b̄).
FresnelOverSlopes brute_force(float f0, float c_mean, Vec2 u, const Sym2& k, int n) {
    std::mt19937 rng(7);
    std::normal_distribution<double> normal;
    const double l11 = std::sqrt(k.xx), l21 = k.xy / l11, l22 = std::sqrt(k.yy - l21 * l21);
    double f = 0, fx = 0, fy = 0, fxx = 0, fxy = 0, fyy = 0;
    int away = 0;
    for (int i = 0; i < n; ++i) {
        const double a = normal(rng), b = normal(rng);
        const double x = l11 * a, y = l21 * a + l22 * b;
        const double c = c_mean + u.x * x + u.y * y;
        if (c < 0) {
            ++away;
            continue;
        }
        const double w = schlick_fresnel(f0, static_cast<float>(c));
        f += w, fx += w * x, fy += w * y, fxx += w * x * x, fxy += w * x * y, fyy += w * y * y;
    }
    FresnelOverSlopes out;
    out.mean = static_cast<float>(f / n);
    out.facing_away = static_cast<float>(away) / static_cast<float>(n);
    const double mx = fx / f, my = fy / f;
    out.mean_slope_shift = {static_cast<float>(mx), static_cast<float>(my)};
    out.covariance = {static_cast<float>(fxx / f - mx * mx), static_cast<float>(fxy / f - mx * my),
                      static_cast<float>(fyy / f - my * my)};
    return out;
}

// Monte Carlo with 10⁶ samples: its own error is ~1e-3 of the quantities' scale.
constexpr float kMonteCarlo = 2e-3f;

TEST(FresnelOverSlopes, MatchesMonteCarloAtAGrazingAngle) {
    // cos θ = 0.15, slopes of σ ≈ 0.05 along the plane of incidence: c stays within [0, 1].
    const Sym2 k{0.0025f, 0.0006f, 0.0016f};
    const Vec2 u{0.95f, 0.1f};
    const FresnelOverSlopes exact = fresnel_over_slopes(0.04f, 0.15f, u, k);
    const FresnelOverSlopes mc = brute_force(0.04f, 0.15f, u, k, 1000000);
    EXPECT_NEAR(exact.mean, mc.mean, kMonteCarlo * mc.mean);
    EXPECT_NEAR(exact.mean_slope_shift.x, mc.mean_slope_shift.x, kMonteCarlo * 0.05f);
    EXPECT_NEAR(exact.mean_slope_shift.y, mc.mean_slope_shift.y, kMonteCarlo * 0.05f);
    EXPECT_NEAR(exact.covariance.xx, mc.covariance.xx, kMonteCarlo * k.xx);
    EXPECT_NEAR(exact.covariance.xy, mc.covariance.xy, kMonteCarlo * k.xx);
    EXPECT_NEAR(exact.covariance.yy, mc.covariance.yy, kMonteCarlo * k.yy);
    // Fresnel falls as cos θ grows: the weighted slopes lean towards smaller c (against K u), and
    // the mean F exceeds F of the mean (F is convex in c).
    EXPECT_LT(exact.mean_slope_shift.x, -0.1f * 0.05f);
    EXPECT_GT(exact.mean, schlick_fresnel(0.04f, 0.15f) * 1.01f);
    EXPECT_LT(exact.covariance.xx, k.xx);
}

TEST(FresnelOverSlopes, MatchesMonteCarloWhereSlopesFaceAway) {
    // σ_c = 0.2 at cos θ = 0.1: a third of the slopes face away from the eye (left out, counted).
    const Sym2 k{0.04f, 0, 0.01f};
    const Vec2 u{1, 0};
    const FresnelOverSlopes exact = fresnel_over_slopes(0.04f, 0.1f, u, k);
    const FresnelOverSlopes mc = brute_force(0.04f, 0.1f, u, k, 1000000);
    EXPECT_NEAR(exact.mean, mc.mean, kMonteCarlo * mc.mean);
    EXPECT_NEAR(exact.facing_away, mc.facing_away, kMonteCarlo * mc.facing_away);
    EXPECT_NEAR(exact.facing_away, 0.3085f, 1e-4f);  // Φ(−0.1/0.2)
    EXPECT_NEAR(exact.mean_slope_shift.x, mc.mean_slope_shift.x, kMonteCarlo * 0.2f);
    EXPECT_NEAR(exact.covariance.xx, mc.covariance.xx, kMonteCarlo * k.xx);
    EXPECT_NEAR(exact.covariance.yy, k.yy, 1e-7f);  // nothing across the plane of incidence
}

TEST(FresnelOverSlopes, WithoutSpreadItIsFresnelOfTheMean) {
    const FresnelOverSlopes flat = fresnel_over_slopes(0.5f, 0.3f, {1, 0}, Sym2{});
    EXPECT_EQ(flat.mean, schlick_fresnel(0.5f, 0.3f));
    EXPECT_EQ(flat.mean_slope_shift.x, 0);
    EXPECT_EQ(flat.mean_slope_shift.y, 0);
    const Sym2 k{0.01f, 0, 0.01f};
    const FresnelOverSlopes facing = fresnel_over_slopes(0.5f, 0.3f, {0, 0}, k);
    EXPECT_EQ(facing.mean, schlick_fresnel(0.5f, 0.3f));
    EXPECT_EQ(facing.covariance.xx, k.xx);
    EXPECT_EQ(facing.facing_away, 0);
}

TEST(FresnelOverSlopes, APerfectMirrorWeighsOnlyWhichSlopesFaceTheEye) {
    // F0 = 1: F = 1 everywhere, so the weighted slopes are the ones facing the eye, a Gaussian
    // truncated at c = 0, z0 = −c̄/σ_c = −2: E[z | z ≥ z0] = φ(z0)/(1 − Φ(z0)).
    const Sym2 k{0.01f, 0, 0.01f};
    const FresnelOverSlopes perfect = fresnel_over_slopes(1.0f, 0.2f, {1, 0}, k);
    const double phi = std::exp(-2.0) / std::sqrt(2 * 3.141592653589793);
    const double front = 1 - 0.5 * std::erfc(2 / std::sqrt(2.0));
    EXPECT_NEAR(perfect.facing_away, 1 - front, 1e-6);
    EXPECT_NEAR(perfect.mean, front, 1e-6);
    EXPECT_NEAR(perfect.mean_slope_shift.x, k.xx * (phi / front) / 0.1, 1e-6);
    EXPECT_NEAR(perfect.mean_slope_shift.y, 0, 1e-9);
    EXPECT_NEAR(perfect.covariance.yy, k.yy, 1e-9);
}

// One call gives every F0's mean: a metal's three channels (F is linear in F0). Checked against a
// call per F0, at a grazing angle with a third of the slopes facing away, and without spread.
TEST(FresnelOverSlopes, OneCallGivesTheMeanOfEveryF0) {
    const Sym2 k{0.04f, 0.005f, 0.01f};
    for (const auto& [cos_mean, u] :
         {std::pair{0.1f, Vec2{1, 0.2f}}, std::pair{0.6f, Vec2{0.5f, 0}},
          std::pair{0.3f, Vec2{0, 0}}}) {
        const FresnelOverSlopes any = fresnel_over_slopes(0.3f, cos_mean, u, k);
        for (float f0 : {0.0f, 0.04f, 0.56f, 0.95f, 1.0f}) {
            const float own = fresnel_over_slopes(f0, cos_mean, u, k).mean;
            EXPECT_NEAR(mean_fresnel(any, f0), own, 1e-6f) << cos_mean << " " << f0;
        }
        EXPECT_GT(any.schlick, 0.0f);
    }
}

}  // namespace
}  // namespace footprint
