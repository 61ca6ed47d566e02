// Tests of metrics/image_metrics.h: RMSE and PSNR against hand-computed values, SSIM against the
// closed form for constant images and against a brute-force implementation of the paper's
// formula written here (direct loops over the window, two-pass moments), masks, flicker.
#include "metrics/image_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace footprint {
namespace {

Image grey(int width, int height, const std::vector<float>& values) {
    Image image(width, height, 1);
    image.pixels = values;
    return image;
}

// A deterministic pseudo-random image in [0, 1) (a small LCG, independent of <random>).
Image noise_image(int width, int height, int channels, unsigned seed) {
    Image image(width, height, channels);
    unsigned state = seed;
    for (float& v : image.pixels) {
        state = state * 1664525u + 1013904223u;
        v = static_cast<float>((state >> 8) & 0xffff) / 65536.0f;
    }
    return image;
}

// SSIM of channel c at pixel (x, y), straight from Wang et al. 2004 with the border rule of
// image_metrics.h: the 11×11 Gaussian window (σ = 1.5) cut to the image, weights renormalised.
// Two-pass moments: σab = Σ w (a − μa)(b − μb) / Σ w.
double brute_force_ssim(const Image& a, const Image& b, int x, int y, int c, double peak) {
    double weight = 0, mu_a = 0, mu_b = 0;
    for (int dy = -5; dy <= 5; ++dy)
        for (int dx = -5; dx <= 5; ++dx) {
            const int sx = x + dx, sy = y + dy;
            if (sx < 0 || sy < 0 || sx >= a.width || sy >= a.height) continue;
            const double w = std::exp(-(dx * dx + dy * dy) / (2 * 1.5 * 1.5));
            weight += w;
            mu_a += w * a.at(sx, sy, c);
            mu_b += w * b.at(sx, sy, c);
        }
    mu_a /= weight;
    mu_b /= weight;
    double var_a = 0, var_b = 0, cov = 0;
    for (int dy = -5; dy <= 5; ++dy)
        for (int dx = -5; dx <= 5; ++dx) {
            const int sx = x + dx, sy = y + dy;
            if (sx < 0 || sy < 0 || sx >= a.width || sy >= a.height) continue;
            const double w = std::exp(-(dx * dx + dy * dy) / (2 * 1.5 * 1.5));
            const double da = a.at(sx, sy, c) - mu_a, db = b.at(sx, sy, c) - mu_b;
            var_a += w * da * da;
            var_b += w * db * db;
            cov += w * da * db;
        }
    var_a /= weight;
    var_b /= weight;
    cov /= weight;
    const double c1 = (0.01 * peak) * (0.01 * peak), c2 = (0.03 * peak) * (0.03 * peak);
    return (2 * mu_a * mu_b + c1) * (2 * cov + c2) /
           ((mu_a * mu_a + mu_b * mu_b + c1) * (var_a + var_b + c2));
}

TEST(ImageMetrics, RmseAndPsnrOfGrey2x2ByHand) {
    const Image a = grey(2, 2, {0.0f, 0.25f, 0.5f, 1.0f});
    const Image b = grey(2, 2, {0.0f, 0.5f, 0.5f, 0.5f});
    // Differences 0, −0.25, 0, 0.5; squares 0 + 0.0625 + 0 + 0.25 = 0.3125; / 4 = 0.078125.
    // RMSE = √0.078125 = 0.27950849718747; PSNR = −10 log10 0.078125 = 10 log10 12.8 = 11.0720997.
    const Result<ImageComparison> r = compare_images(a, b);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_NEAR(r->rmse, 0.2795084971874737, 1e-15);
    EXPECT_NEAR(r->psnr, 11.072099696478684, 1e-12);
    EXPECT_EQ(r->pixels, 4u);
}

TEST(ImageMetrics, RmseAndPsnrOfRgb3x1WithPeakByHand) {
    Image a(3, 1, 3), b(3, 1, 3);
    a.pixels = {0.5f, 0.5f, 0.5f, 1.0f, 0.0f, 0.0f, 0.25f, 0.75f, 0.0f};
    b.pixels = {0.5f, 0.5f, 0.5f, 0.5f, 0.0f, 0.0f, 0.25f, 0.25f, 0.5f};
    // Differences: pixel 0: 0 0 0; pixel 1: 0.5 0 0; pixel 2: 0 0.5 −0.5.
    // Σ squares = 0.25 · 3 = 0.75 over 9 values: 1/12. RMSE = √(1/12) = 0.28867513459481.
    // peak 2: PSNR = 20 log10(2 √12) = 10 log10 48 = 16.8124123737559 dB.
    MetricsOptions options;
    options.peak = 2.0;
    const Result<ImageComparison> r = compare_images(a, b, options);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_NEAR(r->rmse, 0.28867513459481287, 1e-15);
    EXPECT_NEAR(r->psnr, 16.812412373755873, 1e-12);
    EXPECT_EQ(r->pixels, 3u);

    // Mask selecting pixel 2 only: (0.25 + 0.25) / 3 = 1/6, RMSE = √(1/6) = 0.408248290463863,
    // PSNR (peak 1) = 10 log10 6 = 7.78151250383644 dB. SSIM: the map's value at pixel 2.
    Image mask = grey(3, 1, {0.0f, 0.5f, 1.0f});  // 0.5 is not > 0.5
    options.peak = 1.0;
    options.mask = &mask;
    const Result<ImageComparison> m = compare_images(a, b, options);
    ASSERT_TRUE(m.ok()) << m.error().message;
    EXPECT_EQ(m->pixels, 1u);
    EXPECT_NEAR(m->rmse, 0.408248290463863, 1e-15);
    EXPECT_NEAR(m->psnr, 7.781512503836435, 1e-12);
    EXPECT_NEAR(m->ssim, ssim_map(a, b, 1.0).at(2, 0, 0), 1e-7);
}

TEST(ImageMetrics, IdenticalImagesHaveZeroErrorInfinitePsnrAndSsimOne) {
    const Image a = noise_image(7, 5, 3, 1);
    const Result<ImageComparison> r = compare_images(a, a);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->rmse, 0.0);
    EXPECT_TRUE(std::isinf(r->psnr) && r->psnr > 0);
    EXPECT_NEAR(r->ssim, 1.0, 1e-12);
    EXPECT_EQ(r->pixels, 35u);
    const Image map = ssim_map(a, a, 1.0);
    ASSERT_EQ(map.channels, 1);
    for (float v : map.pixels) EXPECT_NEAR(v, 1.0f, 1e-6f);
}

TEST(ImageMetrics, SsimOfConstantImagesByHand) {
    // Constant images: σa = σb = σab = 0, so SSIM = (2 μa μb + C1) / (μa² + μb² + C1).
    // μa = 0.5, μb = 0.75, L = 1: C1 = 1e-4; (0.75 + 1e-4) / (0.25 + 0.5625 + 1e-4)
    //   = 0.7501 / 0.8126 = 0.92308638936746.
    // L = 2: C1 = 4e-4; 0.7504 / 0.8129 = 0.92311477426498.
    const Image a(4, 4, 3, 0.5f), b(4, 4, 3, 0.75f);
    const Result<ImageComparison> r = compare_images(a, b);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_NEAR(r->ssim, 0.9230863893674625, 1e-12);
    MetricsOptions options;
    options.peak = 2.0;
    const Result<ImageComparison> r2 = compare_images(a, b, options);
    ASSERT_TRUE(r2.ok());
    EXPECT_NEAR(r2->ssim, 0.9231147742649772, 1e-12);
}

TEST(ImageMetrics, SsimMatchesBruteForceOnSmallAndLargerImages) {
    // 5×5: every window is cut by the border. 13×12: the centre pixels have the full window.
    for (const auto& [width, height] : {std::pair{5, 5}, std::pair{13, 12}, std::pair{1, 3}}) {
        const Image a = noise_image(width, height, 3, 7);
        Image b = noise_image(width, height, 3, 99);
        for (std::size_t i = 0; i < b.pixels.size(); ++i)  // correlated with a
            b.pixels[i] = 0.6f * a.pixels[i] + 0.4f * b.pixels[i];
        for (double peak : {1.0, 0.5}) {
            double expected_mean = 0;
            const Image map = ssim_map(a, b, peak);
            ASSERT_EQ(map.width, width);
            ASSERT_EQ(map.height, height);
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    double s = 0;
                    for (int c = 0; c < 3; ++c) s += brute_force_ssim(a, b, x, y, c, peak);
                    s /= 3;
                    expected_mean += s;
                    EXPECT_NEAR(map.at(x, y, 0), s, 1e-6) << width << "x" << height;
                }
            expected_mean /= width * height;
            MetricsOptions options;
            options.peak = peak;
            const Result<ImageComparison> r = compare_images(a, b, options);
            ASSERT_TRUE(r.ok()) << r.error().message;
            EXPECT_NEAR(r->ssim, expected_mean, 1e-10) << width << "x" << height;
            EXPECT_LT(r->ssim, 0.99);
        }
    }
}

TEST(ImageMetrics, SsimIsSymmetric) {
    const Image a = noise_image(9, 6, 3, 3), b = noise_image(9, 6, 3, 4);
    const Result<ImageComparison> ab = compare_images(a, b), ba = compare_images(b, a);
    ASSERT_TRUE(ab.ok() && ba.ok());
    EXPECT_NEAR(ab->ssim, ba->ssim, 1e-14);
    EXPECT_EQ(ab->rmse, ba->rmse);
}

TEST(ImageMetrics, MaskSelectingOnePixelGivesThatPixelsError) {
    const Image a = noise_image(6, 4, 3, 11), b = noise_image(6, 4, 3, 12);
    Image mask(6, 4, 2, 0.0f);  // 2 channels: only channel 0 counts
    for (std::size_t p = 0; p < mask.pixel_count(); ++p) mask.pixels[p * 2 + 1] = 1.0f;
    mask.at(4, 2, 0) = 1.0f;
    MetricsOptions options;
    options.mask = &mask;
    const Result<ImageComparison> r = compare_images(a, b, options);
    ASSERT_TRUE(r.ok()) << r.error().message;
    double squared = 0;
    for (int c = 0; c < 3; ++c) {
        const double d = double(a.at(4, 2, c)) - double(b.at(4, 2, c));
        squared += d * d;
    }
    EXPECT_EQ(r->pixels, 1u);
    EXPECT_NEAR(r->rmse, std::sqrt(squared / 3), 1e-15);
    EXPECT_NEAR(r->psnr, -20 * std::log10(std::sqrt(squared / 3)), 1e-12);
    double s = 0;
    for (int c = 0; c < 3; ++c) s += brute_force_ssim(a, b, 4, 2, c, 1.0);
    EXPECT_NEAR(r->ssim, s / 3, 1e-10);
}

TEST(ImageMetrics, MeanAbsoluteDifferenceAndHeatMap) {
    const Image a = grey(4, 1, {0.0f, 0.5f, 1.0f, 0.25f});
    const Image b = grey(4, 1, {0.0f, 0.25f, 0.0f, 0.375f});
    // |a − b| = 0, 0.25, 1, 0.125: mean 1.375 / 4 = 0.34375.
    EXPECT_DOUBLE_EQ(mean_absolute_difference(a, b), 0.34375);
    EXPECT_TRUE(std::isnan(mean_absolute_difference(a, Image(3, 1, 1))));
    // scale 0.5: t = 0 → black, 0.5 → red, 2 → clamped to 1 → white, 0.25 → blue.
    const Image heat = error_heat_map(a, b, 0.5);
    ASSERT_EQ(heat.channels, 3);
    const std::vector<float> expected = {0, 0, 0, 1, 0, 0, 1, 1, 1, 0, 0, 1};
    for (std::size_t i = 0; i < expected.size(); ++i)
        EXPECT_NEAR(heat.pixels[i], expected[i], 1e-6) << i;
    // t = 0.625: halfway from red to yellow: (1, 0.5, 0); t = 0.125: (0, 0, 0.5).
    const Image mid = error_heat_map(grey(2, 1, {0.625f, 0.125f}), grey(2, 1, {0, 0}), 1.0);
    EXPECT_NEAR(mid.pixels[0], 1.0f, 1e-6);
    EXPECT_NEAR(mid.pixels[1], 0.5f, 1e-6);
    EXPECT_NEAR(mid.pixels[2], 0.0f, 1e-6);
    EXPECT_NEAR(mid.pixels[5], 0.5f, 1e-6);
    // RGB: t is the mean over channels: (0.3 + 0.1 + 0.2) / 3 / 0.8 = 0.25 → blue.
    Image c(1, 1, 3), d(1, 1, 3, 0.0f);
    c.pixels = {0.3f, -0.1f, 0.2f};
    const Image rgb = error_heat_map(c, d, 0.8);
    EXPECT_NEAR(rgb.pixels[0], 0.0f, 1e-6);
    EXPECT_NEAR(rgb.pixels[2], 1.0f, 1e-6);
    // scale 0: no difference is black, any difference white.
    const Image zero = error_heat_map(a, b, 0.0);
    EXPECT_EQ(zero.pixels[0], 0.0f);
    EXPECT_EQ(zero.pixels[3], 1.0f);
}

TEST(ImageMetricsErrors, NameTheProblem) {
    const Image a(4, 4, 3, 0.5f);
    auto message = [](const Result<ImageComparison>& r) {
        return r.ok() ? std::string("(ok)") : r.error().message;
    };
    EXPECT_EQ(message(compare_images(a, Image(3, 4, 3))),
              "images differ in size: A is 4x4, B is 3x4");
    EXPECT_EQ(message(compare_images(a, Image(4, 4, 1))),
              "images differ in channels: A has 3, B has 1");
    EXPECT_EQ(message(compare_images(Image(), a)), "A is empty");
    MetricsOptions options;
    Image small_mask(2, 2, 1, 1.0f);
    options.mask = &small_mask;
    EXPECT_EQ(message(compare_images(a, a, options)), "mask is 2x2 but the images are 4x4");
    Image empty_mask(4, 4, 1, 0.5f);
    options.mask = &empty_mask;
    EXPECT_EQ(message(compare_images(a, a, options)),
              "mask selects no pixel (no value of channel 0 is > 0.5)");
    options.mask = nullptr;
    Image bad = a;
    bad.at(1, 2, 2) = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(message(compare_images(a, bad)),
              "A has 0 non-finite pixels; B has 1 non-finite pixel, the first at (1, 2) channel 2 "
              "= nan");
    bad.at(1, 2, 2) = std::numeric_limits<float>::infinity();
    bad.at(3, 3, 0) = -std::numeric_limits<float>::infinity();
    EXPECT_EQ(message(compare_images(bad, bad)),
              "A has 2 non-finite pixels, the first at (1, 2) channel 2 = inf; B has 2 non-finite "
              "pixels, the first at (1, 2) channel 2 = inf");
    options.peak = 0;
    EXPECT_NE(message(compare_images(a, a, options)).find("peak must be finite and > 0"),
              std::string::npos);
}

// Non-finite values are an error, or left out of every metric when ignored: a NaN against a NaN
// must never count as a perfect match.
TEST(ImageMetricsNonFinite, FindCountsPixelsAndNamesTheFirst) {
    Image image(5, 3, 3, 0.25f);
    EXPECT_EQ(find_non_finite(image).count, 0u);
    EXPECT_EQ(non_finite_text(find_non_finite(image)), "0 non-finite pixels");
    image.at(4, 0, 1) = -std::numeric_limits<float>::infinity();
    image.at(4, 0, 2) = std::numeric_limits<float>::quiet_NaN();  // same pixel: counted once
    image.at(0, 2, 0) = std::numeric_limits<float>::quiet_NaN();
    const NonFinitePixels found = find_non_finite(image);
    EXPECT_EQ(found.count, 2u);
    EXPECT_EQ(found.x, 4);
    EXPECT_EQ(found.y, 0);
    EXPECT_EQ(found.channel, 1);
    EXPECT_EQ(non_finite_text(found), "2 non-finite pixels, the first at (4, 0) channel 1 = -inf");
}

TEST(ImageMetricsNonFinite, IgnoredPixelsAreLeftOutOfEveryMetric) {
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    constexpr float kInf = std::numeric_limits<float>::infinity();
    Image a = noise_image(13, 12, 3, 5), b = noise_image(13, 12, 3, 6);
    a.at(2, 3, 0) = kNaN;  // NaN against NaN must not count as equal
    b.at(2, 3, 0) = kNaN;
    b.at(9, 7, 2) = kInf;
    EXPECT_FALSE(compare_images(a, b).ok());
    MetricsOptions ignore;
    ignore.ignore_non_finite = true;
    const Result<ImageComparison> r = compare_images(a, b, ignore);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->non_finite_a, 1u);
    EXPECT_EQ(r->non_finite_b, 2u);
    EXPECT_EQ(r->excluded, 2u);
    EXPECT_EQ(r->pixels, 13u * 12u - 2u);

    // RMSE: exactly the finite pixels' (by hand).
    double squared = 0;
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 13; ++x) {
            if ((x == 2 && y == 3) || (x == 9 && y == 7)) continue;
            for (int c = 0; c < 3; ++c) {
                const double d = double(a.at(x, y, c)) - double(b.at(x, y, c));
                squared += d * d;
            }
        }
    constexpr double kRoundingTolerance = 1e-12;
    EXPECT_NEAR(r->rmse, std::sqrt(squared / ((13 * 12 - 2) * 3)), kRoundingTolerance);
    EXPECT_TRUE(std::isfinite(r->psnr));

    // SSIM never reads the excluded pixels: other values there give the same result.
    Image a2 = a, b2 = b;
    a2.at(2, 3, 0) = kInf;
    b2.at(2, 3, 0) = -kInf;
    b2.at(9, 7, 2) = kNaN;
    const Result<ImageComparison> r2 = compare_images(a2, b2, ignore);
    ASSERT_TRUE(r2.ok());
    EXPECT_EQ(r2->ssim, r->ssim);
    EXPECT_GT(r->ssim, -1.0);
    EXPECT_LT(r->ssim, 1.0);
    // Ignoring with nothing to ignore changes nothing, bit for bit.
    const Image fa = noise_image(13, 12, 3, 5), fb = noise_image(13, 12, 3, 6);
    const Result<ImageComparison> plain = compare_images(fa, fb);
    const Result<ImageComparison> ignored = compare_images(fa, fb, ignore);
    ASSERT_TRUE(plain.ok() && ignored.ok());
    EXPECT_EQ(plain->ssim, ignored->ssim);
    EXPECT_EQ(plain->rmse, ignored->rmse);
    EXPECT_EQ(ignored->excluded, 0u);
}

TEST(ImageMetricsNonFinite, IgnoredSsimMatchesWindowsThatSkipThePixels) {
    // One channel, one bad pixel in the middle: the SSIM of every other pixel is the paper's
    // formula over its window without the bad pixel (weights renormalised), computed directly.
    Image a = noise_image(9, 8, 1, 11), b = noise_image(9, 8, 1, 12);
    a.at(4, 4, 0) = std::numeric_limits<float>::quiet_NaN();
    MetricsOptions ignore;
    ignore.ignore_non_finite = true;
    const Result<ImageComparison> r = compare_images(a, b, ignore);
    ASSERT_TRUE(r.ok()) << r.error().message;
    double sum = 0;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 9; ++x) {
            if (x == 4 && y == 4) continue;
            double weight = 0, mu_a = 0, mu_b = 0, aa = 0, bb = 0, ab = 0;
            for (int sy = std::max(0, y - 5); sy <= std::min(7, y + 5); ++sy)
                for (int sx = std::max(0, x - 5); sx <= std::min(8, x + 5); ++sx) {
                    if (sx == 4 && sy == 4) continue;
                    const double w =
                        std::exp(-((sx - x) * (sx - x) + (sy - y) * (sy - y)) / (2 * 1.5 * 1.5));
                    const double va = a.at(sx, sy, 0), vb = b.at(sx, sy, 0);
                    weight += w;
                    mu_a += w * va;
                    mu_b += w * vb;
                    aa += w * va * va;
                    bb += w * vb * vb;
                    ab += w * va * vb;
                }
            mu_a /= weight;
            mu_b /= weight;
            const double var_a = aa / weight - mu_a * mu_a, var_b = bb / weight - mu_b * mu_b;
            const double cov = ab / weight - mu_a * mu_b;
            const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
            sum += (2 * mu_a * mu_b + c1) * (2 * cov + c2) /
                   ((mu_a * mu_a + mu_b * mu_b + c1) * (var_a + var_b + c2));
        }
    constexpr double kTolerance = 1e-10;
    EXPECT_NEAR(r->ssim, sum / (9 * 8 - 1), kTolerance);
}

TEST(ImageMetricsNonFinite, NothingLeftIsAnError) {
    Image a(2, 1, 1, std::numeric_limits<float>::quiet_NaN());
    MetricsOptions ignore;
    ignore.ignore_non_finite = true;
    const Result<ImageComparison> r = compare_images(a, Image(2, 1, 1, 0.0f), ignore);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message,
              "no pixel left: every counted pixel has a non-finite value in A or B");
}

TEST(ImageMetrics, HeatMapLogarithmicScaleAndRamp) {
    const HeatMapScale log_scale{1.0, 0.001};
    constexpr double kTolerance = 1e-12;
    EXPECT_NEAR(heat_map_position(1.0, log_scale), 1.0, kTolerance);
    EXPECT_NEAR(heat_map_position(0.01, log_scale), 1.0 / 3, kTolerance);
    EXPECT_NEAR(heat_map_position(0.1, log_scale), 2.0 / 3, kTolerance);
    EXPECT_EQ(heat_map_position(0.0001, log_scale), 0.0);
    EXPECT_EQ(heat_map_position(0.0, log_scale), 0.0);
    EXPECT_EQ(heat_map_position(5.0, log_scale), 1.0);
    EXPECT_EQ(heat_map_position(std::nan(""), log_scale), 0.0);
    EXPECT_NEAR(heat_map_position(0.25, HeatMapScale{0.5, 0}), 0.5, kTolerance);
    EXPECT_EQ(heat_map_colour(0.5), (std::array<float, 3>{1, 0, 0}));
    EXPECT_EQ(heat_map_colour(1.0), (std::array<float, 3>{1, 1, 1}));
    // The image uses the same mapping: 0.01 of 3 decades is t = 1/3, between blue and red.
    const Image heat = error_heat_map(grey(1, 1, {0.01f}), grey(1, 1, {0.0f}), log_scale);
    const std::array<float, 3> expected = heat_map_colour(heat_map_position(0.01f, log_scale));
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(heat.pixels[c], expected[c]) << c;
}

std::vector<Image> grey_sequence(const std::vector<std::vector<float>>& frames) {
    std::vector<Image> sequence;
    for (const auto& f : frames) sequence.push_back(grey(static_cast<int>(f.size()), 1, f));
    return sequence;
}

TEST(ImageMetricsFlicker, HandComputedSequences) {
    // Alternating 0, 1, 0, 1 (both pixels): every step |Δ| = 1 → variation 1.
    const auto alternating = grey_sequence({{0, 0}, {1, 1}, {0, 0}, {1, 1}});
    // Ramp 0, 0.25, 0.5, 0.75: every step 0.25 → variation 0.25.
    const auto ramp = grey_sequence({{0, 0}, {0.25, 0.25}, {0.5, 0.5}, {0.75, 0.75}});
    const auto still = grey_sequence({{0.3f, 0.7f}, {0.3f, 0.7f}, {0.3f, 0.7f}, {0.3f, 0.7f}});
    EXPECT_DOUBLE_EQ(temporal_variation(alternating), 1.0);
    EXPECT_DOUBLE_EQ(temporal_variation(ramp), 0.25);
    EXPECT_DOUBLE_EQ(temporal_variation(still), 0.0);
    Result<double> f = flicker(alternating, ramp);
    ASSERT_TRUE(f.ok()) << f.error().message;
    EXPECT_DOUBLE_EQ(*f, 4.0);  // 1 / 0.25
    f = flicker(still, ramp);
    ASSERT_TRUE(f.ok());
    EXPECT_EQ(*f, 0.0);
    f = flicker(ramp, ramp);
    ASSERT_TRUE(f.ok());
    EXPECT_DOUBLE_EQ(*f, 1.0);

    // Pixel 0 flips 0, 1, 1, 0; pixel 1 stays: steps (1+0)/2, 0, (1+0)/2 → (0.5 + 0 + 0.5) / 3.
    const auto one_pixel = grey_sequence({{0, 0.5f}, {1, 0.5f}, {1, 0.5f}, {0, 0.5f}});
    EXPECT_DOUBLE_EQ(temporal_variation(one_pixel), 1.0 / 3.0);
    // Masked to pixel 0: steps 1, 0, 1 → 2/3; flicker against the ramp: (2/3) / 0.25 = 8/3.
    Image mask = grey(2, 1, {1, 0});
    MetricsOptions options;
    options.mask = &mask;
    EXPECT_DOUBLE_EQ(temporal_variation(one_pixel, options), 2.0 / 3.0);
    f = flicker(one_pixel, ramp, options);
    ASSERT_TRUE(f.ok());
    EXPECT_NEAR(*f, 8.0 / 3.0, 1e-15);
    // Masked to pixel 1: static.
    mask = grey(2, 1, {0, 1});
    EXPECT_EQ(temporal_variation(one_pixel, options), 0.0);
}

TEST(ImageMetricsFlicker, Errors) {
    const auto ramp = grey_sequence({{0, 0}, {0.25, 0.25}, {0.5, 0.5}});
    const auto still = grey_sequence({{0.3f, 0.7f}, {0.3f, 0.7f}, {0.3f, 0.7f}});
    auto message = [](const Result<double>& r) { return r.ok() ? "(ok)" : r.error().message; };
    EXPECT_EQ(message(flicker(grey_sequence({{0, 0}}), grey_sequence({{0, 0}}))),
              "the sequence has 1 frame(s); flicker needs at least 2");
    EXPECT_EQ(message(flicker(ramp, grey_sequence({{0, 0}, {1, 1}}))),
              "the sequence has 3 frames but the reference sequence has 2");
    EXPECT_EQ(message(flicker(ramp, still)),
              "the reference sequence is static over the counted pixels (temporal variation 0); "
              "flicker is undefined");
    EXPECT_EQ(message(flicker(ramp, grey_sequence({{0, 0}, {1, 1}, {0, 0, 0}}))),
              "frame 2 of the reference sequence is 3x1 with 1 channel(s), but frame 0 of the "
              "sequence is 2x1 with 1");
    Image mask(3, 1, 1, 1.0f);
    MetricsOptions options;
    options.mask = &mask;
    EXPECT_EQ(message(flicker(ramp, ramp, options)), "mask is 3x1 but the images are 2x1");
    auto nan = ramp;
    nan[1].pixels[1] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(message(flicker(nan, ramp)),
              "frame 1 of the sequence has a non-finite value at pixel (1, 0) channel 0");
    EXPECT_TRUE(std::isnan(temporal_variation(grey_sequence({{0, 0}}))));
    EXPECT_TRUE(std::isnan(temporal_variation(nan)));
    EXPECT_TRUE(std::isnan(temporal_variation({})));
}

}  // namespace
}  // namespace footprint
