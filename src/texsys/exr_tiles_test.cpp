#include "texsys/exr_tiles.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/test_temp_dir.h"

namespace footprint::texsys {
namespace {

namespace fs = std::filesystem;

// A tiled, MIP-mapped OpenEXR file of random texels, written by OpenImageIO (which stores the
// channels in OpenEXR's alphabetical order).
void write_mipmapped(const fs::path& file, int width, int height,
                     const std::vector<std::string>& names, OIIO::TypeDesc format, int tile) {
    OIIO::ImageSpec spec(width, height, static_cast<int>(names.size()), format);
    spec.channelnames = names;
    spec.tile_width = spec.tile_height = tile;
    spec.attribute("textureformat", "Plain Texture");  // with the next two: MIPMAP_LEVELS
    spec.attribute("openexr:levelmode", 1);
    spec.attribute("openexr:roundingmode", 0);
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> value(-2, 2);
    for (int level = 0;; ++level) {
        ASSERT_TRUE(
            out->open(file.string(), spec,
                      level == 0 ? OIIO::ImageOutput::Create : OIIO::ImageOutput::AppendMIPLevel))
            << out->geterror();
        std::vector<float> texels(spec.image_pixels() * spec.nchannels);
        for (float& v : texels) v = value(rng);
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, texels.data())) << out->geterror();
        if (spec.width == 1 && spec.height == 1) break;
        spec.width = std::max(1, spec.width / 2);
        spec.height = std::max(1, spec.height / 2);
        spec.full_width = spec.width;
        spec.full_height = spec.height;
    }
    ASSERT_TRUE(out->close());
}

// Level `level` of `file` as OpenImageIO reads it: floats, its channel order.
std::vector<float> read_by_oiio(const fs::path& file, int level, int& width, int& height) {
    auto in = OIIO::ImageInput::open(file.string());
    EXPECT_TRUE(in && in->seek_subimage(0, level));
    const OIIO::ImageSpec& spec = in->spec();
    width = spec.width;
    height = spec.height;
    std::vector<float> texels(spec.image_pixels() * spec.nchannels);
    EXPECT_TRUE(in->read_image(0, level, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, texels.data()));
    return texels;
}

std::vector<std::string> channel_names(const fs::path& file) {
    auto in = OIIO::ImageInput::open(file.string());
    return in ? in->spec().channelnames : std::vector<std::string>{};
}

// Every level of `file`, read whole through ExrTiles (tile by tile within), equals OpenImageIO's
// reading of it, bit for bit: the channels' order, half to float, the edge tiles.
void expect_levels_as_oiio_reads_them(const fs::path& file) {
    const std::vector<std::string> names = channel_names(file);
    const std::unique_ptr<ExrTiles> tiles = ExrTiles::open(file, 0, names);
    ASSERT_TRUE(tiles);
    auto in = OIIO::ImageInput::open(file.string());
    int levels = 0;
    while (in->seek_subimage(0, levels)) ++levels;
    for (int level = 0; level < levels; ++level) {
        int width = 0, height = 0;
        const std::vector<float> expected = read_by_oiio(file, level, width, height);
        std::vector<float> got(expected.size(), -99.0f);
        std::string why;
        ASSERT_TRUE(tiles->read(level, 0, width, 0, height, got.data(), why)) << why;
        ASSERT_EQ(got, expected) << file << " level " << level;
    }
}

TEST(ExrTiles, LevelsReadAsOpenImageIOReadsThem) {
    test::TempDir dir;
    // RGBA, stored A, B, G, R; half; tiles that do not divide the levels.
    write_mipmapped(dir / "rgba.exr", 100, 60, {"R", "G", "B", "A"}, OIIO::TypeDesc::HALF, 32);
    write_mipmapped(dir / "rgba32.exr", 100, 60, {"R", "G", "B", "A"}, OIIO::TypeDesc::FLOAT, 32);
    expect_levels_as_oiio_reads_them(dir / "rgba32.exr");
    expect_levels_as_oiio_reads_them(dir / "rgba.exr");
    // One float channel, tiles larger than the finest level's rows of them.
    write_mipmapped(dir / "y.exr", 128, 128, {"Y"}, OIIO::TypeDesc::FLOAT, 64);
    expect_levels_as_oiio_reads_them(dir / "y.exr");
}

TEST(ExrTiles, ReadsARegionOfTilesIntoItsRows) {
    test::TempDir dir;
    const fs::path file = dir / "rgb.exr";
    write_mipmapped(file, 96, 80, {"R", "G", "B"}, OIIO::TypeDesc::FLOAT, 16);
    int width = 0, height = 0;
    const std::vector<float> whole = read_by_oiio(file, 0, width, height);
    const std::unique_ptr<ExrTiles> tiles = ExrTiles::open(file, 0, channel_names(file));
    ASSERT_TRUE(tiles);
    // Tiles (1, 2) to (3, 4): x ∈ [16, 64), y ∈ [32, 80), the last row of tiles at the edge.
    const int x0 = 16, x1 = 64, y0 = 32, y1 = 80;
    std::vector<float> region((x1 - x0) * (y1 - y0) * 3);
    std::string why;
    ASSERT_TRUE(tiles->read(0, x0, x1, y0, y1, region.data(), why)) << why;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(region[((y - y0) * (x1 - x0) + (x - x0)) * 3 + c],
                          whole[(y * width + x) * 3 + c]);
}

TEST(ExrTiles, ThreadsReadOneFileAtOnce) {
    test::TempDir dir;
    const fs::path file = dir / "rgba.exr";
    write_mipmapped(file, 256, 256, {"R", "G", "B", "A"}, OIIO::TypeDesc::HALF, 32);
    int width = 0, height = 0;
    const std::vector<float> expected = read_by_oiio(file, 0, width, height);
    const std::unique_ptr<ExrTiles> tiles = ExrTiles::open(file, 0, channel_names(file));
    ASSERT_TRUE(tiles);
    std::vector<std::vector<float>> got(4, std::vector<float>(expected.size()));
    std::vector<std::thread> threads;
    std::vector<int> ok(got.size(), 0);
    for (std::size_t i = 0; i < got.size(); ++i)
        threads.emplace_back([&, i] {
            std::string why;
            ok[i] = tiles->read(0, 0, width, 0, height, got[i].data(), why);
        });
    for (std::thread& t : threads) t.join();
    for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_TRUE(ok[i]);
        EXPECT_EQ(got[i], expected);
    }
}

TEST(ExrTiles, RefusesWhatItDoesNotReadAsOpenImageIO) {
    test::TempDir dir;
    write_mipmapped(dir / "rgb.exr", 64, 64, {"R", "G", "B"}, OIIO::TypeDesc::FLOAT, 32);
    // A channel the file lacks.
    EXPECT_FALSE(ExrTiles::open(dir / "rgb.exr", 0, {"R", "G", "B", "A"}));
    // A part the file lacks.
    EXPECT_FALSE(ExrTiles::open(dir / "rgb.exr", 1, {"R", "G", "B"}));
    // A scanline file, and a file that is not OpenEXR.
    OIIO::ImageSpec spec(16, 16, 3, OIIO::TypeDesc::FLOAT);
    std::vector<float> texels(16 * 16 * 3, 0.5f);
    for (const char* name : {"scanlines.exr", "plain.tif"}) {
        auto out = OIIO::ImageOutput::create(name);
        ASSERT_TRUE(out && out->open((dir / name).string(), spec));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, texels.data()));
        out->close();
        EXPECT_FALSE(ExrTiles::open(dir / name, 0, {"R", "G", "B"})) << name;
    }
    EXPECT_FALSE(ExrTiles::open(dir / "missing.exr", 0, {"R", "G", "B"}));
}

TEST(ExrTiles, ATruncatedTileIsAFailedReadWithOpenExrsReason) {
    test::TempDir dir;
    const fs::path file = dir / "rgb.exr";
    write_mipmapped(file, 128, 128, {"R", "G", "B"}, OIIO::TypeDesc::FLOAT, 32);
    const std::unique_ptr<ExrTiles> tiles = ExrTiles::open(file, 0, channel_names(file));
    ASSERT_TRUE(tiles);
    fs::resize_file(file, fs::file_size(file) / 2);
    // Level 0 is written first: its last tiles are gone, the coarse levels after it too.
    std::vector<float> texels(128 * 128 * 3);
    std::string why;
    EXPECT_FALSE(tiles->read(0, 0, 128, 0, 128, texels.data(), why));
    EXPECT_NE(why.find("OpenEXR"), std::string::npos) << why;
}

}  // namespace
}  // namespace footprint::texsys
