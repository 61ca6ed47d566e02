// Tests of parallax-occlusion mapping (texture/parallax.h): the march against a brute-force
// ray–height-field intersection, and the displaced coordinates' derivatives against finite
// differences.
#include <footprint/texture/parallax.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace footprint {
namespace {

constexpr float kTwoPi = 2 * std::numbers::pi_v<float>;

// A smooth relief with features a few per unit of (s, t), and its exact gradient.
float relief(Vec2 st) {
    return 0.5f + 0.4f * std::sin(kTwoPi * 6 * st.x) * std::cos(kTwoPi * 4 * st.y);
}
Vec2 relief_gradient(Vec2 st) {
    return {0.4f * kTwoPi * 6 * std::cos(kTwoPi * 6 * st.x) * std::cos(kTwoPi * 4 * st.y),
            -0.4f * kTwoPi * 4 * std::sin(kTwoPi * 6 * st.x) * std::sin(kTwoPi * 4 * st.y)};
}

// The first crossing of z with 1 − h along the ray, by 20 000 steps and bisection.
Vec2 brute_force_crossing(Vec2 st, Vec2 shift) {
    constexpr int kSteps = 20000;
    float z_before = 0;
    for (int i = 1; i <= kSteps; ++i) {
        const float z = static_cast<float>(i) / kSteps;
        if (z - (1 - relief(st + z * shift)) < 0) {
            z_before = z;
            continue;
        }
        float lo = z_before, hi = z;
        for (int k = 0; k < 30; ++k) {
            const float mid = 0.5f * (lo + hi);
            (mid - (1 - relief(st + mid * shift)) < 0 ? lo : hi) = mid;
        }
        return st + 0.5f * (lo + hi) * shift;
    }
    return st + shift;
}

TEST(Parallax, TheMarchFindsTheBruteForceIntersection) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1), angle(0, kTwoPi);
    ParallaxOptions options;
    options.depth = 0.3f;
    options.steps = 32;
    options.max_shift = 10;
    double sum_sq = 0, flat_sq = 0;
    int far_off = 0;
    constexpr int kRays = 2000;
    for (int i = 0; i < kRays; ++i) {
        const Vec2 st{u(rng), u(rng)};
        const float a = angle(rng), tilt = 0.2f + 1.3f * u(rng);  // w up to 1.5 per unit depth
        const Vec2 w{tilt * std::cos(a), tilt * std::sin(a)};
        const ParallaxResult r = parallax_march(relief, relief_gradient, st, {}, {}, w, options);
        const Vec2 want = brute_force_crossing(st, options.depth * w);
        const Vec2 e = r.st - want;
        const double d2 = e.x * e.x + e.y * e.y;
        if (std::sqrt(d2) > 0.01) {
            ++far_off;  // a thin peak stepped over: the march meets the relief behind it
        } else {
            sum_sq += d2;
        }
        const Vec2 flat = st - want;  // no parallax at all
        flat_sq += flat.x * flat.x + flat.y * flat.y;
    }
    const double rmse = std::sqrt(sum_sq / (kRays - far_off)), flat = std::sqrt(flat_sq / kRays);
    std::printf(
        "[ parallax ] 32 steps: RMS (s, t) error %.5f where the right peak is met, %d of %d rays "
        "stepped over a peak; no parallax %.4f\n",
        rmse, far_off, kRays, flat);
    // Where the right peak is met, the error is the linear refinement's on a curved relief; a few
    // rays step over a thin peak (docs/performance.md, accuracy bounds).
    constexpr double kRmse = 6e-4, kSteppedOver = 0.01;
    EXPECT_LT(rmse, kRmse);
    EXPECT_LT(far_off, kSteppedOver * kRays);
    EXPECT_GT(flat, 10 * kRmse);
}

TEST(Parallax, FlatReliefsShiftByNothingOrTheWholeDepth) {
    ParallaxOptions options;
    options.depth = 0.2f;
    const Vec2 w{0.5f, -0.25f}, st{0.3f, 0.6f};
    auto top = [](Vec2) { return 1.0f; };
    auto bottom = [](Vec2) { return 0.0f; };
    auto none = [](Vec2) { return Vec2{0, 0}; };
    const ParallaxResult at_top = parallax_march(top, none, st, {}, {}, w, options);
    EXPECT_EQ(at_top.st.x, st.x);
    EXPECT_EQ(at_top.st.y, st.y);
    const ParallaxResult at_bottom = parallax_march(bottom, none, st, {}, {}, w, options);
    EXPECT_NEAR(at_bottom.st.x, st.x + 0.2f * w.x, 1e-6f);
    EXPECT_NEAR(at_bottom.st.y, st.y + 0.2f * w.y, 1e-6f);
    EXPECT_NEAR(at_bottom.depth_fraction, 1, 1e-6f);
}

// ∂s' against central differences of the crossing as the entry point moves (many steps, so that
// the march's own steps do not show), where the ray does not graze the relief.
TEST(Parallax, TheDisplacedDerivativesMatchFiniteDifferences) {
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(0, 1), angle(0, kTwoPi);
    ParallaxOptions options;
    options.depth = 0.05f;
    options.steps = 256;
    options.max_shift = 10;
    constexpr float h = 0.02f;  // of ∂s: 2e-4 in (s, t), above float's noise in the crossing
    int checked = 0;
    double worst = 0;
    for (int i = 0; i < 300; ++i) {
        const Vec2 st{u(rng), u(rng)};
        const float a = angle(rng);
        const Vec2 w{std::cos(a), std::sin(a)};
        const Vec2 dx{0.01f * (u(rng) - 0.5f), 0.01f * (u(rng) - 0.5f)};
        const ParallaxResult r = parallax_march(relief, relief_gradient, st, dx, {}, w, options);
        const Vec2 g = relief_gradient(r.st);
        if (1 + options.depth * (g.x * w.x + g.y * w.y) < 0.5f) continue;  // near grazing
        const Vec2 plus = brute_force_crossing(st + h * dx, options.depth * w);
        const Vec2 minus = brute_force_crossing(st - h * dx, options.depth * w);
        const Vec2 fd = (plus - minus) / (2 * h);
        const Vec2 e = r.dst_dx - fd;
        const double error =
            std::sqrt(e.x * e.x + e.y * e.y) / std::sqrt(dx.x * dx.x + dx.y * dx.y);
        if (error > 0.5) continue;  // the crossing jumped to another peak between the two
        worst = std::max(worst, error);
        ++checked;
    }
    std::printf("[ parallax ] derivatives: worst relative error %.4f over %d points\n", worst,
                checked);
    EXPECT_GT(checked, 200);
    EXPECT_LT(worst, 0.02);
}

}  // namespace
}  // namespace footprint
