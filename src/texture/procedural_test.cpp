// Procedural textures (texture/procedural.h): the noise's own properties, and every pattern's
// band-limited value against a dense integral of its point values over the pixel's footprint.
#include "texture/procedural.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "math/sample_patterns.h"

namespace footprint {
namespace {

Vec3d random_point(std::mt19937& rng, double extent) {
    std::uniform_real_distribution<double> u(-extent, extent);
    return {u(rng), u(rng), u(rng)};
}

TEST(ProceduralTexture, GradientNoiseVanishesOnTheLatticeAndHasTheStatedMoments) {
    std::mt19937 rng(1);
    for (int i = 0; i < 100; ++i) {
        const Vec3d corner{std::round(random_point(rng, 50).x), std::round(random_point(rng, 50).y),
                           std::round(random_point(rng, 50).z)};
        EXPECT_EQ(gradient_noise(corner), 0.0);
    }
    double sum = 0, sum_abs = 0, largest = 0;
    constexpr int kSamples = 400000;
    for (int i = 0; i < kSamples; ++i) {
        const double n = gradient_noise(random_point(rng, 1000));
        sum += n, sum_abs += std::abs(n), largest = std::max(largest, std::abs(n));
    }
    const double mean = sum / kSamples, mean_abs = sum_abs / kSamples;
    std::printf("[ noise ] mean %.5f  E|n| %.5f (kMeanAbsNoise %.4f)  max |n| %.3f\n", mean,
                mean_abs, kMeanAbsNoise, largest);
    EXPECT_NEAR(mean, 0, 0.002);
    EXPECT_NEAR(mean_abs, kMeanAbsNoise, 0.002);  // ± 3σ of 400 000 samples
    EXPECT_LT(largest, 1.1);
    EXPECT_GT(largest, 0.6);  // a noise that is not flat
}

// The band-limited value against the mean of the point values over the footprint's Gaussian
// (σ = ½ pixel along ∂p/∂x and ∂p/∂y: a 24 × 24 grid of its quantiles), for footprints from half
// a lattice cell to eight cells, where a point sample aliases; a footprint far below a cell is
// the point value. The point value's own error shows what filtering
// removes; the bound on the filtered one is what clamping (an octave fades over one octave of
// footprint sizes, instead of a Gaussian's smooth roll-off) leaves.
// The point value's error over each bound, at least: an unfiltered pattern must fail it.
constexpr double kNoFilterRatio = 2;

struct Group {
    ProceduralPattern pattern;
    const char* name;
    double filtered_bound;
};

TEST(ProceduralTexture, BandLimitedValuesApproachTheFootprintsMean) {
    std::vector<double> quantiles;  // of the standard normal, 24 per axis
    for (int i = 0; i < 24; ++i) quantiles.push_back(inverse_normal_cdf((i + 0.5) / 24));
    // Bounds ≈ 1.3× the measured (docs/performance.md, accuracy bounds). The checker's is the
    // loosest: its box is axis-aligned, the footprint is not, and their correlation is lost.
    const Group groups[] = {{ProceduralPattern::noise, "noise", 0.023},
                            {ProceduralPattern::turbulence, "turbulence", 0.032},
                            {ProceduralPattern::marble, "marble", 0.022},
                            {ProceduralPattern::checker, "checker", 0.153}};
    for (const Group& g : groups) {
        ProceduralTexture texture;
        texture.pattern = g.pattern;
        texture.scale = 1;
        texture.octaves = 6;
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(0, 1);
        double filtered_sq = 0, point_sq = 0;
        constexpr int kLookups = 200;
        for (int i = 0; i < kLookups; ++i) {
            const Vec3d p = random_point(rng, 20);
            const double size = 0.5 * std::pow(16.0, u(rng));  // 0.5 … 8 cells per pixel
            Vec3d a = random_point(rng, 1), b = random_point(rng, 1);
            a = size * normalize(a);
            b = size * std::pow(4.0, -u(rng)) * normalize(b);  // up to 4:1
            double mean = 0;
            for (double qa : quantiles)
                for (double qb : quantiles)
                    mean += procedural_value(texture, p + 0.5 * qa * a + 0.5 * qb * b);
            mean /= static_cast<double>(quantiles.size() * quantiles.size());
            const double filtered = procedural_value(texture, p, a, b);
            const double point = procedural_value(texture, p);
            filtered_sq += (filtered - mean) * (filtered - mean);
            point_sq += (point - mean) * (point - mean);
        }
        const double filtered = std::sqrt(filtered_sq / kLookups),
                     point = std::sqrt(point_sq / kLookups);
        std::printf(
            "[ procedural ] %-10s RMSE against the footprint's mean: band-limited %.4f "
            "(bound %.4f), point %.4f\n",
            g.name, filtered, g.filtered_bound, point);
        EXPECT_LT(filtered, g.filtered_bound) << g.name;
        EXPECT_GT(point, kNoFilterRatio * g.filtered_bound)
            << g.name << ": the bound would not see no filter";
        const Vec3d p{0.3, 1.7, -2.2}, tiny{1e-4, 0, 0};
        EXPECT_NEAR(procedural_value(texture, p, tiny, {}), procedural_value(texture, p), 1e-3)
            << g.name;
    }
}

// The noise's gradient against central differences of its value, and its variance per axis.
TEST(ProceduralTexture, GradientNoiseSampleIsTheNoisesDerivative) {
    std::mt19937 rng(3);
    constexpr double h = 1e-5;
    double largest = 0, sum_sq[3] = {0, 0, 0};
    constexpr int kSamples = 200000;
    for (int i = 0; i < kSamples; ++i) {
        const Vec3d x = random_point(rng, 1000);
        const NoiseSample n = gradient_noise_sample(x);
        sum_sq[0] += n.gradient.x * n.gradient.x, sum_sq[1] += n.gradient.y * n.gradient.y;
        sum_sq[2] += n.gradient.z * n.gradient.z;
        if (i >= 1000) continue;
        ASSERT_EQ(n.value, gradient_noise(x));
        const Vec3d fd{gradient_noise(x + Vec3d{h, 0, 0}) - gradient_noise(x - Vec3d{h, 0, 0}),
                       gradient_noise(x + Vec3d{0, h, 0}) - gradient_noise(x - Vec3d{0, h, 0}),
                       gradient_noise(x + Vec3d{0, 0, h}) - gradient_noise(x - Vec3d{0, 0, h})};
        largest = std::max(largest, length(n.gradient - fd / (2 * h)));
    }
    EXPECT_LT(largest, 1e-6);  // central differences' own error at h = 1e-5 near x ≈ 1000
    for (double s : sum_sq) {
        std::printf("[ noise ] Var(dn/dx_k) %.4f (kNoiseGradientVariance %.4f)\n", s / kSamples,
                    kNoiseGradientVariance);
        EXPECT_NEAR(s / kSamples, kNoiseGradientVariance, 0.04);  // the axes' spread, ±0.03
    }
}

// The band-limited slopes against the point gradients' moments over the footprint's Gaussian (the
// grid of the value test): their mean, and the covariance the band limit says it removed against
// theirs (traces). Measured and bounded as the values are.
TEST(ProceduralTexture, BandLimitedSlopesKeepTheFootprintsSlopeMoments) {
    std::vector<double> quantiles;
    for (int i = 0; i < 24; ++i) quantiles.push_back(inverse_normal_cdf((i + 0.5) / 24));
    struct SlopeGroup {
        ProceduralPattern pattern;
        const char* name;
        double mean_bound, covariance_bound;  // RMSE over the RMS point slope
    };
    // RMSE over E|∇v|²'s root, or over E|∇v|² for the traces; bounds ≈ 1.3× the measured
    // (docs/performance.md, accuracy bounds).
    const SlopeGroup groups[] = {{ProceduralPattern::noise, "noise", 0.19, 0.09},
                                 {ProceduralPattern::turbulence, "turbulence", 0.20, 0.08},
                                 {ProceduralPattern::marble, "marble", 0.18, 0.13}};
    for (const SlopeGroup& g : groups) {
        ProceduralTexture texture;
        texture.pattern = g.pattern;
        texture.octaves = 6;
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(0, 1);
        double mean_sq = 0, point_sq = 0, cov_sq = 0, none_sq = 0, slope_sq = 0;
        constexpr int kLookups = 200;
        for (int i = 0; i < kLookups; ++i) {
            const Vec3d p = random_point(rng, 20);
            const double size = 0.5 * std::pow(16.0, u(rng));
            Vec3d a = random_point(rng, 1), b = random_point(rng, 1);
            a = size * normalize(a);
            b = size * std::pow(4.0, -u(rng)) * normalize(b);
            Vec3d mean{0, 0, 0};
            double second = 0;  // E|g|²
            for (double qa : quantiles)
                for (double qb : quantiles) {
                    const Vec3d gp =
                        procedural_slopes(texture, p + 0.5 * qa * a + 0.5 * qb * b).gradient;
                    mean = mean + gp, second += dot(gp, gp);
                }
            const double count = static_cast<double>(quantiles.size() * quantiles.size());
            mean = mean / count, second /= count;
            const double trace_want = second - dot(mean, mean);
            const ProceduralSlopes filtered = procedural_slopes(texture, p, a, b);
            const Vec3d point = procedural_slopes(texture, p).gradient;
            const double trace =
                filtered.covariance[0] + filtered.covariance[1] + filtered.covariance[2];
            mean_sq += dot(filtered.gradient - mean, filtered.gradient - mean);
            point_sq += dot(point - mean, point - mean);
            cov_sq += (trace - trace_want) * (trace - trace_want);
            none_sq += trace_want * trace_want;
            slope_sq += dot(point, point);
        }
        const double scale = slope_sq / kLookups;  // E|∇v|² at points
        const double mean_error = std::sqrt(mean_sq / kLookups / scale);
        const double point_error = std::sqrt(point_sq / kLookups / scale);
        const double cov_error = std::sqrt(cov_sq / kLookups) / scale;
        const double no_cov_error = std::sqrt(none_sq / kLookups) / scale;
        std::printf(
            "[ procedural ] %-10s slopes: mean %.4f (point %.4f), covariance trace %.4f (none "
            "%.4f), relative to E|grad v|^2 = %.4f\n",
            g.name, mean_error, point_error, cov_error, no_cov_error, scale);
        EXPECT_LT(mean_error, g.mean_bound) << g.name;
        EXPECT_GT(point_error, kNoFilterRatio * g.mean_bound) << g.name;
        EXPECT_LT(cov_error, g.covariance_bound) << g.name;
        EXPECT_GT(no_cov_error, kNoFilterRatio * g.covariance_bound) << g.name;
    }
}

TEST(ProceduralTexture, ColoursBlendByTheValueAndBadInputStaysFinite) {
    ProceduralTexture texture;
    texture.pattern = ProceduralPattern::checker;
    texture.colors = {Vec3{1, 0, 0}, Vec3{0, 0, 1}};
    const Vec3 even = procedural_color(texture, {0.5, 0.5, 0.5});
    const Vec3 odd = procedural_color(texture, {1.5, 0.5, 0.5});
    EXPECT_EQ(even.x, 1.0f);
    EXPECT_EQ(even.z, 0.0f);
    EXPECT_EQ(odd.x, 0.0f);
    EXPECT_EQ(odd.z, 1.0f);
    // A footprint of many cells is the checker's mean, grey.
    const Vec3 wide = procedural_color(texture, {0.5, 0.5, 0.5}, {40, 0, 0}, {0, 0, 40});
    EXPECT_NEAR(wide.x, 0.5f, 0.02f);
    const double nan = std::nan("");
    for (ProceduralPattern pattern : {ProceduralPattern::noise, ProceduralPattern::turbulence,
                                      ProceduralPattern::marble, ProceduralPattern::checker}) {
        texture.pattern = pattern;
        for (const auto& [p, d] :
             {std::pair{Vec3d{nan, 0, 0}, Vec3d{}}, std::pair{Vec3d{1e300, 0, 0}, Vec3d{1, 0, 0}},
              std::pair{Vec3d{0.3, 0.2, 0.1}, Vec3d{INFINITY, 0, 0}},
              std::pair{Vec3d{0.3, 0.2, 0.1}, Vec3d{nan, 0, 0}}}) {
            const double v = procedural_value(texture, p, d, {});
            EXPECT_TRUE(std::isfinite(v) && v >= 0 && v <= 1) << int(pattern) << " " << v;
        }
    }
}

}  // namespace
}  // namespace footprint
