// `footprint bake`'s KTX files read by Filament's own reader, image::KtxBundle (Debian's
// libfilament-dev, Filament 1.9; built only where CMake finds the package): the bundle Filament
// uploads (image/KtxUtility.h's createTexture) has footprint's levels, sizes, faces and texels.
#include <gtest/gtest.h>

#include <Imath/half.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bake_command.h"
#include "bump/bump_pyramid.h"
#include "bump/slope_map.h"
#include "core/test_temp_dir.h"
#include "envmap/env_convert.h"
#include "envmap/env_image_io.h"
#include "filament_ktx_reader.h"
#include "image/image_io.h"
#include "image/test_images.h"

namespace footprint {
namespace {

// Half floats keep 11 significant bits: a value is within 2^-11 of itself relative (and 2^-25
// absolute below half's normal range).
float half_tolerance(float v) {
    return std::abs(v) / 2048.0f + 3e-8f;
}

test::FilamentKtx load_bundle(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return test::read_with_filament(bytes.str());
}

// GL's enums, as Filament's KtxBundle names them.
constexpr std::uint32_t kHalfFloat = 0x140B, kRgba = 0x1908, kRgba16f = 0x881A;

int run_quietly(BakeCommandOptions options) {
    options.quiet = true;
    return run_bake_command(options);
}

// Texel (x, y) channel c of blob {level, 0, face}, RGBA16F rows first row first.
float blob_value(const test::FilamentKtx& bundle, int level, int face, int width, int x, int y,
                 int c) {
    const std::uint8_t* data = bundle.blobs[level][face].data();
    Imath::half h;
    std::uint16_t bits;
    std::memcpy(&bits, data + ((std::size_t(y) * width + x) * 4 + c) * 2, 2);
    h.setBits(bits);
    return h;
}

TEST(BakeFilament, KtxBundleReadsTheColourPyramid) {
    test::TempDir dir;
    ASSERT_TRUE(save_image(random_image(40, 24, 4, 3), dir / "in.png"));
    BakeCommandOptions options;
    options.kind = "color";
    options.input = dir / "in.png";
    options.output = dir / "albedo.ktx";
    ASSERT_EQ(run_quietly(options), 0);
    const MipPyramid pyramid = MipPyramid::build(*load_image(dir / "in.png"));
    const test::FilamentKtx bundle = load_bundle(options.output);
    EXPECT_EQ(bundle.gl_type, kHalfFloat);
    EXPECT_EQ(bundle.gl_format, kRgba);
    EXPECT_EQ(bundle.gl_internal_format, kRgba16f);
    EXPECT_EQ(bundle.width, 40u);
    EXPECT_EQ(bundle.height, 24u);
    EXPECT_FALSE(bundle.cubemap);
    EXPECT_EQ(bundle.array_length, 1u);
    ASSERT_EQ(int(bundle.levels), pyramid.level_count());
    EXPECT_EQ(bundle.orientation, "S=r,T=d");
    for (int l = 0; l < pyramid.level_count(); ++l) {
        EXPECT_EQ(bundle.blobs[l][0].size(), std::size_t(pyramid.width(l) * pyramid.height(l) * 8));
        const Image want = pyramid.level_image(l);
        for (const auto& [x, y] : {std::pair{0, 0},
                                   {want.width - 1, 0},
                                   {0, want.height - 1},
                                   {want.width / 2, want.height / 3}})
            for (int c = 0; c < 4; ++c) {
                const float v = want.at(x, y, c);
                EXPECT_NEAR(blob_value(bundle, l, 0, want.width, x, y, c), v, half_tolerance(v))
                    << "level " << l << " texel (" << x << ", " << y << ") channel " << c;
            }
    }
}

TEST(BakeFilament, KtxBundleReadsTheBumpMoments) {
    test::TempDir dir;
    Image slopes = random_image(20, 12, 2, 17);
    for (float& v : slopes.pixels) v = (v - 0.5f) * 0.6f;
    ImageSaveOptions linear;
    linear.encoding = ColorEncoding::linear;
    linear.bits = 16;
    ASSERT_TRUE(save_image(normals_from_slopes(slopes), dir / "n.png", linear));
    BakeCommandOptions options;
    options.kind = "bump";
    options.input = dir / "n.png";
    options.output = dir / "n.ktx";
    ASSERT_EQ(run_quietly(options), 0);
    ImageLoadOptions data;
    data.encoding = ColorEncoding::linear;
    const Result<BumpPyramid> pyramid =
        BumpPyramid::build(*slopes_from_normal_map(*load_image(dir / "n.png", data)));
    ASSERT_TRUE(pyramid);
    const MipPyramid& moments = pyramid->moments();
    const test::FilamentKtx a = load_bundle(dir / "n_a.ktx"), b = load_bundle(dir / "n_b.ktx");
    ASSERT_EQ(int(a.levels), moments.level_count());
    ASSERT_EQ(int(b.levels), moments.level_count());
    EXPECT_FALSE(a.slope_offset.empty());
    for (int l = 0; l < moments.level_count(); ++l) {
        const Image level = moments.level_image(l);
        const int x = level.width / 2, y = level.height / 2;
        for (int c = 0; c < 4; ++c) {
            const float va = level.at(x, y, c);
            EXPECT_NEAR(blob_value(a, l, 0, level.width, x, y, c), va, half_tolerance(va));
        }
        const float vb = level.at(x, y, 4);
        EXPECT_NEAR(blob_value(b, l, 0, level.width, x, y, 0), vb, half_tolerance(vb));
        EXPECT_EQ(blob_value(b, l, 0, level.width, x, y, 3), 1.0f);
    }
}

TEST(BakeFilament, KtxBundleReadsTheCubeMap) {
    test::TempDir dir;
    Image sky = random_image(64, 32, 3, 23);
    for (float& v : sky.pixels) v *= 20.0f;
    ASSERT_TRUE(save_image(sky, dir / "sky.exr"));
    BakeCommandOptions options;
    options.kind = "env";
    options.input = dir / "sky.exr";
    options.output = dir / "sky.ktx";
    options.size = 8;
    ASSERT_EQ(run_quietly(options), 0);
    EnvConvertOptions convert;
    convert.size = 8;
    Result<EnvironmentMap> cube = make_environment_map(
        *convert_environment(*load_environment({dir / "sky.exr"}), EnvLayout::cube, convert));
    ASSERT_TRUE(cube);
    const test::FilamentKtx bundle = load_bundle(options.output);
    EXPECT_TRUE(bundle.cubemap);
    EXPECT_EQ(bundle.width, 8u);
    EXPECT_TRUE(bundle.orientation.empty());  // a cube map's faces: GL's cube map rule
    ASSERT_EQ(bundle.levels, 4u);             // 8, 4, 2, 1
    for (int l = 0; l < 4; ++l)
        for (int f = 0; f < 6; ++f) {
            const int n = 8 >> l;
            ASSERT_EQ(bundle.blobs[l][f].size(), std::size_t(n * n * 8));
            const Image want = cube->face(f).level_image(l);
            for (int c = 0; c < 3; ++c) {
                const float v = want.at(n - 1, 0, c);
                EXPECT_NEAR(blob_value(bundle, l, f, n, n - 1, 0, c), v, half_tolerance(v))
                    << "level " << l << " face " << f;
            }
        }
}

}  // namespace
}  // namespace footprint
