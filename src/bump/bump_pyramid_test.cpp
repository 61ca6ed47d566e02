#include "bump/bump_pyramid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "texture/ewa.h"
#include "texture/footprint_assembly.h"

namespace footprint {
namespace {

// Pyramid statistics against the brute-force mean and covariance over every finest texel a texel
// covers: levels are computed in double and rounded to float once, so μ and K are exact to float
// rounding of the stored moments, relative to the texel's second-moment scale tr K + |μ − offset|².
constexpr double kPyramidRelTolerance = 1e-6;
// Filtered lookups against the brute-force weighted mixture: float arithmetic in the filters
// (weights, bilinear blends, sums over up to a few hundred probes' taps).
constexpr double kLookupRelTolerance = 2e-5;

struct Brute {
    double mean[2] = {0, 0};
    double m2[3] = {0, 0, 0};  // Σ w b bᵀ
    double weight = 0;
};

// Random slopes with a mean tilt (so the offset matters) and structure at several scales.
Image random_slopes(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> g(0, 1);
    Image image(w, h, 2);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            image.at(x, y, 0) = 0.8f + 0.3f * g(rng) + 0.2f * std::sin(0.4f * float(x));
            image.at(x, y, 1) = -0.5f + 0.1f * g(rng) * (x < w / 2 ? 1.0f : 3.0f);
        }
    return image;
}

void expect_statistics(const SlopeStatistics& got, const Brute& b, const Sym2& k0, Vec2 offset,
                       double tol, const std::string& where) {
    const double mx = b.mean[0] / b.weight, my = b.mean[1] / b.weight;
    const double kxx = b.m2[0] / b.weight - mx * mx + k0.xx;
    const double kxy = b.m2[1] / b.weight - mx * my + k0.xy;
    const double kyy = b.m2[2] / b.weight - my * my + k0.yy;
    // float rounding of M2' and μ'μ'ᵀ: relative to tr K + |μ − offset|², the offset being the
    // map's mean slope (asserted below), so that K keeps its digits.
    const double dx = mx - offset.x, dy = my - offset.y;
    const double scale = kxx + kyy + dx * dx + dy * dy + 1e-12;
    EXPECT_NEAR(got.mean.x, mx, tol * std::sqrt(scale) + 1e-6 * std::fabs(mx)) << where;
    EXPECT_NEAR(got.mean.y, my, tol * std::sqrt(scale) + 1e-6 * std::fabs(my)) << where;
    EXPECT_NEAR(got.covariance.xx, kxx, tol * scale) << where;
    EXPECT_NEAR(got.covariance.xy, kxy, tol * scale) << where;
    EXPECT_NEAR(got.covariance.yy, kyy, tol * scale) << where;
}

void add(Brute& b, const Image& slopes, int x, int y, double w) {
    const double b1 = slopes.at(x, y, 0), b2 = slopes.at(x, y, 1);
    b.mean[0] += w * b1;
    b.mean[1] += w * b2;
    b.m2[0] += w * b1 * b1;
    b.m2[1] += w * b1 * b2;
    b.m2[2] += w * b2 * b2;
    b.weight += w;
}

TEST(BumpPyramid, EveryLevelHoldsTheCovarianceOfItsFinestTexels) {
    const int size = 64;
    const Image slopes = random_slopes(size, size, 1);
    for (const Sym2 k0 : {Sym2{}, Sym2{0.01f, 0.004f, 0.02f}}) {
        BumpPyramidOptions options;
        options.micro_roughness = k0;
        const Result<BumpPyramid> p = BumpPyramid::build(slopes, options);
        ASSERT_TRUE(p.ok()) << p.error().message;
        ASSERT_EQ(p->level_count(), 7);
        for (int l = 0; l < p->level_count(); ++l) {
            const int block = 1 << l;
            for (int y = 0; y < p->height(l); ++y)
                for (int x = 0; x < p->width(l); ++x) {
                    Brute b;
                    for (int j = y * block; j < (y + 1) * block; ++j)
                        for (int i = x * block; i < (x + 1) * block; ++i) add(b, slopes, i, j, 1.0);
                    expect_statistics(p->statistics(l, x, y), b, k0, p->slope_offset(),
                                      kPyramidRelTolerance,
                                      "level " + std::to_string(l) + " texel " + std::to_string(x) +
                                          "," + std::to_string(y));
                }
        }
    }
}

// A roughness that varies texel by texel (micro_variance): each coarser texel's K is the
// covariance of its finest slopes plus the mean of their own variances, by brute force.
TEST(BumpPyramid, PerTexelVarianceAddsItsMeanToEveryLevel) {
    const int size = 32;
    const Image slopes = random_slopes(size, size, 5);
    BumpPyramidOptions options;
    options.micro_variance = Image(size, size, 1);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            options.micro_variance.at(x, y, 0) = 0.002f * static_cast<float>((x * 7 + y * 3) % 11);
    const Result<BumpPyramid> p = BumpPyramid::build(slopes, options);
    ASSERT_TRUE(p.ok()) << p.error().message;
    EXPECT_TRUE(p->options().micro_variance.empty());  // not kept twice
    for (int l = 0; l < p->level_count(); ++l) {
        const int block = 1 << l;
        for (int y = 0; y < p->height(l); ++y)
            for (int x = 0; x < p->width(l); ++x) {
                Brute b;
                double variance = 0;
                for (int j = y * block; j < (y + 1) * block; ++j)
                    for (int i = x * block; i < (x + 1) * block; ++i) {
                        add(b, slopes, i, j, 1.0);
                        variance += options.micro_variance.at(i, j, 0);
                    }
                const float own = static_cast<float>(variance / (block * block));
                expect_statistics(p->statistics(l, x, y), b, Sym2{own, 0, own}, p->slope_offset(),
                                  kPyramidRelTolerance, "level " + std::to_string(l));
            }
    }
    // A map of the wrong size, or a negative variance, is refused and says so.
    BumpPyramidOptions small;
    small.micro_variance = Image(4, 4, 1);
    Result<BumpPyramid> bad = BumpPyramid::build(slopes, small);
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("4×4×1"), std::string::npos) << bad.error().message;
    options.micro_variance.at(3, 2, 0) = -1;
    bad = BumpPyramid::build(slopes, options);
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("(3, 2)"), std::string::npos) << bad.error().message;
}

// A map large enough that a sum of its slopes is far from their mean: the offset must be the
// mean (with the sum as the offset, K would lose its digits to M2 − μμᵀ in float).
TEST(BumpPyramid, TheOffsetIsTheMeanSlopeAndLargeMapsKeepTheirCovariance) {
    const int w = 512, h = 256;
    const Image slopes = random_slopes(w, h, 3);
    const Result<BumpPyramid> p = BumpPyramid::build(slopes);
    ASSERT_TRUE(p.ok()) << p.error().message;
    Brute all;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) add(all, slopes, x, y, 1.0);
    EXPECT_NEAR(p->slope_offset().x, all.mean[0] / all.weight, 1e-6);
    EXPECT_NEAR(p->slope_offset().y, all.mean[1] / all.weight, 1e-6);
    for (int l : {1, 2, 4}) {
        const int block = 1 << l;
        for (int y = 0; y < p->height(l); y += 7)
            for (int x = 0; x < p->width(l); x += 5) {
                Brute b;
                for (int j = y * block; j < (y + 1) * block; ++j)
                    for (int i = x * block; i < (x + 1) * block; ++i) add(b, slopes, i, j, 1.0);
                expect_statistics(p->statistics(l, x, y), b, Sym2{}, p->slope_offset(),
                                  kPyramidRelTolerance,
                                  "level " + std::to_string(l) + " texel " + std::to_string(x) +
                                      "," + std::to_string(y));
            }
    }
}

TEST(BumpPyramid, OddSizesUseTheMixtureOfFractionalCoverage) {
    const Image slopes = random_slopes(13, 7, 2);
    const Result<BumpPyramid> p = BumpPyramid::build(slopes);
    ASSERT_TRUE(p.ok());
    // Level 1 is 6×3: texel i covers [i·13/6, (i+1)·13/6) × [j·7/3, (j+1)·7/3) with fractional
    // weights.
    const double rx = 13.0 / 6, ry = 7.0 / 3;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 6; ++x) {
            Brute b;
            for (int j = 0; j < 7; ++j)
                for (int i = 0; i < 13; ++i) {
                    const double ox = std::max(
                        0.0, std::min(i + 1.0, (x + 1) * rx) - std::max(double(i), x * rx));
                    const double oy = std::max(
                        0.0, std::min(j + 1.0, (y + 1) * ry) - std::max(double(j), y * ry));
                    if (ox * oy > 0) add(b, slopes, i, j, ox * oy);
                }
            expect_statistics(p->statistics(1, x, y), b, Sym2{}, p->slope_offset(),
                              kPyramidRelTolerance,
                              "texel " + std::to_string(x) + "," + std::to_string(y));
        }
}

// The effective level-0 weights of a bilinear probe at level `level` (power-of-two map, repeat
// wrap): each level-l texel is the plain mean of its 2^l × 2^l finest texels.
void add_probe(std::vector<double>& weights, int size, int level, double s, double t, double w) {
    const int n = size >> level, block = 1 << level;
    const double x = s * n - 0.5, y = t * n - 0.5;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            const double tap = w * (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) / (block * block);
            const int tx = wrap_index(x0 + dx, n, WrapMode::repeat),
                      ty = wrap_index(y0 + dy, n, WrapMode::repeat);
            for (int j = ty * block; j < (ty + 1) * block; ++j)
                for (int i = tx * block; i < (tx + 1) * block; ++i)
                    weights[std::size_t(j) * size + i] += tap;
        }
}

TEST(BumpPyramid, FootprintAssemblyLookupIsTheWeightedMixture) {
    const int size = 64;
    const Image slopes = random_slopes(size, size, 3);
    BumpPyramidOptions options;
    options.micro_roughness = {0.003f, -0.001f, 0.002f};
    const Result<BumpPyramid> p = BumpPyramid::build(slopes, options);
    ASSERT_TRUE(p.ok());
    const int max_level = p->level_count() - 1;
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(0, 1);
    for (ProbeRule rule : {ProbeRule::gaussian, ProbeRule::moment_matched})
        for (int i = 0; i < 150; ++i) {
            const float major = 0.5f * std::pow(40.0f, u(rng));
            const FootprintEllipse e =
                make_footprint_ellipse(major, major / std::pow(16.0f, u(rng)), 3.2f * u(rng));
            const float s = u(rng), t = u(rng);
            LookupOptions lo;
            lo.probe_rule = rule;
            const SlopeStatistics got = bump_lookup(*p, s, t, e, lo);

            // Brute force: the probes of plan_probes, their weights, the level blend — as level-0
            // weights.
            const ProbePlan plan =
                plan_probes(e, rule, lo.max_probes, max_level, 0.0f, lo.isotropic_ratio);
            const int l0 = std::min(int(plan.lod), max_level);
            const bool several = plan.count > 1;
            double w = l0 < max_level ? plan.lod - l0 : 0.0;
            if (several && w > 0)
                w = (std::exp2(2 * w) - 1) / 3;  // automatic: variance-matched for lines
            std::vector<double> weights(std::size_t(size) * size, 0.0);
            double probe_sum = 0;
            for (int k = 0; k < plan.count; ++k) {
                const double kk = k - 0.5 * (plan.count - 1);
                probe_sum += std::exp(-0.5 * std::pow(plan.weight_falloff * kk, 2));
            }
            for (int k = 0; k < plan.count; ++k) {
                const double kk = k - 0.5 * (plan.count - 1);
                const double pw =
                    std::exp(-0.5 * std::pow(plan.weight_falloff * kk, 2)) / probe_sum;
                const double ps = s + kk * plan.step.x / size, pt = t + kk * plan.step.y / size;
                add_probe(weights, size, l0, ps, pt, pw * (1 - w));
                if (w > 0) add_probe(weights, size, l0 + 1, ps, pt, pw * w);
            }
            Brute b;
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x)
                    if (weights[std::size_t(y) * size + x] != 0)
                        add(b, slopes, x, y, weights[std::size_t(y) * size + x]);
            expect_statistics(
                got, b, options.micro_roughness, p->slope_offset(), kLookupRelTolerance,
                "footprint " + std::to_string(i) + " λ = " + std::to_string(e.major_radius) + "," +
                    std::to_string(e.minor_radius));
        }
}

TEST(BumpPyramid, EwaLookupIsTheWeightedMixtureAtLevel0) {
    const int size = 64;
    const Image slopes = random_slopes(size, size, 5);
    const Result<BumpPyramid> p = BumpPyramid::build(slopes);
    ASSERT_TRUE(p.ok());
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> u(0, 1);
    LookupOptions lo;
    lo.filter = TextureFilter::ewa;
    for (int i = 0; i < 100; ++i) {
        const float minor = 0.2f + 2.6f * u(rng),
                    major = std::max(1.1f, minor * std::pow(8.0f, u(rng)));
        const FootprintEllipse e =
            make_footprint_ellipse(major, std::min(minor, major), 3.2f * u(rng));
        const float s = u(rng), t = u(rng);
        const SlopeStatistics got = bump_lookup(*p, s, t, e, lo);
        const Sym2 sigma =
            (1.0f / ewa_truncation_variance()) * ewa_gaussian_covariance(e, 0.0f, 1.0f);
        const double det = double(sigma.xx) * sigma.yy - double(sigma.xy) * sigma.xy;
        const double cx = double(s) * size - 0.5, cy = double(t) * size - 0.5;
        Brute b;
        for (int y = int(cy) - 40; y <= int(cy) + 40; ++y)
            for (int x = int(cx) - 40; x <= int(cx) + 40; ++x) {
                const double dx = x - cx, dy = y - cy;
                const double r2 =
                    (sigma.yy * dx * dx - 2 * sigma.xy * dx * dy + sigma.xx * dy * dy) / det;
                if (r2 < 9)
                    add(b, slopes, wrap_index(x, size, WrapMode::repeat),
                        wrap_index(y, size, WrapMode::repeat),
                        std::exp(-0.5 * r2) - std::exp(-4.5));
            }
        expect_statistics(got, b, Sym2{}, p->slope_offset(), kLookupRelTolerance,
                          "footprint " + std::to_string(i));
    }
}

TEST(BumpPyramid, BlendingMomentsNotFactors) {
    // [R3e]: a 50/50 blend of regions with K = diag(1, 0) and diag(0, 1) has K = diag(½, ½);
    // blending the factors B would give diag(¼, ¼). Left 2×2 block: slopes (±1, 0); right block:
    // (0, ±1).
    Image slopes(4, 2, 2);
    const float left[4][2] = {{1, 0}, {-1, 0}, {-1, 0}, {1, 0}},
                right[4][2] = {{0, 1}, {0, -1}, {0, -1}, {0, 1}};
    for (int k = 0; k < 4; ++k) {
        const int x = k % 2, y = k / 2;
        slopes.at(x, y, 0) = left[k][0];
        slopes.at(x, y, 1) = left[k][1];
        slopes.at(x + 2, y, 0) = right[k][0];
        slopes.at(x + 2, y, 1) = right[k][1];
    }
    BumpPyramidOptions options;
    options.wrap_s = options.wrap_t = WrapMode::clamp;
    const Result<BumpPyramid> p = BumpPyramid::build(slopes, options);
    ASSERT_TRUE(p.ok());
    EXPECT_NEAR(p->statistics(1, 0, 0).covariance.xx, 1.0f, 1e-6f);
    EXPECT_NEAR(p->statistics(1, 0, 0).covariance.yy, 0.0f, 1e-6f);
    // Half-way between the two level-1 texels, trilinear at exactly level 1.
    LookupOptions lo;
    lo.filter = TextureFilter::trilinear;
    const SlopeStatistics mid = bump_lookup(*p, 0.5f, 0.5f, make_footprint_ellipse(2, 2, 0), lo);
    EXPECT_NEAR(mid.covariance.xx, 0.5f, 1e-6f);
    EXPECT_NEAR(mid.covariance.yy, 0.5f, 1e-6f);
    EXPECT_NEAR(mid.covariance.xy, 0.0f, 1e-6f);
    const RoughnessFactor a = roughness_factor(Sym2{1, 0, 0}), b = roughness_factor(Sym2{0, 0, 1});
    const RoughnessFactor blended{0.5f * (a.d1 + b.d1), 0.5f * (a.d2 + b.d2), 0.5f * (a.d3 + b.d3)};
    EXPECT_NEAR(blended.covariance().xx, 0.25f, 1e-6f);  // what interpolating the d's would do
}

TEST(BumpPyramid, BadInputIsAnErrorThatSaysWhat) {
    Image three(4, 4, 3);
    Result<BumpPyramid> p = BumpPyramid::build(three);
    ASSERT_FALSE(p.ok());
    EXPECT_NE(p.error().message.find("3 channels"), std::string::npos);
    Image nan(4, 4, 2);
    nan.at(2, 1, 1) = NAN;
    p = BumpPyramid::build(nan);
    ASSERT_FALSE(p.ok());
    EXPECT_NE(p.error().message.find("(2, 1)"), std::string::npos) << p.error().message;
    BumpPyramidOptions bad;
    bad.micro_roughness = {1, 2, 1};  // not PSD
    p = BumpPyramid::build(Image(4, 4, 2), bad);
    ASSERT_FALSE(p.ok());
    // A 1×1 map is a valid one-level pyramid.
    Image one(1, 1, 2);
    one.at(0, 0, 0) = 0.3f;
    p = BumpPyramid::build(one);
    ASSERT_TRUE(p.ok());
    EXPECT_NEAR(p->statistics(0, 0, 0).mean.x, 0.3f, 1e-7f);
}

}  // namespace
}  // namespace footprint
