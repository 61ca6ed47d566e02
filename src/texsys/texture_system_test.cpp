#include "texture_system.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <thread>
#include <vector>

#include "bump/bump_pyramid_file.h"
#include "bump/slope_map.h"
#include "core/test_temp_dir.h"
#include "envmap/env_image_io.h"
#include "envmap/env_pyramid_file.h"
#include "image/image_io.h"
#include "image/test_images.h"
#include "texsys/tile_cache.h"
#include "texture/texture_lookup.h"

namespace footprint {
namespace {

constexpr TextureFilter kFilters[] = {TextureFilter::nearest, TextureFilter::bilinear,
                                      TextureFilter::trilinear, TextureFilter::footprint_assembly,
                                      TextureFilter::ewa};

std::unique_ptr<TextureSystem> make_system(const TextureSystemOptions& options = {}) {
    Result<std::unique_ptr<TextureSystem>> made = TextureSystem::create(options);
    EXPECT_TRUE(made) << made.error().message;
    return std::move(*made);
}

// Lookups as a renderer makes them: magnified to strongly minified, isotropic to 16:1, anywhere
// on the texture and beyond its edges.
std::vector<TextureCoords> lookups(int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> position(-0.5f, 1.5f), unit(-1, 1), scale(-11, -2);
    std::vector<TextureCoords> all;
    for (int i = 0; i < count; ++i) {
        const float size = std::exp2(scale(rng)), aniso = 1 + 7.5f * (unit(rng) + 1);
        const float angle = 3.2f * unit(rng);
        all.push_back({position(rng), position(rng), size * aniso * std::cos(angle),
                       size * aniso * std::sin(angle), -size * std::sin(angle),
                       size * std::cos(angle)});
    }
    return all;
}

std::uint32_t bits(float v) {
    return std::bit_cast<std::uint32_t>(v);
}

// Every filter's lookups of `file` through `ts` against texture_lookup() of `pyramid` on the
// same coordinates (every channel): bit for bit where tolerance is 0, else within it.
void expect_lookups_of_pyramid(TextureSystem& ts, const std::string& file,
                               const MipPyramid& pyramid, const std::vector<TextureCoords>& coords,
                               float tolerance = 0) {
    TextureHandle* handle = ts.handle(file);
    for (TextureFilter filter : kFilters) {
        LookupOptions lookup;
        lookup.filter = filter;
        for (const TextureCoords& c : coords) {
            float want[MipPyramid::kMaxChannels], got[MipPyramid::kMaxChannels];
            texture_lookup(pyramid, c, lookup, want);
            ASSERT_TRUE(ts.texture(handle, c, lookup, std::span(got, pyramid.channels())));
            for (int k = 0; k < pyramid.channels(); ++k) {
                if (tolerance == 0) {
                    ASSERT_EQ(bits(got[k]), bits(want[k]))
                        << to_string(filter) << " at (" << c.s << ", " << c.t << "): " << got[k]
                        << " against " << want[k];
                } else {
                    ASSERT_NEAR(got[k], want[k], tolerance) << to_string(filter);
                }
            }
        }
    }
}

// A MIP chain of `image` (a box pyramid) as level images, and written as a tiled MIP-mapped EXR.
std::vector<Image> levels_of(const Image& image) {
    const MipPyramid pyramid = MipPyramid::build(image);
    std::vector<Image> levels;
    for (int l = 0; l < pyramid.level_count(); ++l) levels.push_back(pyramid.level_image(l));
    return levels;
}

TEST(TextureSystem, StoredLevelsLookUpBitForBitAsTheirPyramid) {
    test::TempDir dir;
    const std::vector<Image> levels = levels_of(random_image(300, 200, 3, 1));
    LevelsSaveOptions save;
    save.wrap_modes = "periodic,clamp";
    ASSERT_TRUE(save_image_levels(levels, dir / "stored.exr", save));
    MipPyramidOptions wrap;
    wrap.wrap_t = WrapMode::clamp;
    const MipPyramid pyramid = MipPyramid::from_levels(levels, wrap).value();

    TextureSystemOptions options;
    options.tile_size = 16;  // many tiles, taps across their edges
    auto ts = make_system(options);
    TextureHandle* file = ts->handle((dir / "stored.exr").string());
    Result<TextureInfo> info = ts->info(file);
    ASSERT_TRUE(info) << info.error().message;
    EXPECT_TRUE(info->tiled);
    EXPECT_EQ(info->width, 300);
    EXPECT_EQ(info->levels, pyramid.level_count());
    EXPECT_EQ(info->wrap_t, WrapMode::clamp);
    expect_lookups_of_pyramid(*ts, (dir / "stored.exr").string(), pyramid, lookups(300, 2));
    EXPECT_EQ(ts->stats().bytes_in_memory, 0u);
}

// OpenImageIO's own maketx output (a tiled MIP-mapped TIFF of its own tile size, 8-bit sRGB
// here) is read tile by tile, its levels as stored and decoded as load_image_levels() decodes them.
TEST(TextureSystem, OpenImageIOsMaketxFilesAreReadAsStored) {
    // 8-bit codes are decoded through OpenImageIO's float conversion here and through a table in
    // load_image_levels(): the same sRGB curve, a few ulp of values ≤ 1 apart (measured 2.4e-7).
    constexpr float kSrgbDecodeTolerance = 2e-6f;
    test::TempDir dir;
    const Image image = random_image(200, 120, 3, 12);
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf source(spec, const_cast<float*>(image.pixels.data()));
    OIIO::ImageSpec config;
    config.attribute("maketx:filtername", "box");
    config.attribute("wrapmodes", "periodic,periodic");
    config.set_format(OIIO::TypeDesc::UINT8);
    config.tile_width = config.tile_height = 32;
    const std::string tx = (dir / "maketx.tx").string();
    ASSERT_TRUE(
        OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, source, tx, config))
        << OIIO::geterror();
    Result<std::vector<Image>> levels = load_image_levels(tx);
    ASSERT_TRUE(levels) << levels.error().message;
    const MipPyramid pyramid = MipPyramid::from_levels(*levels).value();

    auto ts = make_system();  // 64² tiles over the file's 32² ones
    Result<TextureInfo> info = ts->info(tx);
    ASSERT_TRUE(info) << info.error().message;
    EXPECT_TRUE(info->tiled);
    EXPECT_EQ(info->levels, pyramid.level_count());
    expect_lookups_of_pyramid(*ts, tx, pyramid, lookups(200, 13), kSrgbDecodeTolerance);
}

// A tiled MIP-mapped TIFF whose alpha is unassociated (straight, as PNG's is): read tile by tile
// with its colour as stored, as load_image_levels() reads it, not multiplied by alpha on the way.
TEST(TextureSystem, StoredStraightAlphaIsReadAsStored) {
    constexpr float kSrgbDecodeTolerance = 2e-6f;  // as in OpenImageIOsMaketxFilesAreReadAsStored
    test::TempDir dir;
    const std::string tif = (dir / "straight.tif").string();
    {
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(tif);
        ASSERT_TRUE(out);
        OIIO::ImageSpec spec(64, 32, 4, OIIO::TypeDesc::UINT8);
        spec.tile_width = spec.tile_height = 16;
        spec.attribute("oiio:UnassociatedAlpha", 1);
        spec.attribute("textureformat", "Plain Texture");  // its subimages are MIP levels
        auto mode = OIIO::ImageOutput::Create;
        for (unsigned level = 0;; ++level) {
            ASSERT_TRUE(out->open(tif, spec, mode)) << out->geterror();
            const Image texels = random_image(spec.width, spec.height, 4, 40 + level);
            ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, texels.pixels.data()));
            if (spec.width == 1 && spec.height == 1) break;
            spec.width = std::max(1, spec.width / 2);
            spec.height = std::max(1, spec.height / 2);
            spec.full_width = spec.width;
            spec.full_height = spec.height;
            mode = OIIO::ImageOutput::AppendSubimage;
        }
        ASSERT_TRUE(out->close());
    }
    Result<std::vector<Image>> levels = load_image_levels(tif);
    ASSERT_TRUE(levels) << levels.error().message;
    const MipPyramid pyramid = MipPyramid::from_levels(*levels).value();

    auto ts = make_system();
    Result<TextureInfo> info = ts->info(tif);
    ASSERT_TRUE(info) << info.error().message;
    ASSERT_TRUE(info->tiled);
    ASSERT_EQ(info->channels, 4);
    expect_lookups_of_pyramid(*ts, tif, pyramid, lookups(200, 41), kSrgbDecodeTolerance);
}

// Textures four times the cache: evicted and read again, with the same results as a cache that
// holds them all, and resident texels within the limit plus the pinned tiles.
TEST(TextureSystem, ASmallCacheKeepsItsBoundAndGivesTheUnboundedResults) {
    test::TempDir dir;
    std::vector<std::string> files;
    LevelsSaveOptions save;
    save.tile_size = 32;
    for (int i = 0; i < 2; ++i) {  // 2 × 512² RGBA texels ≈ 5.6 MiB of float pyramids
        files.push_back((dir / ("big" + std::to_string(i) + ".exr")).string());
        ASSERT_TRUE(
            save_image_levels(levels_of(random_image(512, 512, 3, 10 + i)), files.back(), save));
    }
    TextureSystemOptions small;
    small.max_memory_mb = 1;
    small.tile_size = 32;
    auto bounded = make_system(small);
    auto unbounded = make_system();
    LookupOptions lookup;
    for (int pass = 0; pass < 2; ++pass) {
        for (const TextureCoords& c : lookups(1000, 3 + pass)) {
            for (const std::string& file : files) {
                float want[3], got[3];
                ASSERT_TRUE(unbounded->texture(file, c, lookup, want));
                ASSERT_TRUE(bounded->texture(file, c, lookup, got));
                for (int k = 0; k < 3; ++k) ASSERT_EQ(bits(got[k]), bits(want[k]));
            }
        }
    }
    const TextureSystemStats s = bounded->stats();
    const TextureSystemStats all = unbounded->stats();
    EXPECT_EQ(s.files, 2u);
    EXPECT_GT(all.peak_bytes, 4u << 20);  // what the lookups touched
    // A 32² tile is 16 KiB: the limit, plus this thread's micro-cache and one lookup's pins.
    EXPECT_LE(s.peak_bytes, (1u << 20) + 64 * 16384u);
    EXPECT_GT(s.tiles_loaded, all.tiles_loaded);  // tiles evicted and read again
    EXPECT_EQ(s.tile_misses, s.tiles_loaded);
    EXPECT_GT(s.tile_hits + s.tile_misses, 0u);
}

TEST(TextureSystem, FilesWithoutLevelsAreBuiltInMemoryOrInTheCacheFolder) {
    test::TempDir dir;
    const Image image = random_image(128, 64, 3, 4);
    ASSERT_TRUE(save_image(image, dir / "plain.png"));
    const std::string png = (dir / "plain.png").string();
    const MipPyramid pyramid = MipPyramid::build(*load_image(png));

    TextureSystemOptions memory_options;
    memory_options.build_in_memory = true;
    auto in_memory = make_system(memory_options);
    TextureSystemOptions cached_options;
    cached_options.cache_dir = dir / "cache";
    auto cached = make_system(cached_options);
    expect_lookups_of_pyramid(*in_memory, png, pyramid, lookups(200, 5));
    // The cached file's levels are the built pyramid's, as float, with its prefilter variances
    // (which EWA reads): the same bits.
    expect_lookups_of_pyramid(*cached, png, pyramid, lookups(200, 5));
    EXPECT_FALSE(in_memory->info(png)->tiled);
    // A pyramid held whole is counted as resident, as tiles are.
    const TextureSystemStats held = in_memory->stats();
    EXPECT_GT(held.bytes_in_memory, 128u * 64 * 16);
    EXPECT_GE(held.bytes_resident, held.bytes_in_memory);
    EXPECT_GE(held.peak_bytes, held.bytes_in_memory);
    EXPECT_TRUE(cached->info(png)->tiled);
    EXPECT_EQ(cached->stats().bytes_in_memory, 0u);
    int cache_files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir / "cache")) {
        ++cache_files;
        EXPECT_EQ(entry.path().extension(), ".exr");
    }
    EXPECT_EQ(cache_files, 1);
    // A second system finds the cached file and builds nothing.
    const auto written = std::filesystem::last_write_time(
        std::filesystem::directory_iterator(dir / "cache")->path());
    auto again = make_system(cached_options);
    EXPECT_TRUE(again->info(png)->tiled);
    EXPECT_EQ(std::filesystem::last_write_time(
                  std::filesystem::directory_iterator(dir / "cache")->path()),
              written);
}

// XDG_CACHE_HOME set to `value` (unset where null) while in scope.
class ScopedCacheHome {
  public:
    explicit ScopedCacheHome(const char* value) {
        if (const char* was = std::getenv("XDG_CACHE_HOME")) was_ = was;
        if (value != nullptr)
            ::setenv("XDG_CACHE_HOME", value, 1);
        else
            ::unsetenv("XDG_CACHE_HOME");
    }
    ~ScopedCacheHome() {
        if (was_)
            ::setenv("XDG_CACHE_HOME", was_->c_str(), 1);
        else
            ::unsetenv("XDG_CACHE_HOME");
    }
    ScopedCacheHome(const ScopedCacheHome&) = delete;
    ScopedCacheHome& operator=(const ScopedCacheHome&) = delete;

  private:
    std::optional<std::string> was_;
};

// The files in `dir`, temporary ones too.
std::vector<std::filesystem::path> files_in(const std::filesystem::path& dir) {
    std::vector<std::filesystem::path> files;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
        files.push_back(entry.path());
    return files;
}

// A plain file (no stored levels) is bounded by max_memory_mb by default: its pyramid is built
// into $XDG_CACHE_HOME/footprint and read tile by tile, with the in-memory pyramid's bits for
// every filter, resident texels within the bound; a second system opens the cached file.
TEST(TextureSystem, PlainFilesAreBuiltIntoTheDefaultCacheFolderAndStayWithinTheBound) {
    test::TempDir dir;
    const ScopedCacheHome home((dir / "xdg").c_str());
    EXPECT_EQ(default_texture_cache_dir(), dir / "xdg" / "footprint");
    const Image image = random_image(512, 384, 3, 31);  // 4 MiB of float pyramid
    const std::string exr = (dir / "plain.exr").string();
    ASSERT_TRUE(save_image(image, exr));
    TextureSystemOptions small;
    small.max_memory_mb = 1;
    small.tile_size = 16;
    small.downsample = DownsampleFilter::tent;  // its prefilter variances are not the box's
    auto ts = make_system(small);
    const std::string name = exr;
    MipPyramidOptions tent;
    tent.downsample = DownsampleFilter::tent;
    const MipPyramid built = MipPyramid::build(image, tent);
    expect_lookups_of_pyramid(*ts, name, built, lookups(400, 32));
    const Result<TextureInfo> info = ts->info(name);
    ASSERT_TRUE(info) << info.error().message;
    EXPECT_TRUE(info->tiled);
    const TextureSystemStats s = ts->stats();
    EXPECT_EQ(s.bytes_in_memory, 0u);
    EXPECT_GT(s.tiles_loaded, 0u);
    // 1 MiB, plus this thread's micro-cache and one lookup's pinned tiles (16² RGB tiles: 4 KiB).
    EXPECT_LE(s.peak_bytes, (1u << 20) + 256 * 4096u);
    EXPECT_TRUE(ts->take_warnings().empty());
    const std::vector<std::filesystem::path> cached = files_in(dir / "xdg" / "footprint");
    ASSERT_EQ(cached.size(), 1u);  // no temporary file left
    EXPECT_EQ(cached[0].extension(), ".exr");
    const auto written = std::filesystem::last_write_time(cached[0]);
    auto again = make_system(small);
    expect_lookups_of_pyramid(*again, name, built, lookups(50, 33));
    EXPECT_EQ(std::filesystem::last_write_time(cached[0]), written);  // opened, not rebuilt
    EXPECT_EQ(files_in(dir / "xdg" / "footprint").size(), 1u);
    // build_in_memory keeps the pyramid whole, as before the default folder, and counts it.
    TextureSystemOptions memory = small;
    memory.build_in_memory = true;
    auto whole = make_system(memory);
    expect_lookups_of_pyramid(*whole, name, built, lookups(50, 34));
    EXPECT_FALSE(whole->info(name)->tiled);
    EXPECT_GT(whole->stats().bytes_in_memory, 512u * 384 * 16);
    EXPECT_GE(whole->stats().peak_bytes, whole->stats().bytes_in_memory);
    // A changed source (size, time) is built again, beside the first.
    ASSERT_TRUE(save_image(random_image(256, 256, 3, 35), exr));
    auto changed = make_system(small);
    EXPECT_EQ(changed->info(name)->width, 256);
    EXPECT_EQ(files_in(dir / "xdg" / "footprint").size(), 2u);
}

// A default cache folder that cannot be made is a warning, never an error: pyramids are built in
// memory, with the same results. A cache_dir given with build_in_memory is refused.
TEST(TextureSystem, AnUnusableDefaultCacheFolderFallsBackToMemoryWithAWarning) {
    test::TempDir dir;
    { std::ofstream(dir / "file") << "x"; }
    const ScopedCacheHome home((dir / "file").c_str());  // footprint/ cannot be made in a file
    const Image image = random_image(64, 48, 3, 36);
    const std::string exr = (dir / "plain.exr").string();
    ASSERT_TRUE(save_image(image, exr));
    auto ts = make_system();
    const std::vector<Error> warnings = ts->take_warnings();
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].message.find("file"), std::string::npos) << warnings[0].message;
    EXPECT_NE(warnings[0].message.find("in memory"), std::string::npos) << warnings[0].message;
    expect_lookups_of_pyramid(*ts, exr, MipPyramid::build(image), lookups(100, 37));
    EXPECT_FALSE(ts->info(exr)->tiled);
    EXPECT_TRUE(ts->take_errors().empty());
    EXPECT_TRUE(ts->take_warnings().empty());  // once

    TextureSystemOptions both;
    both.cache_dir = dir / "cache";
    both.build_in_memory = true;
    EXPECT_FALSE(TextureSystem::create(both));
}

// Systems building one file's pyramid into one folder at the same time (as processes do) each
// write a complete file under a name of its own and rename it: one cache file, no temporary ones,
// and every system's lookups right.
TEST(TextureSystem, ConcurrentBuildsOfOneCacheFileLeaveOneCompleteFile) {
    test::TempDir dir;
    const Image image = random_image(256, 256, 4, 38);
    const std::string exr = (dir / "plain.exr").string();
    ASSERT_TRUE(save_image(image, exr));
    TextureSystemOptions options;
    options.cache_dir = dir / "cache";
    options.tile_size = 32;
    constexpr int kSystems = 4;
    std::vector<std::unique_ptr<TextureSystem>> systems;
    for (int i = 0; i < kSystems; ++i) systems.push_back(make_system(options));
    std::vector<std::thread> threads;
    std::atomic<int> tiled{0};
    for (int i = 0; i < kSystems; ++i)
        threads.emplace_back([&, i] {
            if (Result<TextureInfo> info = systems[i]->info(exr); info && info->tiled) ++tiled;
        });
    for (std::thread& t : threads) t.join();
    EXPECT_EQ(tiled, kSystems);
    const MipPyramid pyramid = MipPyramid::build(image);
    for (const auto& ts : systems) expect_lookups_of_pyramid(*ts, exr, pyramid, lookups(30, 39));
    EXPECT_EQ(files_in(dir / "cache").size(), 1u);
}

TEST(TextureSystem, AMissingOrCorruptFileIsAnErrorNamingItReportedOnce) {
    test::TempDir dir;
    {
        std::ofstream corrupt(dir / "corrupt.exr", std::ios::binary);
        corrupt << "v/1\x01 this is not an OpenEXR file";
    }
    auto ts = make_system();
    const TextureCoords c{0.5f, 0.5f, 0.01f, 0, 0, 0.01f};
    for (const char* name : {"missing.png", "corrupt.exr"}) {
        const std::string file = (dir / name).string();
        float out[3] = {9, 9, 9};
        Status s = ts->texture(file, c, {}, out);
        ASSERT_FALSE(s);
        EXPECT_NE(s.error().message.find("'" + file + "'"), std::string::npos) << s.error().message;
        EXPECT_FALSE(ts->info(file));
        const float pink[3] = {1, 0, 1};
        for (int i = 0; i < 100; ++i) EXPECT_TRUE(ts->texture(file, c, {}, out, pink));
        EXPECT_EQ(out[0], 1.0f);
        EXPECT_EQ(out[1], 0.0f);
        EXPECT_EQ(out[2], 1.0f);
    }
    const std::vector<Error> errors = ts->take_errors();
    ASSERT_EQ(errors.size(), 2u);  // once per file, not per lookup
    EXPECT_NE(errors[0].message.find("no such file"), std::string::npos) << errors[0].message;
    EXPECT_TRUE(ts->take_errors().empty());
    EXPECT_EQ(ts->stats().files, 2u);
}

TEST(TextureSystem, UdimNamesResolveTheTileOfTheCoordinates) {
    test::TempDir dir;
    Image red(8, 8, 3), green(8, 8, 3);
    for (std::size_t i = 0; i < red.pixels.size(); i += 3)
        red.pixels[i] = 1, green.pixels[i + 1] = 1;
    ASSERT_TRUE(save_image(red, dir / "paint.1001.exr"));
    ASSERT_TRUE(save_image(green, dir / "paint.1012.exr"));  // u tile 1, v tile 1
    auto ts = make_system();
    const std::string name = (dir / "paint.<UDIM>.exr").string();
    float out[3];
    ASSERT_TRUE(ts->texture(name, {0.5f, 0.5f, 0.01f, 0, 0, 0.01f}, {}, out));
    EXPECT_FLOAT_EQ(out[0], 1);
    EXPECT_FLOAT_EQ(out[1], 0);
    ASSERT_TRUE(ts->texture(name, {1.5f, 1.25f, 0.01f, 0, 0, 0.01f}, {}, out));
    EXPECT_FLOAT_EQ(out[0], 0);
    EXPECT_FLOAT_EQ(out[1], 1);
    Status none = ts->texture(name, {2.5f, 0.5f, 0.01f, 0, 0, 0.01f}, {}, out);
    ASSERT_FALSE(none);
    EXPECT_NE(none.error().message.find("paint.1003.exr"), std::string::npos)
        << none.error().message;
    EXPECT_FALSE(ts->texture(name, {-0.5f, 0.5f, 0.01f, 0, 0, 0.01f}, {}, out));
    EXPECT_EQ(ts->info(name)->width, 8);
}

// Threads sharing one small cache get what one thread alone gets.
TEST(TextureSystem, ConcurrentLookupsGiveTheSingleThreadedResults) {
    test::TempDir dir;
    const std::string file = (dir / "shared.exr").string();
    LevelsSaveOptions save;
    save.tile_size = 32;
    ASSERT_TRUE(save_image_levels(levels_of(random_image(512, 256, 4, 6)), file, save));
    TextureSystemOptions options;
    options.max_memory_mb = 1;
    options.tile_size = 32;
    auto ts = make_system(options);
    const std::vector<TextureCoords> coords = lookups(1000, 7);
    std::vector<float> want(coords.size() * 4);
    {
        auto alone = make_system();
        for (std::size_t i = 0; i < coords.size(); ++i)
            ASSERT_TRUE(alone->texture(file, coords[i], {}, {&want[4 * i], 4}));
    }
    constexpr int kThreads = 4;
    std::vector<std::vector<float>> got(kThreads, std::vector<float>(want.size()));
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([&, t] {
            for (std::size_t n = 0; n < coords.size(); ++n) {
                constexpr std::size_t kSteps[kThreads] = {1, 7919, 7927, 7933};  // prime to 1000
                const std::size_t i = (n * kSteps[t]) % coords.size();  // each its own order
                if (!ts->texture(file, coords[i], {}, {&got[t][4 * i], 4})) return;
            }
        });
    }
    for (std::thread& thread : threads) thread.join();
    for (int t = 0; t < kThreads; ++t)
        for (std::size_t i = 0; i < want.size(); ++i)
            ASSERT_EQ(bits(got[t][i]), bits(want[i])) << "thread " << t << " value " << i;
    EXPECT_LE(ts->stats().peak_bytes, (1u << 20) + kThreads * 64 * 16384u);
}

TEST(TextureSystem, EnvironmentAndBumpLookupsAreTheDirectOnes) {
    test::TempDir dir;
    const std::string sky = (dir / "sky.exr").string();
    ASSERT_TRUE(save_image(random_image(64, 32, 3, 8), sky));
    const EnvironmentMap map = load_environment({sky}).value();
    auto ts = make_system();
    const Vec3 r{0.3f, 0.5f, -0.8f}, dx{0.02f, 0, 0}, dy{0, 0.01f, 0.005f};
    float want[3], got[3];
    environment_lookup(map, r, dx, dy, EnvLookupOptions{}, want);
    ASSERT_TRUE(ts->environment(sky, r, dx, dy, EnvLookupOptions{}, got));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(bits(got[k]), bits(want[k]));
    Result<TextureSystem::EnvironmentShape> shape = ts->environment_shape(sky);
    ASSERT_TRUE(shape);
    const EnvFootprint footprint =
        compute_env_footprint(shape->layout, shape->texel_scale, r, dx, dy);
    environment_lookup(map, footprint, LookupOptions{}, want);
    ASSERT_TRUE(ts->environment(sky, footprint, LookupOptions{}, got));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(bits(got[k]), bits(want[k]));

    const std::string normals = (dir / "normals.png").string();
    Image slopes = random_image(32, 32, 2, 9);
    for (float& v : slopes.pixels) v = v - 0.5f;
    ASSERT_TRUE(save_image(normals_from_slopes(slopes), normals, {ColorEncoding::linear, 16}));
    const BumpPyramid bump = BumpPyramid::build(*load_slope_map(normals)).value();
    const TextureCoords c{0.3f, 0.6f, 0.05f, 0.01f, -0.01f, 0.03f};
    const SlopeStatistics expected = bump_lookup(bump, c, LookupOptions{});
    SlopeStatistics statistics;
    ASSERT_TRUE(ts->bump(normals, c, LookupOptions{}, &statistics));
    EXPECT_EQ(statistics.mean.x, expected.mean.x);
    EXPECT_EQ(statistics.covariance.xy, expected.covariance.xy);
    EXPECT_FALSE(ts->bump((dir / "none.png").string(), c, {}, &statistics));
    EXPECT_FALSE(ts->environment((dir / "none.hdr").string(), r, dx, dy, {}, got));
}

// Bump maps through tiles: a bump pyramid file, and a normal map built once into the cache folder,
// are read tile by tile through a small cache with the whole pyramid's results, bit for bit, also
// when a lookup scales them (strength, micro-roughness).
TEST(TextureSystem, BumpPyramidFilesAreReadTileByTileAsTheirPyramid) {
    test::TempDir dir;
    Image slopes = random_image(200, 120, 2, 12);
    for (float& v : slopes.pixels) v = 0.8f * (v - 0.4f);
    const std::string normals = (dir / "normals.exr").string();
    ASSERT_TRUE(save_image(normals_from_slopes(slopes), normals));
    const BumpPyramid bump = BumpPyramid::build(*load_slope_map(normals)).value();
    const std::string stored = (dir / "bump.exr").string();
    ASSERT_TRUE(save_bump_pyramid(bump, stored, 16));

    TextureSystemOptions small;
    small.max_memory_mb = 1;
    small.tile_size = 16;
    small.cache_dir = dir / "cache";
    auto ts = make_system(small);
    const BumpLookupOptions scaled(LookupOptions{}, 0.7f, Sym2{0.01f, 0.001f, 0.02f});
    for (const std::string& name : {stored, normals}) {
        BumpHandle* handle = ts->bump_handle(name);
        Result<TextureInfo> info = ts->info(handle);
        ASSERT_TRUE(info) << info.error().message;
        EXPECT_TRUE(info->tiled) << name;
        EXPECT_EQ(info->channels, 5);
        for (TextureFilter filter : kFilters) {
            for (const BumpLookupOptions& base : {BumpLookupOptions{}, scaled}) {
                BumpLookupOptions options = base;
                options.filter = filter;
                for (const TextureCoords& c : lookups(300, 13)) {
                    const SlopeStatistics want = bump_lookup(bump, c, options);
                    SlopeStatistics got;
                    ASSERT_TRUE(ts->bump(handle, c, options, &got));
                    ASSERT_EQ(bits(got.mean.x), bits(want.mean.x)) << name << to_string(filter);
                    ASSERT_EQ(bits(got.mean.y), bits(want.mean.y));
                    ASSERT_EQ(bits(got.covariance.xx), bits(want.covariance.xx));
                    ASSERT_EQ(bits(got.covariance.xy), bits(want.covariance.xy));
                    ASSERT_EQ(bits(got.covariance.yy), bits(want.covariance.yy));
                }
            }
        }
    }
    EXPECT_EQ(ts->stats().bytes_in_memory, 0u);  // neither held whole
    EXPECT_GT(ts->stats().tiles_loaded, 0u);
    // The normal map's pyramid went into the cache folder once; a second system opens it there.
    int cached = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir / "cache")) {
        ++cached;
        EXPECT_TRUE(bump_pyramid_file_offset(entry.path())) << entry.path();
    }
    EXPECT_EQ(cached, 1);
    auto again = make_system(small);
    ASSERT_TRUE(again->info(again->bump_handle(normals)));
    EXPECT_EQ(again->stats().bytes_in_memory, 0u);
    // Whole, for a GPU: the file's pyramid.
    Result<std::shared_ptr<const BumpPyramid>> whole = ts->bump_pyramid(ts->bump_handle(stored));
    ASSERT_TRUE(whole);
    EXPECT_EQ((*whole)->slope_offset().x, bump.slope_offset().x);
    EXPECT_EQ((*whole)->moments().level_image(0).pixels, bump.moments().level_image(0).pixels);
}

// Rays as a renderer casts them at an environment: anywhere, a pixel's to a hemisphere's spread,
// up to 16:1 anisotropic.
std::vector<EnvRayDifferential> env_rays(int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> normal;
    std::uniform_real_distribution<float> scale(-10, 0), aniso(0, 4);
    std::vector<EnvRayDifferential> all;
    for (int i = 0; i < count; ++i) {
        const Vec3 r = normalize(Vec3{normal(rng), normal(rng), normal(rng)});
        const float s = std::exp2(scale(rng)), t = s * std::exp2(-aniso(rng));
        all.push_back({r, s * Vec3{normal(rng), normal(rng), normal(rng)},
                       t * Vec3{normal(rng), normal(rng), normal(rng)}});
    }
    return all;
}

// Environment maps through tiles: environment pyramid files of a lat-long map (with its polar
// caps) and a cube map, each larger than the cache, look up through a 1 MiB cache as the maps they
// hold, bit for bit (both forms and point samples), within the cache's bound; a plain file with a
// cache folder has its pyramids kept there once and read tile by tile, also by a second system.
TEST(TextureSystem, EnvironmentMapsAreReadTileByTileWithinTheBound) {
    test::TempDir dir;
    const std::string sky = (dir / "sky.exr").string();
    ASSERT_TRUE(save_image(random_image(512, 256, 3, 14), sky));
    std::vector<std::string> cross_faces;
    for (int f = 0; f < 6; ++f) {
        cross_faces.push_back((dir / ("face" + std::to_string(f) + ".exr")).string());
        ASSERT_TRUE(save_image(random_image(128, 128, 3, 20 + f), cross_faces.back()));
    }
    std::vector<std::filesystem::path> face_paths(cross_faces.begin(), cross_faces.end());
    const EnvironmentMap latlong = load_environment({sky}).value();
    const EnvironmentMap cube = load_environment(face_paths).value();
    ASSERT_EQ(cube.layout(), EnvLayout::cube);
    const std::string latlong_file = (dir / "sky_env.exr").string();
    const std::string cube_file = (dir / "cube_env.exr").string();
    ASSERT_TRUE(save_environment_pyramid(latlong, latlong_file, 16));
    ASSERT_TRUE(save_environment_pyramid(cube, cube_file, 32));  // tiles unlike the cache's

    TextureSystemOptions small;
    small.max_memory_mb = 1;
    small.tile_size = 16;
    small.cache_dir = dir / "cache";
    auto ts = make_system(small);
    auto again = make_system(small);  // finds sky.exr's pyramids in the cache folder
    const auto check = [&](TextureSystem& system, const std::string& name,
                           const EnvironmentMap& map) {
        EnvironmentHandle* env = system.environment_handle(name);
        Result<TextureSystem::EnvironmentShape> shape = system.environment_shape(env);
        ASSERT_TRUE(shape) << shape.error().message;
        EXPECT_EQ(shape->layout, map.layout());
        EXPECT_EQ(shape->texel_scale.x, map.texel_scale().x);
        for (const EnvRayDifferential& ray : env_rays(500, 3)) {
            float want[3], got[3];
            environment_lookup(map, ray.direction, ray.d_dx, ray.d_dy, EnvLookupOptions{}, want);
            ASSERT_TRUE(system.environment(env, ray.direction, ray.d_dx, ray.d_dy, {}, got));
            for (int k = 0; k < 3; ++k) ASSERT_EQ(bits(got[k]), bits(want[k])) << name;
            const EnvFootprint footprint = compute_env_footprint(
                map.layout(), map.texel_scale(), ray.direction, ray.d_dx, 0.2f * ray.d_dy);
            environment_lookup(map, footprint, LookupOptions{}, want);
            ASSERT_TRUE(system.environment(env, footprint, LookupOptions{}, got));
            for (int k = 0; k < 3; ++k) ASSERT_EQ(bits(got[k]), bits(want[k])) << name;
            environment_bilinear(map, ray.direction, 0, want);
            ASSERT_TRUE(system.environment_sample(env, ray.direction, got));
            for (int k = 0; k < 3; ++k) ASSERT_EQ(bits(got[k]), bits(want[k])) << name;
        }
    };
    for (int pass = 0; pass < 2; ++pass) {
        check(*ts, latlong_file, latlong);
        check(*ts, cube_file, cube);
        check(*ts, sky, latlong);
    }
    check(*again, sky, latlong);
    const TextureSystemStats s = ts->stats();
    EXPECT_EQ(s.bytes_in_memory, 0u);  // nothing held whole
    // A 16² tile is 4 KiB: the limit, plus this thread's micro-cache and one lookup's pins.
    EXPECT_LE(s.peak_bytes, (1u << 20) + 256 * 4096u);
    EXPECT_GT(s.tiles_loaded,
              (2u << 20) / 4096);  // more than the maps' texels: evicted, read again
    EXPECT_EQ(again->stats().bytes_in_memory, 0u);
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir / "cache")) {
        ++files;
        EXPECT_TRUE(is_environment_pyramid_file(entry.path())) << entry.path();
    }
    EXPECT_EQ(files, 1);
    // Whole, for a GPU: the map the file holds.
    Result<std::shared_ptr<const EnvironmentMap>> whole =
        ts->environment_map(ts->environment_handle(cube_file));
    ASSERT_TRUE(whole);
    EXPECT_EQ((*whole)->face(3).level_image(1).pixels, cube.face(3).level_image(1).pixels);
}

// A truncated environment pyramid file: an error naming it, reported once; with a missing colour,
// that colour.
#ifdef FOOTPRINT_TEST_DATA_DIR
// A 2 KB OpenEXR file with corrupt header sizes (fuzz_texture_file found it; OpenEXR 3.1's C++
// reader allocates gigabytes on it) is refused by OpenEXR's core library before any reader
// runs: as a texture, a bump map and an environment map.
TEST(TextureSystem, ACorruptExrHeaderIsAnErrorBeforeAnyReaderRuns) {
    const std::string file =
        (std::filesystem::path(FOOTPRINT_TEST_DATA_DIR) / "bad" / "corrupt_header.exr").string();
    const auto expect_named = [&](const Status& s) {
        ASSERT_FALSE(s);
        EXPECT_NE(s.error().message.find("'" + file + "'"), std::string::npos) << s.error().message;
        EXPECT_NE(s.error().message.find("the OpenEXR header is corrupt"), std::string::npos)
            << s.error().message;
    };
    auto ts = make_system();
    const TextureCoords c{0.5f, 0.5f, 0.01f, 0, 0, 0.01f};
    float out[3];
    SlopeStatistics statistics;
    expect_named(ts->texture(file, c, {}, out));
    expect_named(ts->bump(file, c, {}, &statistics));
    expect_named(
        ts->environment(file, Vec3{0, 0, 1}, Vec3{0.01f, 0, 0}, Vec3{0, 0.01f, 0}, {}, out));
    EXPECT_FALSE(load_environment_pyramid(file));
    EXPECT_FALSE(is_environment_pyramid_file(file));
    EXPECT_FALSE(load_bump_pyramid(file));
    EXPECT_FALSE(bump_pyramid_file_offset(file));
}

// A stored MIP level whose TIFF directory claims tiles of 8192 × 16384 texels: the texture system
// reads tiles of stored levels, so it must refuse the file as load_image does.
TEST(TextureSystem, ATiffLevelOfCorruptTileSizesIsAnErrorNamingIt) {
    const std::string file =
        (std::filesystem::path(FOOTPRINT_TEST_DATA_DIR) / "bad" / "huge_tiles_level1.tif").string();
    auto ts = make_system();
    float out[3];
    const Status s = ts->texture(file, TextureCoords{0.5f, 0.5f, 0.3f, 0, 0, 0.3f}, {}, out);
    ASSERT_FALSE(s);
    EXPECT_NE(s.error().message.find("'" + file + "'"), std::string::npos) << s.error().message;
    EXPECT_NE(s.error().message.find("MIP level 1: its tiles (8192 x 16384 texels)"),
              std::string::npos)
        << s.error().message;
}
#endif

TEST(TextureSystem, ATruncatedEnvironmentPyramidIsAnErrorNamingIt) {
    test::TempDir dir;
    const EnvironmentMap map = load_environment({[&] {
                                   const auto sky = dir / "sky.exr";
                                   EXPECT_TRUE(save_image(random_image(256, 128, 3, 5), sky));
                                   return sky;
                               }()})
                                   .value();
    const std::string file = (dir / "sky_env.exr").string();
    ASSERT_TRUE(save_environment_pyramid(map, file, 16));
    std::filesystem::resize_file(file, std::filesystem::file_size(file) * 3 / 4);
    auto ts = make_system();
    const float pink[3] = {1, 0, 1};
    int failed = 0, pink_results = 0;
    for (const EnvRayDifferential& ray : env_rays(300, 8)) {
        float out[3];
        const Status s = ts->environment(file, ray.direction, ray.d_dx, ray.d_dy, {}, out);
        if (!s) {
            ++failed;
            EXPECT_NE(s.error().message.find("'" + file + "'"), std::string::npos)
                << s.error().message;
        }
        ASSERT_TRUE(ts->environment(file, ray.direction, ray.d_dx, ray.d_dy, {}, out, pink));
        pink_results += out[0] == 1 && out[1] == 0 && out[2] == 1;
    }
    EXPECT_GT(failed, 0);
    EXPECT_GT(pink_results, 0);
    EXPECT_EQ(ts->take_errors().size(), 1u);
}

// Tiles pinned by threads of a texture system, then let go by the cache (a budget of one tile):
// freed with the system, the pins of the thread that frees it and of threads still running
// alike; a system made after starts with no tiles, whichever address it gets.
TEST(TileCache, EachThreadsPinsAreFreedWithTheirSystem) {
    static constexpr std::size_t kFloats = 64, kTileBytes = kFloats * sizeof(float);
    texsys::TileCache cache(kTileBytes);
    const std::shared_ptr<texsys::Accounting> accounting = cache.accounting();
    auto pin = [&](texsys::PerThreadTiles& system, std::uint32_t file) {
        const texsys::TileKey key{file, 0, 0, 0};
        system.local().recent.emplace_back(key, cache.get(key, kFloats, [](float* texels) {
            std::fill_n(texels, kFloats, 1.0f);
        }));
    };
    {
        auto system = std::make_unique<texsys::PerThreadTiles>();
        pin(*system, 1);
        std::atomic<bool> pinned = false, freed = false;
        std::thread other([&] {
            pin(*system, 2);
            pinned = true;
            while (!freed) std::this_thread::yield();
        });
        while (!pinned) std::this_thread::yield();
        pin(*system, 3);
        EXPECT_EQ(accounting->resident, 3 * kTileBytes);  // two evicted but pinned, one cached
        system.reset();
        EXPECT_EQ(accounting->resident, kTileBytes);  // the cache's newest only
        freed = true;
        other.join();
    }
    texsys::PerThreadTiles later;
    EXPECT_TRUE(later.local().recent.empty());
    EXPECT_EQ(accounting->resident, kTileBytes);
}

TEST(TextureSystem, RefusesOptionsItCannotHonour) {
    TextureSystemOptions zero;
    zero.max_memory_mb = 0;
    EXPECT_FALSE(TextureSystem::create(zero));
    TextureSystemOptions odd;
    odd.tile_size = 48;
    Result<std::unique_ptr<TextureSystem>> made = TextureSystem::create(odd);
    ASSERT_FALSE(made);
    EXPECT_NE(made.error().message.find("48"), std::string::npos);
    test::TempDir dir;
    { std::ofstream(dir / "file") << "x"; }
    TextureSystemOptions blocked;
    blocked.cache_dir = dir / "file";
    EXPECT_FALSE(TextureSystem::create(blocked));
}

}  // namespace
}  // namespace footprint
