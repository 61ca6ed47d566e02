// The degenerate cases of spec §4, one test each, on environment lookups of every layout.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "bump/roughness.h"
#include "envmap/env_test_maps.h"
#include "texture/footprint_assembly.h"
#include "texture/texture_lookup.h"

namespace footprint {
namespace {

using test::kAllEnvLayouts;
using test::layout_name;

// The bilinear point sample a lookup of K = 0 (or λ1 < 1) takes: level 0 of the map — or, for a
// lat-long direction within 30° of a pole, level 0 of that polar cap (environment_map.h).
float point_sample(const EnvironmentMap& map, Vec3 r) {
    const float len = std::sqrt(dot(r, r));
    if (map.layout() == EnvLayout::latlong && std::fabs(r.y) >= 0.8660254f * len) {
        const EnvCoords c = env_coords(EnvLayout::cube, r);
        float v;
        texture_lookup(*map.polar_cap(r.y > 0 ? 0 : 1), c.s, c.t, FootprintEllipse{},
                       LookupOptions{}, &v);
        return v;
    }
    float v;
    environment_bilinear(map, r, 0, &v);
    return v;
}

float smooth(Vec3 r) {
    return 0.5f + 0.3f * r.x + 0.2f * r.y - 0.1f * r.z;
}

Vec3 random_direction(std::mt19937& rng) {
    std::normal_distribution<float> g(0, 1);
    return {g(rng), g(rng), g(rng)};
}

// §4 row 1: K = 0 (orthographic flat mirror, no roughness) is one bilinear probe at lod 0.
TEST(EnvDegenerate, ZeroFootprintIsOneBilinearProbeAtLevelZero) {
    std::mt19937 rng(11);
    for (EnvLayout layout : kAllEnvLayouts) {
        const EnvironmentMap map = test::env_noise_map(layout, 32, 12);
        for (int i = 0; i < 200; ++i) {
            const Vec3 r = random_direction(rng);
            float filtered;
            environment_lookup(map, r, {}, {}, LookupOptions{}, &filtered);
            ASSERT_EQ(filtered, point_sample(map, r)) << layout_name(layout) << " " << i;
        }
    }
}

// §4 row 3: λ1 < 1 texel is magnification: one probe at lod 0, the same bilinear sample.
TEST(EnvDegenerate, SubTexelFootprintIsMagnification) {
    std::mt19937 rng(13);
    for (EnvLayout layout : kAllEnvLayouts) {
        const EnvironmentMap map = test::env_noise_map(layout, 32, 14);
        for (int i = 0; i < 200; ++i) {
            const Vec3 r = random_direction(rng);
            Vec3 dx, dy;
            test::isotropic_differentials(r, 1e-3f, dx, dy);  // ≪ 1 texel of a 32-texel face
            const EnvFootprint f = compute_env_footprint(layout, map.texel_scale(), r, dx, dy);
            if (f.isotropic_fallback) continue;  // the exact pole / rim: covered below
            ASSERT_LT(make_footprint_ellipse(f.matrix).major_radius, 1.0f);
            float filtered;
            environment_lookup(map, f, LookupOptions{}, &filtered);
            ASSERT_FLOAT_EQ(filtered, point_sample(map, r)) << layout_name(layout) << " " << i;
        }
    }
}

// §4 row 2: λ2 = 0 (rank 1: one ray differential only, e.g. an orthographic view of a cylinder).
// Rule B places N probes along r1 with T_p = T_min; the result is the mean of a line of the map,
// so on a map that varies only across that line it equals the point value, and on any map it is
// finite and inside the range of the map.
TEST(EnvDegenerate, RankOneFootprintFiltersAlongItsLine) {
    // f depends on y only; a footprint along the x axis at the equator (r = +Z) keeps y = 0.
    for (EnvLayout layout : kAllEnvLayouts) {
        const EnvironmentMap map =
            test::env_map(layout, 64, [](Vec3 r) { return 0.5f + 0.4f * r.y; });
        const Vec3 r{0, 0, 1}, dx{0.3f, 0, 0}, dy{0, 0, 0};  // 5–10 texels
        const EnvFootprint f = compute_env_footprint(layout, map.texel_scale(), r, dx, dy);
        const FootprintEllipse e = make_footprint_ellipse(f.matrix);
        EXPECT_GT(e.major_radius, 1.0f) << layout_name(layout);
        EXPECT_EQ(e.minor_radius, 0.0f) << layout_name(layout);
        const ProbePlan plan =
            plan_probes(e, ProbeRule::moment_matched, 30, map.face(f.coords.face).max_level(), 0);
        EXPECT_GT(plan.count, 1) << layout_name(layout);
        float v;
        environment_lookup(map, f, LookupOptions{}, &v);
        EXPECT_NEAR(v, 0.5f, 2e-3f) << layout_name(layout);
    }
}

// §4 row 4: k11 = k22, k12 = 0 is isotropic: r1 = (1, 0) and one probe, so the probe budget and
// rule do not matter.
TEST(EnvDegenerate, IsotropicFootprintTakesOneProbe) {
    const EnvironmentMap map = test::env_noise_map(EnvLayout::cube, 64, 15);
    EnvFootprint f =
        compute_env_footprint(EnvLayout::cube, map.texel_scale(), {0.2f, 0.1f, 1}, {}, {});
    f.matrix = {9, 0, 9};  // 3 texels in every direction
    const FootprintEllipse e = make_footprint_ellipse(f.matrix);
    EXPECT_EQ(e.major_axis.x, 1.0f);
    EXPECT_EQ(e.major_axis.y, 0.0f);
    float budget_30, budget_1, rule_ext;
    LookupOptions options;
    environment_lookup(map, f, options, &budget_30);
    options.max_probes = 1;
    environment_lookup(map, f, options, &budget_1);
    options.max_probes = 30;
    options.probe_rule = ProbeRule::moment_matched;
    environment_lookup(map, f, options, &rule_ext);
    EXPECT_EQ(budget_30, budget_1);
    EXPECT_EQ(budget_30, rule_ext);
}

// §4 row 5: roughness with k22 ≤ ε has B = [[√k11, 0], [0, 0]]; its footprint term K3 is rank 1
// and the lookup stays finite.
TEST(EnvDegenerate, RankOneRoughness) {
    const RoughnessFactor b = roughness_factor(Sym2{0.04f, 0, 0});
    EXPECT_FLOAT_EQ(b.d1, 0.2f);
    EXPECT_EQ(b.d2, 0.0f);
    EXPECT_EQ(b.d3, 0.0f);
    ReflectionGeometry g;
    g.v = {0, 0.3f, 1};
    g.n = {0, 0, 1};
    g.roughness = b;
    const EnvironmentMap map = test::env_noise_map(EnvLayout::cube, 32, 16);
    const EnvFootprint f = compute_env_footprint(EnvLayout::cube, map.texel_scale(), g);
    EXPECT_NEAR(f.roughness.determinant(), 0.0f, 1e-6f * f.roughness.trace() * f.roughness.trace());
    EXPECT_GT(f.roughness.trace(), 0.0f);
    float v;
    environment_lookup(map, f, LookupOptions{}, &v);
    EXPECT_TRUE(std::isfinite(v));
}

// §4 row 6: n_m·v ≤ 0 drops the bump, then n·v ≤ 0 clamps n: the lookup is the unbumped one.
TEST(EnvDegenerate, BumpFacingAwayIsDropped) {
    ReflectionGeometry g;
    g.v = {0, 0, 1};
    g.n = {0, 0, 1};
    g.bump_slope = {-40, 0};  // n_m = (−40, 0, 1): n_m·v > 0 still
    g.t1 = {1, 0, 0};
    g.bump_slope = {0, 0};
    const EnvFootprint plain = compute_env_footprint(EnvLayout::cube, {64, 64}, g);
    g.v = {1, 0, 0.05f};
    g.bump_slope = {-40, 0};  // n_m·v = −40 + 0.05 < 0
    const EnvFootprint dropped = compute_env_footprint(EnvLayout::cube, {64, 64}, g);
    EXPECT_TRUE(dropped.bump_dropped);
    g.bump_slope = {0, 0};
    const EnvFootprint unbumped = compute_env_footprint(EnvLayout::cube, {64, 64}, g);
    EXPECT_FALSE(plain.bump_dropped);
    EXPECT_EQ(dropped.reflected.x, unbumped.reflected.x);
    EXPECT_EQ(dropped.reflected.z, unbumped.reflected.z);
}

// §4 row 7: v_r exactly on a cube edge or corner takes the fixed tie-break (lowest face index)
// and filters like its neighbours a hair away on every adjacent face.
TEST(EnvDegenerate, CubeEdgesAndCornersAreSeamless) {
    const EnvironmentMap map = test::env_map(EnvLayout::cube, 64, smooth);
    const Vec3 corners_and_edges[] = {{1, 1, 1},     {-1, 1, -1},  {1, -1, 0.3f},
                                      {0.2f, 1, -1}, {-1, -1, -1}, {1, 0, -1}};
    for (const Vec3 r : corners_and_edges) {
        Vec3 dx, dy;
        test::isotropic_differentials(r, 0.05f, dx, dy);  // ~1.6 texels
        float at;
        environment_lookup(map, r, dx, dy, LookupOptions{}, &at);
        EXPECT_NEAR(at, smooth(r / std::sqrt(dot(r, r))), 3e-3f);
        const EnvCoords c = env_coords(EnvLayout::cube, r);
        for (int axis = 0; axis < 3; ++axis) {
            Vec3 nudged = r;
            (&nudged.x)[axis] *= 1.0001f;  // moves the direction onto this axis' face
            float near;
            environment_lookup(map, nudged, dx, dy, LookupOptions{}, &near);
            EXPECT_NEAR(at, near, 2e-3f) << "face " << c.face << " axis " << axis;
        }
    }
    EXPECT_EQ(env_coords(EnvLayout::cube, Vec3{1, 1, 1}).face, 0);     // +X wins the tie
    EXPECT_EQ(env_coords(EnvLayout::cube, Vec3{-1, -1, -1}).face, 1);  // −X
}

// §4 row 9 and "NaN or Inf inputs give a finite colour": non-finite directions or differentials
// never reach a pixel.
TEST(EnvDegenerate, NonFiniteInputGivesAFiniteColour) {
    const float nan = std::nanf(""), inf = INFINITY;
    const Vec3 bad[] = {{nan, 0, 1}, {inf, 0, 0}, {0, 0, 0}, {inf, -inf, nan}, {1e30f, 1e30f, 0}};
    for (EnvLayout layout : kAllEnvLayouts) {
        const EnvironmentMap map = test::env_map(layout, 16, smooth);
        for (const Vec3 r : bad)
            for (const Vec3 d : bad) {
                float v = nan;
                environment_lookup(map, r, d, {0.01f, 0, 0}, LookupOptions{}, &v);
                ASSERT_TRUE(std::isfinite(v)) << layout_name(layout);
                environment_lookup(map, {0, 0.3f, 1}, d, d, LookupOptions{}, &v);
                ASSERT_TRUE(std::isfinite(v)) << layout_name(layout);
                ReflectionGeometry g;
                g.v = r;
                g.n = d;
                g.dn_dx = d;
                environment_lookup(map, compute_env_footprint(layout, map.texel_scale(), g),
                                   LookupOptions{}, &v);
                ASSERT_TRUE(std::isfinite(v)) << layout_name(layout);
            }
    }
}

TEST(EnvDegenerate, FootprintsTooLargeForTheirAxesAreFiltered) {
    // A finite K whose ellipse overflows (entries near FLT_MAX, from a direction 1e-19 long next
    // to derivatives of 1e-3: axes NaN or infinite), or whose axes' squares overflow (1.7e19
    // texels), is planned at kMaxPlannedRadius: the probes' count was undefined and their spacing
    // NaN before (found by fuzz_lookup and fuzz_env_layouts, tests/data/bad/fuzz/). The result is a
    // weighted mean of the map's texels, alike alone and in a batch.
    for (EnvLayout layout : kAllEnvLayouts) {
        const EnvironmentMap map = test::env_map(layout, 16, smooth);
        EnvFootprint f = compute_env_footprint(layout, map.texel_scale(), {0.3f, 0.2f, 1},
                                               {1e-3f, 0, 0}, {0, 1e-3f, 0});
        for (const Sym2 k : {Sym2{3e38f, 1e38f, 3e38f}, Sym2{3e38f, 0, 1}}) {
            ASSERT_TRUE(k.is_finite());
            f.matrix = k;
            float single = NAN, batch = NAN;
            environment_lookup(map, f, LookupOptions{}, &single);
            environment_lookup_batch(map, std::span<const EnvFootprint>(&f, 1), LookupOptions{},
                                     &batch);
            // smooth() spans 0.5 ± 0.39 over the sphere; bilinear and the levels' box means stay
            // inside.
            EXPECT_GE(single, 0.1f) << layout_name(layout);
            EXPECT_LE(single, 0.9f) << layout_name(layout);
            EXPECT_EQ(batch, single) << layout_name(layout);
        }
    }
}

// §4 row 10a / §3.4: exactly at a lat-long pole J_P is undefined; the footprint is isotropic
// with T_p = (H0/π)·θ_fp, θ_fp the angular radius of the ray differentials (κ·roughness added in
// form (b)).
TEST(EnvDegenerate, LatLongPoleIsIsotropic) {
    const float h0 = 128;
    const EnvFootprint f = compute_env_footprint(EnvLayout::latlong, {2 * h0, h0}, {0, 2, 0},
                                                 {0.02f, 0, 0}, {0, 0.5f, 0.03f});
    // θ_fp = largest singular value of the tangential parts / |r| = 0.03 / 2 (the y part of ∂r/∂y
    // is radial and drops out).
    const float tp = h0 / std::numbers::pi_v<float> * 0.015f;
    EXPECT_TRUE(f.isotropic_fallback);
    EXPECT_NEAR(f.matrix.xx, tp * tp, 1e-4f * tp * tp);
    EXPECT_NEAR(f.matrix.yy, tp * tp, 1e-4f * tp * tp);
    EXPECT_EQ(f.matrix.xy, 0.0f);
    EXPECT_EQ(f.coords.t, 0.0f);

    // Form (b): a mirror facing +Y seen from straight above reflects to the pole; with roughness
    // K_b = l² I the radius grows by κ·(angular roughness) = κ·2l (A_n scales slopes by 2(n·v)).
    ReflectionGeometry g;
    g.v = {0, 1, 0};
    g.n = {0, 1, 0};
    g.t1 = {1, 0, 0};
    g.t2 = {0, 0, 1};
    g.dv_dx = {-0.01f, 0, 0};
    g.dv_dy = {0, 0, -0.01f};
    const float l = 0.05f;
    g.roughness = roughness_factor(Sym2{l * l, 0, l * l});
    const EnvFootprint fb = compute_env_footprint(EnvLayout::latlong, {2 * h0, h0}, g);
    EXPECT_TRUE(fb.isotropic_fallback);
    // ∂v_r/∂x = A_v ∂v/∂x = −(−0.01 e_x) ... |tangential| = 0.01; roughness: A_n t1 l = 2 l e_x.
    const float theta = 0.01f + 2.0f * (2 * l);
    const float tpb = h0 / std::numbers::pi_v<float> * theta;
    EXPECT_NEAR(std::sqrt(fb.matrix.xx), tpb, 1e-3f * tpb);
    EXPECT_NEAR(std::sqrt(fb.matrix.yy), tpb, 1e-3f * tpb);
}

// §4 row 10b / §3.2: at the sphere map's rim direction −Z the footprint is isotropic at the
// centre's scale; near the rim λ1 is clamped to W/2, and lookups stay finite and
// constant-preserving.
TEST(EnvDegenerate, SphereMapRim) {
    const float w = 64;
    const EnvFootprint f =
        compute_env_footprint(EnvLayout::sphere, {w, w}, {0, 0, -1}, {0.1f, 0, 0}, {0, 0.1f, 0});
    EXPECT_TRUE(f.isotropic_fallback);
    EXPECT_NEAR(std::sqrt(f.matrix.xx), 0.25f * w * 0.1f, 1e-4f);
    const EnvironmentMap constant = test::env_map(EnvLayout::sphere, 64, [](Vec3) { return 0.7f; });
    const EnvironmentMap noise = test::env_noise_map(EnvLayout::sphere, 64, 17);
    for (const float z : {-1.0f, -0.9999f, -0.999f, -0.99f}) {
        const Vec3 r{std::sqrt(1 - z * z), 0, z};
        Vec3 dx, dy;
        test::isotropic_differentials(r, 0.02f, dx, dy);
        const EnvFootprint near_rim = compute_env_footprint(EnvLayout::sphere, {w, w}, r, dx, dy);
        EXPECT_TRUE(near_rim.matrix.is_finite());
        float c, n;
        environment_lookup(constant, near_rim, LookupOptions{}, &c);
        environment_lookup(noise, near_rim, LookupOptions{}, &n);
        EXPECT_NEAR(c, 0.7f, 1e-5f) << z;
        EXPECT_TRUE(n >= 0 && n <= 1) << z;
    }
}

}  // namespace
}  // namespace footprint
