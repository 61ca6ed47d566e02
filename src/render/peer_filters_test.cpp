// Tests of the peers' own steps (render/peer_filters.h) against closed forms and brute force.
#include "render/peer_filters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace footprint::detail {
namespace {

// Float rounding of a handful of operations.
constexpr float kRounding = 1e-6f;

// The mean of the unit normals of slopes b_i, as a pyramid's filter averages them.
Vec3 mean_unit_normal(const std::vector<Vec2>& slopes) {
    Image map(static_cast<int>(slopes.size()), 1, 2);
    for (std::size_t i = 0; i < slopes.size(); ++i) {
        map.at(static_cast<int>(i), 0, 0) = slopes[i].x;
        map.at(static_cast<int>(i), 0, 1) = slopes[i].y;
    }
    const Image normals = unit_normals(map, 1);
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < normals.width; ++i) {
        for (int c = 0; c < 3; ++c) sum[c] += normals.at(i, 0, c);
    }
    const double n = normals.width;
    return {static_cast<float>(sum[0] / n), static_cast<float>(sum[1] / n),
            static_cast<float>(sum[2] / n)};
}

TEST(PeerFilters, ToksvigOfTwoOpposedSlopesIsItsClosedForm) {
    // Slopes ±t along x: n̄ = (0, 0, 1/√(1 + t²)), so σ² = √(1 + t²) − 1 (not t²: Toksvig's
    // variance underestimates wide spreads) and b̄ = 0.
    const float t = 0.5f;
    const SlopeStatistics s = toksvig_slopes(mean_unit_normal({{t, 0}, {-t, 0}}));
    EXPECT_NEAR(s.covariance.xx, std::sqrt(1 + t * t) - 1, kRounding);
    EXPECT_NEAR(s.covariance.yy, s.covariance.xx, kRounding);
    EXPECT_EQ(s.covariance.xy, 0);
    EXPECT_NEAR(s.mean.x, 0, kRounding);
    EXPECT_NEAR(s.mean.y, 0, kRounding);
}

TEST(PeerFilters, ToksvigRecoversAGaussianOfSmallSpread) {
    // Slopes μ + N(0, σ² I) on a grid of Gaussian quantiles. Toksvig measures the normals'
    // angular spread: a slope change along μ turns the unit normal by 1/(1 + |μ|²) of it, one
    // across μ by 1/√(1 + |μ|²), so for small σ, σ²_Toksvig = σ² ½(1/(1 + |μ|²)² + 1/(1 + |μ|²))
    // − O(σ⁴) (−2σ⁴ for μ = 0), and b̄ = μ up to O(σ²): within 5 % and 3 % at σ = 0.1.
    constexpr float kVarianceTolerance = 0.05f, kMeanTolerance = 0.03f;
    const float sigma = 0.1f;
    const Vec2 mu{0.3f, -0.2f};
    std::vector<Vec2> slopes;
    constexpr int m = 64;
    for (int i = 0; i < m; ++i) {
        for (int j = 0; j < m; ++j) {
            const float zi = static_cast<float>(inverse_normal_cdf((i + 0.5) / m));
            const float zj = static_cast<float>(inverse_normal_cdf((j + 0.5) / m));
            slopes.push_back(mu + sigma * Vec2{zi, zj});
        }
    }
    const SlopeStatistics s = toksvig_slopes(mean_unit_normal(slopes));
    const float tilt = 1 + mu.x * mu.x + mu.y * mu.y;
    const float expected = sigma * sigma * 0.5f * (1 / (tilt * tilt) + 1 / tilt);
    EXPECT_NEAR(s.covariance.xx, expected, kVarianceTolerance * expected);
    EXPECT_NEAR(s.mean.x, mu.x, kMeanTolerance * std::abs(mu.x));
    EXPECT_NEAR(s.mean.y, mu.y, kMeanTolerance * std::abs(mu.y));
}

TEST(PeerFilters, ToksvigOfCancellingNormalsIsFiniteAndRough) {
    const SlopeStatistics s = toksvig_slopes({0, 0, 0});
    EXPECT_TRUE(s.covariance.is_finite());
    EXPECT_GT(s.covariance.xx, 100.0f);
    EXPECT_EQ(s.mean.x, 0);
}

TEST(PeerFilters, ScreenSpaceRoughnessIsAQuarterOfTheSlopeChange) {
    // ¼(δx δxᵀ + δy δyᵀ), the covariance of a linear slope ramp under the σ = ½-pixel filter.
    const Sym2 k = screen_space_roughness({0.2f, 0.1f}, {-0.05f, 0.3f});
    EXPECT_NEAR(k.xx, 0.25f * (0.04f + 0.0025f), kRounding);
    EXPECT_NEAR(k.xy, 0.25f * (0.02f - 0.015f), kRounding);
    EXPECT_NEAR(k.yy, 0.25f * (0.01f + 0.09f), kRounding);
}

TEST(PeerFilters, ScreenSpaceRoughnessIsClampedAndStaysPositiveSemiDefinite) {
    constexpr float limit = ScreenSpaceRoughness::kMaxVariance;
    const Sym2 k = screen_space_roughness({1, 1}, {0, 0});  // rank 1, both variances 0.25
    EXPECT_NEAR(k.xx, limit, kRounding);
    EXPECT_NEAR(k.yy, limit, kRounding);
    EXPECT_NEAR(k.xy, limit, kRounding);  // the correlation 1 kept
    EXPECT_GE(k.determinant(), -kRounding);
    const Sym2 one_axis = screen_space_roughness({2, 0}, {0, 0.2f});
    EXPECT_NEAR(one_axis.xx, limit, kRounding);
    EXPECT_NEAR(one_axis.yy, 0.01f, kRounding);
    const Sym2 bad = screen_space_roughness({NAN, 0}, {0, 0});
    EXPECT_TRUE(bad.is_finite());
}

// A rotated anisotropic footprint: axes of 2·8 and 2·2 level-0 texels (σ = 8 and 2 under the
// pixel filter) at 30°, on a 256 × 128 texture.
constexpr int kWidth = 256, kHeight = 128;
TextureCoords rotated_footprint(float sigma_major, float sigma_minor) {
    const float c = std::cos(std::numbers::pi_v<float> / 6),
                s = std::sin(std::numbers::pi_v<float> / 6);
    // J's columns: 2σ along each axis (K/4 = ¼ J Jᵀ has σ² on each).
    TextureCoords coords;
    coords.s = 0.4f, coords.t = 0.6f;
    coords.dsdx = 2 * sigma_major * c / kWidth, coords.dtdx = 2 * sigma_major * s / kHeight;
    coords.dsdy = -2 * sigma_minor * s / kWidth, coords.dtdy = 2 * sigma_minor * c / kHeight;
    return coords;
}

TEST(PeerFilters, StochasticProbesCoverThePixelFiltersGaussian) {
    // σ_minor = 2: lod = log2(2·2) = 2 exactly, so every probe reads level 2 (kernel variance
    // 4²/4 = 4 per axis) and the positions carry the rest of K/4: their covariance + 4 I = K/4.
    // 20000 draws estimate a variance to 1 % (√(2/N)); 4 % would still catch a transposed or
    // unrotated footprint (its xy would be 0 or of the wrong sign).
    constexpr int kDraws = 20000;
    constexpr double kTolerance = 0.04;
    const float major = 8, minor = 2;
    const TextureCoords coords = rotated_footprint(major, minor);
    RandomStream random(7);
    double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (int i = 0; i < kDraws; ++i) {
        const TextureCoords p = stochastic_probe(coords, kWidth, kHeight, random);
        ASSERT_FLOAT_EQ(p.dsdx * kWidth, 4.0f);
        ASSERT_FLOAT_EQ(p.dtdy * kHeight, 4.0f);
        ASSERT_EQ(p.dtdx, 0);
        ASSERT_EQ(p.dsdy, 0);
        const double x = (p.s - coords.s) * kWidth, y = (p.t - coords.t) * kHeight;
        sx += x, sy += y, sxx += x * x, sxy += x * y, syy += y * y;
    }
    const double n = kDraws;
    const double c = std::cos(std::numbers::pi / 6), s = std::sin(std::numbers::pi / 6);
    const double k_xx = major * major * c * c + minor * minor * s * s;
    const double k_xy = (major * major - minor * minor) * c * s;
    const double k_yy = major * major * s * s + minor * minor * c * c;
    EXPECT_NEAR(sx / n, 0, 0.1);
    EXPECT_NEAR(sy / n, 0, 0.1);
    EXPECT_NEAR(sxx / n + 4, k_xx, kTolerance * k_xx);
    EXPECT_NEAR(sxy / n, k_xy, kTolerance * k_xy);
    EXPECT_NEAR(syy / n + 4, k_yy, kTolerance * k_yy);
}

TEST(PeerFilters, StochasticLevelsAverageToTheLod) {
    // σ_minor = 2^1.3 / 2: lod 1.3, so 30 % of the probes read level 2, the rest level 1.
    constexpr int kDraws = 20000;
    constexpr double kTolerance = 0.015;  // ~4.6 standard errors of a share of 0.3
    const float minor = std::exp2(1.3f) / 2;
    const TextureCoords coords = rotated_footprint(8, minor);
    RandomStream random(11);
    int coarser = 0;
    for (int i = 0; i < kDraws; ++i) {
        const float size = stochastic_probe(coords, kWidth, kHeight, random).dsdx * kWidth;
        ASSERT_TRUE(size == 2.0f || size == 4.0f) << size;
        coarser += size == 4.0f;
    }
    EXPECT_NEAR(coarser / static_cast<double>(kDraws), 0.3, kTolerance);
}

TEST(PeerFilters, StochasticProbeOfNoFootprintIsThePointAtLevelZero) {
    TextureCoords coords;
    coords.s = 0.25f, coords.t = 0.75f;
    RandomStream random(3);
    const TextureCoords p = stochastic_probe(coords, kWidth, kHeight, random);
    EXPECT_EQ(p.s, 0.25f);
    EXPECT_EQ(p.t, 0.75f);
    EXPECT_EQ(p.dsdx, 0);
    coords.dsdx = NAN;
    EXPECT_EQ(stochastic_probe(coords, kWidth, kHeight, random).s, 0.25f);
}

TEST(PeerFilters, SampledSlopesHaveTheMoments) {
    constexpr int kDraws = 20000;
    constexpr double kTolerance = 0.04;  // 4 × the ~1 % standard error of a variance
    const SlopeStatistics moments{{0.1f, -0.3f}, {0.04f, 0.01f, 0.02f}};
    RandomStream random(5);
    double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (int i = 0; i < kDraws; ++i) {
        const Vec2 b = sample_slope(moments, random.gaussian()) - moments.mean;
        sx += b.x, sy += b.y, sxx += b.x * b.x, sxy += b.x * b.y, syy += b.y * b.y;
    }
    EXPECT_NEAR(sx / kDraws, 0, 0.005);
    EXPECT_NEAR(sy / kDraws, 0, 0.005);
    EXPECT_NEAR(sxx / kDraws, 0.04, kTolerance * 0.04);
    EXPECT_NEAR(sxy / kDraws, 0.01, kTolerance * 0.04);
    EXPECT_NEAR(syy / kDraws, 0.02, kTolerance * 0.02);
}

}  // namespace
}  // namespace footprint::detail
