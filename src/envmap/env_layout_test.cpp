#include "envmap/env_layout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>

namespace footprint {
namespace {

// ---- Tolerances (each with its reason).
// Central differences in double with h = 1e-5·|r|: truncation h²·|P'''|/6 ≲ 1e-10·(1/ρ³ ≤ 8e3) at
// the lat-long sampling margin ρ/|r| = 0.05, rounding eps/h ≈ 1e-11; relative to |J|.
constexpr double kFdRelTol = 1e-6;
constexpr double kFdStep = 1e-5;
// The same in float with h = 3e-4·|r|: rounding of s, t (6e-8) / 6e-4 ≈ 1e-4, truncation
// 9e-8·8e3/6 ≈ 1.2e-4 at the margin.
constexpr double kFloatFdRelTol = 1e-3;
constexpr float kFloatFdStep = 3e-4f;
// Float vs double evaluation of the same input: a few dozen float ulps (6e-8) through atan2, sqrt,
// hypot and the cancellations inside the rows.
constexpr double kFloatVsDoubleRelTol = 1e-5;
constexpr double kFloatCoordTol = 1e-6;  // s, t ∈ [0,1]: ~8 float ulps of 1
// J r = 0: the products J_ij r_j are of size |J||r| and cancel; a few ulps of that.
constexpr double kEulerRelTol = 1e-13;
constexpr double kFloatEulerRelTol = 1e-5;
// J(λr)·λ vs J(r) for arbitrary λ: only the rounding of λr and of the result.
constexpr double kScaleRelTol = 1e-12;
// Round trips in double: a few ulps amplified by at most ~1e2 (lat-long s near t = 0.01, sphere
// map near its rim at r̂_z = −0.99).
constexpr double kRoundTripTol = 1e-11;
constexpr double kFloatRoundTripTol = 2e-5;  // float, sphere map kept to r̂_z > −0.9
// Exactly known landmark values, in float: two ulps at 1.
constexpr double kLandmarkTol = 2.5e-7;
// Equal-area and conformality identities, double: rounding only.
constexpr double kIdentityRelTol = 1e-10;
constexpr double kFloatIdentityRelTol = 1e-4;

constexpr double kPi = 3.14159265358979323846;
constexpr EnvLayout kLayouts[] = {EnvLayout::cube, EnvLayout::latlong, EnvLayout::sphere,
                                  EnvLayout::paraboloid};
constexpr int kSamples = 3000;

const char* name(EnvLayout l) {
    return env_layout_name(l);
}

double norm(Vec3d a) {
    return std::sqrt(dot(a, a));
}
double frob(const Jacobian23d& j) {
    return std::sqrt(dot(j.ds, j.ds) + dot(j.dt, j.dt));
}
Jacobian23d sub(const Jacobian23d& a, const Jacobian23d& b) {
    return {a.ds - b.ds, a.dt - b.dt};
}
Jacobian23d scaled(const Jacobian23d& a, double k) {
    return {k * a.ds, k * a.dt};
}
Jacobian23d to_double(const Jacobian23& j) {
    return {vec3_cast<double>(j.ds), vec3_cast<double>(j.dt)};
}
double rel(const Jacobian23d& a, const Jacobian23d& ref) {
    return frob(sub(a, ref)) / frob(ref);
}
// |â − b̂|: directions equal up to a positive scale.
double dir_err(Vec3d a, Vec3d b) {
    return norm(normalize(a) - normalize(b));
}

struct Rng {
    std::mt19937 gen{12345};
    double uniform(double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(gen);
    }
    Vec3d unit() {
        std::normal_distribution<double> n;
        for (;;) {
            const Vec3d v{n(gen), n(gen), n(gen)};
            if (norm(v) > 1e-3) return normalize(v);
        }
    }
    // A random positive scale, 1e-3 … 1e3.
    double scale() { return std::exp(uniform(std::log(1e-3), std::log(1e3))); }
};

// Where the coordinates are smooth in a neighbourhood of r (no face change, seam or pole nearby),
// so that finite differences are meaningful.
bool smooth_at(EnvLayout layout, Vec3d r) {
    const Vec3d u = normalize(r);
    switch (layout) {
        case EnvLayout::cube: {
            const int f = cube_coords(r).face;
            for (int i = 0; i < 3; ++i)
                for (double sgn : {-1.0, 1.0}) {
                    Vec3d q = u;
                    (i == 0 ? q.x : i == 1 ? q.y : q.z) += sgn * 1e-3;
                    if (cube_coords(q).face != f) return false;
                }
            return true;
        }
        case EnvLayout::latlong:
            return std::hypot(u.x, u.z) > 0.05 && std::abs(std::atan2(u.x, -u.z)) < kPi - 0.05;
        case EnvLayout::sphere:
            return u.z > -0.9;
        case EnvLayout::paraboloid:
            return std::abs(u.z) > 1e-3;
    }
    return false;
}

template <class T>
Jacobian23T<T> fd_jacobian(EnvLayout layout, Vec3T<T> r, T h) {
    Jacobian23T<T> j;
    Vec3T<T>* rows[2] = {&j.ds, &j.dt};
    for (int i = 0; i < 3; ++i) {
        Vec3T<T> e{};
        (i == 0 ? e.x : i == 1 ? e.y : e.z) = h;
        const EnvCoordsT<T> p = env_coords(layout, r + e), m = env_coords(layout, r - e);
        const T ds = (p.s - m.s) / (2 * h), dt = (p.t - m.t) / (2 * h);
        (i == 0 ? rows[0]->x : i == 1 ? rows[0]->y : rows[0]->z) = ds;
        (i == 0 ? rows[1]->x : i == 1 ? rows[1]->y : rows[1]->z) = dt;
    }
    return j;
}

// ------------------------------------------------------------------------------ all layouts

TEST(EnvLayout, JacobianMatchesFiniteDifferencesDouble) {
    for (EnvLayout layout : kLayouts) {
        Rng rng;
        double worst = 0;
        int used = 0;
        for (int i = 0; i < kSamples; ++i) {
            const Vec3d r = rng.scale() * rng.unit();
            if (!smooth_at(layout, r)) continue;
            ++used;
            const Jacobian23d j = env_jacobian(layout, r);
            worst = std::max(worst, rel(fd_jacobian(layout, r, kFdStep * norm(r)), j));
        }
        EXPECT_GT(used, kSamples / 2) << name(layout);
        EXPECT_LT(worst, kFdRelTol) << name(layout);
    }
}

TEST(EnvLayout, JacobianMatchesFiniteDifferencesFloat) {
    for (EnvLayout layout : kLayouts) {
        Rng rng;
        double worst = 0;
        for (int i = 0; i < kSamples; ++i) {
            const Vec3d rd = rng.scale() * rng.unit();
            if (!smooth_at(layout, rd)) continue;
            const Vec3 r = vec3_cast<float>(rd);
            const Jacobian23d j = to_double(env_jacobian(layout, r));
            const float h = kFloatFdStep * length(r);
            worst = std::max(worst, rel(to_double(fd_jacobian(layout, r, h)), j));
        }
        EXPECT_LT(worst, kFloatFdRelTol) << name(layout);
    }
}

TEST(EnvLayout, FloatAgreesWithDouble) {
    for (EnvLayout layout : kLayouts) {
        Rng rng;
        double worst_j = 0, worst_c = 0;
        for (int i = 0; i < kSamples; ++i) {
            const Vec3 r = vec3_cast<float>(rng.scale() * rng.unit());
            const Vec3d rd = vec3_cast<double>(r);  // the very same input
            if (!smooth_at(layout, rd)) continue;
            worst_j = std::max(worst_j,
                               rel(to_double(env_jacobian(layout, r)), env_jacobian(layout, rd)));
            const EnvCoords c = env_coords(layout, r);
            const EnvCoordsd cd = env_coords(layout, rd);
            EXPECT_EQ(c.face, cd.face);
            worst_c = std::max({worst_c, std::abs(c.s - cd.s), std::abs(c.t - cd.t)});
        }
        EXPECT_LT(worst_j, kFloatVsDoubleRelTol) << name(layout);
        EXPECT_LT(worst_c, kFloatCoordTol) << name(layout);
    }
}

TEST(EnvLayout, JacobianAnnihilatesDirection) {  // [P4]: J r = 0
    for (EnvLayout layout : kLayouts) {
        Rng rng;
        double worst = 0, worst_f = 0;
        for (int i = 0; i < kSamples; ++i) {
            const Vec3d r = rng.scale() * rng.unit();
            const Jacobian23d j = env_jacobian(layout, r);
            const double scale = frob(j) * norm(r);
            if (scale == 0) continue;
            worst = std::max(worst, std::hypot(dot(j.ds, r), dot(j.dt, r)) / scale);
            if (layout == EnvLayout::sphere && normalize(r).z < -0.9) continue;
            const Vec3 rf = vec3_cast<float>(r);
            const Jacobian23 jf = env_jacobian(layout, rf);
            worst_f = std::max(worst_f, double(std::hypot(dot(jf.ds, rf), dot(jf.dt, rf))) / scale);
        }
        EXPECT_LT(worst, kEulerRelTol) << name(layout);
        EXPECT_LT(worst_f, kFloatEulerRelTol) << name(layout);
    }
}

TEST(EnvLayout, JacobianIsHomogeneousOfDegreeMinusOne) {  // J(λr) = J(r)/λ, P(λr) = P(r)
    for (EnvLayout layout : kLayouts) {
        Rng rng;
        double worst = 0;
        for (int i = 0; i < kSamples; ++i) {
            const Vec3d r = rng.scale() * rng.unit();
            const double lambda = std::exp(rng.uniform(-40, 40));  // 4e-18 … 2e17
            const Jacobian23d j = env_jacobian(layout, r);
            if (frob(j) == 0) continue;
            worst = std::max(worst, rel(scaled(env_jacobian(layout, lambda * r), lambda), j));
            const EnvCoordsd a = env_coords(layout, r), b = env_coords(layout, lambda * r);
            if (smooth_at(layout, r)) {
                EXPECT_EQ(a.face, b.face);
                EXPECT_NEAR(a.s, b.s, kScaleRelTol);
                EXPECT_NEAR(a.t, b.t, kScaleRelTol);
            }
            // Powers of two: bit-exact, thanks to the exact power-of-two pre-scaling.
            const Vec3 rf = vec3_cast<float>(r);
            const float p2 = std::ldexp(1.0f, static_cast<int>(rng.uniform(-60, 60)));
            const Jacobian23 jf = env_jacobian(layout, rf), jp = env_jacobian(layout, p2 * rf);
            EXPECT_EQ(jp.ds.x * p2, jf.ds.x);
            EXPECT_EQ(jp.ds.y * p2, jf.ds.y);
            EXPECT_EQ(jp.ds.z * p2, jf.ds.z);
            EXPECT_EQ(jp.dt.x * p2, jf.dt.x);
            EXPECT_EQ(jp.dt.y * p2, jf.dt.y);
            EXPECT_EQ(jp.dt.z * p2, jf.dt.z);
            const EnvCoords cf = env_coords(layout, rf), cp = env_coords(layout, p2 * rf);
            EXPECT_EQ(cf.face, cp.face);
            EXPECT_EQ(cf.s, cp.s);
            EXPECT_EQ(cf.t, cp.t);
        }
        EXPECT_LT(worst, kScaleRelTol) << name(layout);
    }
}

TEST(EnvLayout, RoundTripDirectionCoordsDirection) {
    for (EnvLayout layout : kLayouts) {
        Rng rng;
        double worst = 0, worst_f = 0;
        for (int i = 0; i < kSamples; ++i) {
            const Vec3d r = rng.scale() * rng.unit();
            const double rz = normalize(r).z;
            if (layout == EnvLayout::sphere && rz < -0.99) continue;
            const EnvCoordsd c = env_coords(layout, r);
            worst = std::max(worst, dir_err(env_direction(layout, c.face, c.s, c.t), r));
            if (layout == EnvLayout::sphere && rz < -0.9) continue;
            const EnvCoords cf = env_coords(layout, vec3_cast<float>(r));
            const Vec3d back = vec3_cast<double>(env_direction(layout, cf.face, cf.s, cf.t));
            worst_f = std::max(worst_f, dir_err(back, r));
        }
        EXPECT_LT(worst, kRoundTripTol) << name(layout);
        EXPECT_LT(worst_f, kFloatRoundTripTol) << name(layout);
    }
}

TEST(EnvLayout, RoundTripCoordsDirectionCoords) {
    for (EnvLayout layout : kLayouts) {
        Rng rng;
        double worst = 0;
        for (int i = 0; i < kSamples; ++i) {
            const int face = static_cast<int>(rng.uniform(0, face_count(layout)));
            double s = rng.uniform(0.001, 0.999), t = rng.uniform(0.001, 0.999);
            if (layout == EnvLayout::latlong)
                t = rng.uniform(0.01, 0.99);  // s degenerates at poles
            if (layout == EnvLayout::sphere || layout == EnvLayout::paraboloid) {
                // Inside the disk of radius ½·0.99 (sphere: away from the singular rim).
                const double rad = 0.5 * 0.99 * std::sqrt(rng.uniform(0, 1)),
                             phi = rng.uniform(0, 2 * kPi);
                s = 0.5 + rad * std::cos(phi), t = 0.5 + rad * std::sin(phi);
            }
            const EnvCoordsd c = env_coords(layout, env_direction(layout, face, s, t));
            EXPECT_EQ(c.face, face) << name(layout);
            worst = std::max({worst, std::abs(c.s - s), std::abs(c.t - t)});
        }
        EXPECT_LT(worst, kRoundTripTol) << name(layout);
    }
}

TEST(EnvLayout, DegenerateInputsGiveFiniteValues) {
    constexpr float kInf = std::numeric_limits<float>::infinity();
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    constexpr float kMax = std::numeric_limits<float>::max();
    constexpr float kDen = std::numeric_limits<float>::denorm_min();
    const Vec3 inputs[] = {{0, 0, 0},           {-0.0f, -0.0f, -0.0f},
                           {kNaN, 1, 0},        {kNaN, kNaN, kNaN},
                           {kInf, 5, 0},        {-kInf, kInf, 0},
                           {0, 0, -kInf},       {kDen, 0, 0},
                           {kDen, kDen, -kDen}, {kMax, kMax, -kMax},
                           {kMax, 1, 0},        {0, 1, 0},
                           {0, -1, 0},          {0, 0, -1},
                           {0, 0, -kDen},       {kDen, 1, 0},
                           {kDen, 0, -1},       {1e-20f, 0, -1},
                           {0, 1e-30f, -1},     {1, 1, 1}};
    for (EnvLayout layout : kLayouts) {
        for (const Vec3& r : inputs) {
            const EnvCoords c = env_coords(layout, r);
            EXPECT_TRUE(c.face >= 0 && c.face < face_count(layout)) << name(layout);
            EXPECT_TRUE(c.s >= 0 && c.s <= 1 && c.t >= 0 && c.t <= 1)
                << name(layout) << " " << r.x << " " << r.y << " " << r.z << " → " << c.s << " "
                << c.t;
            const Jacobian23 j = env_jacobian(layout, r);
            EXPECT_TRUE(is_finite(j.ds) && is_finite(j.dt))
                << name(layout) << " " << r.x << " " << r.y << " " << r.z;
            const Jacobian23d jd = env_jacobian(layout, vec3_cast<double>(r));
            EXPECT_TRUE(is_finite(jd.ds) && is_finite(jd.dt)) << name(layout);
        }
        // Zero / NaN / infinite r: zero Jacobian; zero / NaN: the coordinates of +e_z;
        // infinite: the coordinates of the signs of the infinite components.
        for (const Vec3& r : {Vec3{0, 0, 0}, Vec3{kNaN, 1, 0}, Vec3{kInf, 5, 0}}) {
            const Jacobian23 j = env_jacobian(layout, r);
            EXPECT_EQ(frob(to_double(j)), 0.0) << name(layout);
        }
        const EnvCoords z = env_coords(layout, Vec3{0, 0, 0}),
                        ez = env_coords(layout, Vec3{0, 0, 1});
        EXPECT_EQ(z.face, ez.face);
        EXPECT_EQ(z.s, ez.s);
        EXPECT_EQ(z.t, ez.t);
        const EnvCoords inf = env_coords(layout, Vec3{kInf, 5, 0}),
                        ex = env_coords(layout, Vec3{1, 0, 0});
        EXPECT_EQ(inf.face, ex.face);
        EXPECT_EQ(inf.s, ex.s);
        EXPECT_EQ(inf.t, ex.t);
        // Inverse maps: any (face, s, t) gives a finite nonzero direction.
        const float values[] = {kNaN, kInf, -kInf, kMax, -kMax, 1e30f, -3.5f, 0.5f, 2.5f};
        for (int face : {-1, 0, 1, 5, 7})
            for (float s : values)
                for (float t : values) {
                    const Vec3 d = env_direction(layout, face, s, t);
                    EXPECT_TRUE(is_finite(d) && length(d) > 0)
                        << name(layout) << " " << face << " " << s << " " << t;
                }
    }
}

// ------------------------------------------------------------------------------------ cube

struct FaceRow {
    Vec3d axis, gs, gt;  // σ e_a and the g_s, g_t of the OpenGL table (spec §3.1), written out
};
const FaceRow kGlTable[6] = {
    {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}},   // +X
    {{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}},   // −X
    {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},     // +Y
    {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},   // −Y
    {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}},    // +Z
    {{0, 0, -1}, {-1, 0, 0}, {0, -1, 0}},  // −Z
};
int face_of_axis(Vec3d a) {
    for (int f = 0; f < 6; ++f)
        if (dot(kGlTable[f].axis, a) > 0.5) return f;
    return -1;
}

TEST(EnvLayout, CubeFaceTable) {
    for (int f = 0; f < 6; ++f) {
        const FaceRow& row = kGlTable[f];
        for (double lambda : {1.0, 0.01, 37.0}) {
            const CubeCoordsT<double> c = cube_coords(lambda * row.axis);
            EXPECT_EQ(c.face, f);
            EXPECT_EQ(c.s, 0.5);
            EXPECT_EQ(c.t, 0.5);
        }
        // Forward: moving towards g_s raises s only, towards g_t raises t only.
        constexpr double kEps = 0.25;
        const CubeCoordsT<double> cs = cube_coords(row.axis + kEps * row.gs);
        const CubeCoordsT<double> ct = cube_coords(row.axis + kEps * row.gt);
        EXPECT_EQ(cs.face, f);
        EXPECT_EQ(ct.face, f);
        EXPECT_DOUBLE_EQ(cs.s, 0.5 + kEps / 2);
        EXPECT_DOUBLE_EQ(cs.t, 0.5);
        EXPECT_DOUBLE_EQ(ct.s, 0.5);
        EXPECT_DOUBLE_EQ(ct.t, 0.5 + kEps / 2);
        // Inverse: centre, then the s and t axes.
        const Vec3d centre = cube_direction(f, 0.5, 0.5);
        EXPECT_EQ(norm(centre - row.axis), 0.0);
        EXPECT_EQ(norm(cube_direction(f, 1.0, 0.5) - centre - row.gs), 0.0);
        EXPECT_EQ(norm(cube_direction(f, 0.5, 1.0) - centre - row.gt), 0.0);
        // Float path too.
        const CubeCoords c = cube_coords(vec3_cast<float>(row.axis));
        EXPECT_EQ(c.face, f);
        EXPECT_EQ(c.s, 0.5f);
        EXPECT_EQ(c.t, 0.5f);
    }
}

TEST(EnvLayout, CubeJacobianEqualsExplicitRowTable) {  // [E6t]
    Rng rng;
    for (int f = 0; f < 6; ++f)
        for (int i = 0; i < 100; ++i) {
            const double s = rng.uniform(0.02, 0.98), t = rng.uniform(0.02, 0.98), k = rng.scale();
            const Vec3d r = k * cube_direction(f, s, t);
            const double sp = 2 * s - 1, tp = 2 * t - 1, ma2 = 2 * k;  // |ma| = k
            // Spec §3.1 explicit rows (× 1/(2|ma|)).
            const Vec3d rows[6][2] = {{{-sp, 0, -1}, {-tp, -1, 0}}, {{sp, 0, 1}, {tp, -1, 0}},
                                      {{1, -sp, 0}, {0, -tp, 1}},   {{1, sp, 0}, {0, tp, -1}},
                                      {{1, 0, -sp}, {0, -1, -tp}},  {{-1, 0, sp}, {0, -1, tp}}};
            const Jacobian23d expected{rows[f][0] / ma2, rows[f][1] / ma2};
            EXPECT_LT(rel(cube_jacobian(r), expected), kScaleRelTol) << f;
        }
}

TEST(EnvLayout, CubeTiesGoToLowestIndex) {
    EXPECT_EQ(cube_coords(Vec3{1, 1, 0}).face, 0);
    EXPECT_EQ(cube_coords(Vec3{-1, 1, 0}).face, 1);
    EXPECT_EQ(cube_coords(Vec3{1, -1, 1}).face, 0);
    EXPECT_EQ(cube_coords(Vec3{-2, 2, -2}).face, 1);
    EXPECT_EQ(cube_coords(Vec3{0, 1, -1}).face, 2);
    EXPECT_EQ(cube_coords(Vec3{0, -1, 1}).face, 3);
    EXPECT_EQ(cube_coords(Vec3{0.5f, -3, 3}).face, 3);
    // On the tie the coordinates are those of the chosen face, on its edge.
    const CubeCoords c = cube_coords(Vec3{1, 1, 0});  // +X: s = ½(−r_z/1 + 1), t = ½(−r_y + 1)
    EXPECT_EQ(c.s, 0.5f);
    EXPECT_EQ(c.t, 0.0f);
}

TEST(EnvLayout, CubeReprojectHandPicked) {
    constexpr double kEps = 0.001;
    // +X right edge → −Z left edge: r = (1, 0, −(1 + 2ε)) → s = ½(1 − 1/(1 + 2ε)), t = ½.
    const CubeCoordsT<double> a = cube_reproject(0, 1 + kEps, 0.5);
    EXPECT_EQ(a.face, 5);
    EXPECT_NEAR(a.s, 0.5 * (1 - 1 / (1 + 2 * kEps)), 1e-15);
    EXPECT_NEAR(a.t, 0.5, 1e-15);
    // +Z top edge → +Y bottom edge: r = (0, 1 + 2ε, 1) → s = ½, t = ½(1/(1 + 2ε) + 1).
    const CubeCoordsT<double> b = cube_reproject(4, 0.5, -kEps);
    EXPECT_EQ(b.face, 2);
    EXPECT_NEAR(b.s, 0.5, 1e-15);
    EXPECT_NEAR(b.t, 0.5 * (1 / (1 + 2 * kEps) + 1), 1e-15);
    // Inside a face nothing changes.
    const CubeCoordsT<double> c = cube_reproject(3, 0.3, 0.8);
    EXPECT_EQ(c.face, 3);
    EXPECT_NEAR(c.s, 0.3, 1e-15);
    EXPECT_NEAR(c.t, 0.8, 1e-15);
}

TEST(EnvLayout, CubeReprojectAcrossEveryEdge) {
    constexpr double kEps = 1e-3;             // how far beyond the edge, in s or t
    constexpr double kPathStep = 1e-3;        // step of a probe path across an edge
    constexpr double kMaxAngleStep = 2.5e-3;  // |Δr̂| per path step: ≤ 2·kPathStep (the plane
                                              // moves 2 units per unit s; |Δr̂| ≤ |Δr|/|r|), +25 %
    for (int f = 0; f < 6; ++f) {
        const FaceRow& row = kGlTable[f];
        // The four edges: (which coordinate, beyond 1 or below 0, the axis the probe moves to).
        struct Edge {
            bool along_s;
            bool high;
            Vec3d towards;
        };
        const Edge edges[4] = {{true, true, row.gs},
                               {true, false, -row.gs},
                               {false, true, row.gt},
                               {false, false, -row.gt}};
        for (const Edge& e : edges) {
            const int neighbour = face_of_axis(e.towards);
            ASSERT_GE(neighbour, 0);
            for (double u : {0.1, 0.5, 0.9}) {
                const double out = e.high ? 1 + kEps : -kEps;
                const double s = e.along_s ? out : u, t = e.along_s ? u : out;
                const CubeCoordsT<double> c = cube_reproject(f, s, t);
                EXPECT_EQ(c.face, neighbour) << f;
                EXPECT_TRUE(c.s >= 0 && c.s <= 1 && c.t >= 0 && c.t <= 1);
                // At the position the inverse map predicts, next to the shared edge.
                EXPECT_LT(dir_err(cube_direction(c.face, c.s, c.t), cube_direction(f, s, t)),
                          kRoundTripTol);
                EXPECT_LT(std::min({c.s, 1 - c.s, c.t, 1 - c.t}), kEps);
            }
            // A probe path across the edge: its direction moves continuously, one face change.
            Vec3d prev{};
            int changes = 0, prev_face = f;
            for (int k = 0; k <= 200; ++k) {
                const double x = e.high ? 0.9 + k * kPathStep : 0.1 - k * kPathStep;
                const double s = e.along_s ? x : 0.37, t = e.along_s ? 0.37 : x;
                const CubeCoordsT<double> c = cube_reproject(f, s, t);
                const Vec3d d = normalize(cube_direction(c.face, c.s, c.t));
                if (k > 0) {
                    EXPECT_LT(norm(d - prev), kMaxAngleStep) << f << " " << k;
                }
                if (c.face != prev_face) ++changes;
                prev = d, prev_face = c.face;
            }
            EXPECT_EQ(changes, 1);
            EXPECT_EQ(prev_face, neighbour);
        }
    }
}

// -------------------------------------------------------------------------------- lat-long

TEST(EnvLayout, LatLongLandmarks) {
    struct Landmark {
        Vec3 r;
        float s, t;
    };
    const Landmark marks[] = {{{1, 0, 0}, 0.75f, 0.5f},    {{-1, 0, 0}, 0.25f, 0.5f},
                              {{0, 0, -1}, 0.5f, 0.5f},    {{0, 0, 1}, 1.0f, 0.5f},
                              {{-0.0f, 0, 1}, 0.0f, 0.5f}, {{0, 1, 0}, 0.5f, 0.0f},
                              {{0, -1, 0}, 0.5f, 1.0f},    {{0, 3, 0}, 0.5f, 0.0f}};
    for (const Landmark& m : marks) {
        const Vec2 st = latlong_coords(m.r);
        EXPECT_NEAR(st.x, m.s, kLandmarkTol) << m.r.x << " " << m.r.y << " " << m.r.z;
        EXPECT_NEAR(st.y, m.t, kLandmarkTol) << m.r.x << " " << m.r.y << " " << m.r.z;
        EXPECT_LT(dir_err(vec3_cast<double>(latlong_direction(m.s, m.t)), vec3_cast<double>(m.r)),
                  kFloatRoundTripTol);
    }
    // At the exact poles the Jacobian is 0 (the caller's isotropic fallback); just off them the
    // t row keeps |∂t/∂r| = 1/(π|r|).
    EXPECT_EQ(frob(latlong_jacobian(Vec3d{0, 2, 0})), 0.0);
    const Jacobian23d near = latlong_jacobian(Vec3d{1e-9, 2, 0});
    EXPECT_NEAR(norm(near.dt), 1 / (2 * kPi), 1e-12);
}

TEST(EnvLayout, LatLongSeam) {
    constexpr double kTiny = 1e-9;
    Rng rng;
    for (int i = 0; i < 100; ++i) {
        const double t = rng.uniform(0.01, 0.99);
        EXPECT_LT(dir_err(latlong_direction(0.0, t), latlong_direction(1.0, t)), kRoundTripTol);
        // Either side of the seam (+Z half-plane x = 0, z > 0): s → 1 on the +x side, → 0 on −x.
        const Vec3d r = latlong_direction(1.0, t);
        const Vec3d plus = r + Vec3d{kTiny, 0, 0}, minus = r - Vec3d{kTiny, 0, 0};
        EXPECT_GT(latlong_coords(plus).x, 1 - 1e-8);
        EXPECT_LT(latlong_coords(minus).x, 1e-8);
        // The Jacobian is smooth across it.
        EXPECT_LT(rel(latlong_jacobian(plus), latlong_jacobian(minus)), 1e-7);
    }
}

// ---------------------------------------------------------------------------------- sphere

TEST(EnvLayout, SphereLandmarksAndRim) {
    const double q = std::sqrt(2.0) / 4;
    const struct {
        Vec3d r;
        double s, t;
    } marks[] = {{{0, 0, 1}, 0.5, 0.5},
                 {{1, 0, 0}, 0.5 + q, 0.5},
                 {{-1, 0, 0}, 0.5 - q, 0.5},
                 {{0, 1, 0}, 0.5, 0.5 - q},  // +Y up in the image (t = 0 the top row)
                 {{0, -1, 0}, 0.5, 0.5 + q}};
    for (const auto& m : marks) {
        const Vec2d st = sphere_coords(3.0 * m.r);
        EXPECT_NEAR(st.x, m.s, 1e-15);
        EXPECT_NEAR(st.y, m.t, 1e-15);
    }
    // The rim: −Z itself → (1, ½) and J = 0; approaching −Z from azimuth φ → the rim at φ.
    const Vec2d rim = sphere_coords(Vec3d{0, 0, -5});
    EXPECT_EQ(rim.x, 1.0);
    EXPECT_EQ(rim.y, 0.5);
    EXPECT_EQ(frob(sphere_jacobian(Vec3d{0, 0, -5})), 0.0);
    for (double phi : {0.3, 2.0, 4.0}) {
        const double e = 1e-7;
        const Vec3d r{std::sin(e) * std::cos(phi), std::sin(e) * std::sin(phi), -std::cos(e)};
        const Vec2d st = sphere_coords(r);
        EXPECT_NEAR(st.x, 0.5 + 0.5 * std::cos(phi), 1e-9);
        EXPECT_NEAR(st.y, 0.5 - 0.5 * std::sin(phi), 1e-9);
        const Jacobian23d j = sphere_jacobian(r);
        EXPECT_TRUE(is_finite(j.ds) && is_finite(j.dt));
        EXPECT_GT(frob(j), 1e5);  // ∝ 1/m: large, finite
        // The fold through the rim: a little outside the disk ≡ a little inside at azimuth φ + π.
        const double rad = 0.5 * 1.01;
        const Vec3d out = sphere_direction(0.5 + rad * std::cos(phi), 0.5 + rad * std::sin(phi));
        const Vec3d in =
            sphere_direction(0.5 - 0.5 * 0.99 * std::cos(phi), 0.5 - 0.5 * 0.99 * std::sin(phi));
        EXPECT_LT(dir_err(out, in), 1e-12);
    }
    EXPECT_LT(dir_err(sphere_direction(3.0, 0.5), Vec3d{0, 0, -1}), 1e-15);  // √k ≥ 2
}

TEST(EnvLayout, SphereMapIsEqualArea) {  // [P1a]: |det J_tangent| = 1/16 per steradian
    Rng rng;
    double worst = 0, worst_f = 0;
    for (int i = 0; i < kSamples; ++i) {
        const Vec3d u = rng.unit();
        if (u.z < -0.99) continue;
        const Vec3d t1 = normalize(cross(u, rng.unit())), t2 = cross(u, t1);
        const double lambda = rng.scale();
        const Jacobian23d j = scaled(sphere_jacobian(lambda * u), lambda);  // J at unit r
        const double det = dot(j.ds, t1) * dot(j.dt, t2) - dot(j.ds, t2) * dot(j.dt, t1);
        worst = std::max(worst, std::abs(std::abs(det) * 16 - 1));
        if (u.z < -0.9) continue;
        const Jacobian23 jf = sphere_jacobian(vec3_cast<float>(u));
        const Jacobian23d jd = to_double(jf);
        const double detf = dot(jd.ds, t1) * dot(jd.dt, t2) - dot(jd.ds, t2) * dot(jd.dt, t1);
        worst_f = std::max(worst_f, std::abs(std::abs(detf) * 16 - 1));
    }
    EXPECT_LT(worst, kIdentityRelTol);
    EXPECT_LT(worst_f, kFloatIdentityRelTol);
}

// ------------------------------------------------------------------------------ paraboloid

TEST(EnvLayout, ParaboloidIsConformal) {  // [P2c]: J_t J_tᵀ = c² I, c = 1/(2(1 + |r̂_z|))
    Rng rng;
    double worst = 0;
    for (int i = 0; i < kSamples; ++i) {
        const Vec3d u = rng.unit();
        const Vec3d t1 = normalize(cross(u, rng.unit())), t2 = cross(u, t1);
        const double lambda = rng.scale();
        const Jacobian23d j = scaled(paraboloid_jacobian(lambda * u), lambda);
        const double a = dot(j.ds, t1), b = dot(j.ds, t2), c = dot(j.dt, t1), d = dot(j.dt, t2);
        const double c2 = std::pow(1 / (2 * (1 + std::abs(u.z))), 2);
        worst = std::max({worst, std::abs(a * a + b * b - c2) / c2,
                          std::abs(c * c + d * d - c2) / c2, std::abs(a * c + b * d) / c2});
    }
    EXPECT_LT(worst, kIdentityRelTol);
}

TEST(EnvLayout, ParaboloidFacesAgreeOnTheEquator) {
    Rng rng;
    EXPECT_EQ(paraboloid_coords(Vec3d{0, 0, 2}).face, 0);
    EXPECT_EQ(paraboloid_coords(Vec3d{0, 0, -2}).face, 1);
    for (int i = 0; i < 200; ++i) {
        const double phi = rng.uniform(0, 2 * kPi);
        const Vec3d r{std::cos(phi), std::sin(phi), 0};
        const EnvCoordsd front = paraboloid_coords(r),
                         back = paraboloid_coords(r - Vec3d{0, 0, 1e-12});
        EXPECT_EQ(front.face, 0);
        EXPECT_EQ(back.face, 1);
        EXPECT_NEAR(front.s, back.s, 1e-11);
        EXPECT_NEAR(front.t, back.t, 1e-11);
        EXPECT_NEAR(front.s, 0.5 + 0.5 * std::cos(phi), 1e-15);  // on the unit circle
        EXPECT_NEAR(front.t, 0.5 - 0.5 * std::sin(phi), 1e-15);  // +Y up in the image
        EXPECT_LT(dir_err(paraboloid_direction(0, front.s, front.t),
                          paraboloid_direction(1, front.s, front.t)),
                  1e-15);
        // Beyond the circle the inverse continues into the other hemisphere: front (x, y) with
        // k = x² + y² > 1 is back (x, y)/k.
        const double x = 1.2 * std::cos(phi), y = 1.2 * std::sin(phi), k = 1.44;
        const EnvCoordsd other =
            paraboloid_coords(paraboloid_direction(0, 0.5 * (x + 1), 0.5 * (1 - y)));
        EXPECT_EQ(other.face, 1);
        EXPECT_NEAR(other.s, 0.5 * (x / k + 1), 1e-14);
        EXPECT_NEAR(other.t, 0.5 * (1 - y / k), 1e-14);
    }
}

}  // namespace
}  // namespace footprint
