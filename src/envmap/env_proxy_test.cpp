// Tests of the parallax-corrected lookup direction (envmap/env_proxy.h): the exit point lies on the
// proxy, and the footprint's Jacobian ∂d = P ∂p + (t/|r|) P ∂r against central differences of d.
#include <footprint/envmap/env_proxy.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace footprint {
namespace {

Vec3 random_vector(std::mt19937& rng, float extent) {
    std::uniform_real_distribution<float> u(-extent, extent);
    return {u(rng), u(rng), u(rng)};
}

EnvProxy room_box() {
    EnvProxy box;
    box.shape = EnvProxy::Shape::box;
    box.min = {-3, 0, -4}, box.max = {5, 3, 2};
    box.capture = {0.5f, 1.5f, -1};
    return box;
}

EnvProxy room_sphere() {
    EnvProxy sphere;
    sphere.shape = EnvProxy::Shape::sphere;
    sphere.center = {1, 2, -1}, sphere.radius = 4;
    sphere.capture = {0, 1.5f, 0};
    return sphere;
}

// The direction d(p, r) in double-checked form: the exit point q on the proxy's surface.
TEST(EnvProxy, TheLookupDirectionEndsOnTheProxy) {
    std::mt19937 rng(5);
    for (const EnvProxy& proxy : {room_box(), room_sphere()}) {
        for (int i = 0; i < 200; ++i) {
            const Vec3 p = proxy.shape == EnvProxy::Shape::box
                               ? Vec3{0.5f, 1.5f, -1} + random_vector(rng, 1.4f)
                               : proxy.center + random_vector(rng, 2);
            const Vec3 r = random_vector(rng, 1);
            const std::optional<ProxyStep> step = proxy_step(proxy, p, 3.0f * r);
            ASSERT_TRUE(step.has_value());
            const Vec3 q = step->direction + proxy.capture;
            // q is ahead of p along r…
            EXPECT_NEAR(length(cross(q - p, r)), 0, 1e-4f * length(q - p) * length(r));
            EXPECT_GT(dot(q - p, r), 0);
            // …and on the surface.
            if (proxy.shape == EnvProxy::Shape::sphere) {
                EXPECT_NEAR(length(q - proxy.center), proxy.radius, 1e-4f);
            } else {
                const float gap =
                    std::min({std::abs(q.x - proxy.min.x), std::abs(q.x - proxy.max.x),
                              std::abs(q.y - proxy.min.y), std::abs(q.y - proxy.max.y),
                              std::abs(q.z - proxy.min.z), std::abs(q.z - proxy.max.z)});
                EXPECT_LT(gap, 1e-4f);
            }
        }
    }
    // Outside and facing away, or missing: no step (the map at infinity).
    EXPECT_FALSE(proxy_step(room_box(), {10, 1, 0}, {1, 0, 0}).has_value());
    EXPECT_FALSE(proxy_step(room_sphere(), {10, 2, -1}, {0, 1, 0}).has_value());
}

// ∂d against central differences of d(p + h ∂p, r + h ∂r), for random p, r, ∂p, ∂r away from the
// box's edges (where d is not differentiable). A wrong sign of the distance term or a missing
// projection is off by the whole of ∂d.
TEST(EnvProxy, TheFootprintsJacobianMatchesFiniteDifferences) {
    std::mt19937 rng(9);
    constexpr float h = 1e-3f;
    for (const EnvProxy& proxy : {room_box(), room_sphere()}) {
        int checked = 0;
        for (int i = 0; i < 400 && checked < 150; ++i) {
            const Vec3 p = proxy.shape == EnvProxy::Shape::box
                               ? Vec3{0.5f, 1.5f, -1} + random_vector(rng, 1.4f)
                               : proxy.center + random_vector(rng, 2);
            const Vec3 r = 2.0f * random_vector(rng, 1);
            const Vec3 dp = random_vector(rng, 1), dr = random_vector(rng, 1);
            const auto step = proxy_step(proxy, p, r);
            const auto plus = proxy_step(proxy, p + h * dp, r + h * dr);
            const auto minus = proxy_step(proxy, p - h * dp, r - h * dr);
            ASSERT_TRUE(step && plus && minus);
            // The three on one face of the box (else a crease lies between them).
            if (dot(step->m, plus->m) < 0.999f || dot(step->m, minus->m) < 0.999f) continue;
            const Vec3 fd = (plus->direction - minus->direction) / (2 * h);
            const Vec3 analytic = step->move(dp, dr);
            EXPECT_NEAR(length(analytic - fd), 0, 2e-3f * (1 + length(fd)))
                << "analytic " << analytic.x << ' ' << analytic.y << ' ' << analytic.z << ", fd "
                << fd.x << ' ' << fd.y << ' ' << fd.z;
            ++checked;
        }
        EXPECT_GE(checked, 100);
    }
}

// Containment against each shape's inequality, on random points and on the surface itself (a
// room's floor lies on its box's face); volumes from the shapes' formulas.
TEST(EnvProxy, ContainmentFollowsTheShapeAndKeepsItsSurface) {
    std::mt19937 rng(13);
    const EnvProxy box = room_box(), sphere = room_sphere();
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p = Vec3{1, 1.5f, -1} + random_vector(rng, 6);
        const bool in_box = p.x >= -3 && p.x <= 5 && p.y >= 0 && p.y <= 3 && p.z >= -4 && p.z <= 2;
        const bool in_sphere = length(p - sphere.center) <= sphere.radius;
        // Away from the surfaces (1e-3 of the size) the tolerance cannot decide.
        const float box_gap = std::min({std::abs(p.x + 3), std::abs(p.x - 5), std::abs(p.y),
                                        std::abs(p.y - 3), std::abs(p.z + 4), std::abs(p.z - 2)});
        if (box_gap > 8e-3f) {
            EXPECT_EQ(proxy_contains(box, p), in_box) << p.x << " " << p.y;
        }
        if (std::abs(length(p - sphere.center) - sphere.radius) > 4e-3f) {
            EXPECT_EQ(proxy_contains(sphere, p), in_sphere);
        }
    }
    // On the surface, rounded either way by a float's last bits: inside.
    EXPECT_TRUE(proxy_contains(box, {0, std::nextafter(0.0f, -1.0f), 0}));
    EXPECT_TRUE(proxy_contains(box, {5.0001f, 1, 0}));
    EXPECT_FALSE(proxy_contains(box, {5.01f, 1, 0}));
    EXPECT_TRUE(proxy_contains(sphere, sphere.center + Vec3{0, 4.0001f, 0}));
    EXPECT_FALSE(proxy_contains(sphere, sphere.center + Vec3{0, 4.01f, 0}));
    EXPECT_FLOAT_EQ(proxy_volume(box), 8 * 3 * 6);
    EXPECT_FLOAT_EQ(proxy_volume(sphere), 4.0f / 3.0f * 3.14159265f * 64);
}

}  // namespace
}  // namespace footprint
