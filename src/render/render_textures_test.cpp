// Tests of the renderer's maps in its texture system (render/render_scene.h): a texture file that
// stores its MIP levels is read tile by tile through the cache, with the image of the file it was
// made from, whatever the cache holds; a tile that cannot be read is an error naming the file.
#include <gtest/gtest.h>

#include <filesystem>

#include "bump/bump_pyramid_file.h"
#include "bump/slope_map.h"
#include "core/test_temp_dir.h"
#include "envmap/env_image_io.h"
#include "envmap/env_pyramid_file.h"
#include "image/image_io.h"
#include "image/test_images.h"
#include "metrics/image_metrics.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "render/test_expect.h"
#include "texture/mip_pyramid.h"

namespace footprint {
namespace {

// A textured plane seen at a grazing angle, in a sky: magnified near, strongly minified far.
SceneDesc textured_plane(const std::filesystem::path& texture) {
    SceneDesc scene;
    scene.width = 64, scene.height = 40;
    scene.camera.position = {0, 0.6, 3};
    scene.camera.look_at = {0, 0, -2};
    scene.camera.fov_y_deg = 50;
    scene.lights.push_back({LightType::directional, {0.3, -1, -0.4}, {}, {1, 1, 1}});
    PlaneShape plane;
    plane.infinite = true;
    MaterialDesc material;
    material.base_color_map.file = texture;
    material.specular = 0.3f;
    scene.objects.push_back({"plane", plane, material});
    return scene;
}

// `image`'s box pyramid written as stored levels, as `footprint maketx` writes them.
void write_stored_levels(const Image& image, const std::filesystem::path& file) {
    const MipPyramid pyramid = MipPyramid::build(image);
    std::vector<Image> levels;
    for (int l = 0; l < pyramid.level_count(); ++l) levels.push_back(pyramid.level_image(l));
    LevelsSaveOptions options;
    options.wrap_modes = "periodic,periodic";
    options.tile_size = 16;
    ASSERT_TRUE(save_image_levels(levels, file, options));
}

std::shared_ptr<TextureSystem> texture_system(std::size_t max_memory_mb, int tile_size = 64,
                                              bool build_in_memory = false) {
    TextureSystemOptions options;
    options.max_memory_mb = max_memory_mb;
    options.tile_size = tile_size;
    options.build_in_memory = build_in_memory;
    Result<std::unique_ptr<TextureSystem>> made = TextureSystem::create(options);
    EXPECT_TRUE(made) << made.error().message;
    return std::move(*made);
}

Image render_with(const SceneDesc& desc, std::shared_ptr<TextureSystem> textures, FilterMode mode) {
    Result<RenderScene> scene = prepare_render_scene(desc, std::move(textures));
    EXPECT_TRUE(scene) << scene.error().message;
    RenderOptions options;
    options.filter = mode;
    options.spp = mode == FilterMode::reference ? 4 : 1;
    Image image = render(*scene, options);
    EXPECT_TRUE(scene->take_texture_errors());
    return image;
}

TEST(RenderTextures, StoredLevelsRenderAsTheImageTheyWereMadeFromWithAnyCache) {
    test::TempDir dir;
    const Image image = random_image(256, 128, 3, 7);
    ASSERT_TRUE(save_image(image, dir / "plain.exr"));
    write_stored_levels(image, dir / "stored.exr");
    const SceneDesc plain = textured_plane(dir / "plain.exr");
    const SceneDesc stored = textured_plane(dir / "stored.exr");
    for (FilterMode mode : {FilterMode::trilinear, FilterMode::fa_rough, FilterMode::ewa_rough,
                            FilterMode::reference}) {
        const Image want = render_with(plain, nullptr, mode);
        test::expect_bit_identical(render_with(stored, texture_system(1024), mode), want,
                                   filter_mode_name(mode));
        // 1 MiB of 16² tiles holds a quarter of level 0: tiles are evicted and read again.
        const std::shared_ptr<TextureSystem> small = texture_system(1, 16);
        test::expect_bit_identical(render_with(stored, small, mode), want, filter_mode_name(mode));
        const TextureSystemStats stats = small->stats();
        EXPECT_GT(stats.tiles_loaded, 0u) << "the stored file was not read through tiles";
        EXPECT_EQ(stats.bytes_in_memory, 0u) << "the stored file was read whole";
        // The bound: 1 MiB, plus one thread's micro-cache and one lookup's pinned tiles.
        constexpr std::size_t kTileBytes = 16 * 16 * 4 * sizeof(float);
        constexpr std::size_t kSlack = (TextureSystem::kMicroCacheTiles + 64) * kTileBytes;
        EXPECT_LE(stats.peak_bytes, (std::size_t{1} << 20) + kSlack);
    }
}

TEST(RenderTextures, ScenesShareATextureSystemAndEachMapIsHeldOnce) {
    test::TempDir dir;
    ASSERT_TRUE(save_image(random_image(64, 64, 3, 3), dir / "a.exr"));
    SceneDesc desc = textured_plane(dir / "a.exr");
    desc.objects.push_back(desc.objects[0]);  // a second object with the same map
    // Held whole (build_in_memory), to count it: by default the file's pyramid is read by tiles.
    const std::shared_ptr<TextureSystem> textures = texture_system(64, 64, true);
    ASSERT_TRUE(prepare_render_scene(desc, textures));
    const std::size_t one_scene = textures->stats().bytes_in_memory;
    EXPECT_GT(one_scene, 64u * 64 * 3 * sizeof(float));
    EXPECT_EQ(textures->stats().files, 1u);
    ASSERT_TRUE(prepare_render_scene(desc, textures));  // a file is opened once per system
    EXPECT_EQ(textures->stats().bytes_in_memory, one_scene);
}

TEST(RenderTextures, ATileThatCannotBeReadIsAnErrorNamingTheFile) {
    test::TempDir dir;
    write_stored_levels(random_image(256, 256, 3, 5), dir / "stored.exr");
    const SceneDesc desc = textured_plane(dir / "stored.exr");
    Result<RenderScene> scene = prepare_render_scene(desc, texture_system(1, 16));
    ASSERT_TRUE(scene) << scene.error().message;
    // Cut the file after its header and offset tables: its tiles can no longer be read.
    std::filesystem::resize_file(dir / "stored.exr", 4096);
    static_cast<void>(render(*scene, RenderOptions{}));
    const Status errors = scene->take_texture_errors();
    ASSERT_FALSE(errors);
    EXPECT_NE(errors.error().message.find("stored.exr"), std::string::npos)
        << errors.error().message;
    EXPECT_TRUE(scene->take_texture_errors()) << "an error is reported once";
}

// A material's bump map given as a bump pyramid file (strength 1, `footprint maketx --bump`) is
// read tile by tile, its slopes scaled by the material's strength with its micro-roughness added at
// each lookup: the image of the normal map it was made from, to float rounding.
TEST(RenderTextures, ABumpPyramidFileRendersAsItsNormalMapAtTheMaterialsStrength) {
    test::TempDir dir;
    Image slopes = random_image(128, 128, 2, 17);
    for (float& b : slopes.pixels) b = 1.2f * (b - 0.45f);
    ASSERT_TRUE(save_image(normals_from_slopes(slopes), dir / "normals.exr"));
    ASSERT_TRUE(save_bump_pyramid(BumpPyramid::build(*load_slope_map(dir / "normals.exr")).value(),
                                  dir / "bump.exr", 16));
    std::vector<Image> images;
    std::shared_ptr<TextureSystem> small = texture_system(1, 16);
    for (const char* file : {"normals.exr", "bump.exr"}) {
        SceneDesc desc = textured_plane(dir / "normals.exr");
        desc.objects[0].material.base_color_map = {};
        desc.objects[0].material.specular = 0.8f;
        desc.objects[0].material.shininess = 80;
        desc.objects[0].material.micro_roughness = 0.05f;
        desc.objects[0].material.bump.source = BumpDesc::Source::normal_map;
        desc.objects[0].material.bump.map.file = dir / file;
        desc.objects[0].material.bump.strength = 0.6f;
        images.push_back(render_with(desc, small, FilterMode::fa_rough));
    }
    EXPECT_GT(small->stats().tiles_loaded, 0u) << "the bump pyramid file was not read by tiles";
    // Float rounding of the moments scaled after filtering against before; a strength applied
    // twice or not at all, or a micro-roughness lost, changes the highlights by > 1e-2.
    constexpr double kRmse = 1e-5;
    const Result<ImageComparison> d = compare_images(images[1], images[0]);
    ASSERT_TRUE(d) << d.error().message;
    EXPECT_LT(d->rmse, kRmse);
}

// An environment given as an environment pyramid file (`footprint maketx --env`) renders as the
// file it was made from: the texture system's entry itself at intensity 1, read tile by tile, bit
// for bit; a copy scaled by the intensity otherwise (scaled after filtering: float rounding).
TEST(RenderTextures, AnEnvironmentPyramidFileRendersAsItsSource) {
    test::TempDir dir;
    ASSERT_TRUE(save_image(random_image(128, 64, 3, 23), dir / "sky.exr"));
    ASSERT_TRUE(save_environment_pyramid(load_environment({dir / "sky.exr"}).value(),
                                         dir / "sky_env.exr", 16));
    for (const float intensity : {1.0f, 2.5f}) {
        std::vector<Image> images;
        const std::shared_ptr<TextureSystem> small = texture_system(1, 16);
        for (const char* file : {"sky.exr", "sky_env.exr"}) {
            SceneDesc desc = textured_plane(dir / "sky.exr");
            desc.objects[0].material.base_color_map = {};
            desc.objects[0].material.mirror = 0.8f;
            desc.objects.push_back({"ball", SphereShape{{0, 0.5, -1}, 0.5}, {}});
            desc.objects.back().material.mirror = 1;
            EnvironmentDesc env;
            env.images.push_back(ImageSource{dir / file, nullptr, file});
            env.detect_layout = true;
            env.intensity = intensity;
            desc.environment = env;
            images.push_back(
                render_with(desc, images.empty() ? nullptr : small, FilterMode::fa_rough));
        }
        if (intensity == 1) {
            test::expect_bit_identical(images[1], images[0], "intensity 1");
            EXPECT_GT(small->stats().tiles_loaded, 0u);
            EXPECT_EQ(small->stats().bytes_in_memory, 0u) << "the file was read whole";
        } else {
            constexpr double kRmse = 1e-5;  // rounding of the levels scaled after the box filter
            const Result<ImageComparison> d = compare_images(images[1], images[0]);
            ASSERT_TRUE(d) << d.error().message;
            EXPECT_LT(d->rmse, kRmse);
        }
    }
}

}  // namespace
}  // namespace footprint
