#include "scene/ray_differentials.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "scene/shapes.h"

namespace footprint {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Central differences of re-intersected rays at x ± h and x ± 2h, h = 1e-3 pixel, in the
// fourth-order five-point stencil (8 (f(h) − f(−h)) − (f(2h) − f(−2h)))/(12h): near the silhouette
// (|cos| ~ 0.05) the plain (f(h) − f(−h))/(2h) is off by ~2e-4 relative (h²/6·|p'''|/|p'|, and p'''
// grows like 1/cos³). Rounding ~1e-16·|p|/h ~ 1e-12 world units per pixel. 1e-4 relative (plus
// 1e-10 absolute, for zero derivatives) still fails on any sign or factor error.
constexpr double kPixelStep = 1e-3;
constexpr double kRelTolerance = 1e-4;
constexpr double kAbsTolerance = 1e-10;
// Pixels whose ray meets the surface at |cos| below this are skipped: there the finite
// difference itself is poorly conditioned (the derivative grows like 1/cos).
constexpr double kMinTestCosine = 0.05;

// A camera: the ray through pixel (x, y) and its derivatives.
struct Camera {
    std::function<Ray(double, double)> ray;
    std::function<RayDifferential(double, double)> differential;
};

struct Basis {
    Vec3d eye, forward, right, up;
};

Basis look_at(Vec3d eye, Vec3d target) {
    const Vec3d f = normalize(target - eye);
    const Vec3d r = normalize(cross(f, Vec3d{0, 1, 0}));
    return {eye, f, r, cross(r, f)};
}

constexpr int kWidth = 64, kHeight = 48;

// Pinhole: o = eye, d = forward + (x − W/2)·a·right − (y − H/2)·a·up.
Camera pinhole(Vec3d eye, Vec3d target, double fov_y_deg) {
    const Basis b = look_at(eye, target);
    const double a = 2 * std::tan(fov_y_deg * 3.14159265358979323846 / 360) / kHeight;
    Camera c;
    c.ray = [=](double x, double y) {
        return Ray{b.eye, b.forward + ((x - kWidth / 2.0) * a) * b.right -
                              ((y - kHeight / 2.0) * a) * b.up};
    };
    c.differential = [=](double x, double y) {
        return RayDifferential{c.ray(x, y), {}, a * b.right, {}, -a * b.up};
    };
    return c;
}

// Orthographic: o = eye + (x − W/2)·s·right − (y − H/2)·s·up, d = forward.
Camera orthographic(Vec3d eye, Vec3d target, double pixel_size) {
    const Basis b = look_at(eye, target);
    const double s = pixel_size;
    Camera c;
    c.ray = [=](double x, double y) {
        return Ray{b.eye + ((x - kWidth / 2.0) * s) * b.right - ((y - kHeight / 2.0) * s) * b.up,
                   2.0 * b.forward};
    };
    c.differential = [=](double x, double y) {
        return RayDifferential{c.ray(x, y), s * b.right, {}, -s * b.up, {}};
    };
    return c;
}

// Both origin and direction move (an off-centre lens point, say), and |d| varies.
Camera general(Vec3d eye, Vec3d target, double fov_y_deg) {
    const Basis b = look_at(eye, target);
    const double a = 2 * std::tan(fov_y_deg * 3.14159265358979323846 / 360) / kHeight;
    const double k = 0.01;  // origin shift per pixel
    Camera c;
    c.ray = [=](double x, double y) {
        const double dx = x - kWidth / 2.0, dy = y - kHeight / 2.0;
        return Ray{b.eye + (k * dx) * b.right + (0.5 * k * dy) * b.forward,
                   (1.5 + 0.01 * dx) * b.forward + (dx * a) * b.right - (dy * a) * b.up};
    };
    c.differential = [=](double x, double y) {
        return RayDifferential{c.ray(x, y), k * b.right, 0.01 * b.forward + a * b.right,
                               (0.5 * k) * b.forward, -a * b.up};
    };
    return c;
}

struct Scene {
    std::string name;
    ShapeDesc shape;
    Vec3d eye, target;
};

std::vector<Scene> scenes() {
    return {
        {"plane", PlaneShape{{0, 0, 0}, {0, 1, 0}, {1, 1}, true, 0.5}, {0, 1, 5}, {0, 0, 0}},
        {"tilted plane",
         PlaneShape{{0.2, 0.1, 0}, {0.3, 1, 0.6}, {3, 3}, false, 2},
         {0.5, 2, 4},
         {0, 0, 0}},
        {"sphere", SphereShape{{0.3, 0.2, -0.1}, 1}, {0.5, 1.2, 4}, {0.3, 0.2, -0.1}},
        {"cylinder", CylinderShape{{0, 0, 0}, {0.2, 1, 0.1}, 0.8, 2}, {0.4, 0.8, 4}, {0, 0, 0}},
        {"paraboloid", ParaboloidShape{{0, 0, 0}, {0, 0, 1}, 0.5, 1}, {0.3, 0.5, 3}, {0, 0, -0.5}},
        {"torus", TorusShape{{0, 0, 0}, {0, 1, 0.5}, 1, 0.35}, {0, 2, 4}, {0, 0, 0}},
    };
}

bool near_vec(Vec3d a, Vec3d b) {
    const double tol = kRelTolerance * std::max(length(a), length(b)) + kAbsTolerance;
    return length(a - b) <= tol;
}

bool near_vec(Vec2d a, Vec2d b) {
    const double tol = kRelTolerance * std::max(length(a), length(b)) + kAbsTolerance;
    return length(a - b) <= tol;
}

std::string str(Vec3d v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) +
           ")";
}
std::string str(Vec2d v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ")";
}

// Checks every pixel of a coarse grid that hits the shape (and whose neighbours at ±h, ±2h do, on
// the same sheet and side of any seam); returns the number of pixels checked.
int check_against_finite_differences(const Scene& scene, const Camera& camera) {
    int checked = 0;
    const auto hit_at = [&](double x, double y) {
        return intersect_analytic(scene.shape, camera.ray(x, y), 1e-9, 1e9);
    };
    for (int py = 2; py < kHeight; py += 4) {
        for (int px = 2; px < kWidth; px += 4) {
            const double x = px + 0.5, y = py + 0.5;
            const std::optional<SurfaceHit> h = hit_at(x, y);
            if (!h) continue;
            const RayDifferential rd = camera.differential(x, y);
            const Vec3d d = normalize(rd.ray.direction);
            if (std::abs(dot(d, h->geometric_normal)) < kMinTestCosine) continue;
            // Hits at x + k h (k = −2, −1, 1, 2), then at y + k h.
            std::optional<SurfaceHit> sx[4], sy[4];
            const double offsets[4] = {-2, -1, 1, 2};
            bool all = true;
            for (int k = 0; k < 4; ++k) {
                sx[k] = hit_at(x + offsets[k] * kPixelStep, y);
                sy[k] = hit_at(x, y + offsets[k] * kPixelStep);
                all = all && sx[k] && sy[k];
            }
            if (!all) continue;
            // Same sheet of the surface (no jump to another part along the ray), and no u or v
            // seam (sphere, cylinder, torus: u; torus: v) in between.
            const double jump = 1e-2 * length(rd.ray.direction) * h->t + 1e-9;
            bool smooth = true;
            for (const auto* samples : {sx, sy}) {
                smooth = smooth && length(samples[3]->p - samples[0]->p) <= jump &&
                         std::abs(samples[3]->uv.x - samples[0]->uv.x) < 0.25 &&
                         std::abs(samples[3]->uv.y - samples[0]->uv.y) < 0.25;
            }
            if (!smooth) continue;
            const SurfaceDifferentials sd = surface_differentials(rd, *h);
            EXPECT_TRUE(sd.valid) << scene.name;
            const auto fd = [&](const std::optional<SurfaceHit>* s, auto field) {
                return (8.0 * (field(*s[2]) - field(*s[1])) - (field(*s[3]) - field(*s[0]))) /
                       (12 * kPixelStep);
            };
            const auto p = [](const SurfaceHit& hit) { return hit.p; };
            const auto n = [](const SurfaceHit& hit) { return hit.n; };
            const auto uv = [](const SurfaceHit& hit) { return hit.uv; };
            const std::string where =
                scene.name + " pixel (" + std::to_string(px) + ", " + std::to_string(py) + ") ";
            const Vec3d fd_dpdx = fd(sx, p), fd_dpdy = fd(sy, p);
            const Vec3d fd_dndx = fd(sx, n), fd_dndy = fd(sy, n);
            const Vec2d fd_duvdx = fd(sx, uv), fd_duvdy = fd(sy, uv);
            EXPECT_TRUE(near_vec(sd.dpdx, fd_dpdx)) << where << str(sd.dpdx) << str(fd_dpdx);
            EXPECT_TRUE(near_vec(sd.dpdy, fd_dpdy)) << where << str(sd.dpdy) << str(fd_dpdy);
            EXPECT_TRUE(near_vec(sd.dndx, fd_dndx)) << where << str(sd.dndx) << str(fd_dndx);
            EXPECT_TRUE(near_vec(sd.dndy, fd_dndy)) << where << str(sd.dndy) << str(fd_dndy);
            EXPECT_TRUE(near_vec(sd.duvdx, fd_duvdx)) << where << str(sd.duvdx) << str(fd_duvdx);
            EXPECT_TRUE(near_vec(sd.duvdy, fd_duvdy)) << where << str(sd.duvdy) << str(fd_duvdy);
            // ∂p lies in the tangent plane.
            EXPECT_NEAR(dot(sd.dpdx, h->geometric_normal), 0, 1e-12 * (1 + length(sd.dpdx)));
            EXPECT_NEAR(dot(sd.dpdy, h->geometric_normal), 0, 1e-12 * (1 + length(sd.dpdy)));
            ++checked;
        }
    }
    return checked;
}

TEST(RayDifferentials, PinholeMatchesFiniteDifferencesOnEveryShape) {
    for (const Scene& s : scenes()) {
        const int checked = check_against_finite_differences(s, pinhole(s.eye, s.target, 40));
        EXPECT_GE(checked, 20) << s.name;
    }
}

TEST(RayDifferentials, OrthographicMatchesFiniteDifferencesOnEveryShape) {
    for (const Scene& s : scenes()) {
        const double pixel = 2.4 / kHeight;  // a 2.4-unit-high view
        const int checked =
            check_against_finite_differences(s, orthographic(s.eye, s.target, pixel));
        EXPECT_GE(checked, 20) << s.name;
    }
}

TEST(RayDifferentials, MovingOriginAndDirectionMatchFiniteDifferences) {
    for (const Scene& s : scenes()) {
        const int checked = check_against_finite_differences(s, general(s.eye, s.target, 40));
        EXPECT_GE(checked, 20) << s.name;
    }
}

TEST(RayDifferentials, PlaneSeenHeadOnIsExact) {
    // Pinhole at height 2 above the plane y = 0 looking straight down, a per pixel: the
    // footprint is a·2 world units per pixel, uv_scale·2a texture units.
    const PlaneShape plane{{0, 0, 0}, {0, 1, 0}, {1, 1}, true, 0.25};
    const double a = 1e-3;
    const RayDifferential rd{{{0, 2, 0}, {0, -1, 0}}, {}, {a, 0, 0}, {}, {0, 0, a}};
    const SurfaceHit h = *intersect(plane, rd.ray, 0, 1e9);
    const SurfaceDifferentials sd = surface_differentials(rd, h);
    ASSERT_TRUE(sd.valid);
    EXPECT_NEAR(sd.dpdx.x, 2 * a, 1e-15);
    EXPECT_NEAR(sd.dpdy.z, 2 * a, 1e-15);
    EXPECT_NEAR(sd.duvdx.x, 0.25 * 2 * a, 1e-15);  // a_u = +x
    EXPECT_NEAR(sd.duvdx.y, 0, 1e-15);
    EXPECT_NEAR(sd.duvdy.y, -0.25 * 2 * a, 1e-15);  // a_v = −z
    EXPECT_EQ(length(sd.dndx), 0);
}

TEST(RayDifferentials, GrazingAndNonFiniteInputAreInvalidAndZero) {
    const PlaneShape plane{{0, 0, 0}, {0, 1, 0}, {1, 1}, true, 1};
    SurfaceHit h = *evaluate(plane, {0.5, 0.5});
    h.t = 3;
    const auto expect_zero = [](const SurfaceDifferentials& sd) {
        EXPECT_FALSE(sd.valid);
        for (const Vec3d v : {sd.dpdx, sd.dpdy, sd.dndx, sd.dndy}) EXPECT_EQ(length(v), 0);
        EXPECT_EQ(length(sd.duvdx), 0);
        EXPECT_EQ(length(sd.duvdy), 0);
    };
    // Exactly and nearly parallel to the plane.
    expect_zero(
        surface_differentials({{{-3, 0, 0}, {1, 0, 0}}, {}, {0, 1e-3, 0}, {}, {0, 0, 1}}, h));
    expect_zero(surface_differentials({{{-3, 0, 0}, {1, -1e-10, 0}}, {}, {0, 1e-3, 0}, {}, {}}, h));
    // Non-finite ray, derivatives, hit.
    const RayDifferential ok{{{0, 3, 0}, {0, -1, 0}}, {}, {1e-3, 0, 0}, {}, {0, 0, 1e-3}};
    EXPECT_TRUE(surface_differentials(ok, h).valid);
    RayDifferential bad = ok;
    bad.dddx.x = kNaN;
    expect_zero(surface_differentials(bad, h));
    bad = ok;
    bad.ray.origin.y = kNaN;
    expect_zero(surface_differentials(bad, h));
    bad = ok;
    bad.dody.z = std::numeric_limits<double>::infinity();
    expect_zero(surface_differentials(bad, h));
    SurfaceHit bad_hit = h;
    bad_hit.t = kNaN;
    expect_zero(surface_differentials(ok, bad_hit));
    bad_hit = h;
    bad_hit.geometric_normal = {};
    expect_zero(surface_differentials(ok, bad_hit));
    bad_hit = h;
    bad_hit.dndu.x = kNaN;
    expect_zero(surface_differentials(ok, bad_hit));
    expect_zero(surface_differentials({{{0, 3, 0}, {0, 0, 0}}, {}, {}, {}, {}}, h));
}

TEST(RayDifferentials, SpherePoleIsFiniteAndValid) {
    // At the pole ∂p/∂u = 0: u is undefined, ∂u = 0 and v follows from ∂p/∂v alone.
    const SphereShape s{{0, 0, 0}, 1};
    const double a = 1e-3;
    const RayDifferential rd{{{0, 5, 0}, {0, -1, 0}}, {}, {a, 0, 0}, {}, {0, 0, a}};
    const SurfaceHit h = *intersect(s, rd.ray, 0, 1e9);
    const SurfaceDifferentials sd = surface_differentials(rd, h);
    ASSERT_TRUE(sd.valid);
    EXPECT_TRUE(is_finite(sd.duvdx) && is_finite(sd.duvdy) && is_finite(sd.dndx) &&
                is_finite(sd.dndy));
    EXPECT_EQ(sd.duvdx.x, 0);
    EXPECT_NEAR(sd.dpdx.x, 4 * a, 1e-15);
    // At the pole φ = 0, ∂p/∂v = −π e(0) = −π·(+z): moving towards +z lowers v.
    EXPECT_NEAR(sd.duvdy.y, -4 * a / 3.14159265358979323846, 1e-15);
    EXPECT_NEAR(sd.dndy.z, 4 * a, 1e-15);
}

}  // namespace
}  // namespace footprint
