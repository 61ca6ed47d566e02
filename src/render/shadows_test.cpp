// Shadow rays (SampleShader::in_shadow(), RenderScene::occluded()) against brute force: the
// shadow of a sphere on a plane worked out per pixel from the two shapes' equations.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

#include "render/camera.h"
#include "render/render_scene.h"
#include "render/renderer.h"

namespace footprint {
namespace {

constexpr Vec3d kSphereCentre{0, 1, 0};
constexpr double kSphereRadius = 0.5;

// A matte floor (y = 0) and a sphere above it, lit by `light` only (no environment).
SceneDesc sphere_over_floor(const LightDesc& light) {
    SceneDesc scene;
    scene.width = 64, scene.height = 48;
    scene.camera = {{0, 3, 4}, {0, 0, -0.5}, {0, 1, 0}, 50};
    scene.lights.push_back(light);
    MaterialDesc matte;
    matte.base_color = {0.8f, 0.8f, 0.8f};
    matte.specular = 0;
    PlaneShape floor;
    floor.infinite = true;
    scene.objects.push_back({"floor", floor, matte});
    scene.objects.push_back({"sphere", SphereShape{kSphereCentre, kSphereRadius}, matte});
    return scene;
}

Image render_scene(const SceneDesc& desc) {
    Result<RenderScene> scene = prepare_render_scene(desc);
    EXPECT_TRUE(scene) << scene.error().message;
    RenderOptions options;
    options.filter = FilterMode::bilinear;  // one sample at each pixel's centre
    return scene ? render(*scene, options) : Image{};
}

// Whether the segment from p towards `to_light` (t in (0, t_max)) meets the sphere: the quadratic.
bool sphere_blocks(Vec3d p, Vec3d to_light, double t_max) {
    const Vec3d f = p - kSphereCentre;
    const double a = dot(to_light, to_light), b = dot(f, to_light);
    const double c = dot(f, f) - kSphereRadius * kSphereRadius;
    const double disc = b * b - a * c;
    if (disc < 0) return false;
    const double t0 = (-b - std::sqrt(disc)) / a, t1 = (-b + std::sqrt(disc)) / a;
    return (t0 > 0 && t0 < t_max) || (t1 > 0 && t1 < t_max);
}

// Per pixel: the floor point the centre ray meets (none where it meets the sphere or the sky).
std::optional<Vec3d> floor_point(const SceneDesc& desc, int x, int y) {
    const PinholeCamera camera(desc.camera, desc.width, desc.height);
    const Ray ray = camera.ray(x + 0.5, y + 0.5).ray;
    if (!(ray.direction.y < 0)) return std::nullopt;
    if (sphere_blocks(ray.origin, ray.direction, 1e30)) return std::nullopt;
    return ray.origin + (-ray.origin.y / ray.direction.y) * ray.direction;
}

// The render with shadows equals, pixel by pixel, the render without them where the light sees
// the floor point and black (no light, no environment) where the sphere hides it. The pixels whose
// shadow ray passes within kEdge of the sphere's silhouette are left out (float hit points).
void expect_brute_force_shadow(const LightDesc& light, int* shadowed_pixels) {
    const SceneDesc desc = sphere_over_floor(light);
    SceneDesc unshadowed = desc;
    unshadowed.lights[0].shadows = false;
    const Image with = render_scene(desc), without = render_scene(unshadowed);
    ASSERT_EQ(with.width, desc.width);
    constexpr double kEdge = 1e-4;
    constexpr float kTolerance = 1e-6f;  // the same shading in float
    *shadowed_pixels = 0;
    for (int y = 0; y < desc.height; ++y)
        for (int x = 0; x < desc.width; ++x) {
            const std::optional<Vec3d> p = floor_point(desc, x, y);
            if (!p) continue;
            const bool point = light.type == LightType::point;
            const Vec3d to_light = point ? light.position - *p : -light.direction;
            const double t_max = point ? 1 : 1e30;
            const bool blocked = sphere_blocks(*p, to_light, t_max);
            const Vec3d inward = kSphereCentre - *p;  // the ray's distance from the centre
            const Vec3d u = normalize(to_light);
            const double miss = length(inward - dot(inward, u) * u) - kSphereRadius;
            if (std::abs(miss) < kEdge) continue;
            *shadowed_pixels += blocked;
            for (int c = 0; c < 3; ++c) {
                const float expected = blocked ? 0.0f : without.at(x, y)[c];
                ASSERT_NEAR(with.at(x, y)[c], expected, kTolerance)
                    << "pixel " << x << "," << y << (blocked ? " (in shadow)" : " (lit)");
            }
        }
}

TEST(Shadows, ASphereShadowsTheFloorWhereItsEquationsSay) {
    int shadowed = 0;
    expect_brute_force_shadow({LightType::directional, {0.4, -1, -0.3}, {}, {1, 1, 1}}, &shadowed);
    EXPECT_GT(shadowed, 20);  // the shadow is in view
}

// A point light: the shadow is a cone from the light, and an object beyond the light blocks
// nothing (the shadow ray ends at the light).
TEST(Shadows, APointLightsShadowEndsAtTheLight) {
    int shadowed = 0;
    expect_brute_force_shadow({LightType::point, {}, {0.3, 2.2, 0.2}, {3, 3, 3}}, &shadowed);
    EXPECT_GT(shadowed, 20);
    // The light inside the sphere's shadow cone but below the sphere: nothing in between.
    int beyond = 0;
    expect_brute_force_shadow({LightType::point, {}, {0, 0.3, 0}, {1, 1, 1}}, &beyond);
    EXPECT_EQ(beyond, 0);
}

// A convex object alone never shadows itself: shadows on and off give the same image, at every
// distance from the origin (the bias grows with it), on analytic shapes and on a mesh.
TEST(Shadows, AConvexObjectAloneCastsNoShadowOnItself) {
    for (const double offset : {0.0, 1e3}) {
        SceneDesc desc;
        desc.width = 48, desc.height = 36;
        const Vec3d o{offset, 0, offset};
        desc.camera = {o + Vec3d{0, 1.5, 3}, o, {0, 1, 0}, 50};
        desc.lights.push_back({LightType::directional, {0.5, -0.3, -1}, {}, {1, 1, 1}});
        MaterialDesc m;
        m.specular = 0.5f;
        desc.objects.push_back({"sphere", SphereShape{o + Vec3d{-0.6, 0, 0}, 0.5}, m});
        TerrainShape hill;  // a height field is no convex object: only a smooth, gentle one
        hill.center = o + Vec3d{0.6, -0.2, 0};
        hill.size = {1, 1};
        hill.subdivisions = 3;
        hill.height = 0.01;
        desc.objects.push_back({"hill", hill, m});
        SceneDesc unshadowed = desc;
        unshadowed.lights[0].shadows = false;
        const Image with = render_scene(desc), without = render_scene(unshadowed);
        ASSERT_EQ(with.pixels.size(), without.pixels.size());
        int lit = 0;
        for (std::size_t i = 0; i < with.pixels.size(); ++i) {
            ASSERT_EQ(with.pixels[i], without.pixels[i]) << "value " << i << " offset " << offset;
            lit += with.pixels[i] > 0;
        }
        EXPECT_GT(lit, 300);
    }
}

// The any-hit query agrees with the nearest-hit query on every ray, over analytic shapes and the
// meshes' Embree BVH.
TEST(Shadows, OccludedAgreesWithIntersectOnRandomRays) {
    SceneDesc desc = sphere_over_floor({LightType::directional, {0, -1, 0}, {}, {1, 1, 1}});
    TerrainShape mounds;
    mounds.center = {1.5, 0, 0};
    mounds.size = {2, 2};
    mounds.subdivisions = 5;
    mounds.height = 0.5;
    desc.objects.push_back({"mounds", mounds, MaterialDesc{}});
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene) << scene.error().message;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> position(-3, 3), length(0.1, 6);
    int blocked = 0;
    constexpr int kRays = 20000;
    for (int i = 0; i < kRays; ++i) {
        const Ray ray{{position(rng), std::abs(position(rng)) + 0.01, position(rng)},
                      {position(rng), position(rng), position(rng)}};
        const double t_max = length(rng);
        const bool any = scene->occluded(ray, 0, t_max);
        ASSERT_EQ(any, scene->intersect(ray, 0, t_max).has_value()) << "ray " << i;
        blocked += any;
    }
    EXPECT_GT(blocked, kRays / 10);
    EXPECT_LT(blocked, kRays * 9 / 10);
}

}  // namespace
}  // namespace footprint
