// Where threads meet: many threads sharing one texture cache too small for their texture set, so
// that tiles are evicted and reloaded while others read them, and a render on many threads whose
// maps come through such a cache. Both must give the single-threaded bits. These tests are part of
// footprint-tests, and with the texture system's own tests they make footprint-tsan-tests, the
// ThreadSanitizer build (make test-tsan, docs/testing.md).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/test_temp_dir.h"
#include "image/image_io.h"
#include "image/test_images.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "render/test_expect.h"
#include "render/test_scene_parts.h"
#include "texture/mip_pyramid.h"
#include "texture_system.h"

namespace footprint {
namespace {

constexpr int kTileSize = 16;
constexpr std::size_t kTileBytes = kTileSize * kTileSize * 4 * sizeof(float);  // RGBA float
constexpr std::size_t kCacheBytes = 1u << 20;  // max_memory_mb = 1: 256 tiles

std::uint32_t bits(float v) {
    return std::bit_cast<std::uint32_t>(v);
}

std::unique_ptr<TextureSystem> make_system(std::size_t max_memory_mb) {
    TextureSystemOptions options;
    options.max_memory_mb = max_memory_mb;
    options.tile_size = kTileSize;
    Result<std::unique_ptr<TextureSystem>> made = TextureSystem::create(options);
    EXPECT_TRUE(made) << made.error().message;
    return std::move(*made);
}

// A texture set as a renderer has one: files that store their MIP levels in 16² tiles (maketx
// output), 256² RGBA each, together about six times the cache.
std::vector<std::string> write_tiled_textures(const test::TempDir& dir, int count) {
    std::vector<std::string> files;
    for (int i = 0; i < count; ++i) {
        const MipPyramid pyramid = MipPyramid::build(random_image(256, 256, 4, 100 + i));
        std::vector<Image> levels;
        for (int l = 0; l < pyramid.level_count(); ++l) levels.push_back(pyramid.level_image(l));
        LevelsSaveOptions save;
        save.tile_size = kTileSize;
        files.push_back((dir / ("texture" + std::to_string(i) + ".exr")).string());
        EXPECT_TRUE(save_image_levels(levels, files.back(), save));
    }
    return files;
}

// Lookups magnified to minified, isotropic to 16:1, on and beyond the texture, each on one of the
// files with one of the filters.
struct Lookup {
    int file;
    TextureCoords coords;
    LookupOptions options;
};
std::vector<Lookup> random_lookups(int count, int files) {
    constexpr TextureFilter kFilters[] = {TextureFilter::bilinear, TextureFilter::trilinear,
                                          TextureFilter::footprint_assembly, TextureFilter::ewa};
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> position(-0.5f, 1.5f), unit(-1, 1), scale(-9, -3);
    std::vector<Lookup> all;
    for (int i = 0; i < count; ++i) {
        const float size = std::exp2(scale(rng)), aniso = 1 + 7.5f * (unit(rng) + 1);
        const float angle = 3.2f * unit(rng);
        Lookup lookup{
            i % files,
            {position(rng), position(rng), size * aniso * std::cos(angle),
             size * aniso * std::sin(angle), -size * std::sin(angle), size * std::cos(angle)},
            {}};
        lookup.options.filter = kFilters[(i / files) % 4];
        all.push_back(lookup);
    }
    return all;
}

// Sixteen threads, each in its own order, through one 1 MiB cache that holds a sixth of the files'
// tiles: tiles are evicted and reloaded under the readers, and every value is the one a thread
// alone with a cache that holds everything reads.
TEST(Threads, ManyThreadsEvictingOneSmallCacheGetTheSingleThreadedResults) {
    test::TempDir dir;
    const std::vector<std::string> files = write_tiled_textures(dir, 6);
    const std::vector<Lookup> lookups = random_lookups(1200, 6);
    std::vector<float> want(lookups.size() * 4);
    {
        auto alone = make_system(1024);
        for (std::size_t i = 0; i < lookups.size(); ++i) {
            const Lookup& l = lookups[i];
            ASSERT_TRUE(alone->texture(files[l.file], l.coords, l.options, {&want[4 * i], 4}));
        }
    }
    auto shared = make_system(1);
    constexpr int kThreads = 16;
    std::vector<std::vector<float>> got(kThreads, std::vector<float>(want.size()));
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([&, t] {
            // Each its own order: steps prime to 1200 visit every lookup once.
            constexpr std::size_t kSteps[kThreads] = {1,  7,  11, 13, 17, 19, 23, 29,
                                                      31, 37, 41, 43, 47, 49, 53, 59};
            const std::size_t step = kSteps[t];
            for (std::size_t n = 0; n < lookups.size(); ++n) {
                const std::size_t i = (n * step + 37 * t) % lookups.size();
                const Lookup& l = lookups[i];
                if (!shared->texture(files[l.file], l.coords, l.options, {&got[t][4 * i], 4}))
                    return;
            }
        });
    }
    for (std::thread& thread : threads) thread.join();
    for (int t = 0; t < kThreads; ++t)
        for (std::size_t i = 0; i < want.size(); ++i)
            ASSERT_EQ(bits(got[t][i]), bits(want[i])) << "thread " << t << " value " << i;
    const TextureSystemStats stats = shared->stats();
    // The cache was under pressure: it loaded several times its size ...
    EXPECT_GT(stats.tiles_loaded * kTileBytes, 4 * kCacheBytes);
    // ... and stayed within its bound plus what each thread may hold (its micro-cache, pins).
    EXPECT_LE(stats.peak_bytes, kCacheBytes + kThreads * 64 * kTileBytes);
}

// A scene whose colour map is read tile by tile through the cache, with a bumpy mirror (the
// roughness pyramid; toksvig's normal map, made lazily by whichever thread asks first) in a
// striped environment.
SceneDesc textured_scene(const std::string& color_file) {
    SceneDesc scene;
    scene.width = 48, scene.height = 32;
    scene.camera.position = {0, 1.2, 4};
    scene.camera.look_at = {0, 0.3, 0};
    scene.environment =
        test::latlong_environment(std::make_shared<Image>(random_image(128, 64, 3, 9)), "sky");
    scene.lights.push_back({LightType::directional, {-1, -1, -0.5}, {}, {1, 0.9f, 0.8f}});
    MaterialDesc bumpy;
    bumpy.diffuse = 0.2f;
    bumpy.mirror = 1;
    bumpy.specular = 0.5f;
    bumpy.bump.source = BumpDesc::Source::height_map;
    bumpy.bump.map = ImageSource{{}, std::make_shared<Image>(random_image(64, 64, 1, 3)), "bumps"};
    bumpy.bump.strength = 0.05f;
    scene.objects.push_back({"sphere", SphereShape{{0, 0.8, 0}, 0.8}, bumpy});
    PlaneShape floor;
    floor.infinite = true;
    floor.uv_scale = 3;
    MaterialDesc textured;
    textured.base_color_map = ImageSource{color_file, nullptr, ""};
    scene.objects.push_back({"floor", floor, textured});
    return scene;
}

// Eight threads rendering through a 1 MiB cache give the pixels of one thread with a cache that
// holds everything, in every mode that keeps state between pixels or threads.
TEST(Threads, ARenderOnEightThreadsThroughASmallCacheIsTheOneThreadRender) {
    test::TempDir dir;
    const SceneDesc desc = textured_scene(write_tiled_textures(dir, 1)[0]);
    Result<RenderScene> alone = prepare_render_scene(desc, make_system(1024));
    Result<RenderScene> shared = prepare_render_scene(desc, make_system(1));
    ASSERT_TRUE(alone) << alone.error().message;
    ASSERT_TRUE(shared) << shared.error().message;
    for (FilterMode mode : {FilterMode::fa_rough, FilterMode::ewa_rough, FilterMode::reference,
                            FilterMode::toksvig, FilterMode::stochastic}) {
        RenderOptions options;
        options.filter = mode;
        options.spp = mode == FilterMode::reference ? 4 : 1;
        options.threads = 1;
        const Image one = render(*alone, options);
        options.threads = 8;
        const Image eight = render(*shared, options);
        for (float v : eight.pixels) ASSERT_TRUE(std::isfinite(v)) << filter_mode_name(mode);
        test::expect_bit_identical(one, eight, filter_mode_name(mode));
    }
}

}  // namespace
}  // namespace footprint
