// Dynamic environment maps (material.environment_probe): the probe's cube map against the scene it
// was rendered from, and a probed mirror against the ray-traced reflection of the reference.
#include "render/environment_probe.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "metrics/image_metrics.h"
#include "render/camera.h"
#include "render/renderer.h"
#include "render/sample_shader.h"
#include "render/test_scene_parts.h"

namespace footprint {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A lat-long map that varies smoothly and differently along every axis (a flipped or transposed
// face would show), 256 × 128.
EnvironmentDesc smooth_environment() {
    auto image = std::make_shared<Image>(256, 128, 3);
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 256; ++x) {
            const double phi = 2 * kPi * (x + 0.5) / 256, theta = kPi * (y + 0.5) / 128;
            float* p = image->at(x, y);
            p[0] = static_cast<float>(0.5 + 0.4 * std::cos(phi) * std::sin(theta));
            p[1] = static_cast<float>(0.5 + 0.4 * std::cos(theta));
            p[2] = static_cast<float>(0.5 + 0.4 * std::sin(phi) * std::sin(theta));
        }
    return test::latlong_environment(std::move(image), "smooth environment");
}

MaterialDesc probed_mirror(Vec3d centre) {
    MaterialDesc m = test::mirror_material(1);
    m.environment_probe = EnvironmentProbeDesc{centre, 64};
    return m;
}

// With nothing else in the scene, the probe sees the environment: its texels in every direction
// are the environment's, to the resampling of a smooth map. The environment is rotated: the probe
// holds it in world axes.
TEST(EnvironmentProbe, AProbeOfAnEmptySceneIsTheEnvironment) {
    SceneDesc desc;
    desc.environment = smooth_environment();
    desc.environment->rotation_deg = {20, 60, 0};
    desc.objects.push_back({"mirror", SphereShape{{0, 0, 0}, 1}, probed_mirror({0, 0, 0})});
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene) << scene.error().message;
    const RenderMaterial& material = *scene->intersect({{0, 0, 5}, {0, 0, -1}}, 0, 10)->material;
    ASSERT_NE(material.probe, nullptr);
    EXPECT_EQ(material.probe->layout, EnvLayout::cube);
    const RenderEnvironment& env = *scene->environment();
    std::mt19937 rng(2);
    std::normal_distribution<float> gaussian;
    constexpr float kTolerance = 0.01f;  // the map's 0.4 amplitude resampled at 64² per face
    float worst = 0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 d = normalize(Vec3{gaussian(rng), gaussian(rng), gaussian(rng)});
        float probe[3], truth[3];
        ASSERT_TRUE(scene->textures().environment_sample(material.probe->map, d, probe));
        ASSERT_TRUE(scene->textures().environment_sample(env.map, env.rotation * d, truth));
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(probe[c] - truth[c]));
    }
    EXPECT_LT(worst, kTolerance);
}

// The scene: a mirror sphere of `radius` beside a red sphere under a sun, the camera's
// field of view scaled with the mirror. Its reflection of the red sphere is read from the probe at
// its centre (or, without the probe, the red sphere is missing from it).
constexpr Vec3d kRedCentre{2.4, 0, -0.8};

SceneDesc mirror_beside_red_sphere(double radius, bool probe) {
    SceneDesc desc;
    desc.width = 96, desc.height = 72;
    desc.camera = {{0, 0.3, 3}, {0, 0, 0}, {0, 1, 0}, 50 * radius};
    desc.environment = smooth_environment();
    desc.lights.push_back({LightType::directional, {-0.3, -1, -0.5}, {}, {1, 1, 1}});
    MaterialDesc mirror = probed_mirror({0, 0, 0});
    mirror.environment_probe->size = 256;
    if (!probe) mirror.environment_probe.reset();
    desc.objects.push_back({"mirror", SphereShape{{0, 0, 0}, radius}, mirror});
    MaterialDesc red;
    red.base_color = {0.9f, 0.1f, 0.05f};
    desc.objects.push_back({"red", SphereShape{kRedCentre, 0.9}, red});
    return desc;
}

// RMSE over the pixels whose whole pixel filter sees the mirror.
double mirror_rmse(const SceneDesc& desc, const RenderScene& scene, const Image& a,
                   const Image& b) {
    Image mask = interior_mask(scene);
    const PinholeCamera camera(desc.camera, desc.width, desc.height);
    for (int y = 0; y < desc.height; ++y)
        for (int x = 0; x < desc.width; ++x) {
            const std::optional<SceneHit> hit =
                scene.intersect(camera.ray(x + 0.5, y + 0.5).ray, 0, 100);
            if (!hit || hit->surface.object != 0) mask.at(x, y)[0] = 0;
        }
    MetricsOptions options;
    options.mask = &mask;
    Result<ImageComparison> d = compare_images(a, b, options);
    EXPECT_TRUE(d) << d.error().message;
    return d ? d->rmse : INFINITY;
}

struct ProbeErrors {
    double with_probe, without;  // fa-rough's mirror RMSE against the traced reference
};

ProbeErrors probe_errors(double radius) {
    const SceneDesc desc = mirror_beside_red_sphere(radius, true);
    Result<RenderScene> scene = prepare_render_scene(desc);
    Result<RenderScene> at_infinity = prepare_render_scene(mirror_beside_red_sphere(radius, false));
    EXPECT_TRUE(scene && at_infinity);
    if (!scene || !at_infinity) return {INFINITY, INFINITY};
    RenderOptions reference_options;
    reference_options.filter = FilterMode::reference;
    reference_options.spp = 64;
    const Image reference = render(*scene, reference_options);
    const ProbeErrors e{
        mirror_rmse(desc, *scene, render(*scene, RenderOptions{}), reference),
        mirror_rmse(desc, *scene, render(*at_infinity, RenderOptions{}), reference)};
    std::printf(
        "mirror of radius %.1f, RMSE vs the traced reflection: probe %.4f, environment "
        "only %.4f\n",
        radius, e.with_probe, e.without);
    return e;
}

// The probe sees the red sphere from the mirror's centre, the reflection from its surface: the
// parallax, up to one radius, is the error left, and it shrinks with the mirror (the figures:
// docs/performance.md, accuracy bounds).
TEST(EnvironmentProbe, AMirrorShowsItsNeighbourAsTheRayTracedReflectionDoes) {
    constexpr double kParallaxRmse = 0.045;  // radius 0.5 at 2.5 from the neighbour
    const ProbeErrors large = probe_errors(0.5);
    EXPECT_LT(large.with_probe, kParallaxRmse);
    EXPECT_LT(large.with_probe, 0.75 * large.without);
    constexpr double kSmallParallaxRmse = 0.012;  // radius 0.1
    const ProbeErrors small = probe_errors(0.1);
    EXPECT_LT(small.with_probe, kSmallParallaxRmse);
    EXPECT_LT(small.with_probe, 0.25 * small.without);
}

// Every probed object has a probe of its own, which shows the other probed objects (and not its
// own object).
TEST(EnvironmentProbe, EachProbedObjectSeesTheOthers) {
    SceneDesc desc;
    desc.environment = smooth_environment();
    desc.objects.push_back({"left", SphereShape{{-1.5, 0, 0}, 0.5}, probed_mirror({-1.5, 0, 0})});
    desc.objects.push_back({"right", SphereShape{{1.5, 0, 0}, 0.5}, probed_mirror({1.5, 0, 0})});
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene) << scene.error().message;
    const RenderMaterial* left = scene->intersect({{-1.5, 0, 5}, {0, 0, -1}}, 0, 10)->material;
    const RenderMaterial* right = scene->intersect({{1.5, 0, 5}, {0, 0, -1}}, 0, 10)->material;
    ASSERT_TRUE(left->probe && right->probe);
    EXPECT_NE(left->probe, right->probe);
    // Towards each other each probe sees the other mirror (which reflects the environment back,
    // about the opposite direction's colour); away from each other, the environment.
    float towards[3], truth[3];
    const RenderEnvironment& env = *scene->environment();
    ASSERT_TRUE(scene->textures().environment_sample(left->probe->map, {1, 0, 0}, towards));
    ASSERT_TRUE(scene->textures().environment_sample(env.map, env.rotation * Vec3{1, 0, 0}, truth));
    EXPECT_GT(std::abs(towards[2] - truth[2]), 0.5f);  // blue: 0.1 towards +x, 0.9 towards −x
    ASSERT_TRUE(scene->textures().environment_sample(right->probe->map, {1, 0, 0}, towards));
    EXPECT_NEAR(towards[2], truth[2], 0.01f);
}

// The reference's traced reflection shows the red sphere where the mirror faces it.
TEST(EnvironmentProbe, TheReflectionTowardsTheNeighbourIsRed) {
    const SceneDesc desc = mirror_beside_red_sphere(0.5, true);
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene) << scene.error().message;
    // The point of the mirror whose normal bisects the eye and the red sphere's centre.
    const Vec3d eye = desc.camera.position;
    const Vec3d n = normalize(normalize(eye) + normalize(kRedCentre));
    for (FilterMode mode : {FilterMode::reference, FilterMode::fa_rough, FilterMode::bilinear}) {
        const RenderOptions options{mode};  // the shader keeps a reference to it
        detail::SampleShader shader(*scene, options);
        const Vec3d p = 0.5 * n;
        const detail::Rgb c = shader.shade({{eye, p - eye}, {}, {}, {}, {}}, {0.5, 0.5});
        EXPECT_GT(c[0], 3 * c[1]) << filter_mode_name(mode);
        EXPECT_GT(c[0], 0.1f) << filter_mode_name(mode);
    }
}

}  // namespace
}  // namespace footprint
