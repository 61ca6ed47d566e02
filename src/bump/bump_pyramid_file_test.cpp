// Tests of bump pyramid files (bump/bump_pyramid_file.h): what is saved is read back bit for bit,
// marked as a bump pyramid, and a scaled lookup equals the lookup of the scaled slopes' pyramid.
#include "bump/bump_pyramid_file.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>

#include "core/test_temp_dir.h"
#include "image/image_io.h"

namespace footprint {
namespace {

BumpPyramid built(const Image& slopes, const BumpPyramidOptions& options = {}) {
    Result<BumpPyramid> pyramid = BumpPyramid::build(slopes, options);
    EXPECT_TRUE(pyramid) << pyramid.error().message;
    return std::move(*pyramid);
}

// Random slopes around a tilt, so that the offset and the moments are all exercised.
Image random_slopes(int width, int height, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> slope(0, 0.3f);
    Image slopes(width, height, 2);
    for (std::size_t i = 0; i < slopes.pixel_count(); ++i) {
        slopes.pixels[2 * i] = 0.2f + slope(rng);
        slopes.pixels[2 * i + 1] = -0.1f + slope(rng);
    }
    return slopes;
}

TEST(BumpPyramidFile, RoundTripsBitForBitWithItsOffsetAndWraps) {
    test::TempDir dir;
    BumpPyramidOptions options;
    options.wrap_s = WrapMode::clamp;
    options.wrap_t = WrapMode::mirror;
    options.micro_roughness = Sym2{0.01f, 0.002f, 0.02f};
    const BumpPyramid saved = built(random_slopes(37, 20, 1), options);
    ASSERT_TRUE(save_bump_pyramid(saved, dir / "bump.exr", 16));
    const std::optional<Vec2> offset = bump_pyramid_file_offset(dir / "bump.exr");
    ASSERT_TRUE(offset);
    EXPECT_EQ(offset->x, saved.slope_offset().x);
    EXPECT_EQ(offset->y, saved.slope_offset().y);

    Result<BumpPyramid> loaded = load_bump_pyramid(dir / "bump.exr");
    ASSERT_TRUE(loaded) << loaded.error().message;
    ASSERT_EQ(loaded->level_count(), saved.level_count());
    EXPECT_EQ(loaded->moments().wrap_s(), WrapMode::clamp);
    EXPECT_EQ(loaded->moments().wrap_t(), WrapMode::mirror);
    for (int l = 0; l < saved.level_count(); ++l) {
        const Image a = saved.moments().level_image(l), b = loaded->moments().level_image(l);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        for (std::size_t i = 0; i < a.pixels.size(); ++i)
            ASSERT_EQ(std::bit_cast<std::uint32_t>(a.pixels[i]),
                      std::bit_cast<std::uint32_t>(b.pixels[i]))
                << "level " << l << " value " << i;
    }
}

TEST(BumpPyramidFile, OtherFilesAreNotBumpPyramidsAndSayWhy) {
    test::TempDir dir;
    ASSERT_TRUE(save_image(Image(8, 8, 3, 0.5f), dir / "plain.exr"));
    EXPECT_FALSE(bump_pyramid_file_offset(dir / "plain.exr"));
    EXPECT_FALSE(bump_pyramid_file_offset(dir / "missing.exr"));
    Result<BumpPyramid> plain = load_bump_pyramid(dir / "plain.exr");
    ASSERT_FALSE(plain);
    EXPECT_NE(plain.error().message.find("plain.exr"), std::string::npos);
    EXPECT_NE(plain.error().message.find("not a bump pyramid"), std::string::npos);
    Result<BumpPyramid> missing = load_bump_pyramid(dir / "missing.exr");
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().message.find("missing.exr"), std::string::npos);
}

TEST(BumpPyramidFile, AFailedSaveLeavesNothing) {
    test::TempDir dir;
    const BumpPyramid pyramid = built(random_slopes(8, 8, 2));
    EXPECT_FALSE(save_bump_pyramid(pyramid, dir / "no" / "such" / "dir.exr"));
    EXPECT_FALSE(save_bump_pyramid(pyramid, dir / "bump.png"));
    EXPECT_EQ(dir.entries(), 0);
}

// Lookups scaled at lookup time (BumpLookupOptions) against the lookups of a pyramid built from
// the scaled slopes with the micro-roughness as K_0, and against scaled().
TEST(BumpPyramid, ScaledLookupsAreThoseOfTheScaledSlopes) {
    const Image slopes = random_slopes(64, 48, 3);
    const float strength = 0.6f;
    const Sym2 micro{0.0025f, 0.0005f, 0.004f};
    Image scaled_slopes = slopes;
    for (float& b : scaled_slopes.pixels) b *= strength;
    BumpPyramidOptions baked;
    baked.micro_roughness = micro;
    const BumpPyramid unit = built(slopes);
    const BumpPyramid want = built(scaled_slopes, baked);
    const BumpPyramid copy = unit.scaled(strength, micro);
    // Float rounding of the moments (each ~1e-7 relative to tr K + |μ|²), not a wrong factor:
    // a missing strength² or a dropped K_0 is off by > 1e-3.
    constexpr float kTolerance = 2e-6f;
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> position(0, 1), size(0.001f, 0.3f);
    for (int i = 0; i < 200; ++i) {
        const TextureCoords c{position(rng), position(rng), size(rng), 0, 0, size(rng) * 0.3f};
        const LookupOptions lookup;
        const SlopeStatistics a = bump_lookup(unit, c, BumpLookupOptions(lookup, strength, micro));
        for (const BumpPyramid* other : {&want, &copy}) {
            const SlopeStatistics b = bump_lookup(*other, c, lookup);
            EXPECT_NEAR(a.mean.x, b.mean.x, kTolerance);
            EXPECT_NEAR(a.mean.y, b.mean.y, kTolerance);
            EXPECT_NEAR(a.covariance.xx, b.covariance.xx, kTolerance);
            EXPECT_NEAR(a.covariance.xy, b.covariance.xy, kTolerance);
            EXPECT_NEAR(a.covariance.yy, b.covariance.yy, kTolerance);
        }
    }
}

}  // namespace
}  // namespace footprint
