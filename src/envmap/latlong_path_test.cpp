// QuadraticPath: the quadratic through a lat-long line's centre and ends, and the box that
// environment_map.cpp's lines inside the map rely on (every probe within it, no edge tests).
#include "envmap/latlong_path.h"

#include <gtest/gtest.h>

#include <random>

namespace footprint {
namespace {

TEST(LatLongPath, PassesThroughTheCentreAndTheEnds) {
    const EnvCoords c{0, 0.3f, 0.6f}, a{0, 0.34f, 0.58f}, b{0, 0.27f, 0.63f};
    const QuadraticPath path = QuadraticPath::through(c, a, b);
    for (const int n : {3, 9}) {
        EXPECT_NEAR(path.position(n - 1, n).x, a.s, 1e-6f);
        EXPECT_NEAR(path.position(n - 1, n).y, a.t, 1e-6f);
        EXPECT_NEAR(path.position(0, n).x, b.s, 1e-6f);
        EXPECT_NEAR(path.position(0, n).y, b.t, 1e-6f);
        EXPECT_EQ(path.position((n - 1) / 2, n).x, c.s);
        EXPECT_EQ(path.position((n - 1) / 2, n).y, c.t);
    }
    // Across the seam the ends are unwrapped: s continues past 1 instead of jumping back.
    const QuadraticPath seam =
        QuadraticPath::through({0, 0.99f, 0.5f}, {0, 0.01f, 0.5f}, {0, 0.97f, 0.5f});
    EXPECT_NEAR(seam.position(4, 5).x, 1.01f, 1e-6f);
}

// bounds() holds every probe of any count (to float rounding, far below line_inside()'s margin of
// 1/64 texel), and is tight: each of its sides is reached by p(u) for some u ∈ [−1, 1] — curved
// paths whose vertex lies inside (the box is then larger than the ends' box) included.
TEST(LatLongPath, BoundsHoldEveryProbeAndAreTight) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> centre(0.1f, 0.9f), offset(-0.02f, 0.02f);
    int curved = 0;
    for (int k = 0; k < 2000; ++k) {
        const EnvCoords c{0, centre(rng), centre(rng)};
        const EnvCoords a{0, c.s + offset(rng), c.t + offset(rng)};
        const EnvCoords b{0, c.s + offset(rng), c.t + offset(rng)};
        const QuadraticPath path = QuadraticPath::through(c, a, b);
        const auto [lower, upper] = path.bounds();
        Vec2 seen_lower{1e9f, 1e9f}, seen_upper{-1e9f, -1e9f};
        for (const int n : {3, 4, 7, 32, 1024}) {
            for (int i = 0; i < n; ++i) {
                const Vec2 p = path.position(i, n);
                ASSERT_GE(p.x, lower.x - 1e-6f) << "path " << k << " probe " << i << " of " << n;
                ASSERT_LE(p.x, upper.x + 1e-6f) << "path " << k << " probe " << i << " of " << n;
                ASSERT_GE(p.y, lower.y - 1e-6f) << "path " << k << " probe " << i << " of " << n;
                ASSERT_LE(p.y, upper.y + 1e-6f) << "path " << k << " probe " << i << " of " << n;
                seen_lower = {std::min(seen_lower.x, p.x), std::min(seen_lower.y, p.y)};
                seen_upper = {std::max(seen_upper.x, p.x), std::max(seen_upper.y, p.y)};
            }
        }
        EXPECT_NEAR(seen_lower.x, lower.x, 1e-5f);
        EXPECT_NEAR(seen_lower.y, lower.y, 1e-5f);
        EXPECT_NEAR(seen_upper.x, upper.x, 1e-5f);
        EXPECT_NEAR(seen_upper.y, upper.y, 1e-5f);
        const Vec2 ends_lower{std::min(a.s, b.s), std::min(a.t, b.t)};
        const Vec2 ends_upper{std::max(a.s, b.s), std::max(a.t, b.t)};
        if (lower.x < ends_lower.x - 1e-4f || lower.y < ends_lower.y - 1e-4f ||
            upper.x > ends_upper.x + 1e-4f || upper.y > ends_upper.y + 1e-4f)
            ++curved;
    }
    EXPECT_GT(curved, 200);  // the vertex case is exercised
}

}  // namespace
}  // namespace footprint
