#include "bump/local_frame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <utility>

#include "bump/slope_map.h"

namespace footprint {
namespace {

// Unit lengths, dot products and e1 × e2 = n̂ of a float frame: a few float ulps (6e-8) from
// normalize(), one cross product and the re-orthogonalisation; 1e-6 is ~8 ulps.
constexpr float kOrthonormalTolerance = 1e-6f;
// Comparing a float frame with its double-precision formula: the float rounding of m × n̂ is
// ~1e-7 absolute, divided by |m̂ × n̂| on normalising; kDirectionTolerance / sin(angle) bounds it.
constexpr double kDirectionTolerance = 1e-6;
// Products of vectors with components up to ~4, relative to |p_u||p_v|: float rounding ~1e-7,
// summed over a few terms.
constexpr double kNaturalRelTolerance = 2e-6;
// Central finite differences of analytic surfaces in double with step 1e-5: truncation
// O(h²·|p'''|) ≈ 1e-10 and cancellation ~1e-16/1e-5 = 1e-11; the result is compared with a float
// frame, so float rounding (kNaturalRelTolerance) dominates.
constexpr double kFiniteDifferenceStep = 1e-5;

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

Vec3 random_unit(std::mt19937& rng) {
    std::normal_distribution<float> g;
    for (;;) {
        const Vec3 v{g(rng), g(rng), g(rng)};
        if (length(v) > 1e-3f) return normalize(v);
    }
}

Vec3d to_double(Vec3 v) {
    return vec3_cast<double>(v);
}

double max_abs_diff(Vec3d a, Vec3d b) {
    return max_abs_component(a - b);
}

void expect_orthonormal_right_handed(const OrthonormalFrame& f) {
    ASSERT_TRUE(is_finite(f.e1) && is_finite(f.e2) && is_finite(f.normal));
    EXPECT_NEAR(length(f.e1), 1.0f, kOrthonormalTolerance);
    EXPECT_NEAR(length(f.e2), 1.0f, kOrthonormalTolerance);
    EXPECT_NEAR(length(f.normal), 1.0f, kOrthonormalTolerance);
    EXPECT_NEAR(dot(f.e1, f.e2), 0.0f, kOrthonormalTolerance);
    EXPECT_NEAR(dot(f.e1, f.normal), 0.0f, kOrthonormalTolerance);
    EXPECT_NEAR(dot(f.e2, f.normal), 0.0f, kOrthonormalTolerance);
    const Vec3 c = cross(f.e1, f.e2);  // right-handed: e1 × e2 = n̂
    EXPECT_NEAR(c.x, f.normal.x, kOrthonormalTolerance);
    EXPECT_NEAR(c.y, f.normal.y, kOrthonormalTolerance);
    EXPECT_NEAR(c.z, f.normal.z, kOrthonormalTolerance);
}

TEST(LocalFrame, OrthonormalAndRightHandedForRandomInput) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> log_length(-3.0f, 3.0f);
    std::uniform_real_distribution<float> tiny(-1e-4f, 1e-4f);
    int fallbacks = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 n = std::pow(10.0f, log_length(rng)) * random_unit(rng);
        Vec3 m = std::pow(10.0f, log_length(rng)) * random_unit(rng);
        // One in eight: m within ~1e-4 of ±n (inside the default fallback cap).
        if (i % 8 == 0) {
            m = (i % 16 == 0 ? 1.0f : -2.0f) *
                (normalize(n) + Vec3{tiny(rng), tiny(rng), tiny(rng)});
        }
        const OrthonormalFrame f = make_orthonormal_frame(n, m);
        expect_orthonormal_right_handed(f);
        const Vec3d nh = normalize(to_double(n)), mh = normalize(to_double(m));
        EXPECT_LT(max_abs_diff(to_double(f.normal), nh), kOrthonormalTolerance);
        const double sin_angle = length(cross(mh, nh));
        if (f.origin == FrameOrigin::fallback_direction) {
            ++fallbacks;
            EXPECT_LT(sin_angle, 1e-3 + 1e-6);
            continue;
        }
        ASSERT_EQ(f.origin, FrameOrigin::main_direction);
        EXPECT_GE(sin_angle, 1e-3 - 1e-6);
        // Spec §6.2: e1 = (m × n̂)/|m × n̂| ⟂ plane(n, m); e2 = the normalised tangent part of m.
        const Vec3d e1 = cross(mh, nh) / sin_angle;
        const Vec3d e2 = normalize(mh - dot(mh, nh) * nh);
        EXPECT_LT(max_abs_diff(to_double(f.e1), e1), kDirectionTolerance / sin_angle) << i;
        EXPECT_LT(max_abs_diff(to_double(f.e2), e2), kDirectionTolerance / sin_angle) << i;
        EXPECT_NEAR(dot(to_double(f.e1), mh), 0.0, kDirectionTolerance);
    }
    EXPECT_EQ(fallbacks, 20000 / 8);
}

TEST(LocalFrame, OrthonormalFrameIsContinuousAwayFromTheFallback) {
    // e1 = w/|w| with w = m̂ × n̂, so |Δe1| ≤ |Δn̂|/sin(angle) to first order, and e2 = n̂ × e1
    // gives |Δe2| ≤ |Δn̂| + |Δe1|. With sin ≥ 0.2 and |Δn̂| ≤ 1e-3 the second-order terms are
    // ≤ (5e-3)² relative: the bound ×1.05 plus float noise (2·kDirectionTolerance/sin) holds.
    std::mt19937 rng(2);
    int tested = 0;
    for (int i = 0; i < 5000; ++i) {
        const Vec3 n = random_unit(rng), m = random_unit(rng);
        const float sin_angle = length(cross(m, n));
        if (sin_angle < 0.2f) continue;
        const Vec3 n2 = normalize(n + 1e-3f * random_unit(rng));
        const double dn = length(to_double(n2) - to_double(n));
        const OrthonormalFrame a = make_orthonormal_frame(n, m), b = make_orthonormal_frame(n2, m);
        const double noise = 2 * kDirectionTolerance / sin_angle;
        const double de1 = length(to_double(a.e1) - to_double(b.e1));
        const double de2 = length(to_double(a.e2) - to_double(b.e2));
        EXPECT_LE(de1, 1.05 * dn / sin_angle + noise) << i;
        EXPECT_LE(de2, 1.05 * (dn + dn / sin_angle) + noise) << i;
        ++tested;
    }
    EXPECT_GT(tested, 4000);
    // Inside the fallback cap the frame uses one fixed axis, so it is continuous there too.
    const Vec3 m{0.0f, 0.0f, 1.0f};
    const OrthonormalFrame a = make_orthonormal_frame(Vec3{1e-5f, 0.0f, 1.0f}, m);
    const OrthonormalFrame b = make_orthonormal_frame(Vec3{0.0f, 2e-5f, 1.0f}, m);
    ASSERT_EQ(a.origin, FrameOrigin::fallback_direction);
    ASSERT_EQ(b.origin, FrameOrigin::fallback_direction);
    EXPECT_LT(max_abs_diff(to_double(a.e1), to_double(b.e1)), 1e-4);
    EXPECT_LT(max_abs_diff(to_double(a.e2), to_double(b.e2)), 1e-4);
}

TEST(LocalFrame, EarthAxisGivesEastAndNorth) {
    // [F3e]: n̂ on the unit sphere at (latitude φ, longitude λ), m = the axis z:
    // east = (−sin λ, cos λ, 0), north = (−sin φ cos λ, −sin φ sin λ, cos φ).
    const Vec3 axis{0.0f, 0.0f, 1.0f};
    for (int lat = -85; lat <= 85; lat += 5) {
        for (int lon = -180; lon < 180; lon += 15) {
            const double phi = lat * std::numbers::pi / 180, lam = lon * std::numbers::pi / 180;
            const Vec3d n{std::cos(phi) * std::cos(lam), std::cos(phi) * std::sin(lam),
                          std::sin(phi)};
            const Vec3d east{-std::sin(lam), std::cos(lam), 0.0};
            const Vec3d north{-std::sin(phi) * std::cos(lam), -std::sin(phi) * std::sin(lam),
                              std::cos(phi)};
            // The radius (any positive length of n) does not matter.
            const OrthonormalFrame f = make_orthonormal_frame(vec3_cast<float>(6371.0 * n), axis);
            ASSERT_EQ(f.origin, FrameOrigin::main_direction);
            const double tol = kDirectionTolerance / std::cos(phi);
            EXPECT_LT(max_abs_diff(to_double(f.e1), east), tol) << lat << " " << lon;
            EXPECT_LT(max_abs_diff(to_double(f.e2), north), tol) << lat << " " << lon;
        }
    }
    // At the poles: the fallback axis least aligned with m = z is x; e2 is x's tangent part.
    for (float sign : {1.0f, -1.0f}) {
        const OrthonormalFrame pole = make_orthonormal_frame(Vec3{0.0f, 0.0f, sign}, axis);
        EXPECT_EQ(pole.origin, FrameOrigin::fallback_direction);
        expect_orthonormal_right_handed(pole);
        EXPECT_NEAR(pole.e2.x, 1.0f, kOrthonormalTolerance);
    }
}

TEST(LocalFrame, MainDirectionPvGivesE2AlongPvAndE1AlongPu) {
    // [F3u]: m = p_v ⇒ e2 = p̂_v, e1 ⟂ p_v, e1·p_u > 0, for non-orthogonal p_u, p_v too.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> len(0.1f, 10.0f);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p_u = len(rng) * random_unit(rng), p_v = len(rng) * random_unit(rng);
        const float sin_angle = length(cross(normalize(p_u), normalize(p_v)));
        if (sin_angle < 0.05f) continue;
        const OrthonormalFrame f = make_orthonormal_frame(cross(p_u, p_v), p_v);
        ASSERT_EQ(f.origin, FrameOrigin::main_direction);
        EXPECT_LT(max_abs_diff(to_double(f.e2), normalize(to_double(p_v))),
                  kDirectionTolerance / sin_angle);
        EXPECT_NEAR(dot(f.e1, normalize(p_v)), 0.0f, kOrthonormalTolerance);
        EXPECT_GT(dot(f.e1, p_u), 0.0f);
    }
}

TEST(LocalFrame, FallbackNearParallelIsFiniteAndOrthonormal) {
    const Vec3 m{0.3f, -0.5f, 0.8f};
    for (const Vec3 n :
         {m, -m, 7.0f * m, m + Vec3{1e-5f, 0.0f, 0.0f}, -m + Vec3{0.0f, 3e-5f, 0.0f}}) {
        const OrthonormalFrame f = make_orthonormal_frame(n, m);
        EXPECT_EQ(f.origin, FrameOrigin::fallback_direction);
        expect_orthonormal_right_handed(f);
        // Automatic fallback: the axis least aligned with m is x (|0.3| smallest); e2 is its
        // tangent projection.
        const Vec3d nh = normalize(to_double(n));
        const Vec3d x{1.0, 0.0, 0.0};
        EXPECT_LT(max_abs_diff(to_double(f.e2), normalize(x - dot(x, nh) * nh)), 1e-5);
    }
    // A chosen fallback direction is used instead.
    OrthonormalFrameOptions options;
    options.fallback_direction = Vec3{0.0f, 0.0f, 2.0f};
    const OrthonormalFrame f = make_orthonormal_frame(m, m, options);
    EXPECT_EQ(f.origin, FrameOrigin::fallback_direction);
    expect_orthonormal_right_handed(f);
    const Vec3d nh = normalize(to_double(m)), z{0.0, 0.0, 1.0};
    EXPECT_LT(max_abs_diff(to_double(f.e2), normalize(z - dot(z, nh) * nh)), 1e-5);
    // A fallback direction that is itself parallel to n is skipped.
    options.fallback_direction = -m;
    const OrthonormalFrame g = make_orthonormal_frame(m, m, options);
    expect_orthonormal_right_handed(g);
    // A larger cap: 0.1 rad away from m is a fallback with min_sin_angle = 0.2; a NaN threshold
    // takes the floor (no fallback), never a NaN frame.
    const Vec3 tilted =
        normalize(normalize(m) + 0.1f * normalize(cross(m, Vec3{1.0f, 0.0f, 0.0f})));
    options = {};
    options.min_sin_angle = 0.2f;
    EXPECT_EQ(make_orthonormal_frame(tilted, m, options).origin, FrameOrigin::fallback_direction);
    options.min_sin_angle = kNan;
    const OrthonormalFrame h = make_orthonormal_frame(tilted, m, options);
    EXPECT_EQ(h.origin, FrameOrigin::main_direction);
    expect_orthonormal_right_handed(h);
}

TEST(LocalFrame, DegenerateInputNeverGivesNan) {
    const Vec3 good{0.2f, 0.3f, 0.9f};
    const Vec3 bad[] = {Vec3{}, Vec3{kNan, 0.0f, 1.0f}, Vec3{kInf, 0.0f, 0.0f},
                        Vec3{1e-40f, 0.0f, 0.0f} /* subnormal: still a direction */};
    for (const Vec3 m : bad) {
        const OrthonormalFrame f = make_orthonormal_frame(good, m);
        expect_orthonormal_right_handed(f);
    }
    for (int i = 0; i < 3; ++i) {
        const OrthonormalFrame f = make_orthonormal_frame(bad[i], good);
        EXPECT_EQ(f.origin, FrameOrigin::degenerate_normal);
        expect_orthonormal_right_handed(f);
        const Vec3 p = perturbed_normal(bad[i], f, Vec2{0.5f, 0.5f});
        EXPECT_TRUE(is_finite(p));
    }
    // Subnormal n is still a direction.
    EXPECT_NE(make_orthonormal_frame(bad[3], good).origin, FrameOrigin::degenerate_normal);
    // Both unusable.
    expect_orthonormal_right_handed(make_orthonormal_frame(Vec3{}, Vec3{}));

    // Natural frame: a degenerate parameterisation is the zero frame.
    for (const auto& [p_u, p_v] : {std::pair{Vec3{}, good}, std::pair{good, 2.0f * good},
                                   std::pair{Vec3{kNan, 0.0f, 0.0f}, good}}) {
        const NaturalFrame f = make_natural_frame(p_u, p_v);
        EXPECT_EQ(length(f.n), 0.0f);
        EXPECT_EQ(length(f.s_u), 0.0f);
        const TangentFrame t = tangent_frame(f);
        EXPECT_EQ(length(t.t1), 0.0f);
        EXPECT_TRUE(is_finite(perturbed_normal(f, Vec2{1.0f, 1.0f})));
        // With a shading normal: the normal is kept, the bump dropped.
        const NaturalFrame s = make_natural_frame(p_u, p_v, good);
        EXPECT_LT(max_abs_diff(to_double(s.n), normalize(to_double(good))), 1e-6);
        EXPECT_EQ(length(s.s_v), 0.0f);
    }
    // perturbed_normal: NaN slopes are no bump, a NaN normal gives zero.
    const OrthonormalFrame f = make_orthonormal_frame(good, Vec3{0.0f, 1.0f, 0.0f});
    const Vec3 p = perturbed_normal(good, f, Vec2{kNan, 1.0f});
    EXPECT_EQ(p.x, good.x);
    EXPECT_EQ(p.y, good.y);
    EXPECT_EQ(p.z, good.z);
    EXPECT_EQ(length(perturbed_normal(Vec3{kNan, 0.0f, 0.0f}, f, Vec2{})), 0.0f);
    EXPECT_EQ(length(perturbed_normal(Vec3{kInf, 0.0f, 0.0f}, f, Vec2{})), 0.0f);
}

TEST(LocalFrame, PerturbedNormalFollowsSpec22) {
    // n_m = n + |n|(b1 e1 + b2 e2): scaling n by λ > 0 scales n_m by λ (the direction is the same).
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> slope(-2.0f, 2.0f);
    for (int i = 0; i < 1000; ++i) {
        const Vec3 n = 3.0f * random_unit(rng), m = random_unit(rng);
        const OrthonormalFrame f = make_orthonormal_frame(n, m);
        const Vec2 b{slope(rng), slope(rng)};
        const Vec3 nm = perturbed_normal(n, f, b);
        const Vec3d expected =
            to_double(n) + 3.0 * (double(b.x) * to_double(f.e1) + double(b.y) * to_double(f.e2));
        EXPECT_LT(max_abs_diff(to_double(nm), expected), 1e-5);
        const Vec3 nm2 = perturbed_normal(0.25f * n, f, b);
        EXPECT_LT(max_abs_diff(to_double(nm2), 0.25 * to_double(nm)), 1e-5);
        // In-frame components: n_m·e_i = |n| b_i, n_m·n̂ = |n|.
        EXPECT_NEAR(dot(nm, f.e1), 3.0f * b.x, 1e-5f);
        EXPECT_NEAR(dot(nm, f.normal), 3.0f, 1e-5f);
    }
}

// ---- Natural frame -----------------------------------------------------------------------------

TEST(LocalFrame, NaturalFrameIdentitiesF1AndDualBasis) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> len(0.2f, 4.0f);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p_u = len(rng) * random_unit(rng), p_v = len(rng) * random_unit(rng);
        const double scale = length(p_u) * length(p_v);
        if (length(cross(p_u, p_v)) < 0.05 * scale) continue;
        const NaturalFrame f = make_natural_frame(p_u, p_v);
        const double n_len = length(to_double(f.n));
        // [F1] n = p_u × p_v = s_u × s_v
        EXPECT_LT(max_abs_diff(to_double(f.n), cross(to_double(p_u), to_double(p_v))),
                  kNaturalRelTolerance * scale);
        EXPECT_LT(max_abs_diff(to_double(cross(f.s_u, f.s_v)), to_double(f.n)),
                  kNaturalRelTolerance * scale);
        // Dual basis: s_u·p_u = −|n|, s_u·p_v = 0, s_v·p_v = −|n|, s_v·p_u = 0.
        EXPECT_NEAR(dot(f.s_u, p_u), -n_len, kNaturalRelTolerance * scale);
        EXPECT_NEAR(dot(f.s_u, p_v), 0.0, kNaturalRelTolerance * scale);
        EXPECT_NEAR(dot(f.s_v, p_v), -n_len, kNaturalRelTolerance * scale);
        EXPECT_NEAR(dot(f.s_v, p_u), 0.0, kNaturalRelTolerance * scale);
        // T = (s_u s_v)/|n| reproduces n' through the generic §2.2 form.
        const Vec2 g{len(rng) - 2.0f, len(rng) - 2.0f};
        EXPECT_LT(max_abs_diff(to_double(perturbed_normal(f.n, tangent_frame(f), g)),
                               to_double(perturbed_normal(f, g))),
                  4 * kNaturalRelTolerance * scale);
        // The shading-normal form with the geometric normal is the same frame.
        const NaturalFrame s = make_natural_frame(p_u, p_v, 0.1f * f.n);
        EXPECT_LT(max_abs_diff(to_double(s.s_u), to_double(f.s_u)), kNaturalRelTolerance * scale);
        EXPECT_LT(max_abs_diff(to_double(s.n), to_double(f.n)), kNaturalRelTolerance * scale);
    }
}

// True normal of the displaced surface q(u, v) = p(u, v) + f(u, v) n̂(u, v), by central
// differences in double.
template <class Surface, class Height>
Vec3d displaced_normal(const Surface& p, const Height& f, double u, double v) {
    const auto q = [&](double uu, double vv) {
        const double e = 1e-4;  // n̂ by central differences: smooth O(e²) error, little noise
        const Vec3d n =
            normalize(cross(p(uu + e, vv) - p(uu - e, vv), p(uu, vv + e) - p(uu, vv - e)));
        return p(uu, vv) + f(uu, vv) * n;
    };
    const double h = kFiniteDifferenceStep;
    return cross((q(u + h, v) - q(u - h, v)) / (2 * h), (q(u, v + h) - q(u, v - h)) / (2 * h));
}

TEST(LocalFrame, NaturalFramePerturbationIsTheDisplacedSurfaceNormal) {
    // (a) Flat, non-orthogonal base: q_u × q_v = (p_u + f_u n̂) × (p_v + f_v n̂) = n + f_u s_u + f_v
    // s_v
    //     exactly, for any f.
    const Vec3d o{0.5, -1.0, 2.0}, a{1.5, 0.2, -0.3}, b{0.7, 1.1, 0.4};
    const auto plane = [&](double u, double v) { return o + u * a + v * b; };
    const auto bumps = [](double u, double v) {
        return 0.3 * std::sin(3 * u + 1) * std::cos(2 * v);
    };
    const auto bumps_du = [](double u, double v) {
        return 0.9 * std::cos(3 * u + 1) * std::cos(2 * v);
    };
    const auto bumps_dv = [](double u, double v) {
        return -0.6 * std::sin(3 * u + 1) * std::sin(2 * v);
    };
    const NaturalFrame flat = make_natural_frame(vec3_cast<float>(a), vec3_cast<float>(b));
    const double area = length(cross(a, b));
    for (double u = -1.0; u <= 1.0; u += 0.25) {
        for (double v = -1.0; v <= 1.0; v += 0.25) {
            const Vec3d truth = displaced_normal(plane, bumps, u, v);
            const Vec2 fd{static_cast<float>(bumps_du(u, v)), static_cast<float>(bumps_dv(u, v))};
            const Vec3d ours = to_double(perturbed_normal(flat, fd));
            EXPECT_LT(max_abs_diff(ours, truth), 4 * kNaturalRelTolerance * area) << u << " " << v;
        }
    }
    // (b) Curved base, the sphere p(θ, φ) = R(sin θ cos φ, sin θ sin φ, cos θ) (outward n):
    //     where f = 0 the formula is exact; elsewhere the neglected terms are
    //     f·(p_u × n̂_v + n̂_u × p_v + f_u n̂ × n̂_v + f_v n̂_u × n̂ + f n̂_u × n̂_v) with n̂_u = p_u/R,
    //     so |error| ≤ |f|(2|p_u||p_v|/R + (|f_u||p_v| + |f_v||p_u|)/R + |f||p_u||p_v|/R²).
    const double R = 2.0;
    const auto sphere = [&](double t, double ph) {
        return R * Vec3d{std::sin(t) * std::cos(ph), std::sin(t) * std::sin(ph), std::cos(t)};
    };
    const double k = 0.01;  // bump amplitude: zero on the lines θ = 1.2 + jπ/5
    const auto bump = [&](double t, double ph) {
        return k * std::sin(5 * (t - 1.2)) * std::cos(3 * ph);
    };
    const auto bump_t = [&](double t, double ph) {
        return 5 * k * std::cos(5 * (t - 1.2)) * std::cos(3 * ph);
    };
    const auto bump_p = [&](double t, double ph) {
        return -3 * k * std::sin(5 * (t - 1.2)) * std::sin(3 * ph);
    };
    int exact_points = 0;
    for (double t = 0.6; t < 2.6; t += 0.1) {
        for (double ph = 0.0; ph < 6.2; ph += 0.4) {
            const Vec3d p_u{R * std::cos(t) * std::cos(ph), R * std::cos(t) * std::sin(ph),
                            -R * std::sin(t)};
            const Vec3d p_v{-R * std::sin(t) * std::sin(ph), R * std::sin(t) * std::cos(ph), 0.0};
            const NaturalFrame frame =
                make_natural_frame(vec3_cast<float>(p_u), vec3_cast<float>(p_v));
            const Vec2 fd{static_cast<float>(bump_t(t, ph)), static_cast<float>(bump_p(t, ph))};
            const Vec3d ours = to_double(perturbed_normal(frame, fd));
            const Vec3d truth = displaced_normal(sphere, bump, t, ph);
            const double lu = length(p_u), lv = length(p_v), f = std::abs(bump(t, ph));
            const double neglected =
                f * (2 * lu * lv / R + (std::abs(fd.x) * lv + std::abs(fd.y) * lu) / R +
                     f * lu * lv / (R * R));
            const double float_noise = 8 * kNaturalRelTolerance * lu * lv;
            EXPECT_LT(max_abs_diff(ours, truth), neglected + float_noise) << t << " " << ph;
            if (f < 1e-12) ++exact_points;
        }
    }
    // The lines θ = 1.2 + jπ/5 (θ ≈ 1.2, 1.828, 2.457) hit the grid: f = 0 there, exact within
    // noise.
    for (double t : {1.2, 1.2 + std::numbers::pi / 5}) {
        for (double ph = 0.1; ph < 6.2; ph += 0.7) {
            const Vec3d p_u{R * std::cos(t) * std::cos(ph), R * std::cos(t) * std::sin(ph),
                            -R * std::sin(t)};
            const Vec3d p_v{-R * std::sin(t) * std::sin(ph), R * std::sin(t) * std::cos(ph), 0.0};
            const NaturalFrame frame =
                make_natural_frame(vec3_cast<float>(p_u), vec3_cast<float>(p_v));
            const Vec2 fd{static_cast<float>(bump_t(t, ph)), static_cast<float>(bump_p(t, ph))};
            const Vec3d diff =
                to_double(perturbed_normal(frame, fd)) - displaced_normal(sphere, bump, t, ph);
            EXPECT_LT(max_abs_component(diff), 8 * kNaturalRelTolerance * length(p_u) * length(p_v))
                << t << " " << ph;
            ++exact_points;
        }
    }
    EXPECT_GT(exact_points, 10);
}

TEST(LocalFrame, MirroredUvKeepsTheShadingSideAndTheBumpSign) {
    // p_u × p_v points down (−z) while the shading normal points up: σ = −1.
    const Vec3 p_u{0.0f, 2.0f, 0.0f}, p_v{0.5f, 0.0f, 0.0f}, up{0.0f, 0.0f, 1.0f};
    const NaturalFrame f = make_natural_frame(p_u, p_v, up);
    EXPECT_NEAR(f.n.z, 1.0f, 1e-6f);             // |n̂_s·(p_u × p_v)| n̂_s
    EXPECT_NEAR(dot(f.s_u, p_u), -1.0f, 1e-6f);  // dual basis with −|n|
    EXPECT_NEAR(dot(f.s_v, p_v), -1.0f, 1e-6f);
    EXPECT_NEAR(dot(f.s_u, p_v), 0.0f, 1e-6f);
    const Vec3 c = cross(f.s_u, f.s_v);  // [F1] with σ: n = σ s_u × s_v
    EXPECT_NEAR(-c.z, f.n.z, 1e-6f);
    // The height rising along u (f_u > 0) tilts n' away from p_u, as for a right-handed mapping.
    EXPECT_LT(dot(perturbed_normal(f, Vec2{0.3f, 0.0f}), p_u), 0.0f);
    // A shading normal in the tangent plane of the parameterisation is degenerate.
    const NaturalFrame d = make_natural_frame(p_u, p_v, Vec3{1.0f, 0.0f, 0.0f});
    EXPECT_EQ(length(d.s_u), 0.0f);
    EXPECT_NEAR(d.n.x, 1.0f, 1e-6f);
}

TEST(LocalFrame, NaturalAndOrthonormalFramesAgree) {
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> len(0.2f, 4.0f), g(-1.0f, 1.0f);
    for (int i = 0; i < 1000; ++i) {
        // Orthogonal parameterisation: the slope_map.h conversion and the frame with m = p_v.
        const Vec3 eu = random_unit(rng);
        const Vec3 ev = normalize(cross(random_unit(rng), eu));
        if (length(ev) == 0.0f) continue;
        const float lu = len(rng), lv = len(rng);
        const Vec3 p_u = lu * eu, p_v = lv * ev;
        const NaturalFrame natural = make_natural_frame(p_u, p_v);
        const OrthonormalFrame ortho = make_orthonormal_frame(natural.n, p_v);
        const Vec2 f{g(rng), g(rng)};
        const Vec3d expected = to_double(perturbed_normal(natural, f));
        const Vec2 b = slopes_from_natural_derivatives(f, lu, lv);
        const Vec3d ours = to_double(perturbed_normal(natural.n, ortho, b));
        EXPECT_LT(max_abs_diff(ours, expected), 8 * kNaturalRelTolerance * lu * lv) << i;
        // Non-orthogonal: slopes_in_frame re-expresses natural derivatives exactly.
        const Vec3 q_u = p_u + 0.7f * p_v;
        const NaturalFrame skew = make_natural_frame(q_u, p_v);
        const OrthonormalFrame skew_ortho = make_orthonormal_frame(skew.n, p_v);
        const Vec2 bs = slopes_in_frame(f, tangent_frame(skew), skew_ortho);
        EXPECT_LT(max_abs_diff(to_double(perturbed_normal(skew.n, skew_ortho, bs)),
                               to_double(perturbed_normal(skew, f))),
                  8 * kNaturalRelTolerance * length(q_u) * lv)
            << i;
    }
}

TEST(LocalFrame, SlopeMapOnATiltedPlaneGivesTheDisplacedNormal) {
    // End to end: a W×H height map of h(u, v) on a tilted, orthogonally parameterised plane
    // (u, v ∈ [0, 1], v up the image), slopes_from_height_map with the world texel sizes, the
    // frame with m = p_v, and n + |n|(b1 e1 + b2 e2) must be the normal of the displaced plane at
    // each texel centre, up to the central-difference error of the slopes (sine test bound,
    // per axis: amplitude·(1 − sin θ/θ)).
    const int w = 32, h = 24;
    const Vec3d eu = normalize(Vec3d{1.0, 0.2, -0.3});
    const Vec3d ev = normalize(cross(Vec3d{0.1, 0.3, 1.0}, eu));
    const double lu = 4.0, lv = 3.0;  // |p_u|, |p_v|: world size of the map
    const Vec3d p_u = lu * eu, p_v = lv * ev;
    const auto plane = [&](double u, double v) { return u * p_u + v * p_v; };
    const double A = 0.05, a = 2 * std::numbers::pi * 2, c = 2 * std::numbers::pi * 3;  // periods
    const auto height = [&](double u, double v) { return A * std::sin(a * u) * std::cos(c * v); };
    Image map(w, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            map.at(x, y, 0) = static_cast<float>(height((x + 0.5) / w, (h - y - 0.5) / h));
        }
    }
    HeightMapOptions options;
    options.texel_size_u = static_cast<float>(lu / w);
    options.texel_size_v = static_cast<float>(lv / h);
    const Result<Image> slopes = slopes_from_height_map(map, options);
    ASSERT_TRUE(slopes.ok());
    const Vec3 n = vec3_cast<float>(cross(p_u, p_v));
    const OrthonormalFrame frame = make_orthonormal_frame(n, vec3_cast<float>(p_v));
    // Slope amplitudes in world units and their central-difference errors.
    const double theta_u = a / w, theta_v = c / h;
    const double err_u = A * a / lu * (1 - std::sin(theta_u) / theta_u);
    const double err_v = A * c / lv * (1 - std::sin(theta_v) / theta_v);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double u = (x + 0.5) / w, v = (h - y - 0.5) / h;
            const Vec3d truth = normalize(displaced_normal(plane, height, u, v));
            const Vec2 b{slopes->at(x, y, 0), slopes->at(x, y, 1)};
            const Vec3d ours = normalize(to_double(perturbed_normal(n, frame, b)));
            // |Δn̂| ≤ |Δb| for a unit normal (n̂ + b)/|n̂ + b|, plus float noise.
            EXPECT_LT(length(ours - truth), std::hypot(err_u, err_v) + 1e-5) << x << " " << y;
        }
    }
}

}  // namespace
}  // namespace footprint
