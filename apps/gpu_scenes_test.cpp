// The GPU path against the CPU renderer and the ground truth on the built-in demo scenes
// (gpu/gpu_renderer.h, apps/demo_scenes.h).
#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "demo_assets.h"
#include "demo_scenes.h"
#include "envmap/env_convert.h"
#include "envmap/environment_map.h"
#include "gpu/gpu_renderer.h"
#include "gpu/gpu_test_device.h"
#include "metrics/image_metrics.h"
#include "render/renderer.h"

namespace footprint {
namespace {

// The CPU mode each GPU mode reproduces (hw-aniso has none).
std::optional<FilterMode> cpu_counterpart(GpuFilter f) {
    switch (f) {
        case GpuFilter::point:
            return FilterMode::bilinear;
        case GpuFilter::trilinear:
            return FilterMode::trilinear;
        case GpuFilter::fa:
            return FilterMode::fa;
        case GpuFilter::fa_rough:
            return FilterMode::fa_rough;
        case GpuFilter::hw_aniso:
            return std::nullopt;
    }
    return std::nullopt;
}

// GPU against CPU, RMSE in linear light, per mode. Both run the same steps on the same pyramids;
// what differs: the GPU's geometry is float around the camera (the CPU's double), and its
// bilinear taps weigh with 8 fractional bits on most hardware. `point` reads level 0 of every map
// at one position per pixel, so a position moved by rounding lands on texel-scale contrast (the
// aliased detail is all there is); the filtered modes read levels whose contrast per texel is
// lower. Measured on llvmpipe: point ≤ 6e-4, the filtered modes ≤ 1.3e-4 (docs/gpu.md). The
// tolerances are 5 to 8 times that, and 10 times below the smallest difference between two CPU
// modes on a scene (checked below), so that a wrong sign or a transposed matrix fails.
double gpu_cpu_tolerance(GpuFilter f) {
    return f == GpuFilter::point ? 3e-3 : 1e-3;
}

struct DemoRender {
    RenderScene scene;
    Image mask;
};

DemoRender prepare_demo(const std::string& name, int width, int height) {
    DemoSceneOptions options;
    options.width = width;
    options.height = height;
    Result<DemoScene> demo = make_demo_scene(name, options);
    EXPECT_TRUE(demo) << name;
    Result<RenderScene> scene = prepare_render_scene(demo->scene);
    EXPECT_TRUE(scene) << scene.error().message;
    Image mask = interior_mask(*scene);
    return {std::move(*scene), std::move(mask)};
}

Image gpu_render(GpuRenderer& renderer, GpuFilter filter) {
    GpuRenderOptions options;
    options.filter = filter;
    Result<Image> image = renderer.render(options);
    EXPECT_TRUE(image) << image.error().message;
    return image ? *image : Image{};
}

double rmse(const Image& a, const Image& b, const Image* mask = nullptr) {
    MetricsOptions options;
    options.mask = mask;
    Result<ImageComparison> d = compare_images(a, b, options);
    EXPECT_TRUE(d) << d.error().message;
    return d ? d->rmse : INFINITY;
}

TEST(GpuScenes, EveryModeMatchesTheCpuRendererOnEveryDemoScene) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    for (const std::string& name : demo_scene_names()) {
        DemoRender demo = prepare_demo(name, 160, 90);
        Result<GpuRenderer> gpu = GpuRenderer::create(demo.scene);
        ASSERT_TRUE(gpu) << gpu.error().message;
        std::map<FilterMode, Image> cpu;
        for (GpuFilter f : all_gpu_filters()) {
            const std::optional<FilterMode> mode = cpu_counterpart(f);
            if (!mode) continue;
            RenderOptions options;
            options.filter = *mode;
            cpu[*mode] = render(demo.scene, options);
            const double d = rmse(gpu_render(*gpu, f), cpu[*mode]);
            std::printf("%-17s %-9s GPU vs CPU RMSE %.2e\n", name.c_str(), gpu_filter_name(f), d);
            EXPECT_LT(d, gpu_cpu_tolerance(f)) << name << " " << gpu_filter_name(f);
        }
        // The tolerance resolves the method: the CPU's own modes differ by far more (except on
        // the parabolic mirror, whose footprint vanishes, so that every mode is the point lookup).
        if (name == "parabolic_mirror") continue;
        const double trilinear_vs_fa = rmse(cpu[FilterMode::trilinear], cpu[FilterMode::fa_rough]);
        EXPECT_GT(trilinear_vs_fa, 10 * gpu_cpu_tolerance(GpuFilter::fa_rough)) << name;
    }
}

// A cube map: the zebra sky converted to six faces, on a mirror sphere and a bumpy mirror plate.
// Footprint-assembly probes cross face edges on both paths (the GPU's by its seamless cube
// filtering); CPU trilinear reads the centre face only (envmap/environment_map.h), the GPU's is
// seamless, so trilinear is not compared.
TEST(GpuScenes, CubeMapsMatchTheCpuRenderer) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    Result<EnvironmentMap> latlong = EnvironmentMap::from_latlong(make_zebra_latlong(256));
    ASSERT_TRUE(latlong);
    EnvConvertOptions convert;
    convert.size = 64;
    Result<EnvImages> cube = convert_environment(*latlong, EnvLayout::cube, convert);
    ASSERT_TRUE(cube) << cube.error().message;
    SceneDesc desc;
    desc.width = 96;
    desc.height = 54;
    desc.camera = {{0, 1.2, 3}, {0, 0.3, 0}, {0, 1, 0}, 50};
    EnvironmentDesc env;
    env.layout = EnvLayout::cube;
    for (Image& face : cube->faces)
        env.images.push_back({{}, std::make_shared<Image>(std::move(face)), "zebra cube face"});
    desc.environment = env;
    ObjectDesc sphere;
    sphere.shape = SphereShape{{-0.6, 0.5, 0}, 0.5};
    sphere.material.diffuse = 0;
    sphere.material.mirror = 1;
    sphere.material.fresnel_f0 = 0.9f;
    desc.objects.push_back(sphere);
    ObjectDesc plate;
    PlaneShape plane;
    plane.size = {6, 6};
    plate.shape = plane;
    plate.material.diffuse = 0.2f;
    plate.material.mirror = 1;
    plate.material.fresnel_f0 = 0.5f;
    plate.material.bump.source = BumpDesc::Source::height_map;
    plate.material.bump.map = {{}, std::make_shared<Image>(make_water_height_map(128)), "waves"};
    plate.material.bump.strength = 0.01f;
    plate.material.micro_roughness = 0.02f;
    desc.objects.push_back(plate);
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene) << scene.error().message;
    Result<GpuRenderer> gpu = GpuRenderer::create(*scene);
    ASSERT_TRUE(gpu) << gpu.error().message;
    for (GpuFilter f : {GpuFilter::point, GpuFilter::fa, GpuFilter::fa_rough}) {
        RenderOptions options;
        options.filter = *cpu_counterpart(f);
        const double d = rmse(gpu_render(*gpu, f), render(*scene, options));
        std::printf("cube map          %-9s GPU vs CPU RMSE %.2e\n", gpu_filter_name(f), d);
        EXPECT_LT(d, gpu_cpu_tolerance(f)) << gpu_filter_name(f);
    }
}

TEST(GpuScenes, TheParabolicMirrorSeenFromItsFocusHasAVanishingFootprint) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    // Every reflected ray is parallel to the axis: the curvature cancels the aperture, K = 0, and
    // the filtered lookups are the point lookups (spec erratum 2).
    DemoRender demo = prepare_demo("parabolic_mirror", 96, 54);
    Result<GpuRenderer> gpu = GpuRenderer::create(demo.scene);
    ASSERT_TRUE(gpu) << gpu.error().message;
    const Image point = gpu_render(*gpu, GpuFilter::point);
    for (GpuFilter f : {GpuFilter::trilinear, GpuFilter::fa, GpuFilter::fa_rough})
        EXPECT_LT(rmse(gpu_render(*gpu, f), point, &demo.mask), 1e-4) << gpu_filter_name(f);
}

// Against the ground truth (the CPU's reference mode, 1024 samples per pixel), interior RMSE:
// GPU fa-rough within 10 % of CPU fa-rough, and better than the GPU's own anisotropic filtering
// on every scene with a reflection or a bump map (all six). Small images keep the reference
// affordable; under the sanitizers it is left to the Release suite.
// Below this an interior RMSE is rounding (the parabolic mirror's, where fa-rough is exact).
constexpr double kNegligibleRmse = 1e-5;

TEST(GpuScenes, FaRoughIsAsCloseToTheTruthAsOnTheCpuAndBeatsHardwareAnisotropy) {
#ifdef FOOTPRINT_SANITIZED
    GTEST_SKIP() << "the 1024-spp references are too slow under the sanitizers (Release runs it)";
#endif
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    for (const std::string& name : demo_scene_names()) {
        DemoRender demo = prepare_demo(name, 64, 36);
        RenderOptions reference_options;
        reference_options.filter = FilterMode::reference;
        reference_options.spp = 1024;
        const Image reference = render(demo.scene, reference_options);
        RenderOptions cpu_options;
        cpu_options.filter = FilterMode::fa_rough;
        const double cpu = rmse(render(demo.scene, cpu_options), reference, &demo.mask);
        Result<GpuRenderer> gpu = GpuRenderer::create(demo.scene);
        ASSERT_TRUE(gpu) << gpu.error().message;
        const double gpu_fa = rmse(gpu_render(*gpu, GpuFilter::fa_rough), reference, &demo.mask);
        const double hw = rmse(gpu_render(*gpu, GpuFilter::hw_aniso), reference, &demo.mask);
        const double trilinear =
            rmse(gpu_render(*gpu, GpuFilter::trilinear), reference, &demo.mask);
        std::printf(
            "%-17s interior RMSE vs 1024 spp: CPU fa-rough %.4f  GPU fa-rough %.4f  "
            "GPU hw-aniso %.4f  GPU trilinear %.4f\n",
            name.c_str(), cpu, gpu_fa, hw, trilinear);
        EXPECT_LE(gpu_fa, 1.1 * cpu + kNegligibleRmse) << name;
        EXPECT_LT(gpu_fa, hw) << name;
        // llvmpipe's anisotropic sampler is defective (docs/gpu.md), which would make the line
        // above too easy there; trilinear, which it samples right, must be beaten as well.
        if (name != "parabolic_mirror") {
            EXPECT_LT(gpu_fa, trilinear) << name;
        }
    }
}

}  // namespace
}  // namespace footprint
