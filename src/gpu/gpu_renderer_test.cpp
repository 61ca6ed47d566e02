// The GPU path's analytic checks (gpu/gpu_renderer.h); the demo scenes against the CPU renderer
// are in apps/gpu_scenes_test.cpp.
#include "gpu/gpu_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>

#include "bump/bump_pyramid_file.h"
#include "bump/slope_map.h"
#include "core/test_temp_dir.h"
#include "gpu/gpu_test_device.h"
#include "image/image_io.h"
#include "image/test_images.h"
#include "metrics/image_metrics.h"
#include "render/camera.h"
#include "render/renderer.h"

namespace footprint {
namespace {

// A lat-long environment of one colour, in memory.
EnvironmentDesc constant_environment(std::array<float, 3> colour) {
    auto image = std::make_shared<Image>(64, 32, 3);
    for (std::size_t i = 0; i < image->pixel_count(); ++i)
        for (int c = 0; c < 3; ++c) image->pixels[i * 3 + c] = colour[c];
    EnvironmentDesc env;
    env.images.push_back({{}, image, "constant"});
    env.layout = EnvLayout::latlong;
    return env;
}

SceneDesc mirror_plane_scene(int width, int height) {
    SceneDesc desc;
    desc.width = width;
    desc.height = height;
    desc.camera = {{0, 1, 3}, {0, 0, 0}, {0, 1, 0}, 50};
    desc.environment = constant_environment({0.5f, 1.0f, 2.0f});
    ObjectDesc plane;
    PlaneShape shape;
    shape.infinite = true;
    plane.shape = shape;
    plane.material.diffuse = 0;
    plane.material.mirror = 1;
    plane.material.fresnel_f0 = 0.04f;
    desc.objects.push_back(plane);
    return desc;
}

Image render_gpu(const RenderScene& scene, GpuFilter filter) {
    Result<GpuRenderer> renderer = GpuRenderer::create(scene);
    EXPECT_TRUE(renderer) << renderer.error().message;
    if (!renderer) return {};
    GpuRenderOptions options;
    options.filter = filter;
    Result<Image> image = renderer->render(options);
    EXPECT_TRUE(image) << image.error().message;
    return image ? *image : Image{};
}

// A constant environment filtered by any footprint is the constant (up to float rounding of the
// probe weights): what a mirror shows is environment × Schlick's Fresnel of the pixel's angle.
constexpr float kConstantTolerance = 1e-4f;  // relative

TEST(GpuRenderer, MirrorPlaneInAConstantEnvironmentIsEnvironmentTimesFresnel) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    const SceneDesc desc = mirror_plane_scene(48, 32);
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene) << scene.error().message;
    const PinholeCamera camera(desc.camera, desc.width, desc.height);
    for (GpuFilter filter : all_gpu_filters()) {
        const Image image = render_gpu(*scene, filter);
        ASSERT_EQ(image.width, desc.width);
        int checked = 0;
        for (int y = 0; y < desc.height; ++y)
            for (int x = 0; x < desc.width; ++x) {
                const RayDifferential ray = camera.ray(x + 0.5, y + 0.5);
                const Vec3d d = normalize(ray.ray.direction);
                const std::array<float, 3> env{0.5f, 1.0f, 2.0f};
                if (d.y >= 0) {  // the sky: the environment itself
                    for (int c = 0; c < 3; ++c)
                        EXPECT_NEAR(image.at(x, y, c), env[c], kConstantTolerance * env[c]);
                    continue;
                }
                const float cosine = static_cast<float>(-d.y);  // n̂·v̂ on the plane y = 0
                const float c5 = std::pow(1 - cosine, 5.0f);
                const float fresnel = 0.04f + 0.96f * c5;
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(image.at(x, y, c), fresnel * env[c],
                                kConstantTolerance * env[c] + 1e-5f)
                        << gpu_filter_name(filter) << " at (" << x << ", " << y << ")";
                ++checked;
            }
        EXPECT_GT(checked, desc.width * desc.height / 4);
    }
}

TEST(GpuRenderer, TheSameFrameTwiceGivesIdenticalPixels) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    SceneDesc desc = mirror_plane_scene(37, 23);
    desc.objects[0].material.bump.source = BumpDesc::Source::height_map;
    auto height = std::make_shared<Image>(32, 32, 1);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) height->at(x, y, 0) = std::sin(0.7f * x) * std::cos(0.4f * y);
    desc.objects[0].material.bump.map = {{}, height, "waves"};
    desc.objects[0].material.bump.strength = 0.05f;
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene) << scene.error().message;
    Result<GpuRenderer> renderer = GpuRenderer::create(*scene);
    ASSERT_TRUE(renderer) << renderer.error().message;
    for (GpuFilter filter : all_gpu_filters()) {
        GpuRenderOptions options;
        options.filter = filter;
        Result<Image> a = renderer->render(options), b = renderer->render(options);
        ASSERT_TRUE(a && b);
        EXPECT_EQ(a->pixels, b->pixels) << gpu_filter_name(filter);
    }
}

// The tolerance of the GPU against the CPU renderer per pixel value: float geometry around the
// camera (the CPU's is double) and the hardware's bilinear weights (8 fractional bits on most
// GPUs) move a value by a few 1e-4 where the image has texel-scale contrast.
constexpr double kGpuCpuRmse = 1e-3;

TEST(GpuRenderer, OneByOneAndOddSizesMatchTheCpu) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    for (auto [w, h] : {std::pair{1, 1}, {7, 5}, {33, 17}, {2, 31}}) {
        SceneDesc desc = mirror_plane_scene(w, h);
        ObjectDesc sphere;
        sphere.shape = SphereShape{{0, 0.5, 0}, 0.5};
        sphere.material.specular = 0.5f;
        desc.objects.push_back(sphere);
        desc.lights.push_back({LightType::point, {}, {1, 3, 2}, {4, 4, 4}});
        Result<RenderScene> scene = prepare_render_scene(desc);
        ASSERT_TRUE(scene) << scene.error().message;
        const Image gpu = render_gpu(*scene, GpuFilter::fa_rough);
        ASSERT_EQ(gpu.width, w);
        ASSERT_EQ(gpu.height, h);
        RenderOptions cpu_options;
        cpu_options.filter = FilterMode::fa_rough;
        const Result<ImageComparison> d = compare_images(gpu, render(*scene, cpu_options));
        ASSERT_TRUE(d) << d.error().message;
        EXPECT_LT(d->rmse, kGpuCpuRmse) << w << "x" << h;
    }
}

const char* highlight_label(MaterialDesc::Highlight highlight) {
    switch (highlight) {
        case MaterialDesc::Highlight::blinn_phong:
            return "blinn-phong";
        case MaterialDesc::Highlight::beckmann:
            return "beckmann";
        case MaterialDesc::Highlight::ggx:
            return "ggx";
    }
    return "?";
}

// Three bump-mapped spheres whose lights' highlight is `highlight` (roughness 0.35, 0.5, 0.7: α
// 0.12, 0.25, 0.49; dielectric, metal, in between; no mirror term) over the mirror plane, lit by a
// point and a directional light.
SceneDesc highlight_scene(MaterialDesc::Highlight highlight) {
    SceneDesc desc = mirror_plane_scene(64, 40);
    desc.camera = {{0, 1.0, 2.6}, {0, 0.4, 0}, {0, 1, 0}, 50};
    auto height = std::make_shared<Image>(64, 64, 1);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            height->at(x, y, 0) =
                std::sin(0.9f * x) * std::cos(0.6f * y) + 0.3f * std::sin(2.1f * y);
    const float roughness[3] = {0.35f, 0.5f, 0.7f}, f0[3] = {0.04f, 0.9f, 0.3f};
    for (int i = 0; i < 3; ++i) {
        ObjectDesc sphere;
        sphere.shape = SphereShape{{-1.1 + 1.1 * i, 0.45, 0}, 0.45};
        MaterialDesc& m = sphere.material;
        m.diffuse = 0.3f;
        m.specular = 1;
        m.highlight = highlight;
        m.roughness = roughness[i];
        m.fresnel_f0 = f0[i];
        m.bump.source = BumpDesc::Source::height_map;
        m.bump.map = {{}, height, "ripples"};
        m.bump.strength = 0.01f;
        m.micro_roughness = 0.03f;
        desc.objects.push_back(sphere);
    }
    desc.lights.push_back({LightType::point, {}, {1.5, 3, 2.5}, {10, 10, 10}});
    desc.lights.push_back({LightType::directional, {0.3, -1, -0.6}, {}, {0.6, 0.6, 0.6}});
    return desc;
}

// The microfacet highlights (shading/microfacet.h) on the GPU are the CPU's, within the GPU-vs-CPU
// tolerance, in the modes that widen them by K_b (fa-rough) and those that do not; and the
// tolerance resolves the model and the widening: GGX, Beckmann and Blinn-Phong differ by far more,
// and so do GGX widened and not (the spheres have no mirror term, so fa-rough and fa differ in the
// highlights only).
TEST(GpuRenderer, MicrofacetHighlightsMatchTheCpu) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    std::map<MaterialDesc::Highlight, Image> cpu_rough, cpu_plain;
    for (const MaterialDesc::Highlight highlight :
         {MaterialDesc::Highlight::ggx, MaterialDesc::Highlight::beckmann,
          MaterialDesc::Highlight::blinn_phong}) {
        Result<RenderScene> scene = prepare_render_scene(highlight_scene(highlight));
        ASSERT_TRUE(scene) << scene.error().message;
        for (const auto& [gpu_filter, cpu_filter] :
             {std::pair{GpuFilter::fa_rough, FilterMode::fa_rough},
              std::pair{GpuFilter::fa, FilterMode::fa}}) {
            RenderOptions cpu_options;
            cpu_options.filter = cpu_filter;
            const Image cpu = render(*scene, cpu_options);
            const Result<ImageComparison> d = compare_images(render_gpu(*scene, gpu_filter), cpu);
            ASSERT_TRUE(d) << d.error().message;
            std::printf("%-11s %-8s GPU vs CPU RMSE %.2e\n", highlight_label(highlight),
                        gpu_filter_name(gpu_filter), d->rmse);
            EXPECT_LT(d->rmse, kGpuCpuRmse)
                << highlight_label(highlight) << " " << gpu_filter_name(gpu_filter);
            if (gpu_filter == GpuFilter::fa_rough) cpu_rough[highlight] = cpu;
            if (gpu_filter == GpuFilter::fa) cpu_plain[highlight] = cpu;
        }
    }
    const auto differ = [&](MaterialDesc::Highlight a, MaterialDesc::Highlight b) {
        const Result<ImageComparison> d = compare_images(cpu_rough[a], cpu_rough[b]);
        return d ? d->rmse : 0.0;
    };
    const double ggx_beckmann =
        differ(MaterialDesc::Highlight::ggx, MaterialDesc::Highlight::beckmann);
    const double ggx_blinn_phong =
        differ(MaterialDesc::Highlight::ggx, MaterialDesc::Highlight::blinn_phong);
    const Result<ImageComparison> widening = compare_images(
        cpu_rough[MaterialDesc::Highlight::ggx], cpu_plain[MaterialDesc::Highlight::ggx]);
    ASSERT_TRUE(widening);
    EXPECT_GT(widening->rmse, 10 * kGpuCpuRmse);
    std::printf(
        "CPU fa-rough RMSE: ggx vs beckmann %.2e, ggx vs blinn-phong %.2e; ggx fa-rough vs fa "
        "%.2e\n",
        ggx_beckmann, ggx_blinn_phong, widening->rmse);
    EXPECT_GT(ggx_beckmann, 10 * kGpuCpuRmse);
    EXPECT_GT(ggx_blinn_phong, 10 * kGpuCpuRmse);
}

TEST(GpuRenderer, RefusesImageSizesTheGpuCannotHold) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    Result<RenderScene> scene = prepare_render_scene(mirror_plane_scene(8, 8));
    ASSERT_TRUE(scene);
    Result<GpuRenderer> renderer = GpuRenderer::create(*scene);
    ASSERT_TRUE(renderer);
    Result<Image> image = renderer->render(scene->desc().camera, 0, 8, GpuRenderOptions{});
    ASSERT_FALSE(image);
    EXPECT_NE(image.error().message.find("image size 0x8 is outside 1x1 to"), std::string::npos)
        << image.error().message;
}

// The GPU uploads a map whole: a stored-levels file (read tile by tile on the CPU) is read whole
// for it, and a grey file becomes grey RGB; both give the image of the plain file.
TEST(GpuRenderer, StoredLevelsAndGreyMapsUploadAsThePlainFile) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    test::TempDir dir;
    const Image grey = random_image(64, 32, 1, 11);
    Image rgb(grey.width, grey.height, 3);
    for (std::size_t i = 0; i < grey.pixel_count(); ++i)
        std::fill_n(&rgb.pixels[i * 3], 3, grey.pixels[i]);
    ASSERT_TRUE(save_image(rgb, dir / "rgb.exr"));
    ASSERT_TRUE(save_image(grey, dir / "grey.exr"));
    const MipPyramid pyramid = MipPyramid::build(rgb);
    std::vector<Image> levels;
    for (int l = 0; l < pyramid.level_count(); ++l) levels.push_back(pyramid.level_image(l));
    LevelsSaveOptions stored;
    stored.wrap_modes = "periodic,periodic";
    stored.tile_size = 16;
    ASSERT_TRUE(save_image_levels(levels, dir / "stored.exr", stored));
    std::vector<Image> images;
    for (const char* file : {"rgb.exr", "stored.exr", "grey.exr"}) {
        SceneDesc desc = mirror_plane_scene(40, 24);
        desc.objects[0].material.mirror = 0.5f;
        desc.objects[0].material.diffuse = 1;
        desc.objects[0].material.base_color_map.file = dir / file;
        Result<RenderScene> scene = prepare_render_scene(desc);
        ASSERT_TRUE(scene) << scene.error().message;
        images.push_back(render_gpu(*scene, GpuFilter::fa_rough));
    }
    for (std::size_t i : {1u, 2u}) {
        ASSERT_EQ(images[i].pixels.size(), images[0].pixels.size());
        EXPECT_EQ(images[i].pixels, images[0].pixels) << i;
    }
}

// A bump pyramid file at strength 1 is uploaded scaled by the material's strength with its
// micro-roughness: the normal map's image, to float rounding.
TEST(GpuRenderer, ABumpPyramidFileUploadsAsItsNormalMapAtTheMaterialsStrength) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    test::TempDir dir;
    Image slopes = random_image(64, 64, 2, 19);
    for (float& b : slopes.pixels) b = b - 0.5f;
    ASSERT_TRUE(save_image(normals_from_slopes(slopes), dir / "normals.exr"));
    ASSERT_TRUE(save_bump_pyramid(BumpPyramid::build(*load_slope_map(dir / "normals.exr")).value(),
                                  dir / "bump.exr", 16));
    std::vector<Image> images;
    for (const char* file : {"normals.exr", "bump.exr"}) {
        SceneDesc desc = mirror_plane_scene(40, 24);
        MaterialDesc& m = desc.objects[0].material;
        m.specular = 0.5f;
        m.micro_roughness = 0.05f;
        m.bump.source = BumpDesc::Source::normal_map;
        m.bump.map.file = dir / file;
        m.bump.strength = 0.5f;
        desc.lights.push_back({LightType::point, {}, {1, 3, 2}, {4, 4, 4}});
        Result<RenderScene> scene = prepare_render_scene(desc);
        ASSERT_TRUE(scene) << scene.error().message;
        images.push_back(render_gpu(*scene, GpuFilter::fa_rough));
    }
    constexpr double kRmse = 1e-5;  // float rounding of the scaled moments (see the CPU's test)
    const Result<ImageComparison> d = compare_images(images[1], images[0]);
    ASSERT_TRUE(d) << d.error().message;
    EXPECT_LT(d->rmse, kRmse);
}

// A filter's first draw is one pixel, untimed, so that a driver compiling shaders at their first
// draw (llvmpipe: seconds on a cold shader cache) does it there: the first frame of each filter
// costs what the next one does, not the compilation.
TEST(GpuRenderer, ShaderCompilationIsNotInAFramesTime) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    const Result<RenderScene> scene = prepare_render_scene(mirror_plane_scene(64, 36));
    ASSERT_TRUE(scene) << scene.error().message;
    Result<GpuRenderer> renderer = GpuRenderer::create(*scene);
    ASSERT_TRUE(renderer) << renderer.error().message;
    EXPECT_EQ(renderer->warmup_ms(), 0.0);  // nothing drawn yet
    for (GpuFilter filter : all_gpu_filters()) {
        GpuRenderOptions options;
        options.filter = filter;
        GpuFrameStats first, second;
        const double before = renderer->warmup_ms();
        ASSERT_TRUE(renderer->render(options, &first));
        const double warmed = renderer->warmup_ms();
        EXPECT_GT(warmed, before) << gpu_filter_name(filter);  // the filter's first draw
        ASSERT_TRUE(renderer->render(options, &second));
        EXPECT_EQ(renderer->warmup_ms(), warmed) << gpu_filter_name(filter);  // once a filter
        constexpr double kSlack = 4, kJitterMs = 50;  // a busy machine's frames vary this much
        EXPECT_LT(first.wall_ms, kSlack * second.wall_ms + kJitterMs) << gpu_filter_name(filter);
        EXPECT_LT(first.gpu_ms, kSlack * second.gpu_ms + kJitterMs) << gpu_filter_name(filter);
    }
}

TEST(GpuFilter, NamesRoundTrip) {
    for (GpuFilter f : all_gpu_filters()) EXPECT_EQ(parse_gpu_filter(gpu_filter_name(f)), f);
    EXPECT_FALSE(parse_gpu_filter("bilinear"));
    EXPECT_EQ(all_gpu_filters().size(), 5u);
}

}  // namespace
}  // namespace footprint
