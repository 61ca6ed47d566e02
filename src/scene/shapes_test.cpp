#include "scene/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace footprint {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Central differences of the parameterisation with step 1e-5 in (u, v): truncation h²/6·|p'''|
// ≤ ~(2π)³·1e-10/6 per unit of size, rounding 1e-16·|p|/h ~ 1e-11: 1e-7 relative to the size of
// the derivative (plus 1e-7 absolute for zero ones) leaves room and still catches any sign error.
constexpr double kFdStep = 1e-5;
constexpr double kFdTolerance = 1e-7;
// A hit lies on the implicit surface to rounding: ~1e-16 × the coordinates' magnitude (≤ 1e3
// here) times a few operations.
constexpr double kSurfaceTolerance = 1e-9;
// intersect() against the brute-force march (bisected to 1e-13): the same root to rounding.
constexpr double kRootTolerance = 1e-8;

void expect_vec_near(Vec3d a, Vec3d b, double tol, const std::string& what) {
    EXPECT_NEAR(a.x, b.x, tol) << what;
    EXPECT_NEAR(a.y, b.y, tol) << what;
    EXPECT_NEAR(a.z, b.z, tol) << what;
}

// ---- Independent descriptions of the shapes: a signed implicit function (distance-like, > 0
// outside for closed shapes, < 0 on the focus side of the mirror) and the bounds.
struct TestShape {
    std::string name;
    ShapeDesc shape;
    std::function<double(Vec3d)> implicit;
    std::function<bool(Vec3d)> in_bounds;
    Vec3d centre;
    double size;          // a length scale: ray origins come from ~3 sizes around the centre
    double v_lo, v_hi;    // the range of v to sample (u ∈ [0, 1] always)
    bool closed_outward;  // n points to implicit > 0 (closed shapes) or < 0 (the mirror)
    bool is_distance;     // the implicit function is the signed distance to the (unbounded) surface
};

TestShape plane_case(Vec3d c, Vec3d normal, Vec2d size, double uv_scale) {
    PlaneShape s{c, normal, size, false, uv_scale};
    const ShapeAxes a = *shape_axes(normal);
    return {"plane",
            s,
            [=](Vec3d p) { return dot(p - c, a.axis); },
            [=](Vec3d p) {
                return std::abs(dot(p - c, a.u)) <= size.x / 2 &&
                       std::abs(dot(p - c, a.v)) <= size.y / 2;
            },
            c,
            std::max(size.x, size.y),
            0.5 - uv_scale * size.y / 2,
            0.5 + uv_scale * size.y / 2,
            true,
            true};
}

TestShape sphere_case(Vec3d c, double r) {
    return {"sphere",
            SphereShape{c, r},
            [=](Vec3d p) { return length(p - c) - r; },
            [](Vec3d) { return true; },
            c,
            r,
            0.02,
            0.98,
            true,
            true};
}

TestShape cylinder_case(Vec3d c, Vec3d axis, double r, double h) {
    const Vec3d a = normalize(axis);
    const auto perp = [=](Vec3d p) { return length((p - c) - dot(p - c, a) * a); };
    return {"cylinder",
            CylinderShape{c, axis, r, h},
            [=](Vec3d p) { return perp(p) - r; },
            [=](Vec3d p) { return std::abs(dot(p - c, a)) <= h / 2; },
            c,
            std::max(r, h),
            0,
            1,
            true,
            true};
}

TestShape paraboloid_case(Vec3d focus, Vec3d axis, double f, double r) {
    const Vec3d a = normalize(axis);
    const Vec3d vertex = focus - f * a;
    const auto rho2 = [=](Vec3d p) {
        const Vec3d q = p - vertex;
        const Vec3d perp = q - dot(q, a) * a;
        return dot(perp, perp);
    };
    // ρ²/(4f) − z: < 0 on the focus side (−f at the focus).
    return {"paraboloid",
            ParaboloidShape{focus, axis, f, r},
            [=](Vec3d p) { return rho2(p) / (4 * f) - dot(p - vertex, a); },
            [=](Vec3d p) { return rho2(p) <= r * r; },
            vertex,
            std::max(r, f),
            0,
            1,
            false,
            false};
}

TestShape torus_case(Vec3d c, Vec3d axis, double big, double small) {
    const Vec3d a = normalize(axis);
    return {"torus",
            TorusShape{c, axis, big, small},
            [=](Vec3d p) {
                const Vec3d q = p - c;
                const double z = dot(q, a);
                const double rho = length(q - z * a);
                return std::hypot(rho - big, z) - small;
            },
            [](Vec3d) { return true; },
            c,
            big + small,
            0,
            1,
            true,
            true};
}

std::vector<TestShape> test_shapes() {
    return {
        plane_case({0.5, -1, 2}, {0.3, 1, -0.2}, {3, 2}, 0.7),
        plane_case({0, 0, 0}, {0, 0, 1}, {1, 1}, 1),
        sphere_case({0.3, -0.2, 0.7}, 1.3),
        sphere_case({100, -40, 250}, 0.05),
        cylinder_case({0.2, 0.1, -0.3}, {0.2, 1, 0.4}, 0.8, 2.5),
        cylinder_case({0, 0, 0}, {1, 0, 0}, 2, 0.5),
        paraboloid_case({0.1, 0.2, 0.3}, {0.3, -0.2, 1}, 0.6, 1.1),
        paraboloid_case({0, 0, 0}, {0, 1, 0}, 2, 3),
        torus_case({0.1, -0.3, 0.2}, {0.1, 1, 0.3}, 1.2, 0.35),
        torus_case({30, -10, 5}, {1, 0, 0}, 3, 1.5),
        torus_case({0, 0, 0}, {0, 0, 1}, 1, 0.05),
    };
}

// (u, v) inside the shape's bounds (the mirror: inside the aperture disc).
Vec2d random_uv(const TestShape& s, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(0, 1);
    for (;;) {
        const Vec2d uv{unit(rng), s.v_lo + (s.v_hi - s.v_lo) * unit(rng)};
        if (std::holds_alternative<PlaneShape>(s.shape)) {
            const PlaneShape& p = std::get<PlaneShape>(s.shape);
            return {0.5 + p.uv_scale * p.size.x * (uv.x - 0.5), uv.y};
        }
        if (std::holds_alternative<ParaboloidShape>(s.shape)) {
            if (std::hypot(uv.x - 0.5, uv.y - 0.5) > 0.5) continue;
        }
        return uv;
    }
}

Vec3d random_unit(std::mt19937& rng) {
    std::normal_distribution<double> g;
    for (;;) {
        const Vec3d v{g(rng), g(rng), g(rng)};
        if (length(v) > 1e-3) return normalize(v);
    }
}

TEST(ShapesAxes, DocumentedFramesAndRightHanded) {
    const ShapeAxes y = *shape_axes({0, 2, 0});
    expect_vec_near(y.u, {1, 0, 0}, 1e-15, "+y: a_u");
    expect_vec_near(y.v, {0, 0, -1}, 1e-15, "+y: a_v");
    const ShapeAxes z = *shape_axes({0, 0, 1});
    expect_vec_near(z.u, {1, 0, 0}, 1e-15, "+z: a_u");
    expect_vec_near(z.v, {0, 1, 0}, 1e-15, "+z: a_v");
    const ShapeAxes x = *shape_axes({3, 0, 0});
    expect_vec_near(x.u, {0, 0, -1}, 1e-15, "+x: a_u");
    expect_vec_near(x.v, {0, 1, 0}, 1e-15, "+x: a_v");
    std::mt19937 rng(3);
    for (int i = 0; i < 1000; ++i) {
        const Vec3d n = random_unit(rng);
        const ShapeAxes a = *shape_axes(7.0 * n);
        expect_vec_near(a.axis, n, 1e-15, "axis");
        expect_vec_near(cross(a.u, a.v), n, 1e-14, "a_u × a_v = a");
        EXPECT_NEAR(length(a.u), 1, 1e-15);
        EXPECT_NEAR(dot(a.u, a.v), 0, 1e-15);
    }
    EXPECT_FALSE(shape_axes({0, 0, 0}));
    EXPECT_FALSE(shape_axes({kNaN, 1, 0}));
    EXPECT_FALSE(shape_axes({kInf, 1, 0}));
}

// Every derivative of evaluate() against central differences of evaluate() itself; n unit,
// tangent, oriented as documented (∂p/∂u × ∂p/∂v ∝ +n, n towards implicit > 0 or < 0).
TEST(ShapesDerivatives, MatchCentralDifferencesOfTheParameterisation) {
    std::mt19937 rng(11);
    for (const TestShape& s : test_shapes()) {
        for (int i = 0; i < 200; ++i) {
            const Vec2d uv = random_uv(s, rng);
            const std::optional<SurfaceHit> h = evaluate_analytic(s.shape, uv);
            ASSERT_TRUE(h) << s.name;
            const double hstep = kFdStep;
            const SurfaceHit up = *evaluate_analytic(s.shape, {uv.x + hstep, uv.y});
            const SurfaceHit um = *evaluate_analytic(s.shape, {uv.x - hstep, uv.y});
            const SurfaceHit vp = *evaluate_analytic(s.shape, {uv.x, uv.y + hstep});
            const SurfaceHit vm = *evaluate_analytic(s.shape, {uv.x, uv.y - hstep});
            const auto check = [&](Vec3d analytic, Vec3d fd, const char* what) {
                const double tol = kFdTolerance * (1 + length(analytic));
                expect_vec_near(analytic, fd, tol, s.name + " " + what);
            };
            check(h->dpdu, (up.p - um.p) / (2 * hstep), "dpdu");
            check(h->dpdv, (vp.p - vm.p) / (2 * hstep), "dpdv");
            check(h->dndu, (up.n - um.n) / (2 * hstep), "dndu");
            check(h->dndv, (vp.n - vm.n) / (2 * hstep), "dndv");
            EXPECT_NEAR(length(h->n), 1, 1e-14) << s.name;
            expect_vec_near(h->geometric_normal, h->n, 0, s.name + " geometric normal");
            EXPECT_NEAR(dot(h->n, h->dpdu), 0, 1e-12 * (1 + length(h->dpdu))) << s.name;
            EXPECT_NEAR(dot(h->n, h->dpdv), 0, 1e-12 * (1 + length(h->dpdv))) << s.name;
            EXPECT_NEAR(dot(h->n, h->dndu), 0, 1e-12 * (1 + length(h->dndu))) << s.name;
            EXPECT_NEAR(dot(h->n, h->dndv), 0, 1e-12 * (1 + length(h->dndv))) << s.name;
            const Vec3d c = cross(h->dpdu, h->dpdv);
            EXPECT_GT(dot(c, h->n), 0.999999 * length(c)) << s.name << ": ∂p/∂u × ∂p/∂v ∝ +n";
            EXPECT_NEAR(s.implicit(h->p), 0, kSurfaceTolerance * (1 + s.size)) << s.name;
            const double eps = 1e-4 * s.size;
            const double side = s.implicit(h->p + eps * h->n);
            if (s.closed_outward) {
                EXPECT_GT(side, 0) << s.name << ": n points outward";
            } else {
                EXPECT_LT(side, 0) << s.name << ": n points to the focus side";
            }
        }
    }
}

// The nearest root of the implicit function (within bounds) in (t_min, t_max) by marching and
// bisecting the first sign change whose root is in bounds; nullopt if none. The march takes 20000
// equal steps, shortened where the implicit function is a signed distance (all shapes but the
// mirror) to 0.9·|f|/|d| (sphere tracing: no root can lie closer), down to 1e-9·size, so even
// rays grazing a thin tube by 1e-8 are resolved.
std::optional<double> brute_force_t(const TestShape& s, const Ray& ray, double t_min,
                                    double t_max) {
    const double uniform = (t_max - t_min) / 20000, dlen = length(ray.direction);
    const double min_step = 1e-9 * s.size / dlen;
    const auto f = [&](double t) { return s.implicit(ray.origin + t * ray.direction); };
    double a = t_min, fa = f(a);
    while (a < t_max) {
        double step = uniform;
        if (s.is_distance) step = std::min(step, std::max(0.9 * std::abs(fa) / dlen, min_step));
        const double b = std::min(a + step, t_max);
        const double fb = f(b);
        if ((fa < 0) != (fb < 0)) {
            double lo = a, hi = b, flo = fa;
            for (int k = 0; k < 200 && hi - lo > 1e-14 * (1 + std::abs(hi)); ++k) {
                const double mid = 0.5 * (lo + hi), fm = f(mid);
                if ((fm < 0) == (flo < 0)) {
                    lo = mid;
                    flo = fm;
                } else {
                    hi = mid;
                }
            }
            const double t = 0.5 * (lo + hi);
            if (s.in_bounds(ray.origin + t * ray.direction)) return t;
        }
        a = b;
        fa = fb;
    }
    return std::nullopt;
}

// Random rays aimed at random surface points (and some random ones): a hit is on the surface, in
// range, the nearest (brute force), and its fields are evaluate() at its (u, v).
TEST(ShapesIntersect, HitsAreOnTheSurfaceNearestAndConsistent) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0, 1);
    for (const TestShape& s : test_shapes()) {
        int hits = 0;
        for (int i = 0; i < 150; ++i) {
            const Vec3d origin = s.centre + (3 * s.size * (0.5 + unit(rng))) * random_unit(rng);
            Vec3d dir;
            if (i % 5 == 4) {
                dir = random_unit(rng);
            } else {
                const Vec2d uv = random_uv(s, rng);
                dir = evaluate_analytic(s.shape, uv)->p - origin;
            }
            dir = (0.1 + 10 * unit(rng)) * normalize(dir);  // t is in units of |direction|
            const Ray ray{origin, dir};
            const double t_max = 8 * s.size / length(dir);
            const std::optional<SurfaceHit> h = intersect_analytic(s.shape, ray, 0, t_max);
            const std::optional<double> brute = brute_force_t(s, ray, 0, t_max);
            ASSERT_EQ(h.has_value(), brute.has_value()) << s.name << " ray " << i;
            if (!h) continue;
            ++hits;
            EXPECT_NEAR(h->t, *brute, kRootTolerance * t_max) << s.name << " ray " << i;
            EXPECT_GT(h->t, 0);
            EXPECT_LT(h->t, t_max);
            expect_vec_near(h->p, origin + h->t * dir, 1e-12 * (1 + length(origin)), s.name);
            EXPECT_NEAR(s.implicit(h->p), 0, kSurfaceTolerance * (1 + length(h->p))) << s.name;
            EXPECT_TRUE(s.in_bounds(h->p)) << s.name;
            EXPECT_EQ(h->object, -1);
            EXPECT_EQ(h->primitive, -1);
            const SurfaceHit e = *evaluate_analytic(s.shape, h->uv);
            const double tol = 1e-9 * (1 + length(h->p));
            expect_vec_near(e.p, h->p, tol, s.name + " p(uv)");
            expect_vec_near(e.n, h->n, 1e-9, s.name + " n(uv)");
            expect_vec_near(e.geometric_normal, h->geometric_normal, 1e-9, s.name + " n_g(uv)");
            expect_vec_near(e.dpdu, h->dpdu, tol * (1 + length(e.dpdu)), s.name + " dpdu(uv)");
            expect_vec_near(e.dpdv, h->dpdv, tol * (1 + length(e.dpdv)), s.name + " dpdv(uv)");
            expect_vec_near(e.dndu, h->dndu, tol * (1 + length(e.dndu)), s.name + " dndu(uv)");
            expect_vec_near(e.dndv, h->dndv, tol * (1 + length(e.dndv)), s.name + " dndv(uv)");
            // The direct overload agrees with the dispatcher.
            const std::optional<SurfaceHit> direct = std::visit(
                [&](const auto& shape) -> std::optional<SurfaceHit> {
                    if constexpr (is_mesh_shape<std::decay_t<decltype(shape)>>) {
                        return std::nullopt;
                    } else {
                        return intersect(shape, ray, 0, t_max);
                    }
                },
                s.shape);
            ASSERT_TRUE(direct);
            EXPECT_EQ(direct->t, h->t);
            // Moving t_min just past the hit finds the next one (or none) beyond it.
            const std::optional<SurfaceHit> next =
                intersect_analytic(s.shape, ray, h->t * (1 + 1e-9) + 1e-12, t_max);
            if (next) {
                EXPECT_GT(next->t, h->t);
            }
        }
        EXPECT_GT(hits, 50) << s.name;
    }
}

TEST(ShapesIntersect, RangeIsOpenAndRespected) {
    const SphereShape s{{0, 0, 0}, 1};
    const Ray ray{{0, 0, 5}, {0, 0, -2}};  // hits at t = 2 and 3
    EXPECT_DOUBLE_EQ(intersect(s, ray, 0, kInf)->t, 2);
    EXPECT_DOUBLE_EQ(intersect(s, ray, 2.5, kInf)->t, 3);
    EXPECT_FALSE(intersect(s, ray, 0, 1.9));
    EXPECT_FALSE(intersect(s, ray, 3.1, kInf));
    EXPECT_DOUBLE_EQ(intersect(s, ray, -kInf, kInf)->t, 2);
    EXPECT_DOUBLE_EQ(intersect(s, Ray{{0, 0, 0}, {0, 0, 1}}, -kInf, kInf)->t, -1);
}

TEST(ShapesIntersect, DegenerateShapesAndRaysGiveNothing) {
    const Ray good{{0.1, 0.2, 5}, {0, 0, -1}};
    const std::vector<ShapeDesc> bad = {
        PlaneShape{{0, 0, 0}, {0, 0, 0}, {1, 1}, false, 1},
        PlaneShape{{0, 0, 0}, {0, 0, 1}, {0, 1}, false, 1},
        PlaneShape{{0, 0, 0}, {0, 0, 1}, {1, 1}, false, 0},
        PlaneShape{{kNaN, 0, 0}, {0, 0, 1}, {1, 1}, true, 1},
        SphereShape{{0, 0, 0}, 0},
        SphereShape{{0, 0, 0}, -1},
        SphereShape{{0, 0, 0}, kNaN},
        SphereShape{{0, 0, 0}, kInf},
        CylinderShape{{0, 0, 0}, {0, 0, 0}, 1, 1},
        CylinderShape{{0, 0, 0}, {0, 1, 0}, 0, 1},
        CylinderShape{{0, 0, 0}, {0, 1, 0}, 1, -1},
        ParaboloidShape{{0, 0, 0}, {0, 0, 1}, 0, 1},
        ParaboloidShape{{0, 0, 0}, {0, 0, 1}, 1, 0},
        ParaboloidShape{{0, 0, 0}, {kNaN, 0, 1}, 1, 1},
        TorusShape{{0, 0, 0}, {0, 0, 1}, 1, 0},
        TorusShape{{0, 0, 0}, {0, 0, 1}, 1, 1},  // horn torus: not a ring torus
        TorusShape{{0, 0, 0}, {0, 0, 1}, 0, 0.5},
        TorusShape{{0, 0, 0}, {0, 0, 0}, 1, 0.5},
        MeshShape{},
    };
    for (const ShapeDesc& s : bad) {
        EXPECT_FALSE(intersect_analytic(s, good, 0, kInf)) << s.index();
        EXPECT_FALSE(evaluate_analytic(s, {0.3, 0.4})) << s.index();
    }
    const std::vector<ShapeDesc> shapes = {
        PlaneShape{{0, 0, 0}, {0, 0, 1}, {1, 1}, true, 1},
        SphereShape{{0, 0, 0}, 1},
        CylinderShape{{0, 0, 0}, {0, 1, 0}, 1, 2},
        ParaboloidShape{{0, 0, 0}, {0, 0, 1}, 1, 1},
        TorusShape{{0, 0, 0}, {0, 1, 0}, 1, 0.25},
    };
    const std::vector<Ray> bad_rays = {
        {{kNaN, 0, 5}, {0, 0, -1}}, {{0, 0, kInf}, {0, 0, -1}}, {{0, 0, 5}, {0, 0, 0}},
        {{0, 0, 5}, {0, kNaN, -1}}, {{0, 0, 5}, {0, 0, -kInf}},
    };
    for (const ShapeDesc& s : shapes) {
        EXPECT_TRUE(intersect_analytic(s, {{0.1, 0.05, 5}, {0, 0, -1}}, 0, kInf) ||
                    std::holds_alternative<CylinderShape>(s))
            << s.index();
        for (const Ray& r : bad_rays) EXPECT_FALSE(intersect_analytic(s, r, 0, kInf)) << s.index();
        EXPECT_FALSE(intersect_analytic(s, good, 1, 1)) << "empty range";
        EXPECT_FALSE(intersect_analytic(s, good, kNaN, kInf)) << "NaN range";
        EXPECT_FALSE(intersect_analytic(s, good, 0, kNaN)) << "NaN range";
        EXPECT_FALSE(evaluate_analytic(s, {kNaN, 0.5}));
    }
}

TEST(ShapesPlane, BothSidesBoundsAndUvConvention) {
    const PlaneShape s{{1, 2, 3}, {0, 5, 0}, {2, 4}, false, 0.5};
    // From above and from below: n is never flipped.
    const auto above = intersect(s, {{1.5, 7, 2}, {0, -1, 0}}, 0, kInf);
    const auto below = intersect(s, {{1.5, -7, 2}, {0, 2, 0}}, 0, kInf);
    ASSERT_TRUE(above && below);
    EXPECT_DOUBLE_EQ(above->t, 5);
    EXPECT_DOUBLE_EQ(below->t, 4.5);
    expect_vec_near(above->n, {0, 1, 0}, 0, "above");
    expect_vec_near(below->n, {0, 1, 0}, 0, "below");
    // a_u = +x, a_v = −z: uv = 0.5·(0.5, 1) + ½.
    EXPECT_DOUBLE_EQ(above->uv.x, 0.75);
    EXPECT_DOUBLE_EQ(above->uv.y, 1.0);
    expect_vec_near(above->dpdu, {2, 0, 0}, 0, "dpdu = a_u/uv_scale");
    expect_vec_near(above->dpdv, {0, 0, -2}, 0, "dpdv = a_v/uv_scale");
    expect_vec_near(above->dndu, {0, 0, 0}, 0, "dndu");
    // Bounds: |l_u| ≤ 1, |l_v| ≤ 2.
    EXPECT_TRUE(intersect(s, {{1.99, 5, 3}, {0, -1, 0}}, 0, kInf));
    EXPECT_FALSE(intersect(s, {{2.01, 5, 3}, {0, -1, 0}}, 0, kInf));
    EXPECT_TRUE(intersect(s, {{1, 5, 4.99}, {0, -1, 0}}, 0, kInf));
    EXPECT_FALSE(intersect(s, {{1, 5, 5.01}, {0, -1, 0}}, 0, kInf));
    PlaneShape inf = s;
    inf.infinite = true;
    EXPECT_TRUE(intersect(inf, {{1000, 5, -3000}, {0, -1, 0}}, 0, kInf));
    // Parallel rays miss.
    EXPECT_FALSE(intersect(inf, {{0, 5, 0}, {1, 0, 0}}, 0, kInf));
    // A plane with uv_scale·size = 1 spans uv ∈ [0, 1]² corner to corner.
    const PlaneShape unit{{0, 0, 0}, {0, 0, 1}, {2, 2}, false, 0.5};
    const auto corner = intersect(unit, {{-0.999999, -0.999999, 1}, {0, 0, -1}}, 0, kInf);
    ASSERT_TRUE(corner);
    EXPECT_NEAR(corner->uv.x, 0, 1e-6);
    EXPECT_NEAR(corner->uv.y, 0, 1e-6);
    const auto centre = intersect(unit, {{0, 0, 1}, {0, 0, -1}}, 0, kInf);
    EXPECT_DOUBLE_EQ(centre->uv.x, 0.5);
    EXPECT_DOUBLE_EQ(centre->uv.y, 0.5);
}

TEST(ShapesSphere, UvConventionAndPoles) {
    const SphereShape s{{1, 1, 1}, 2};
    const auto front = intersect(s, {{1, 1, 10}, {0, 0, -1}}, 0, kInf);  // +z point
    ASSERT_TRUE(front);
    EXPECT_NEAR(front->uv.x, 0.5, 1e-15);
    EXPECT_NEAR(front->uv.y, 0.5, 1e-15);
    expect_vec_near(front->n, {0, 0, 1}, 1e-15, "front n");
    expect_vec_near(front->dpdu, {2 * kPi * 2, 0, 0}, 1e-12, "u grows towards +x");
    expect_vec_near(front->dpdv, {0, kPi * 2, 0}, 1e-12, "v grows up");
    const auto right = intersect(s, {{10, 1, 1}, {-1, 0, 0}}, 0, kInf);  // +x point
    EXPECT_NEAR(right->uv.x, 0.75, 1e-15);
    const auto left = intersect(s, {{-10, 1, 1}, {1, 0, 0}}, 0, kInf);  // −x point
    EXPECT_NEAR(left->uv.x, 0.25, 1e-15);
    // Poles: degenerate but finite.
    for (const double dir : {-1.0, 1.0}) {
        const auto pole = intersect(s, {{1, 1 - 10 * dir, 1}, {0, dir, 0}}, 0, kInf);
        ASSERT_TRUE(pole);
        EXPECT_NEAR(pole->uv.y, dir < 0 ? 1 : 0, 1e-15);
        expect_vec_near(pole->dpdu, {0, 0, 0}, 1e-15, "pole dpdu");
        expect_vec_near(pole->dndu, {0, 0, 0}, 1e-15, "pole dndu");
        EXPECT_TRUE(is_finite(pole->dpdv) && is_finite(pole->dndv) && is_finite(pole->uv));
        EXPECT_NEAR(length(pole->dpdv), kPi * 2, 1e-12);
    }
    // From inside: the far side, outward normal.
    const auto inside = intersect(s, {{1, 1, 1}, {0, 0, 3}}, 0, kInf);
    EXPECT_NEAR(inside->t, 2.0 / 3, 1e-15);
    expect_vec_near(inside->n, {0, 0, 1}, 1e-15, "inside");
}

TEST(ShapesCylinder, OpenTubeBothSidesAndUv) {
    const CylinderShape s{{0, 0, 0}, {0, 1, 0}, 1, 2};
    // Down the axis: parallel, no hit; through the open ends: inside wall, outward n.
    EXPECT_FALSE(intersect(s, {{0, 5, 0}, {0, -1, 0}}, 0, kInf));
    EXPECT_FALSE(intersect(s, {{0.5, 5, 0}, {0, -1, 0}}, 0, kInf));
    const auto wall = intersect(s, {{0, 0, 0}, {0, 0, 1}}, 0, kInf);
    ASSERT_TRUE(wall);
    EXPECT_NEAR(wall->t, 1, 1e-15);
    expect_vec_near(wall->n, {0, 0, 1}, 1e-15, "outward from inside");
    EXPECT_NEAR(wall->uv.x, 0.5, 1e-15);
    EXPECT_NEAR(wall->uv.y, 0.5, 1e-15);
    const auto outside = intersect(s, {{0, 0.9, 5}, {0, 0, -1}}, 0, kInf);
    EXPECT_NEAR(outside->t, 4, 1e-15);
    EXPECT_NEAR(outside->uv.y, 0.95, 1e-15);
    // Just above the top rim: through the open end, hits the far inner wall? No: the ray at
    // y = 1.01 passes above the tube entirely.
    EXPECT_FALSE(intersect(s, {{0, 1.01, 5}, {0, 0, -1}}, 0, kInf));
    // A slanted ray entering through the top opening hits the inner wall below the rim.
    const auto in_top = intersect(s, {{0, 2, 0}, {0.5, -1, 0}}, 0, kInf);
    ASSERT_TRUE(in_top);
    EXPECT_NEAR(in_top->t, 2, 1e-14);
    EXPECT_NEAR(in_top->uv.x, 0.75, 1e-15);
    EXPECT_NEAR(in_top->uv.y, 0.5, 1e-15);
}

TEST(ShapesParaboloid, RaysFromTheFocusReflectParallelToTheAxis) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> unit(0, 1);
    const ParaboloidShape s{{0.3, -0.1, 0.7}, {0.2, 0.4, 1}, 0.8, 1.5};
    const Vec3d axis = normalize(s.axis);
    for (int i = 0; i < 500; ++i) {
        Vec2d uv{unit(rng), unit(rng)};
        if (std::hypot(uv.x - 0.5, uv.y - 0.5) > 0.5) continue;
        const Vec3d target = evaluate(s, uv)->p;
        const Ray ray{s.focus, target - s.focus};
        const auto h = intersect(s, ray, 1e-9, kInf);
        ASSERT_TRUE(h);
        EXPECT_NEAR(h->t, 1, 1e-12);
        EXPECT_NEAR(h->uv.x, uv.x, 1e-12);
        EXPECT_NEAR(h->uv.y, uv.y, 1e-12);
        const Vec3d d = normalize(ray.direction);
        const Vec3d r = d - 2 * dot(d, h->n) * h->n;
        expect_vec_near(r, axis, 1e-12, "reflection from the focus ∥ +axis");
        EXPECT_LT(dot(d, h->n), 0) << "the focus sees the reflecting (n) side";
        // And back: a ray coming in along −axis reflects through the focus.
        const Ray in{h->p + 3.0 * axis, -axis};
        const auto back = intersect(s, in, 0, kInf);
        ASSERT_TRUE(back);
        const Vec3d out = -axis - 2 * dot(-axis, back->n) * back->n;
        const Vec3d to_focus = s.focus - back->p;
        EXPECT_NEAR(length(cross(out, to_focus)), 0, 1e-12) << "passes through the focus";
        EXPECT_GT(dot(out, to_focus), 0);
    }
    // The vertex is at focus − f·axis, with n = axis there; outside the aperture: no hit.
    const auto vertex = intersect(s, {s.focus + 2.0 * axis, -axis}, 0, kInf);
    expect_vec_near(vertex->p, s.focus - s.focal_length * axis, 1e-14, "vertex");
    expect_vec_near(vertex->n, axis, 1e-15, "vertex n");
    EXPECT_NEAR(vertex->uv.x, 0.5, 1e-14);
    EXPECT_NEAR(vertex->uv.y, 0.5, 1e-14);
    const ShapeAxes a = *shape_axes(s.axis);
    EXPECT_FALSE(intersect(s, {s.focus + 1.51 * a.u + 2.0 * axis, -axis}, 0, kInf));
    EXPECT_TRUE(intersect(s, {s.focus + 1.49 * a.u + 2.0 * axis, -axis}, 0, kInf));
}

// A ray along a_u in the torus's equatorial plane (or at height z) at offset w along −a_v meets
// the torus where ρ² = x² + w² and (ρ − R)² + z² = r²: x = ±√((R ± √(r² − z²))² − w²).
std::vector<double> torus_line_roots(double big, double small, double w, double z) {
    std::vector<double> xs;
    if (std::abs(z) >= small) return xs;
    const double half = std::sqrt(small * small - z * z);
    for (const double rho : {big - half, big + half}) {
        if (rho * rho > w * w) {
            const double x = std::sqrt(rho * rho - w * w);
            xs.push_back(-x);
            xs.push_back(x);
        }
    }
    std::sort(xs.begin(), xs.end());
    return xs;
}

TEST(ShapesTorus, GrazingAndThreadingRaysFindEveryRootInOrder) {
    const TorusShape s{{0.5, -0.2, 0.1}, {0.3, 1, -0.2}, 1.5, 0.4};
    const ShapeAxes a = *shape_axes(s.axis);
    const double big = s.major_radius, small = s.minor_radius;
    struct Case {
        double w, z;
        size_t roots;
    };
    const Case cases[] = {
        {0, 0, 4},                   // through the centre: two tube crossings
        {big - small - 1e-7, 0, 4},  // threading the hole, just grazing the inner equator
        {big - small + 1e-7, 0, 2},  // just inside the inner equator: one long chord
        {big + small - 1e-7, 0, 2},  // grazing the outer equator: two roots 1e-3 apart
        {big + small + 1e-7, 0, 0},  // just missing it
        {0, small - 1e-7, 4},        // skimming the top of the tube across the hole
        {0, small + 1e-7, 0},        // just above it
        {big, small * 0.999999, 2},  // tangent-ish to the top circle's ring
        {0.3, -0.2, 4},              // generic
    };
    for (const Case& c : cases) {
        const std::vector<double> xs = torus_line_roots(big, small, c.w, c.z);
        ASSERT_EQ(xs.size(), c.roots) << c.w << " " << c.z;
        const double start = 10;
        const Ray ray{s.center - start * a.u - c.w * a.v + c.z * a.axis, a.u};
        double t_min = 0;
        for (size_t k = 0; k < xs.size(); ++k) {
            const auto h = intersect(s, ray, t_min, kInf);
            ASSERT_TRUE(h) << "w " << c.w << " z " << c.z << " root " << k;
            EXPECT_NEAR(h->t, start + xs[k], 1e-9) << "w " << c.w << " z " << c.z << " root " << k;
            t_min = 0.5 * (h->t + start + (k + 1 < xs.size() ? xs[k + 1] : xs[k] + 1));
        }
        EXPECT_FALSE(intersect(s, ray, t_min, kInf)) << "w " << c.w << " z " << c.z;
    }
    // Down the axis through the hole: nothing; down through the tube: the top and the bottom.
    EXPECT_FALSE(intersect(s, {s.center + 5.0 * a.axis, -a.axis}, 0, kInf));
    const auto top = intersect(s, {s.center + big * a.u + 5.0 * a.axis, -a.axis}, 0, kInf);
    ASSERT_TRUE(top);
    EXPECT_NEAR(top->t, 5 - small, 1e-12);
    EXPECT_NEAR(top->uv.y, 0.25, 1e-12);
    expect_vec_near(top->n, a.axis, 1e-12, "top n");
    // uv: outer equator at the front (−a_v) is (½, 0), the inner equator there v = ½.
    const auto outer = intersect(s, {s.center - 5.0 * a.v, a.v}, 0, kInf);
    EXPECT_NEAR(outer->uv.x, 0.5, 1e-12);
    EXPECT_NEAR(std::fmod(outer->uv.y + 0.5, 1.0), 0.5, 1e-12);
    const auto inner = intersect(s, {s.center, -a.v}, 0, kInf);
    EXPECT_NEAR(inner->uv.x, 0.5, 1e-12);
    EXPECT_NEAR(inner->uv.y, 0.5, 1e-12);
    expect_vec_near(inner->n, a.v, 1e-12, "inner equator n points to the axis");
}

// Many rays through and near the hole of a thin torus far from the origin against the march.
TEST(ShapesTorus, MatchesBruteForceNearTheHole) {
    const TestShape s = torus_case({40, -25, 60}, {0.2, 0.3, 1}, 2, 0.3);
    const TorusShape& torus = std::get<TorusShape>(s.shape);
    const ShapeAxes a = *shape_axes(torus.axis);
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> unit(-1, 1);
    int hits = 0;
    for (int i = 0; i < 300; ++i) {
        // Aim at a point in the hole or on the inner half of the tube, from above or the side.
        const double rho = 1.7 + 0.3 * unit(rng), phi = kPi * unit(rng), z = 0.35 * unit(rng);
        const Vec3d target =
            torus.center + rho * (std::sin(phi) * a.u - std::cos(phi) * a.v) + z * a.axis;
        const Vec3d origin = target + 6.0 * normalize(Vec3d{unit(rng), unit(rng), unit(rng)});
        const Ray ray{origin, target - origin};
        const std::optional<SurfaceHit> h = intersect(torus, ray, 0, 3);
        const std::optional<double> brute = brute_force_t(s, ray, 0, 3);
        ASSERT_EQ(h.has_value(), brute.has_value()) << i;
        if (!h) continue;
        ++hits;
        EXPECT_NEAR(h->t, *brute, kRootTolerance) << i;
        EXPECT_NEAR(s.implicit(h->p), 0, kSurfaceTolerance) << i;
    }
    EXPECT_GT(hits, 100);
}

}  // namespace
}  // namespace footprint
