#include "texture/mip_pyramid.h"
#include "core/test_temp_dir.h"
#include "image/image_io.h"
#include "image/test_images.h"
#include "texture/texture_lookup.h"

#include <gtest/gtest.h>

#include <random>

namespace footprint {
namespace {

// Level means against the image mean: each level is a float average of float averages; summing in
// double, the difference stays at a few float ulps of the values (≤ 1).
constexpr double kMeanTolerance = 2e-6;
// A box-pyramid texel against the double-precision mean of the level-0 texels it covers.
constexpr double kBoxTexelTolerance = 2e-6;

std::vector<double> mean_of(const Image& image) {
    std::vector<double> mean(image.channels, 0.0);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        mean[i % image.channels] += image.pixels[i];
    for (double& m : mean) m /= double(image.pixel_count());
    return mean;
}

TEST(MipPyramid, LevelSizesFollowTheSpec) {
    const MipPyramid p = MipPyramid::build(random_image(13, 5, 1, 1));
    // W_l = max(1, ⌊W0/2^l⌋): 13 6 3 1 1, 5 2 1 1 1
    ASSERT_EQ(p.level_count(), 4);
    const int widths[] = {13, 6, 3, 1}, heights[] = {5, 2, 1, 1};
    for (int l = 0; l < 4; ++l) {
        EXPECT_EQ(p.width(l), widths[l]);
        EXPECT_EQ(p.height(l), heights[l]);
    }
    EXPECT_EQ(MipPyramid::build(random_image(1, 1, 1, 1)).level_count(), 1);
    EXPECT_EQ(MipPyramid::build(random_image(4096, 1, 1, 1)).level_count(), 13);
}

TEST(MipPyramid, NonPowerOfTwoLevelsKeepTheMean) {
    for (DownsampleFilter f : {DownsampleFilter::box, DownsampleFilter::tent})
        for (auto [w, h] :
             {std::pair{5, 3}, {37, 1}, {1, 29}, {255, 257}, {1023, 17}, {64, 48}, {7, 7}}) {
            const Image image = random_image(w, h, 3, unsigned(w * 1000 + h));
            MipPyramidOptions options;
            options.downsample = f;
            const MipPyramid p = MipPyramid::build(image, options);
            const std::vector<double> mean = mean_of(image);
            for (int l = 0; l < p.level_count(); ++l) {
                const std::vector<double> level_mean = mean_of(p.level_image(l));
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(level_mean[c], mean[c], kMeanTolerance)
                        << (f == DownsampleFilter::box ? "box " : "tent ") << w << "x" << h
                        << " level " << l;
            }
        }
}

TEST(MipPyramid, BoxTexelIsTheMeanOfTheLevel0TexelsItCovers) {
    // Texel i of level l covers [i·W0/W_l, (i+1)·W0/W_l) in level-0 texels (fractional coverage
    // for odd sizes): compare against that exact weighted mean.
    const Image image = random_image(23, 11, 1, 9);
    const MipPyramid p = MipPyramid::build(image);
    for (int l = 1; l < 2; ++l) {  // level 1 (23×11 → 11×5: ratios 2.09 and 2.2)
        const double rx = 23.0 / p.width(l), ry = 11.0 / p.height(l);
        for (int y = 0; y < p.height(l); ++y)
            for (int x = 0; x < p.width(l); ++x) {
                double sum = 0;
                for (int j = 0; j < 11; ++j) {
                    const double oy = std::max(
                        0.0, std::min(j + 1.0, (y + 1) * ry) - std::max(double(j), y * ry));
                    for (int i = 0; i < 23; ++i) {
                        const double ox = std::max(
                            0.0, std::min(i + 1.0, (x + 1) * rx) - std::max(double(i), x * rx));
                        sum += ox * oy * image.at(i, j, 0);
                    }
                }
                EXPECT_NEAR(p.texel(l, x, y)[0], sum / (rx * ry), kBoxTexelTolerance);
            }
    }
    // Power-of-two: every level texel is exactly the mean of its 2^l × 2^l block.
    const Image pot = random_image(32, 16, 2, 3);
    const MipPyramid q = MipPyramid::build(pot);
    for (int l = 1; l < q.level_count(); ++l) {
        const int b = 1 << l;
        for (int y = 0; y < q.height(l); ++y)
            for (int x = 0; x < q.width(l); ++x)
                for (int c = 0; c < 2; ++c) {
                    double sum = 0;
                    int n = 0;
                    for (int j = y * b; j < std::min(16, (y + 1) * b); ++j)
                        for (int i = x * b; i < (x + 1) * b; ++i, ++n) sum += pot.at(i, j, c);
                    EXPECT_NEAR(q.texel(l, x, y)[c], sum / n, kBoxTexelTolerance) << "level " << l;
                }
    }
}

TEST(MipPyramid, PrefilterVarianceOfTheBoxPyramid) {
    const MipPyramid p = MipPyramid::build(random_image(64, 64, 1, 2));
    for (int l = 0; l < p.level_count(); ++l) {
        const float t = float(1 << l);
        EXPECT_NEAR(p.prefilter_variance(l).x, (t * t - 1) / 12, 1e-3f * t * t);  // (T² − 1)/12
        EXPECT_NEAR(p.prefilter_variance(l).y, (t * t - 1) / 12, 1e-3f * t * t);
    }
}

// for_each_mip_level() makes build()'s levels one at a time, bit for bit (its channels unpadded),
// and mip_prefilter_variances() build()'s variances, for every channel count, filter and wrap.
TEST(MipPyramid, LevelsMadeOneAtATimeAreTheBuiltPyramids) {
    for (int channels = 1; channels <= MipPyramid::kMaxChannels; ++channels) {
        for (DownsampleFilter filter : {DownsampleFilter::box, DownsampleFilter::tent}) {
            const Image image = random_image(53, 22, channels, 40 + channels);
            MipPyramidOptions options;
            options.downsample = filter;
            options.wrap_s = WrapMode::mirror;
            options.wrap_t = channels % 2 ? WrapMode::clamp : WrapMode::repeat;
            const MipPyramid pyramid = MipPyramid::build(image, options);
            int l = 0;
            ASSERT_TRUE(for_each_mip_level(image, options, [&](const Image& level) -> Status {
                EXPECT_LT(l, pyramid.level_count());
                EXPECT_EQ(level.pixels, pyramid.level_image(l).pixels)
                    << channels << " channels, level " << l;
                ++l;
                return {};
            }));
            EXPECT_EQ(l, pyramid.level_count());
            const std::vector<Vec2> variances = mip_prefilter_variances(53, 22, filter);
            ASSERT_EQ(static_cast<int>(variances.size()), pyramid.level_count());
            for (int k = 0; k < pyramid.level_count(); ++k) {
                EXPECT_EQ(variances[k].x, pyramid.prefilter_variance(k).x) << k;
                EXPECT_EQ(variances[k].y, pyramid.prefilter_variance(k).y) << k;
            }
        }
    }
    // take's error ends it.
    int calls = 0;
    const Status stopped = for_each_mip_level(random_image(8, 8, 3, 1), {}, [&](const Image&) {
        return ++calls == 2 ? Status(Error{"full"}) : Status();
    });
    EXPECT_FALSE(stopped);
    EXPECT_EQ(calls, 2);
}

TEST(MipPyramid, EveryTileLayoutStoresTheSameTexels) {
    const Image image = random_image(37, 19, 3, 4);
    MipPyramidOptions options;
    options.tile_log2 = 0;
    const MipPyramid linear = MipPyramid::build(image, options);
    for (int tile_log2 : {1, 2, 3}) {
        options.tile_log2 = tile_log2;
        const MipPyramid tiled = MipPyramid::build(image, options);
        for (int l = 0; l < linear.level_count(); ++l)
            for (int y = 0; y < linear.height(l); ++y)
                for (int x = 0; x < linear.width(l); ++x)
                    for (int c = 0; c < 3; ++c)
                        ASSERT_EQ(linear.texel(l, x, y)[c], tiled.texel(l, x, y)[c]);
    }
    // Level 0 is the image itself, bit for bit; the padding channel is zero.
    for (int y = 0; y < 19; ++y)
        for (int x = 0; x < 37; ++x) {
            for (int c = 0; c < 3; ++c) ASSERT_EQ(linear.texel(0, x, y)[c], image.at(x, y, c));
            ASSERT_EQ(linear.texel(0, x, y)[3], 0.0f);
        }
}

TEST(MipPyramid, ABorderKeepsTheLevelsAndStoresTexelsAroundThem) {
    // Levels with a border hold the same texels as without, bit for bit (built and from_levels);
    // the border starts at zero, is written through writable_texel() alone, and a bilinear sample
    // whose taps reach into it counts as inside.
    const Image image = random_image(13, 6, 3, 8);
    MipPyramidOptions options;
    const MipPyramid plain = MipPyramid::build(image, options);
    options.border = 2;
    MipPyramid bordered = MipPyramid::build(image, options);
    std::vector<Image> levels;
    for (int l = 0; l < plain.level_count(); ++l) levels.push_back(plain.level_image(l));
    const MipPyramid from_levels = MipPyramid::from_levels(levels, options).value();
    ASSERT_EQ(bordered.level_count(), plain.level_count());
    for (int l = 0; l < plain.level_count(); ++l) {
        const int w = plain.width(l), h = plain.height(l);
        EXPECT_EQ(bordered.level(l).border, 2);
        EXPECT_EQ(bordered.level(l).row_floats, (w + 4) * 4);
        for (int y = -2; y < h + 2; ++y)
            for (int x = -2; x < w + 2; ++x)
                for (int c = 0; c < 4; ++c) {
                    const bool on_level = x >= 0 && y >= 0 && x < w && y < h;
                    const float want = on_level ? plain.texel(l, x, y)[c] : 0.0f;
                    ASSERT_EQ(bordered.texel(l, x, y)[c], want) << l << " " << x << " " << y;
                    ASSERT_EQ(from_levels.texel(l, x, y)[c], want) << l << " " << x << " " << y;
                }
    }
    // Writing every border texel of one level leaves the others and the level itself as they were.
    const int w = bordered.width(1), h = bordered.height(1);
    for (int y = -2; y < h + 2; ++y)
        for (int x = -2; x < w + 2; ++x)
            if (x < 0 || y < 0 || x >= w || y >= h) bordered.writable_texel(1, x, y)[0] = 7;
    for (int l = 0; l < plain.level_count(); ++l)
        for (int y = -2; y < plain.height(l) + 2; ++y)
            for (int x = -2; x < plain.width(l) + 2; ++x) {
                const bool on_level = x >= 0 && y >= 0 && x < plain.width(l) && y < plain.height(l);
                const float want = on_level ? plain.texel(l, x, y)[0] : l == 1 ? 7.0f : 0.0f;
                ASSERT_EQ(bordered.texel(l, x, y)[0], want) << l << " " << x << " " << y;
            }
    EXPECT_EQ(bordered.level_image(1).pixels, plain.level_image(1).pixels);
}

TEST(MipPyramid, FromLevelsValidatesTheChain) {
    std::vector<Image> levels = {Image(4, 2, 1, 1.0f), Image(2, 1, 1, 2.0f), Image(1, 1, 1, 3.0f)};
    const Result<MipPyramid> ok = MipPyramid::from_levels(levels);
    ASSERT_TRUE(ok.ok());
    EXPECT_EQ(ok->texel(1, 1, 0)[0], 2.0f);
    levels[1] = Image(3, 1, 1);
    const Result<MipPyramid> bad = MipPyramid::from_levels(levels);
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("level 1"), std::string::npos) << bad.error().message;
    levels.pop_back();
    EXPECT_FALSE(MipPyramid::from_levels(levels).ok());
    EXPECT_FALSE(MipPyramid::from_levels({}).ok());
}

// A pyramid's levels written as a MIP-mapped file and read back (image/image_io.h) are the same
// pyramid: every texel, and so every lookup, bit for bit — what a texture cache of stored levels
// relies on.
TEST(MipPyramid, ItsLevelsThroughAMipMappedFileAreTheSamePyramid) {
    const MipPyramid built = MipPyramid::build(random_image(45, 23, 3, 5));
    std::vector<Image> levels;
    for (int l = 0; l < built.level_count(); ++l) levels.push_back(built.level_image(l));
    test::TempDir dir;
    ASSERT_TRUE(save_image_levels(levels, dir / "pyramid.exr").ok());
    const Result<std::vector<Image>> read = load_image_levels(dir / "pyramid.exr");
    ASSERT_TRUE(read.ok()) << read.error().message;
    const Result<MipPyramid> loaded = MipPyramid::from_levels(*read);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    ASSERT_EQ(loaded->level_count(), built.level_count());
    for (int l = 0; l < built.level_count(); ++l)
        EXPECT_EQ(loaded->level_image(l).pixels, built.level_image(l).pixels) << l;
    LookupOptions options;
    for (float d : {0.001f, 0.03f, 0.4f}) {
        const TextureCoords c{0.37f, 0.81f, d, 0.2f * d, -0.1f * d, 0.5f * d};
        float a[4], b[4];
        texture_lookup(built, c, options, a);
        texture_lookup(*loaded, c, options, b);
        EXPECT_EQ(std::vector<float>(a, a + 3), std::vector<float>(b, b + 3)) << d;
    }
}

TEST(WrapMode, IndicesAndParsing) {
    const int repeat[] = {3, 4, 0, 1, 2, 3, 4, 0};  // i = −2..5, n = 5
    const int clamp[] = {0, 0, 0, 1, 2, 3, 4, 4};
    const int mirror[] = {1, 0, 0, 1, 2, 3, 4, 4};
    for (int i = -2; i <= 5; ++i) {
        EXPECT_EQ(wrap_index(i, 5, WrapMode::repeat), repeat[i + 2]);
        EXPECT_EQ(wrap_index(i, 5, WrapMode::clamp), clamp[i + 2]);
        EXPECT_EQ(wrap_index(i, 5, WrapMode::mirror), mirror[i + 2]);
    }
    EXPECT_EQ(wrap_index(-11, 5, WrapMode::mirror), wrap_index(-11 + 10, 5, WrapMode::mirror));
    EXPECT_EQ(parse_wrap_mode("mirror"), WrapMode::mirror);
    EXPECT_FALSE(parse_wrap_mode("border").has_value());
}

}  // namespace
}  // namespace footprint
