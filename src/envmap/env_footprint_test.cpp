#include "envmap/env_footprint.h"
#include "envmap/env_footprint_plain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

namespace footprint {
namespace {

// Chain-rule D against central differences of the whole pipeline pixel → v, n → v_r → (s, t),
// evaluated in float: a step of 0.05 px gives a difference error of ~eps·S/h ≈ 1e−3 texel/px (plus
// h²-truncation, far smaller), against |D| of order 0.1–10: a wrong sign (erratum 2) or a
// transposed term misses by ≥ 50 %.
constexpr float kChainRuleRelTolerance = 5e-3f;
constexpr float kChainRuleAbsTolerance = 3e-3f;
constexpr float kPixelStep = 0.05f;

struct Case {
    EnvLayout layout;
    Vec2 scale;  // S
};
constexpr Case kLayouts[] = {{EnvLayout::cube, {512, 512}},
                             {EnvLayout::latlong, {2048, 1024}},
                             {EnvLayout::sphere, {1024, 1024}},
                             {EnvLayout::paraboloid, {512, 512}}};

// The paper's camera: eye at the origin looking along +z, focal distance z0 pixels; v = −(x, y,
// z0).
constexpr float kZ0 = 400;
Vec3 view(float x, float y) {
    return {-x, -y, -kZ0};
}

// A smooth normal field over the screen (curvature), facing the eye.
struct NormalField {
    Vec3 n0, ax, ay;
    Vec3 operator()(float x, float y) const { return n0 + x * ax + y * ay; }
};

Vec2 map_position(EnvLayout layout, Vec2 scale, const ReflectionGeometry& g, int* face) {
    const EnvFootprint f = compute_env_footprint(layout, scale, g);
    *face = f.coords.face;
    return {f.coords.s * scale.x, f.coords.t * scale.y};
}

TEST(EnvFootprint, ChainRuleMatchesFiniteDifferencesInEveryLayout) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1, 1);
    for (const Case& c : kLayouts) {
        int checked = 0;
        for (int i = 0; i < 4000 && checked < 300; ++i) {
            const float x = 200 * u(rng), y = 200 * u(rng);
            NormalField field{{0.6f * u(rng), 0.6f * u(rng), -1.0f},
                              {2e-3f * u(rng), 2e-3f * u(rng), 1e-3f * u(rng)},
                              {2e-3f * u(rng), 2e-3f * u(rng), 1e-3f * u(rng)}};
            field.n0 = 1.7f * field.n0;  // any scale
            auto geometry = [&](float px, float py) {
                ReflectionGeometry g;
                g.v = view(px, py);
                g.n = field(px, py);
                g.dn_dx = field.ax;
                g.dn_dy = field.ay;
                return g;
            };
            const ReflectionGeometry g = geometry(x, y);
            const EnvFootprint f = compute_env_footprint(c.layout, c.scale, g);
            if (f.bump_dropped || f.normal_clamped) continue;
            int faces[4];
            const Vec2 px0 =
                map_position(c.layout, c.scale, geometry(x - kPixelStep, y), &faces[0]);
            const Vec2 px1 =
                map_position(c.layout, c.scale, geometry(x + kPixelStep, y), &faces[1]);
            const Vec2 py0 =
                map_position(c.layout, c.scale, geometry(x, y - kPixelStep), &faces[2]);
            const Vec2 py1 =
                map_position(c.layout, c.scale, geometry(x, y + kPixelStep), &faces[3]);
            // Stay away from face changes, the lat-long seam and its poles (finite differences
            // jump).
            if (faces[0] != f.coords.face || faces[1] != f.coords.face ||
                faces[2] != f.coords.face || faces[3] != f.coords.face)
                continue;
            const Vec2 fd_x = (px1 - px0) / (2 * kPixelStep), fd_y = (py1 - py0) / (2 * kPixelStep);
            if (length(fd_x) > 50 || length(fd_y) > 50)
                continue;  // a seam or a pole inside the step
            const float tol_x = kChainRuleRelTolerance * length(fd_x) + kChainRuleAbsTolerance;
            const float tol_y = kChainRuleRelTolerance * length(fd_y) + kChainRuleAbsTolerance;
            EXPECT_NEAR(f.d_dx.x, fd_x.x, tol_x) << int(c.layout) << " case " << i;
            EXPECT_NEAR(f.d_dx.y, fd_x.y, tol_x) << int(c.layout) << " case " << i;
            EXPECT_NEAR(f.d_dy.x, fd_y.x, tol_y) << int(c.layout) << " case " << i;
            EXPECT_NEAR(f.d_dy.y, fd_y.y, tol_y) << int(c.layout) << " case " << i;
            ++checked;
        }
        EXPECT_GE(checked, 100) << "layout " << int(c.layout);
    }
}

TEST(EnvFootprint, ParabolicMirrorSeenFromItsFocusHasNoFootprint) {
    // [E7b]: the mirror z = f − (x² + y²)/(4f) with its focus at the eye reflects every view ray to
    // −z, so D = 0. With the paper's printed ∂v/∂x = +e_x it would come out ~1 texel/px.
    const double focal = 50;
    auto surface = [&](double px, double py, Vec3* normal) {
        // Ray (px, py, z0) from the focus: τ z0 − f + τ²(px² + py²)/(4f) = 0.
        const double a = (px * px + py * py) / (4 * focal), b = kZ0, c = -focal;
        const double tau = a > 0 ? (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a) : -c / b;
        const double x = tau * px, y = tau * py;
        *normal =
            Vec3{float(-x / (2 * focal)), float(-y / (2 * focal)), -1.0f};  // −∇F, towards the eye
        return tau;
    };
    const Vec2 scale{2048, 1024};
    for (double px : {-150.0, -40.0, 0.0, 75.0})
        for (double py : {-120.0, 10.0, 90.0}) {
            ReflectionGeometry g;
            g.v = view(float(px), float(py));
            surface(px, py, &g.n);
            const double h = 1e-3;
            Vec3 n_px0, n_px1, n_py0, n_py1;
            surface(px - h, py, &n_px0);
            surface(px + h, py, &n_px1);
            surface(px, py - h, &n_py0);
            surface(px, py + h, &n_py1);
            g.dn_dx = (n_px1 - n_px0) / float(2 * h);
            g.dn_dy = (n_py1 - n_py0) / float(2 * h);
            const EnvFootprint f = compute_env_footprint(EnvLayout::latlong, scale, g);
            EXPECT_LT(length(f.d_dx) + length(f.d_dy), 2e-2f) << px << "," << py;
            // The paper's sign: the two terms add instead of cancelling.
            ReflectionGeometry wrong = g;
            wrong.dv_dx = {1, 0, 0};
            wrong.dv_dy = {0, 1, 0};
            const EnvFootprint w = compute_env_footprint(EnvLayout::latlong, scale, wrong);
            EXPECT_GT(length(w.d_dx) + length(w.d_dy), 0.5f) << px << "," << py;
        }
}

TEST(EnvFootprint, RoughnessTermIsTheSlopeJacobianTimesB) {
    // K3 = (M E B)(M E B)ᵀ: the columns of M E are the map motion per unit slope, ∂(S·P(v_r))/∂b —
    // checked by finite differences over b — and K3 is the covariance of the texel position under
    // slope noise N(0, B Bᵀ) to first order.
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(-1, 1);
    const Vec2 scale{2048, 1024};
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        ReflectionGeometry g;
        g.v = view(150 * u(rng), 150 * u(rng));
        g.n = {0.4f * u(rng), 0.4f * u(rng), -1.3f};
        g.t1 = {1, 0, 0.4f * u(rng)};
        g.t2 = {0, 1, 0.4f * u(rng)};
        g.roughness = roughness_factor(Sym2{0.02f, 0.005f, 0.01f});
        const EnvFootprint f = compute_env_footprint(EnvLayout::latlong, scale, g);
        if (f.isotropic_fallback) continue;  // the footprint reaches a pole (§3.4)
        const float h = 1e-3f;
        int face;
        Vec2 cols[2];
        for (int k = 0; k < 2; ++k) {
            ReflectionGeometry lo = g, hi = g;
            (k == 0 ? lo.bump_slope.x : lo.bump_slope.y) -= h;
            (k == 0 ? hi.bump_slope.x : hi.bump_slope.y) += h;
            cols[k] = (map_position(EnvLayout::latlong, scale, hi, &face) -
                       map_position(EnvLayout::latlong, scale, lo, &face)) /
                      (2 * h);
        }
        if (length(cols[0]) > 1e4f || length(cols[1]) > 1e4f) continue;  // the seam
        // B' = (M E) B with B = [[d1, d2], [0, d3]].
        const RoughnessFactor& b = g.roughness;
        const Vec2 b1 = b.d1 * cols[0], b2 = b.d2 * cols[0] + b.d3 * cols[1];
        const Sym2 want = footprint_matrix(b1, b2);
        const float scale_k = want.trace();
        ++checked;
        EXPECT_NEAR(f.roughness.xx, want.xx, 5e-3f * scale_k) << i;
        EXPECT_NEAR(f.roughness.xy, want.xy, 5e-3f * scale_k) << i;
        EXPECT_NEAR(f.roughness.yy, want.yy, 5e-3f * scale_k) << i;
        // K = K12 + κ² K3 with κ = 2.
        EXPECT_NEAR(f.matrix.xx, f.curvature.xx + 4 * f.roughness.xx,
                    1e-4f * (f.matrix.trace() + 1));
    }
    EXPECT_GT(checked, 150);
}

TEST(EnvFootprint, RayDifferentialFormAgreesWithSchillingsForm) {
    // Form (a) with r = v_r and ∂r/∂x = A_v ∂v/∂x + A_n ∂n/∂x (computed here by finite differences
    // of v_r over the pixel) gives form (b)'s D; with an environment rotation as well.
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> u(-1, 1);
    const Mat3 rotation = rotation_xyz_degrees(20, -35, 70);
    for (const Case& c : kLayouts)
        for (int i = 0; i < 200; ++i) {
            const float x = 150 * u(rng), y = 150 * u(rng);
            const NormalField field{{0.5f * u(rng), 0.5f * u(rng), -1},
                                    {1e-3f * u(rng), 1e-3f * u(rng), 0},
                                    {1e-3f * u(rng), 1e-3f * u(rng), 0}};
            // v_r in double: the finite differences must not drown in float rounding of |v_r| ≈
            // 500.
            auto reflect_d = [&](double px, double py) {
                const Vec3d v{-px, -py, -double(kZ0)};
                const Vec3d n{field.n0.x + px * field.ax.x + py * field.ay.x,
                              field.n0.y + px * field.ax.y + py * field.ay.y,
                              field.n0.z + px * field.ax.z + py * field.ay.z};
                return 2 * dot(n, v) * n - dot(n, n) * v;
            };
            auto to_float = [](Vec3d a) { return Vec3{float(a.x), float(a.y), float(a.z)}; };
            ReflectionGeometry g;
            g.v = view(x, y);
            g.n = field(x, y);
            g.dn_dx = field.ax;
            g.dn_dy = field.ay;
            EnvFootprintOptions options;
            options.rotation = rotation;
            const EnvFootprint b = compute_env_footprint(c.layout, c.scale, g, options);
            const double h = 0.01;
            const Vec3 dr_dx = to_float((reflect_d(x + h, y) - reflect_d(x - h, y)) / (2 * h));
            const Vec3 dr_dy = to_float((reflect_d(x, y + h) - reflect_d(x, y - h)) / (2 * h));
            const EnvFootprint a = compute_env_footprint(
                c.layout, c.scale, to_float(reflect_d(x, y)), dr_dx, dr_dy, rotation);
            EXPECT_EQ(a.coords.face, b.coords.face);
            const float tol = 2e-3f * (length(b.d_dx) + length(b.d_dy)) + 1e-3f;
            EXPECT_NEAR(a.d_dx.x, b.d_dx.x, tol) << int(c.layout) << " " << i;
            EXPECT_NEAR(a.d_dx.y, b.d_dx.y, tol) << int(c.layout) << " " << i;
            EXPECT_NEAR(a.d_dy.x, b.d_dy.x, tol) << int(c.layout) << " " << i;
            EXPECT_NEAR(a.d_dy.y, b.d_dy.y, tol) << int(c.layout) << " " << i;
        }
    const EnvFootprint bad = compute_env_footprint(EnvLayout::cube, {64, 64}, {NAN, 0, 0}, {}, {});
    EXPECT_TRUE(bad.matrix.is_finite());
}

TEST(EnvFootprint, DegenerateInputsStayFinite) {
    const float nan = std::nanf(""), inf = INFINITY;
    const Vec3 bad[] = {{0, 0, 0}, {nan, 0, 1}, {inf, 0, 0}, {0, 0, 1e-30f}};
    for (const Case& c : kLayouts)
        for (const Vec3 v : bad)
            for (const Vec3 n : bad) {
                ReflectionGeometry g;
                g.v = v;
                g.n = n;
                const EnvFootprint f = compute_env_footprint(c.layout, c.scale, g);
                EXPECT_TRUE(f.matrix.is_finite());
                EXPECT_TRUE(std::isfinite(f.coords.s) && std::isfinite(f.coords.t));
            }
    // A normal facing away from the eye (silhouette): clamped, finite, flagged.
    ReflectionGeometry g;
    g.v = view(10, 20);
    g.n = {0, 0, 1};  // away from the eye at the origin
    g.bump_slope = {0.5f, 0.2f};
    const EnvFootprint f = compute_env_footprint(EnvLayout::cube, {256, 256}, g);
    EXPECT_TRUE(f.normal_clamped);
    EXPECT_TRUE(f.matrix.is_finite());
    EXPECT_GT(dot(f.reflected, f.reflected), 0.0f);
}

// The fast path of form (a) is compute_env_footprint() bit for bit wherever it answers, answers
// for the common case, and declines every rare one. Directions are drawn on the whole sphere, on
// cube edges and corners, at the lat-long seam and near the poles, at scales from 2^-110 to 2^110;
// differentials from 0 to huge, sometimes non-finite; with and without a rotation.
bool same(float a, float b) {
    return std::memcmp(&a, &b, sizeof(float)) == 0;
}
bool same3(Vec3 a, Vec3 b) {
    return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z);
}
bool same2(Vec2 a, Vec2 b) {
    return same(a.x, b.x) && same(a.y, b.y);
}

// Form-(a) rays for the fast paths' bit-for-bit tests: directions anywhere, at poles, cube edges
// and corners, the lat-long seam and on the axes (signed zeros), at scales 2^±110; differentials at
// moderate scales, with some NaN, infinite, zero or huge. Ray i is ordinary() where it is drawn
// to be one of the common lookups.
struct RandomRays {
    std::mt19937 rng{7};
    std::uniform_real_distribution<float> unit{-1, 1}, exponent{-110, 110}, spread{-12, 4};

    static bool ordinary(int i, const EnvRayDifferential& ray) {
        return i % 5 == 0 && std::isfinite(ray.d_dx.y) && std::isfinite(ray.d_dy.z);
    }
    EnvRayDifferential operator()(int i) {
        const Vec3 r = direction(i);
        const float size = std::ldexp(1.0f, static_cast<int>(spread(rng))) * std::sqrt(dot(r, r));
        Vec3 dx = size * Vec3{unit(rng), unit(rng), unit(rng)};
        Vec3 dy = size * Vec3{unit(rng), unit(rng), unit(rng)};
        if (i % 97 == 0) dx.y = std::nanf("");
        if (i % 89 == 0) dy.z = INFINITY;
        if (i % 83 == 0) dx = dy = {};
        if (i % 79 == 0) dx = 1e30f * dx;
        return {r, dx, dy};
    }
    Vec3 direction(int kind) {
        Vec3 r{unit(rng), unit(rng), unit(rng)};
        switch (kind % 6) {
            case 1:
                r.y = std::copysign(1.0f, r.y), r.x *= 1e-3f, r.z *= 1e-3f;
                break;  // a pole
            case 2:
                r.x = std::copysign(std::fabs(r.y), r.x);
                break;  // a cube edge
            case 3:
                r = {std::copysign(1.0f, r.x), std::copysign(1.0f, r.y), r.z > 0 ? 1.0f : -1.0f};
                break;  // a cube corner
            case 4:
                r.x = 1e-7f * r.x, r.z = -std::fabs(r.z);
                break;  // the lat-long seam
            case 5:
                r = kind % 4 == 1 ? Vec3{-0.0f, 0.0f, r.z} : Vec3{r.x, -0.0f, 0.0f};
                break;  // an axis, with signed zeros
        }
        return std::ldexp(1.0f, static_cast<int>(exponent(rng)) / (kind % 3 == 0 ? 1 : 8)) * r;
    }
};

const Mat3 kRotations[] = {Mat3{}, rotation_xyz_degrees(20, -35, 50)};

TEST(EnvFootprint, PlainFootprintIsTheFullOneBitForBit) {
    const float nan = std::nanf(""), inf = INFINITY;
    RandomRays rays;
    for (EnvLayout layout : {EnvLayout::latlong, EnvLayout::cube, EnvLayout::sphere}) {
        const Vec2 scale = layout == EnvLayout::latlong ? Vec2{2048, 1024} : Vec2{1024, 1024};
        int answered = 0, common = 0;
        for (const Mat3& rotation : kRotations)
            for (int i = 0; i < 4000; ++i) {
                const auto [r, dx, dy] = rays(i);
                common += RandomRays::ordinary(i, {r, dx, dy});
                PlainEnvFootprint plain;
                const bool answers = plain_env_footprint(layout, scale, r, dx, dy,
                                                         IdentitySkippingRotation(rotation), plain);
                if (!answers) continue;
                ++answered;
                const EnvFootprint full = plain.full();
                const EnvFootprint f = compute_env_footprint(layout, scale, r, dx, dy, rotation);
                SCOPED_TRACE(testing::Message() << env_layout_name(layout) << " case " << i);
                ASSERT_EQ(full.coords.face, f.coords.face);
                ASSERT_TRUE(same(full.coords.s, f.coords.s) && same(full.coords.t, f.coords.t));
                ASSERT_TRUE(same3(full.reflected, f.reflected) &&
                            same3(full.map_direction, f.map_direction) &&
                            same3(full.map_dr_dx, f.map_dr_dx) &&
                            same3(full.map_dr_dy, f.map_dr_dy));
                ASSERT_TRUE(same2(full.d_dx, f.d_dx) && same2(full.d_dy, f.d_dy));
                ASSERT_TRUE(same(full.matrix.xx, f.matrix.xx) &&
                            same(full.matrix.xy, f.matrix.xy) && same(full.matrix.yy, f.matrix.yy));
                ASSERT_TRUE(same(full.curvature.xx, f.curvature.xx) &&
                            same(full.curvature.yy, f.curvature.yy));
                ASSERT_FALSE(f.isotropic_fallback);
            }
        if (layout == EnvLayout::sphere) {
            EXPECT_EQ(answered, 0);  // only lat-long and cube have a fast path
        } else {
            // It answers the ordinary lookups (drawn at every 5th case: directions anywhere, finite
            // differentials at moderate scales), not just a few.
            EXPECT_GT(answered, common * 3 / 4) << env_layout_name(layout);
        }
    }
    // It declines what only the careful path handles.
    const IdentitySkippingRotation identity{Mat3{}};
    PlainEnvFootprint plain;
    const Vec3 d{1e-3f, 0, 0};
    EXPECT_FALSE(plain_env_footprint(EnvLayout::latlong, {2048, 1024}, {0, 1, 0}, d, d, identity,
                                     plain));  // at the pole
    EXPECT_FALSE(plain_env_footprint(EnvLayout::latlong, {2048, 1024}, {1e-4f, 1, 0}, d, d,
                                     identity, plain));  // reaching it
    EXPECT_FALSE(
        plain_env_footprint(EnvLayout::cube, {512, 512}, {0, 0, 0}, d, d, identity, plain));
    EXPECT_FALSE(
        plain_env_footprint(EnvLayout::cube, {512, 512}, {nan, 0, 1}, d, d, identity, plain));
    EXPECT_FALSE(plain_env_footprint(EnvLayout::cube, {512, 512}, {0, 0, 1}, {inf, 0, 0}, d,
                                     identity, plain));
    EXPECT_FALSE(plain_env_footprint(EnvLayout::cube, {512, 512}, {0, 0, 1e35f}, d, d, identity,
                                     plain));  // beyond 2^100
    EXPECT_TRUE(plain_env_footprint(EnvLayout::latlong, {2048, 1024}, {1, 0.3f, -0.2f}, d, d,
                                    identity, plain));
}

TEST(EnvFootprint, FourPlainFootprintsAreThePlainOnesBitForBit) {
    RandomRays random;
    for (const Mat3& rotation : kRotations)
        for (EnvLayout layout : {EnvLayout::cube, EnvLayout::latlong}) {
            const Vec2 scale = layout == EnvLayout::latlong ? Vec2{2048, 1024} : Vec2{1024, 1024};
            const IdentitySkippingRotation to_map(rotation);
            int answered = 0, taken = 0;
            for (int first = 0; first < 8000; first += 4) {
                EnvRayDifferential rays[4];
                for (int lane = 0; lane < 4; ++lane) rays[lane] = random(first + lane);
                PlainEnvFootprints4 four;
                plain_env_footprints4(layout, scale, rays, to_map, four);
                for (int lane = 0; lane < 4; ++lane) {
                    const auto& [r, dx, dy] = rays[lane];
                    PlainEnvFootprint plain;
                    const bool answers =
                        plain_env_footprint(layout, scale, r, dx, dy, to_map, plain);
                    const bool took = four.plain >> lane & 1;
                    answered += answers;
                    taken += took;
                    SCOPED_TRACE(testing::Message()
                                 << env_layout_name(layout) << " ray " << first + lane << " ("
                                 << r.x << ", " << r.y << ", " << r.z << ")");
                    if (!took) {
                        // Left to the scalar path: refused there too, or beyond 2^100 (its rare
                        // path).
                        const Vec3 m = to_map(r);
                        EXPECT_TRUE(!answers || max_abs_component(m) > 0x1p100f);
                        continue;
                    }
                    ASSERT_TRUE(answers);
                    EXPECT_EQ(four.coords(lane).face, plain.coords.face);
                    EXPECT_TRUE(same(four.coords(lane).s, plain.coords.s) &&
                                same(four.coords(lane).t, plain.coords.t));
                    const Sym2 k = four.matrix(lane);
                    EXPECT_TRUE(same(k.xx, plain.matrix.xx) && same(k.xy, plain.matrix.xy) &&
                                same(k.yy, plain.matrix.yy));
                    EXPECT_TRUE(same3(four.map_direction(lane), plain.map_direction));
                }
            }
            // Nearly every ray the scalar fast path answers is taken four at a time.
            EXPECT_GT(taken, answered * 98 / 100);
            EXPECT_GT(answered, 8000 * 4 / 10);  // lat-long: not at or near the poles
        }
}

}  // namespace
}  // namespace footprint
