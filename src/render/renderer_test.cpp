// Tests of the renderer (render/renderer.h) and scene preparation (render/render_scene.h).
#include "render/renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "envmap/env_layout.h"
#include "math/sample_patterns.h"
#include "metrics/test_rmse.h"
#include "render/camera.h"
#include "render/render_scene.h"
#include "render/test_expect.h"
#include "render/test_scene_parts.h"

namespace footprint {
namespace {

using test::rmse;

std::shared_ptr<const Image> constant_image(int w, int h, float r, float g, float b) {
    auto image = std::make_shared<Image>(w, h, 3);
    for (std::size_t i = 0; i < image->pixel_count(); ++i) {
        image->pixels[i * 3 + 0] = r, image->pixels[i * 3 + 1] = g, image->pixels[i * 3 + 2] = b;
    }
    return image;
}

// A lat-long map whose colour varies smoothly with direction plus fine stripes (so that filtering
// matters), 256 × 128.
std::shared_ptr<const Image> striped_latlong() {
    auto image = std::make_shared<Image>(256, 128, 3);
    for (int y = 0; y < 128; ++y) {
        for (int x = 0; x < 256; ++x) {
            const float stripe = ((x / 2 + y / 2) % 2) ? 1.0f : 0.2f;
            float* p = image->at(x, y);
            p[0] = stripe, p[1] = 0.5f * stripe + 0.25f * y / 128.0f, p[2] = 0.3f;
        }
    }
    return image;
}

using test::latlong_environment;
using test::mirror_material;

// A mirror plane y = 0 seen from above at an angle, in a constant environment.
SceneDesc mirror_plane_scene(float f0) {
    SceneDesc scene;
    scene.width = 48, scene.height = 32;
    scene.camera.position = {0, 2, 4};
    scene.camera.look_at = {0, 0, 0};
    scene.camera.fov_y_deg = 50;
    scene.environment = latlong_environment(constant_image(64, 32, 0.5f, 0.25f, 1.0f));
    PlaneShape plane;
    plane.infinite = true;
    scene.objects.push_back({"mirror", plane, mirror_material(f0)});
    return scene;
}

const FilterMode kAllModes[] = {
    FilterMode::bilinear,    FilterMode::trilinear, FilterMode::fa,   FilterMode::fa_rough,
    FilterMode::ewa_rough,   FilterMode::reference, FilterMode::lean, FilterMode::toksvig,
    FilterMode::specular_aa, FilterMode::stochastic};

TEST(Renderer, MirrorPlaneInConstantEnvironmentIsEnvironmentTimesFresnel) {
    constexpr float kF0 = 0.04f;
    const SceneDesc desc = mirror_plane_scene(kF0);
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const PinholeCamera camera(desc.camera, desc.width, desc.height);
    for (FilterMode mode : kAllModes) {
        RenderOptions options;
        options.filter = mode;
        options.spp = mode == FilterMode::reference ? 64 : 1;
        const Image image = render(*scene, options);
        int checked = 0;
        for (int y = 0; y < desc.height; ++y) {
            for (int x = 0; x < desc.width; ++x) {
                // Every sample of this pixel hits the plane (the horizon is far above): the
                // expected colour at the centre ray; sample offsets change cos θ a little, so the
                // reference gets a looser tolerance.
                const Vec3d d = normalize(camera.ray(x + 0.5, y + 0.5).ray.direction);
                if (d.y > -0.05) continue;
                const double cos_theta = -d.y;  // n = +y, v = −d
                const double fresnel = kF0 + (1 - kF0) * std::pow(1 - cos_theta, 5);
                // The reference's samples spread over the pixel, where Fresnel varies: checked
                // only where it is nearly flat, with a tolerance for its curvature.
                if (mode == FilterMode::reference && cos_theta < 0.5) continue;
                const double tol = mode == FilterMode::reference ? 1e-3 : 2e-5;
                const float* p = image.at(x, y);
                EXPECT_NEAR(p[0], 0.5 * fresnel, tol)
                    << filter_mode_name(mode) << " " << x << "," << y;
                EXPECT_NEAR(p[1], 0.25 * fresnel, tol) << filter_mode_name(mode);
                EXPECT_NEAR(p[2], 1.0 * fresnel, tol) << filter_mode_name(mode);
                ++checked;
            }
        }
        EXPECT_GT(checked, desc.width * desc.height / 4);
    }
}

// A matte white sphere in a rotated environment whose radiance is linear in the map's direction d,
// L = a + B d: its irradiance is E(n) = π a + (2π/3) B A n (A: world → map), exact in nine
// coefficients, so every pixel on the sphere is a + (2/3) B A n. The environment read in world
// space rotated by Aᵀ instead would be off by up to 1.0.
TEST(Renderer, AMatteSphereIsLitByTheEnvironmentsIrradianceAtItsNormal) {
    const float a[3] = {1.0f, 0.9f, 0.8f};
    const Vec3 b[3] = {{0.8f, 0, 0}, {0, 0.7f, 0.2f}, {0, 0, 0.6f}};
    auto image = std::make_shared<Image>(256, 128, 3);
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 256; ++x) {
            const Vec3 d =
                normalize(env_direction(EnvLayout::latlong, 0, (x + 0.5f) / 256, (y + 0.5f) / 128));
            for (int c = 0; c < 3; ++c) image->at(x, y, c) = a[c] + dot(b[c], d);
        }
    SceneDesc desc;
    desc.width = desc.height = 32;
    desc.camera.position = {0, 0, 4};
    desc.camera.look_at = {0, 0, 0};
    desc.camera.fov_y_deg = 35;
    desc.environment = latlong_environment(image);
    desc.environment->rotation_deg = {0, 90, 30};
    MaterialDesc matte;
    matte.base_color = {1, 1, 1};
    desc.objects.push_back({"sphere", SphereShape{{0, 0, 0}, 1}, matte});
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mat3 rotation = rotation_xyz_degrees(0, 90, 30);
    const PinholeCamera camera(desc.camera, desc.width, desc.height);
    constexpr float kTolerance = 2e-3f;  // the map's texels and the projection's quadrature
    for (FilterMode mode : {FilterMode::trilinear, FilterMode::fa_rough}) {
        RenderOptions options;
        options.filter = mode;
        const Image rendered = render(*scene, options);
        int checked = 0;
        for (int y = 0; y < desc.height; ++y)
            for (int x = 0; x < desc.width; ++x) {
                const Ray ray = camera.ray(x + 0.5, y + 0.5).ray;
                const std::optional<SceneHit> hit = scene->intersect(ray, 0, INFINITY);
                if (!hit) continue;
                const Vec3d p = hit->surface.p;
                const Vec3 n = normalize(Vec3{float(p.x), float(p.y), float(p.z)});
                const Vec3 n_map = rotation * n;
                for (int c = 0; c < 3; ++c) {
                    EXPECT_NEAR(rendered.at(x, y, c), a[c] + 2.0f / 3 * dot(b[c], n_map),
                                kTolerance)
                        << filter_mode_name(mode) << " pixel " << x << "," << y << " channel " << c;
                }
                ++checked;
            }
        EXPECT_GT(checked, 200);
    }
}

// Smooth colours over a room's walls, floor and ceiling, for the local-map tests.
Vec3 smooth_wall(Vec3 q) {
    return Vec3{0.5f + 0.4f * std::sin(1.3f * q.x + 0.7f * q.z),
                0.5f + 0.4f * std::sin(2.2f * q.y + 0.5f * q.x),
                0.5f + 0.4f * std::cos(0.9f * q.z - 0.6f * q.y)};
}

// The walls `wall` paints on `proxy` seen from its capture point: a 1024 × 512 lat-long local map
// with that proxy.
template <class Wall>
EnvironmentDesc captured_walls(const EnvProxy& proxy, Wall wall) {
    auto image = std::make_shared<Image>(1024, 512, 3);
    for (int y = 0; y < 512; ++y)
        for (int x = 0; x < 1024; ++x) {
            const Vec3 w =
                env_direction(EnvLayout::latlong, 0, (x + 0.5f) / 1024, (y + 0.5f) / 512);
            const Vec3 c = wall(proxy_step(proxy, proxy.capture, w)->direction + proxy.capture);
            image->at(x, y, 0) = c.x, image->at(x, y, 1) = c.y, image->at(x, y, 2) = c.z;
        }
    EnvironmentDesc env = latlong_environment(image);
    env.proxy = proxy;
    return env;
}

// A local map (envmap/env_proxy.h): a box room's walls captured from a point c into a lat-long
// map, and a mirror floor away from c. With the room as the proxy every mirror pixel shows the
// walls its reflected rays meet: a ray-traced one-bounce reference, computed here over the pixel
// filter's Gaussian (8 × 8 quantiles of σ = ½ pixel); read at infinity, as without the proxy, the
// reflection is the wrong part of the room.
TEST(Renderer, ALocalMapsProxyShowsTheWallTheReflectedRayMeets) {
    EnvProxy room;
    room.min = {-4, 0, -4}, room.max = {4, 3, 4};
    room.capture = {0, 1.5f, 0};
    SceneDesc desc;
    desc.width = 48, desc.height = 32;
    desc.camera = {{-2, 2.5, 3}, {1, 0.5, 0.5}, {0, 1, 0}, 50};
    desc.environment = captured_walls(room, smooth_wall);
    PlaneShape floor;
    floor.center = {1, 0.5, 1};
    floor.size = {4, 4};
    desc.objects.push_back({"mirror floor", floor, mirror_material(1)});
    const PinholeCamera camera(desc.camera, desc.width, desc.height);
    std::vector<double> quantiles;
    for (int i = 0; i < 8; ++i) quantiles.push_back(inverse_normal_cdf((i + 0.5) / 8));
    double error[2] = {0, 0}, largest = 0;
    std::pair<int, int> where;
    int pixels = 0;
    for (bool local : {true, false}) {
        desc.environment->proxy = local ? std::optional<EnvProxy>(room) : std::nullopt;
        Result<RenderScene> scene = prepare_render_scene(desc);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        const Image mask = interior_mask(*scene);
        RenderOptions options;
        options.filter = FilterMode::fa;
        const Image rendered = render(*scene, options);
        pixels = 0;
        for (int y = 0; y < desc.height; ++y)
            for (int x = 0; x < desc.width; ++x) {
                if (mask.at(x, y, 0) < 0.5f) continue;
                Vec3 want{0, 0, 0};
                for (double qx : quantiles)
                    for (double qy : quantiles) {
                        const Ray ray = camera.ray(x + 0.5 + 0.5 * qx, y + 0.5 + 0.5 * qy).ray;
                        const std::optional<SceneHit> hit = scene->intersect(ray, 0, INFINITY);
                        ASSERT_TRUE(hit.has_value());  // interior pixels: the floor throughout
                        const Vec3d d = normalize(ray.direction);
                        const Vec3 r{float(d.x), -float(d.y), float(d.z)};  // the floor's n = +y
                        const Vec3 p{float(hit->surface.p.x), float(hit->surface.p.y),
                                     float(hit->surface.p.z)};
                        want = want + (1.0f / 64) * smooth_wall(proxy_step(room, p, r)->direction +
                                                                room.capture);
                    }
                for (int c = 0; c < 3; ++c) {
                    const double e = std::abs(rendered.at(x, y, c) - (&want.x)[c]);
                    error[local ? 0 : 1] += e;
                    if (local && e > largest) {
                        largest = e;
                        where = {x, y};
                    }
                }
                ++pixels;
            }
        ASSERT_GT(pixels, 300);
        error[local ? 0 : 1] /= 3.0 * pixels;
    }
    std::printf(
        "[ local map ] mean |error| against the one-bounce reference: proxy %.4f "
        "(largest %.4f at pixel %d,%d), at infinity %.4f\n",
        error[0], largest, where.first, where.second, error[1]);
    // The largest error is where a pixel's rays straddle the wall/ceiling edge: the footprint is
    // linearised on one face (docs/performance.md, accuracy bounds).
    constexpr double kMean = 0.002, kLargest = 0.05;
    EXPECT_LT(error[0], kMean);
    EXPECT_LT(largest, kLargest);
    EXPECT_GT(error[1], 50 * error[0]);
}

// Nested local maps: a point reads the innermost map whose proxy contains it (the smallest), the
// scene's environment outside them all. Uniform maps make each pixel that map's colour exactly —
// the mirror's (F0 = 1) and the diffuse light's (L = E/π) — and the background seen from a camera
// inside, between or outside the proxies. The outer room is listed first, so that taking the
// maps in the scene's order instead of the innermost fails.
TEST(Renderer, TheInnermostLocalMapContainingThePointWins) {
    EnvProxy room, alcove;
    room.min = {-4, 0, -4}, room.max = {4, 3, 4};
    alcove.shape = EnvProxy::Shape::sphere;
    alcove.center = {1.5f, 0.5f, 0}, alcove.radius = 1.6f;
    alcove.capture = alcove.center;
    SceneDesc desc;
    desc.width = 48, desc.height = 32;
    desc.camera = {{0, 6, 7}, {0, 0.5, 0}, {0, 1, 0}, 75};
    desc.environment = latlong_environment(constant_image(16, 8, 0, 1, 0));           // green
    desc.local_environments = {latlong_environment(constant_image(16, 8, 1, 0, 0)),   // red room
                               latlong_environment(constant_image(16, 8, 0, 0, 1))};  // blue
    desc.local_environments[0].proxy = room;
    desc.local_environments[1].proxy = alcove;
    const Vec3 red{1, 0, 0}, green{0, 1, 0}, blue{0, 0, 1};
    auto expected = [&](Vec3 p) {  // from the shapes' inequalities
        if (length(p - alcove.center) < alcove.radius) return blue;
        if (std::abs(p.x) < 4 && p.y > 0 && p.y < 3 && std::abs(p.z) < 4) return red;
        return green;
    };
    auto near_an_edge = [&](Vec3 p) {
        return std::abs(length(p - alcove.center) - alcove.radius) < 0.15f ||
               std::abs(std::abs(p.x) - 4) < 0.15f || std::abs(std::abs(p.z) - 4) < 0.15f;
    };
    PlaneShape floor;  // y = 0.5, reaching beyond the room
    floor.center = {0, 0.5, 0};
    floor.size = {12, 12};
    MaterialDesc matte;
    matte.diffuse = 1, matte.base_color = {1, 1, 1};
    for (const MaterialDesc& material : {mirror_material(1), matte}) {
        desc.objects = {{"floor", floor, material}};
        Result<RenderScene> scene = prepare_render_scene(desc);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        const PinholeCamera camera(desc.camera, desc.width, desc.height);
        for (FilterMode mode : {FilterMode::bilinear, FilterMode::fa, FilterMode::fa_rough}) {
            RenderOptions options;
            options.filter = mode;
            const Image rendered = render(*scene, options);
            std::map<int, int> seen;  // pixels per expected colour (by its channel)
            for (int y = 0; y < desc.height; ++y)
                for (int x = 0; x < desc.width; ++x) {
                    const Ray ray = camera.ray(x + 0.5, y + 0.5).ray;
                    const std::optional<SceneHit> hit = scene->intersect(ray, 0, INFINITY);
                    if (!hit) continue;
                    const Vec3 p = vec3_cast<float>(hit->surface.p);
                    if (near_an_edge(p)) continue;
                    const Vec3 want = expected(p);
                    for (int c = 0; c < 3; ++c)
                        ASSERT_NEAR(rendered.at(x, y, c), (&want.x)[c], 1e-4)
                            << "pixel " << x << "," << y << " mode " << filter_mode_name(mode);
                    ++seen[want.x > 0 ? 0 : want.y > 0 ? 1 : 2];
                }
            EXPECT_GT(seen[0], 50);
            EXPECT_GT(seen[1], 50);
            EXPECT_GT(seen[2], 20);
        }
    }
    // The background, from a camera in the alcove, in the room, and outside both.
    desc.objects.clear();
    for (const auto& [position, want] :
         {std::pair{Vec3d{1.5, 0.6, 0.2}, blue}, std::pair{Vec3d{-2, 2, 2}, red},
          std::pair{Vec3d{0, 5, 9}, green}}) {
        desc.camera = {position, {0, 1, 0}, {0, 1, 0}, 60};
        Result<RenderScene> scene = prepare_render_scene(desc);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        RenderOptions options;
        options.filter = FilterMode::fa;
        const Image rendered = render(*scene, options);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(rendered.at(7, 11, c), (&want.x)[c], 1e-4);
    }
}

// Nested local maps against the ray-traced one-bounce reference, as the test above it: a room and
// an alcove in it, each captured from its own point, and a mirror floor reaching into both. Each
// pixel reads the map of the proxy around its hit point along that proxy's own parallax; pixels
// whose Gaussian's rays fall on both sides of the alcove's wall are left out.
TEST(Renderer, NestedLocalMapsShowTheWallsOfTheProxyAroundThePoint) {
    EnvProxy room, alcove;
    room.min = {-4, 0, -4}, room.max = {4, 3, 4};
    room.capture = {0, 1.5f, 0};
    alcove.min = {0.5f, 0, -1.5f}, alcove.max = {3.5f, 2, 2.5f};
    alcove.capture = {2, 1, 0.5f};
    auto alcove_wall = [](Vec3 q) {
        return Vec3{0.3f + 0.2f * std::cos(1.7f * q.z - 0.4f * q.y),
                    0.4f + 0.3f * std::sin(1.1f * q.x + 1.9f * q.y),
                    0.6f + 0.3f * std::sin(0.8f * q.x + 1.2f * q.z)};
    };
    SceneDesc desc;
    desc.width = 48, desc.height = 32;
    desc.camera = {{-2, 2.5, 3}, {1, 0.5, 0.5}, {0, 1, 0}, 50};
    desc.local_environments = {captured_walls(room, smooth_wall),
                               captured_walls(alcove, alcove_wall)};
    PlaneShape floor;
    floor.center = {1, 0.5, 1};
    floor.size = {4, 4};
    desc.objects.push_back({"mirror floor", floor, mirror_material(1)});
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Image mask = interior_mask(*scene);
    RenderOptions options;
    options.filter = FilterMode::fa;
    const Image rendered = render(*scene, options);
    const PinholeCamera camera(desc.camera, desc.width, desc.height);
    std::vector<double> quantiles;
    for (int i = 0; i < 8; ++i) quantiles.push_back(inverse_normal_cdf((i + 0.5) / 8));
    auto in_alcove = [&](Vec3 p) {
        return p.x > alcove.min.x && p.x < alcove.max.x && p.z > alcove.min.z &&
               p.z < alcove.max.z;  // (the floor lies between its floor and ceiling)
    };
    double error = 0, largest = 0;
    int pixels[2] = {0, 0};
    for (int y = 0; y < desc.height; ++y)
        for (int x = 0; x < desc.width; ++x) {
            if (mask.at(x, y, 0) < 0.5f) continue;
            Vec3 want{0, 0, 0};
            int inside = 0;
            for (double qx : quantiles)
                for (double qy : quantiles) {
                    const Ray ray = camera.ray(x + 0.5 + 0.5 * qx, y + 0.5 + 0.5 * qy).ray;
                    const std::optional<SceneHit> hit = scene->intersect(ray, 0, INFINITY);
                    ASSERT_TRUE(hit.has_value());
                    const Vec3 d = vec3_cast<float>(normalize(ray.direction));
                    const Vec3 r{d.x, -d.y, d.z};  // the floor's n = +y
                    const Vec3 p = vec3_cast<float>(hit->surface.p);
                    const bool in = in_alcove(p);
                    inside += in;
                    const EnvProxy& proxy = in ? alcove : room;
                    const Vec3 q = proxy_step(proxy, p, r)->direction + proxy.capture;
                    want = want + (1.0f / 64) * (in ? alcove_wall(q) : smooth_wall(q));
                }
            if (inside != 0 && inside != 64) continue;  // straddling the alcove's wall
            for (int c = 0; c < 3; ++c) {
                const double e = std::abs(rendered.at(x, y, c) - (&want.x)[c]);
                error += e;
                largest = std::max(largest, e);
            }
            ++pixels[inside == 64];
        }
    ASSERT_GT(pixels[0], 150);
    ASSERT_GT(pixels[1], 100);
    error /= 3.0 * (pixels[0] + pixels[1]);
    std::printf(
        "[ nested local maps ] mean |error| %.4f, largest %.4f (%d room, %d alcove pixels)\n",
        error, largest, pixels[0], pixels[1]);
    constexpr double kMean = 0.002, kLargest = 0.05;  // as the single local map's bounds
    EXPECT_LT(error, kMean);
    EXPECT_LT(largest, kLargest);
}

SceneDesc busy_scene() {
    SceneDesc scene;
    scene.width = 40, scene.height = 30;
    scene.camera.position = {0, 1.2, 4};
    scene.camera.look_at = {0, 0.3, 0};
    scene.environment = latlong_environment(striped_latlong());
    scene.lights.push_back({LightType::directional, {-1, -1, -0.5}, {}, {1, 0.9f, 0.8f}});
    SphereShape sphere;
    sphere.radius = 0.8;
    sphere.center = {0, 0.8, 0};
    MaterialDesc shiny = mirror_material(0.9f);
    shiny.specular = 0.5f;
    shiny.micro_roughness = 0.05f;
    scene.objects.push_back({"sphere", sphere, shiny});
    PlaneShape floor;
    floor.infinite = true;
    floor.uv_scale = 2;
    MaterialDesc checker;
    checker.base_color_map = ImageSource{{}, striped_latlong(), "checker"};
    scene.objects.push_back({"floor", floor, checker});
    return scene;
}

TEST(Renderer, OneAndTwoThreadsAreBitIdentical) {
    Result<RenderScene> scene = prepare_render_scene(busy_scene());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    for (FilterMode mode : {FilterMode::fa_rough, FilterMode::reference, FilterMode::ewa_rough,
                            FilterMode::stochastic}) {
        RenderOptions options;
        options.filter = mode;
        options.spp = mode == FilterMode::reference ? 4 : 1;
        options.threads = 1;
        const Image one = render(*scene, options);
        options.threads = 2;
        test::expect_bit_identical(one, render(*scene, options), filter_mode_name(mode));
    }
}

TEST(Renderer, EveryPixelIsFinite) {
    Result<RenderScene> scene = prepare_render_scene(busy_scene());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    for (FilterMode mode : kAllModes) {
        RenderOptions options;
        options.filter = mode;
        RenderStats stats;
        const Image image = render(*scene, options, &stats);
        for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v)) << filter_mode_name(mode);
        EXPECT_EQ(stats.non_finite_samples, 0u);
        EXPECT_EQ(stats.pixels, 40u * 30u);
        EXPECT_GT(stats.lookups, stats.pixels / 2) << filter_mode_name(mode);
    }
}

// A sphere whose every lit sample is NaN (diffuse weight NaN, lit by a point light at the eye so
// that every visible point is lit) in front of a constant background: a pixel on the silhouette
// mixes NaN samples and background samples, a pixel inside the disc has only NaN samples.
SceneDesc nan_sphere_scene() {
    SceneDesc scene;
    scene.width = 24, scene.height = 16;
    scene.camera.position = {0, 0, 4};
    scene.camera.look_at = {0, 0, 0};
    scene.background = {0.2f, 0.4f, 0.6f};
    scene.lights.push_back({LightType::point, {}, {0, 0, 4}, {1, 1, 1}});
    MaterialDesc nan_material;
    nan_material.diffuse = std::numeric_limits<float>::quiet_NaN();
    scene.objects.push_back({"sphere", SphereShape{{0, 0, 0}, 1.0}, nan_material});
    return scene;
}

// Non-finite samples are dropped and the pixel is the mean of the samples kept (not their sum over
// every sample, which darkens it); a pixel without any finite sample is 0; both are counted.
TEST(Renderer, NonFiniteSamplesAreDroppedFromTheMean) {
    const SceneDesc desc = nan_sphere_scene();
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    RenderOptions options;
    options.filter = FilterMode::reference;
    options.spp = 16;
    RenderStats stats;
    const Image image = render(*scene, options, &stats);
    constexpr float kTolerance = 1e-6f;  // float rounding of a mean of equal values
    std::uint64_t zero_pixels = 0;
    for (int y = 0; y < desc.height; ++y) {
        for (int x = 0; x < desc.width; ++x) {
            const float* p = image.at(x, y);
            if (p[0] == 0 && p[1] == 0 && p[2] == 0) {
                ++zero_pixels;
                continue;
            }
            EXPECT_NEAR(p[0], desc.background.x, kTolerance) << x << "," << y;
            EXPECT_NEAR(p[1], desc.background.y, kTolerance) << x << "," << y;
            EXPECT_NEAR(p[2], desc.background.z, kTolerance) << x << "," << y;
        }
    }
    EXPECT_GT(zero_pixels, 0u);
    EXPECT_EQ(stats.non_finite_pixels, zero_pixels);
    // Some samples were dropped from pixels that kept others (the silhouette).
    EXPECT_GT(stats.non_finite_samples, zero_pixels * options.spp);
    EXPECT_EQ(stats.samples, stats.pixels * options.spp);
}

// The seed chooses the samples: the same seed gives the same image, another seed other samples
// (the pixels that differ are those whose samples do not all see one constant colour).
TEST(Renderer, TheSeedChoosesTheSamples) {
    Result<RenderScene> scene = prepare_render_scene(busy_scene());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    RenderOptions options;
    options.filter = FilterMode::reference;
    options.spp = 16;
    const Image first = render(*scene, options);
    EXPECT_EQ(render(*scene, options).pixels, first.pixels);
    options.seed = 2;
    const Image second = render(*scene, options);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < first.pixels.size(); ++i)
        differ += first.pixels[i] != second.pixels[i];
    constexpr double kVaryingFraction = 0.5;  // of this scene's values; about 3/4 vary
    EXPECT_GT(differ, kVaryingFraction * first.pixels.size()) << differ;
}

// The point of the project: one filtered sample per pixel lands much closer to the ground truth
// than one unfiltered (bilinear) sample, and roughness-aware filtering closer than filtering
// without it.
TEST(Renderer, FilteredModesApproachTheReference) {
    Result<RenderScene> scene = prepare_render_scene(busy_scene());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    RenderOptions options;
    options.filter = FilterMode::reference;
    options.spp = 256;
    const Image reference = render(*scene, options);
    options.spp = 1;
    double error[std::size(kAllModes)] = {};
    for (FilterMode mode : kAllModes) {
        if (mode == FilterMode::reference) continue;
        options.filter = mode;
        error[static_cast<int>(mode)] = rmse(render(*scene, options), reference);
    }
    const double bilinear = error[static_cast<int>(FilterMode::bilinear)];
    const double fa = error[static_cast<int>(FilterMode::fa)];
    const double fa_rough = error[static_cast<int>(FilterMode::fa_rough)];
    const double ewa_rough = error[static_cast<int>(FilterMode::ewa_rough)];
    EXPECT_LT(fa_rough, 0.5 * bilinear) << fa_rough << " vs bilinear " << bilinear;
    EXPECT_LT(ewa_rough, 0.5 * bilinear) << ewa_rough << " vs bilinear " << bilinear;
    EXPECT_LT(fa_rough, fa) << fa_rough << " vs fa " << fa;
}

// A fractal terrain (scene/terrain.h) is a generated mesh: every mode renders it, finite and lit,
// and on its far slopes, where the striped texture is minified, the filtered modes land closer to
// the reference than point sampling.
TEST(Renderer, ATerrainRendersInEveryModeAndItsFilteredModesApproachTheReference) {
    SceneDesc desc;
    desc.width = 48, desc.height = 32;
    desc.camera = {{0, 1.5, 9}, {0, 0, 0}, {0, 1, 0}, 40};
    desc.environment = latlong_environment(striped_latlong());
    desc.lights.push_back({LightType::directional, {-1, -1, -0.5}, {}, {1, 0.9f, 0.8f}});
    TerrainShape land;
    land.size = {16, 16};
    land.subdivisions = 6;
    land.height = 1;
    land.seed = 3;
    MaterialDesc ground;
    ground.base_color_map = ImageSource{{}, striped_latlong(), "stripes"};
    desc.objects.push_back({"land", land, ground});
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    RenderOptions options;
    options.filter = FilterMode::reference;
    options.spp = 256;
    const Image reference = render(*scene, options);
    options.spp = 1;
    double error[std::size(kAllModes)] = {};
    for (FilterMode mode : kAllModes) {
        options.filter = mode;
        const Image image = render(*scene, options);
        double sum = 0;
        for (float v : image.pixels) {
            ASSERT_TRUE(std::isfinite(v)) << filter_mode_name(mode);
            sum += v;
        }
        EXPECT_GT(sum / image.pixels.size(), 0.05) << filter_mode_name(mode) << ": not lit";
        error[static_cast<int>(mode)] = rmse(image, reference);
    }
    const double bilinear = error[static_cast<int>(FilterMode::bilinear)];
    for (FilterMode mode :
         {FilterMode::trilinear, FilterMode::fa, FilterMode::fa_rough, FilterMode::ewa_rough})
        EXPECT_LT(error[static_cast<int>(mode)], 0.75 * bilinear)
            << filter_mode_name(mode) << " vs bilinear " << bilinear;
}

// An infinite floor of `material` seen at a grazing angle (the eye half a unit above it, looking
// at the horizon), 64 × 40, in `environment`.
SceneDesc grazing_floor_scene(EnvironmentDesc environment, const MaterialDesc& material) {
    SceneDesc desc;
    desc.width = 64, desc.height = 40;
    desc.camera = {{0, 0.5, 0}, {0, 0.1, -5}, {0, 1, 0}, 40};
    desc.environment = std::move(environment);
    PlaneShape floor;
    floor.infinite = true;
    desc.objects.push_back({"floor", floor, material});
    return desc;
}

// A solid marble texture (texture/procedural.h) on a plane at a grazing angle: band-limited by the
// footprint at one sample per pixel it is closer to the 1024-spp truth than 16-spp supersampling,
// whose samples of the unresolved octaves are noise (interior pixels: the horizon is left out).
TEST(Renderer, AGrazingMarblePlaneFilteredAtOneSampleBeatsSixteenSamples) {
    MaterialDesc marble;
    marble.base_color = {1, 1, 1};
    marble.base_color_procedural = ProceduralTexture{
        ProceduralPattern::marble, 6, 6, {Vec3{0.1f, 0.1f, 0.1f}, Vec3{0.9f, 0.9f, 0.9f}}};
    SceneDesc desc =
        grazing_floor_scene(latlong_environment(constant_image(16, 8, 0.3f, 0.3f, 0.3f)), marble);
    desc.lights.push_back({LightType::directional, {-0.3, -1, -0.2}, {}, {1, 1, 1}});
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Image mask = interior_mask(*scene);
    RenderOptions options;
    options.filter = FilterMode::reference;
    options.spp = 1024;
    const Image truth = render(*scene, options);
    options.spp = 16;
    options.seed = 2;
    const double supersampled = rmse(render(*scene, options), truth, &mask);
    options.spp = 1;
    double filtered[2];
    for (FilterMode mode : {FilterMode::fa, FilterMode::bilinear}) {
        options.filter = mode;
        filtered[mode == FilterMode::fa ? 0 : 1] = rmse(render(*scene, options), truth, &mask);
    }
    std::printf("[ marble ] interior RMSE: fa 1 spp %.4f, bilinear 1 spp %.4f, 16 spp %.4f\n",
                filtered[0], filtered[1], supersampled);
    EXPECT_LT(filtered[0], supersampled);
    EXPECT_LT(filtered[0], 0.5 * filtered[1]);
}

// A procedural bump (noise as a height field) on a mirror plane at a grazing angle, reflecting a
// striped sky: at one sample per pixel the band-limited slopes with the roughness their band limit
// removed (fa-rough) are closer to the 1024-spp truth than the band-limited mean slope alone (fa,
// a sharp mirror where the waves blur the sky) and than point slopes (bilinear).
TEST(Renderer, AGrazingProceduralBumpKeepsTheRoughnessItsBandLimitRemoves) {
    MaterialDesc waves = mirror_material(1);
    waves.bump.source = BumpDesc::Source::procedural;
    waves.bump.procedural = ProceduralTexture{ProceduralPattern::noise, 8, 6};
    waves.bump.strength = 0.05f;
    const SceneDesc desc = grazing_floor_scene(latlong_environment(striped_latlong()), waves);
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Image mask = interior_mask(*scene);
    RenderOptions options;
    options.filter = FilterMode::reference;
    options.spp = 1024;
    const Image truth = render(*scene, options);
    options.spp = 1;
    std::map<FilterMode, double> error;
    for (FilterMode mode : kAllModes) {
        if (mode == FilterMode::reference) continue;
        options.filter = mode;
        const Image image = render(*scene, options);
        for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v)) << filter_mode_name(mode);
        error[mode] = rmse(image, truth, &mask);
    }
    std::printf("[ procedural bump ] interior RMSE: fa-rough %.4f, fa %.4f, bilinear %.4f\n",
                error[FilterMode::fa_rough], error[FilterMode::fa], error[FilterMode::bilinear]);
    EXPECT_LT(error[FilterMode::fa_rough], 0.75 * error[FilterMode::fa]);
    EXPECT_LT(error[FilterMode::fa_rough], 0.75 * error[FilterMode::bilinear]);
}

// RenderOptions::max_probes is footprint assembly's N_max in fa and fa-rough: one probe per lookup
// blurs the grazing floor, the default 30 do not, and the peers' GPU-style filter keeps its own.
TEST(Renderer, MaxProbesBoundsFootprintAssemblysProbeLines) {
    Result<RenderScene> scene = prepare_render_scene(busy_scene());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    RenderOptions options;
    for (FilterMode mode : {FilterMode::fa, FilterMode::fa_rough, FilterMode::lean}) {
        options.filter = mode;
        options.max_probes = 30;
        const Image many = render(*scene, options);
        options.max_probes = 1;
        const Image one = render(*scene, options);
        if (mode == FilterMode::lean) {
            EXPECT_EQ(one.pixels, many.pixels);
        } else {
            EXPECT_GT(rmse(one, many), 1e-3) << filter_mode_name(mode);
        }
    }
}

TEST(Renderer, FilterModeNamesRoundTrip) {
    ASSERT_EQ(all_filter_modes().size(), std::size(kAllModes));
    for (FilterMode mode : kAllModes) {
        EXPECT_EQ(parse_filter_mode(filter_mode_name(mode)), mode);
    }
    EXPECT_FALSE(parse_filter_mode("fa_rough").has_value());
    EXPECT_FALSE(parse_filter_mode("point").has_value());  // bilinear: the texture filters' name
    ASSERT_EQ(peer_filter_modes().size(), 4u);
    for (FilterMode mode : peer_filter_modes()) {
        EXPECT_NE(std::find(std::begin(kAllModes), std::end(kAllModes), mode), std::end(kAllModes));
    }
}

// A rippled mirror plane at a grazing angle with a highlight, the ripples finer than a pixel far
// away: where the peers' sources of slopes and roughness differ.
SceneDesc rippled_plane_scene() {
    SceneDesc scene;
    scene.width = 40, scene.height = 24;
    scene.camera.position = {0, 0.8, 3};
    scene.camera.look_at = {0, 0, -2};
    scene.environment = latlong_environment(striped_latlong());
    scene.lights.push_back({LightType::directional, {0, -0.5, 1}, {}, {1, 1, 1}});
    auto height = std::make_shared<Image>(64, 64, 1);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            height->at(x, y, 0) =
                std::sin(0.9f * x) * std::cos(0.5f * y) + 0.3f * std::sin(2.3f * y);
        }
    }
    MaterialDesc m = mirror_material(0.5f);
    m.diffuse = 0.3f, m.specular = 0.5f, m.shininess = 200;
    m.bump.source = BumpDesc::Source::height_map;
    m.bump.map = {{}, height, "ripples"};
    m.bump.strength = 0.01f;
    m.micro_roughness = 0.02f;
    PlaneShape plane;
    plane.infinite = true;
    plane.uv_scale = 2;
    scene.objects.push_back({"water", plane, m});
    return scene;
}

// Every peer renders the bumped scene with finite pixels, and bit-identically on one and two
// threads (toksvig makes its normal map at the first lookup, from whichever thread comes first).
TEST(Renderer, PeersRenderFiniteAndDeterministic) {
    Result<RenderScene> scene = prepare_render_scene(rippled_plane_scene());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    for (FilterMode mode : peer_filter_modes()) {
        RenderOptions options;
        options.filter = mode;
        options.threads = 1;
        RenderStats stats;
        const Image one = render(*scene, options, &stats);
        EXPECT_EQ(stats.non_finite_samples, 0u) << filter_mode_name(mode);
        options.threads = 2;
        test::expect_bit_identical(one, render(*scene, options), filter_mode_name(mode));
    }
}

// Two scenes sharing one texture system and bump map both get Toksvig's normal map (the second
// finds the name the first took), and render alike.
TEST(Renderer, ScenesSharingATextureSystemShareToksvigNormals) {
    Result<std::unique_ptr<TextureSystem>> made = TextureSystem::create();
    ASSERT_TRUE(made) << made.error().message;
    const std::shared_ptr<TextureSystem> textures = std::move(*made);
    const SceneDesc desc = rippled_plane_scene();
    Result<RenderScene> a = prepare_render_scene(desc, textures);
    Result<RenderScene> b = prepare_render_scene(desc, textures);
    ASSERT_TRUE(a && b);
    RenderOptions options;
    options.filter = FilterMode::toksvig;
    EXPECT_EQ(render(*a, options).pixels, render(*b, options).pixels);
    const RenderMaterial* material = a->analytic_material(0);
    ASSERT_NE(material, nullptr);
    EXPECT_NE(a->toksvig_normals(*material), nullptr);
    EXPECT_NE(b->toksvig_normals(*b->analytic_material(0)), nullptr);
}

// Stochastic texture filtering is unbiased: with more samples per pixel it converges to the
// reference, where a filtered mode keeps its bias. At 64 spp its error is a fraction of its
// 1-spp noise (noise alone would fall to 1/8) and near the reference's own at that rate (its
// levels' box prefilter is its only bias).
constexpr double kConvergedShare = 0.35, kSupersamplingMargin = 1.5;
// How much closer widening must bring the highlight (it is most of the image's error there).
constexpr double kWideningGain = 0.8;
TEST(Renderer, StochasticFilteringConvergesToTheReference) {
    Result<RenderScene> scene = prepare_render_scene(rippled_plane_scene());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    RenderOptions options;
    options.filter = FilterMode::reference;
    options.spp = 1024;
    const Image reference = render(*scene, options);
    options.spp = 64;
    options.seed = 2;
    const double supersampled = rmse(render(*scene, options), reference);
    options.filter = FilterMode::stochastic;
    const double stochastic_64 = rmse(render(*scene, options), reference);
    options.spp = 1;
    const double stochastic_1 = rmse(render(*scene, options), reference);
    EXPECT_LT(stochastic_64, kConvergedShare * stochastic_1)
        << stochastic_64 << " at 64 spp, " << stochastic_1 << " at 1";
    EXPECT_LT(stochastic_64, kSupersamplingMargin * supersampled)
        << stochastic_64 << " against supersampling's " << supersampled;
}

// A microfacet highlight on the ripples: the rough modes widen its distribution by the filtered
// K_b (shading/microfacet.h), which brings it closer to the reference's many sharp highlights than
// the mean normal's alone.
TEST(Renderer, RoughModesWidenMicrofacetHighlightsTowardsTheReference) {
    for (auto highlight : {MaterialDesc::Highlight::beckmann, MaterialDesc::Highlight::ggx}) {
        SceneDesc desc = rippled_plane_scene();
        MaterialDesc& m = desc.objects[0].material;
        m.highlight = highlight;
        m.roughness = 0.2f;
        m.mirror = 0;
        Result<RenderScene> scene = prepare_render_scene(desc);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        RenderOptions options;
        options.filter = FilterMode::reference;
        options.spp = 256;
        const Image reference = render(*scene, options);
        options.spp = 1;
        options.filter = FilterMode::fa;
        const double plain = rmse(render(*scene, options), reference);
        options.filter = FilterMode::fa_rough;
        const double rough = rmse(render(*scene, options), reference);
        EXPECT_LT(rough, kWideningGain * plain)
            << static_cast<int>(highlight) << ": fa-rough " << rough << ", fa " << plain;
    }
}

TEST(RenderScene, MissingImageFileNamesTheKeyAndTheFile) {
    SceneDesc desc = mirror_plane_scene(1);
    desc.source = "scenes/test.json";
    desc.objects[0].material.base_color_map.file = "/nonexistent/wood.png";
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_FALSE(scene.ok());
    const std::string& message = scene.error().message;
    EXPECT_NE(message.find("scenes/test.json"), std::string::npos) << message;
    EXPECT_NE(message.find("objects[0].material.base_color: "), std::string::npos) << message;
    EXPECT_NE(message.find("wood.png"), std::string::npos) << message;
}

}  // namespace
}  // namespace footprint
