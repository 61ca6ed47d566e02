#include "envmap/environment_map.h"

#include "envmap/env_test_maps.h"
#include "envmap/polar_caps.h"
#include "texture/footprint_assembly.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

namespace footprint {
namespace {

// A smooth function of direction, for maps whose filtered values are known.
float smooth(Vec3 r) {
    const float n = std::sqrt(dot(r, r));
    return 0.5f + 0.3f * r.x / n + 0.2f * r.y / n - 0.1f * r.z / n;
}

EnvironmentMap smooth_cube(int size) {
    std::array<Image, 6> faces;
    for (int f = 0; f < 6; ++f) {
        faces[f] = Image(size, size, 1);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                faces[f].at(x, y, 0) = smooth(env_direction(
                    EnvLayout::cube, f, (x + 0.5f) / float(size), (y + 0.5f) / float(size)));
    }
    return std::move(EnvironmentMap::from_cube_faces(faces).value());
}

EnvironmentMap noise_cube(int size, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0, 1);
    std::array<Image, 6> faces;
    for (Image& face : faces) {
        face = Image(size, size, 1);
        for (float& v : face.pixels) v = u(rng);
    }
    return std::move(EnvironmentMap::from_cube_faces(faces).value());
}

// A cube map's faces as plain textures, each confined to itself (clamped at its edges, without
// the neighbours' texels that the map keeps around each face): the baseline that seamless
// filtering is measured against.
std::vector<MipPyramid> confined_faces(const EnvironmentMap& cube) {
    MipPyramidOptions options;
    options.wrap_s = options.wrap_t = WrapMode::clamp;
    std::vector<MipPyramid> faces;
    for (int f = 0; f < 6; ++f)
        faces.push_back(MipPyramid::build(cube.face(f).level_image(0), options));
    return faces;
}

// A footprint of angular radius `angle` (radians) around direction r, as ray differentials.
EnvFootprint footprint_around(const EnvironmentMap& map, Vec3 r, float angle) {
    Vec3 dx, dy;
    test::isotropic_differentials(r, angle, dx, dy);
    return compute_env_footprint(map.layout(), map.texel_scale(), r, dx, dy);
}

TEST(EnvironmentMap, ConstantMapsStayConstantAcrossFaces) {
    std::array<Image, 6> faces;
    for (Image& f : faces) f = Image(16, 16, 3, 0.25f);
    const EnvironmentMap cube = std::move(EnvironmentMap::from_cube_faces(faces).value());
    std::mt19937 rng(1);
    std::normal_distribution<float> g(0, 1);
    std::uniform_real_distribution<float> u(0, 1);
    for (int i = 0; i < 500; ++i) {
        const EnvFootprint f = footprint_around(cube, {g(rng), g(rng), g(rng)}, 0.5f * u(rng));
        float out[3];
        environment_lookup(cube, f, LookupOptions{}, out);
        for (float v : out) ASSERT_NEAR(v, 0.25f, 1e-6f);
    }
}

TEST(EnvironmentMap, SmallFootprintsReproduceASmoothEnvironment) {
    // Bilinear reconstruction of a smooth function of direction: error ≤ ½·(texel angle)²·|∇²f|,
    // about 1e−3 at 64 texels per face (and the small footprint's blur, of the same order).
    constexpr float kTolerance = 3e-3f;
    const EnvironmentMap cube = smooth_cube(64);
    Image latlong_image(256, 128, 1);
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 256; ++x)
            latlong_image.at(x, y, 0) =
                smooth(env_direction(EnvLayout::latlong, 0, (x + 0.5f) / 256, (y + 0.5f) / 128));
    const EnvironmentMap latlong = std::move(EnvironmentMap::from_latlong(latlong_image).value());
    std::mt19937 rng(2);
    std::normal_distribution<float> g(0, 1);
    for (const EnvironmentMap* map : {&cube, &latlong})
        for (int i = 0; i < 1000; ++i) {
            const Vec3 r{g(rng), g(rng), g(rng)};
            if (map == &latlong && std::fabs(r.y) > 0.95f * std::sqrt(dot(r, r)))
                continue;  // poles: the polar-cap tests below
            float v;
            environment_lookup(*map, footprint_around(*map, r, 0.01f), LookupOptions{}, &v);
            ASSERT_NEAR(v, smooth(r), kTolerance) << i;
        }
}

TEST(EnvironmentMap, LookupsAgreeAcrossCubeEdges) {
    // Directions a fraction of a texel either side of a face edge, with a footprint ~8 texels wide:
    // the probes re-projected onto the neighbour face make both sides read nearly the same texels.
    // Confining the probes to their own face (clamp-to-edge, the non-seamless baseline) does not.
    const int size = 64;
    const EnvironmentMap cube = noise_cube(size, 3);
    const std::vector<MipPyramid> confined_face = confined_faces(cube);
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(0.1f, 0.9f);
    double seamless = 0, confined = 0;
    int n = 0;
    for (int face = 0; face < 6; ++face)
        for (int k = 0; k < 40; ++k) {
            const float along = u(rng), eps = 0.2f / size;
            const Vec3 inside = env_direction(EnvLayout::cube, face, 1 - eps, along);
            const Vec3 outside = env_direction(EnvLayout::cube, face, 1 + eps, along);
            const float angle = 8.0f * 2 / size;  // ~8 texels
            const EnvFootprint a = footprint_around(cube, inside, angle),
                               b = footprint_around(cube, outside, angle);
            ASSERT_NE(a.coords.face, b.coords.face);
            float va, vb;
            environment_lookup(cube, a, LookupOptions{}, &va);
            environment_lookup(cube, b, LookupOptions{}, &vb);
            seamless += std::fabs(va - vb);
            // The baseline: the same footprint assembly, confined to each direction's own face.
            float ca, cb;
            texture_lookup(confined_face[a.coords.face], a.coords.s, a.coords.t,
                           make_footprint_ellipse(a.matrix), LookupOptions{}, &ca);
            texture_lookup(confined_face[b.coords.face], b.coords.s, b.coords.t,
                           make_footprint_ellipse(b.matrix), LookupOptions{}, &cb);
            confined += std::fabs(ca - cb);
            ++n;
        }
    seamless /= n;
    confined /= n;
    std::printf("mean |difference| across an edge: seamless %.4f, confined to a face %.4f\n",
                seamless, confined);
    // Measured 0.0035 vs 0.0318 (noise of σ = 0.29 per texel): the remaining difference is the
    // clamp-to-edge bilinear taps and the probes' slightly different face planes.
    EXPECT_LT(seamless, 0.3 * confined);
    EXPECT_LT(seamless, 0.01);
}

TEST(EnvironmentMap, BilinearTapsCrossCubeEdges) {
    // Point lookups a hundredth of a texel either side of a face edge: each side's bilinear taps
    // straddle the edge, so both blend the same two edge texels and agree to ~1 % of a texel step —
    // where clamping to the own face's edge would read two unrelated texels (noise σ = 0.29).
    const int size = 32;
    const EnvironmentMap cube = noise_cube(size, 5);
    const std::vector<MipPyramid> confined_face = confined_faces(cube);
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> u(0.1f, 0.9f);
    double seamless = 0, confined = 0;
    int n = 0;
    for (int face = 0; face < 6; ++face)
        for (int k = 0; k < 20; ++k) {
            const float along = u(rng), eps = 0.01f / size;
            const EnvFootprint a =
                footprint_around(cube, env_direction(EnvLayout::cube, face, 1 - eps, along), 1e-5f);
            const EnvFootprint b =
                footprint_around(cube, env_direction(EnvLayout::cube, face, 1 + eps, along), 1e-5f);
            float va, vb, ca, cb;
            environment_lookup(cube, a, LookupOptions{}, &va);
            environment_lookup(cube, b, LookupOptions{}, &vb);
            texture_lookup(confined_face[a.coords.face], a.coords.s, a.coords.t, FootprintEllipse{},
                           LookupOptions{}, &ca);
            texture_lookup(confined_face[b.coords.face], b.coords.s, b.coords.t, FootprintEllipse{},
                           LookupOptions{}, &cb);
            seamless += std::fabs(va - vb);
            confined += std::fabs(ca - cb);
            ++n;
        }
    seamless /= n;
    confined /= n;
    std::printf("point lookups across an edge: seamless %.4f, clamped to the face %.4f\n", seamless,
                confined);
    EXPECT_LT(seamless, 0.02);
    EXPECT_GT(confined, 0.1);
}

TEST(EnvironmentMap, CubeFaceBordersHoldTheTexelsTheirDirectionsFind) {
    // Each cube face keeps a one-texel border on every level. Each border texel must hold the texel
    // of the map that its centre's direction falls in (on another face), found here by direction
    // alone — env_direction() and env_coords(), not the border's own edge tables. A border copied
    // from the wrong edge, flipped along it, or left at zero, fails.
    for (const int size : {1, 2, 5, 16}) {
        const EnvironmentMap cube = noise_cube(size, 9);
        int checked = 0;
        for (int f = 0; f < 6; ++f) {
            const MipPyramid& face = cube.face(f);
            ASSERT_EQ(face.border(), 1);
            for (int l = 0; l < face.level_count(); ++l) {
                const int w = face.width(l);
                for (int y = -1; y <= w; ++y)
                    for (int x = -1; x <= w; ++x) {
                        if (x >= 0 && x < w && y >= 0 && y < w) continue;
                        // A corner texel's centre lies beyond two edges: its direction is
                        // (−½, −½) texels off the corner, which lands on one of the two other
                        // faces at the corner (within rounding of the exact diagonal).
                        const Vec3 r = env_direction(EnvLayout::cube, f, (x + 0.5f) / float(w),
                                                     (y + 0.5f) / float(w));
                        const EnvCoords c = env_coords(EnvLayout::cube, r);
                        ASSERT_NE(c.face, f);
                        const int tx = std::clamp(static_cast<int>(c.s * float(w)), 0, w - 1);
                        const int ty = std::clamp(static_cast<int>(c.t * float(w)), 0, w - 1);
                        EXPECT_EQ(*face.texel(l, x, y), *cube.face(c.face).texel(l, tx, ty))
                            << "size " << size << " face " << f << " level " << l << " border ("
                            << x << ", " << y << ")";
                        ++checked;
                    }
            }
        }
        EXPECT_GT(checked, 6 * 4 * size);
    }
}

TEST(EnvironmentMap, SmallFootprintsReproduceASmoothEnvironmentInEveryLayout) {
    // Sphere and paraboloid maps, and the lat-long poles, with footprints of ~1–2 texels: the error
    // is bilinear reconstruction of a linear function of direction on a curved map (measured
    // ≤ 2.2e−3 at 128 texels). The sphere map is left out within 25° of its singular rim
    // (−Z), where one texel spans ever more solid angle in one direction.
    constexpr float kTolerance = 4e-3f;
    std::mt19937 rng(21);
    std::normal_distribution<float> g(0, 1);
    for (EnvLayout layout : test::kAllEnvLayouts) {
        const EnvironmentMap map = test::env_map(layout, 128, [](Vec3 r) { return smooth(r); });
        float worst = 0;
        for (int i = 0; i < 2000; ++i) {
            Vec3 r{g(rng), g(rng), g(rng)};
            if (i < 20) r = {0.001f * g(rng), i % 2 ? 1.0f : -1.0f, 0.001f * g(rng)};  // poles
            r = r / std::sqrt(dot(r, r));
            if (layout == EnvLayout::sphere && r.z < -std::cos(25 * 3.14159265f / 180)) continue;
            Vec3 dx, dy;
            test::isotropic_differentials(r, 0.01f, dx, dy);
            float v;
            environment_lookup(map, r, dx, dy, LookupOptions{}, &v);
            worst = std::max(worst, std::fabs(v - smooth(r)));
        }
        std::printf("%s: max |error| %.4f\n", test::layout_name(layout), worst);
        EXPECT_LT(worst, kTolerance) << test::layout_name(layout);
    }
}

TEST(EnvironmentMap, ParaboloidLookupsAgreeAcrossTheEquator) {
    // Directions a fraction of a texel either side of the equator land on different faces; with
    // the disk exteriors filled by the other hemisphere and probes moved onto it, both read nearly
    // the same texels (noise of σ = 0.29 per texel). Confined to their own face they do not.
    const int size = 64;
    const EnvironmentMap map = test::env_noise_map(EnvLayout::paraboloid, size, 22);
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> u(0, 2 * 3.14159265f);
    double seamless = 0, confined = 0;
    const int n = 200;
    for (int k = 0; k < n; ++k) {
        const float phi = u(rng), eps = 0.2f / size;
        const Vec3 above{std::cos(phi), std::sin(phi), eps},
            below{std::cos(phi), std::sin(phi), -eps};
        Vec3 dx, dy;
        test::isotropic_differentials(above, 8.0f * 4 / size, dx, dy);  // ~8 texels at the rim
        const EnvFootprint a =
            compute_env_footprint(EnvLayout::paraboloid, map.texel_scale(), above, dx, dy);
        const EnvFootprint b =
            compute_env_footprint(EnvLayout::paraboloid, map.texel_scale(), below, dx, dy);
        ASSERT_NE(a.coords.face, b.coords.face);
        float va, vb, ca, cb;
        environment_lookup(map, a, LookupOptions{}, &va);
        environment_lookup(map, b, LookupOptions{}, &vb);
        seamless += std::fabs(va - vb);
        texture_lookup(map.face(a.coords.face), a.coords.s, a.coords.t,
                       make_footprint_ellipse(a.matrix), LookupOptions{}, &ca);
        texture_lookup(map.face(b.coords.face), b.coords.s, b.coords.t,
                       make_footprint_ellipse(b.matrix), LookupOptions{}, &cb);
        confined += std::fabs(ca - cb);
    }
    seamless /= n;
    confined /= n;
    std::printf("mean |difference| across the equator: seamless %.4f, confined %.4f\n", seamless,
                confined);
    // Measured 0.0058 vs 0.0153: what remains is the exterior texels being a resampled (bilinear)
    // copy of the other hemisphere rather than its texels.
    EXPECT_LT(seamless, 0.5 * confined);
    EXPECT_LT(seamless, 0.008);
}

TEST(EnvironmentMap, LatLongPolarCapsHoldTheMapAndJoinItSmoothly) {
    // The caps are the map resampled: a smooth environment is reproduced on them, and lookups
    // either side of the 30° switch between cap and lat-long agree to the reconstruction error.
    const EnvironmentMap map =
        test::env_map(EnvLayout::latlong, 128, [](Vec3 r) { return smooth(r); });
    ASSERT_NE(map.polar_cap(0), nullptr);
    EXPECT_EQ(map.polar_cap(0)->width(0), 123);  // ⌈1.5·2·128/π⌉
    std::mt19937 rng(24);
    std::uniform_real_distribution<float> u(0, 2 * 3.14159265f);
    float worst_value = 0, worst_jump = 0;
    for (int i = 0; i < 400; ++i) {
        const float phi = u(rng), pole = i % 2 ? 1.0f : -1.0f;
        for (float colatitude_deg : {0.0f, 10.0f, 29.99f, 30.01f}) {
            const float c = colatitude_deg * 3.14159265f / 180;
            const Vec3 r{std::sin(c) * std::cos(phi), pole * std::cos(c),
                         std::sin(c) * std::sin(phi)};
            Vec3 dx, dy;
            test::isotropic_differentials(r, 0.02f, dx, dy);  // ~1.6 t-texels
            float v;
            environment_lookup(map, r, dx, dy, LookupOptions{}, &v);
            worst_value = std::max(worst_value, std::fabs(v - smooth(r)));
        }
        const float c0 = 29.99f * 3.14159265f / 180, c1 = 30.01f * 3.14159265f / 180;
        const Vec3 a{std::sin(c0) * std::cos(phi), pole * std::cos(c0),
                     std::sin(c0) * std::sin(phi)};
        const Vec3 b{std::sin(c1) * std::cos(phi), pole * std::cos(c1),
                     std::sin(c1) * std::sin(phi)};
        Vec3 dx, dy;
        test::isotropic_differentials(a, 0.05f, dx, dy);
        float va, vb;
        environment_lookup(map, a, dx, dy, LookupOptions{}, &va);
        environment_lookup(map, b, dx, dy, LookupOptions{}, &vb);
        worst_jump = std::max(worst_jump, std::fabs(va - vb));
    }
    std::printf("polar caps: max |error| %.4f, max jump at the 30° switch %.4f\n", worst_value,
                worst_jump);
    // Measured 1e−4 and 3e−4; a cap mirrored or turned by 90° errs by ~0.1.
    EXPECT_LT(worst_value, 1e-3f);
    EXPECT_LT(worst_jump, 1.5e-3f);
}

TEST(EnvironmentMap, ThePoleTexelOfAnOddSizedCapAveragesEveryLongitude) {
    // A cap of odd size has a texel centred on the pole, where a lat-long texel is 0 radians wide:
    // that texel takes the most samples (64²), not an infinite count converted to int (undefined;
    // 2² on x86). Found by fuzz_lookup (tests/data/bad/fuzz/lookup/).
    Image image(6, 3, 1, 0.0f);
    image.at(0, 0, 0) = 1;  // the top row's mean is 1/6
    const EnvironmentMap map = std::move(EnvironmentMap::from_latlong(image).value());
    ASSERT_NE(map.polar_cap(0), nullptr);
    ASSERT_EQ(map.polar_cap(0)->width(0), 3);  // ⌈1.5·2·3/π⌉
    const float pole = map.polar_cap(0)->texel(0, 1, 1)[0];
    // The pole texel averages the top row over every longitude: measured 0.0037 off its mean with
    // 64² samples; 2² samples (four longitudes) are 0.021 off.
    constexpr float kPoleTolerance = 0.008f;
    EXPECT_NEAR(pole, 1.0f / 6, kPoleTolerance);
}

TEST(EnvironmentMap, PolarCapsKeepTheRoughnessFallbackOfNonFiniteInput) {
    // A non-finite ∂n/∂x near a pole leaves §4's isotropic fallback from the roughness alone, in
    // lat-long texels and without direction differentials: the caps must not turn it into a point
    // lookup, so the lookup equals that of the same map without caps.
    const EnvironmentMap noise = test::env_noise_map(EnvLayout::latlong, 64, 25);
    Image image(128, 64, 1);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 128; ++x) image.at(x, y, 0) = noise.face(0).level(0).texel(x, y)[0];
    LatLongOptions no_caps;
    no_caps.polar_caps = false;
    const EnvironmentMap with = std::move(EnvironmentMap::from_latlong(image).value());
    const EnvironmentMap without = std::move(EnvironmentMap::from_latlong(image, no_caps).value());
    ReflectionGeometry g;
    g.v = {0, 1, 0.05f};
    g.n = {0, 1, 0};
    g.t1 = {1, 0, 0};
    g.t2 = {0, 0, 1};
    g.dn_dx = {INFINITY, 0, 0};
    g.roughness = roughness_factor(Sym2{0.01f, 0, 0.01f});
    const EnvFootprint f = compute_env_footprint(EnvLayout::latlong, with.texel_scale(), g);
    ASSERT_TRUE(f.isotropic_fallback);
    ASSERT_GT(f.matrix.trace(), 2.0f);  // more than one texel: not a point lookup
    float a, b;
    environment_lookup(with, f, LookupOptions{}, &a);
    environment_lookup(without, f, LookupOptions{}, &b);
    EXPECT_EQ(a, b);
}

TEST(EnvironmentMap, PolarCapsCanBeTurnedOff) {
    // Without caps a lookup at the pole is the spec's §3.4 isotropic probe on the lat-long map.
    Image image(64, 32, 1, 0.25f);
    LatLongOptions no_caps;
    no_caps.polar_caps = false;
    const EnvironmentMap map = std::move(EnvironmentMap::from_latlong(image, no_caps).value());
    EXPECT_EQ(map.polar_cap(0), nullptr);
    float v;
    environment_lookup(map, {0, 1, 0}, {0.1f, 0, 0}, {0, 0, 0.1f}, LookupOptions{}, &v);
    EXPECT_FLOAT_EQ(v, 0.25f);
    LatLongOptions bad;
    bad.polar_cap_resolution = 0;
    EXPECT_FALSE(EnvironmentMap::from_latlong(image, bad).ok());
}

TEST(EnvironmentMap, PolarCapLookupsSkipOnlyTheUnusedLatLongFootprint) {
    // A ray-differential lookup near a pole goes straight to its cap, without the lat-long
    // footprint; it must equal the lookup of the full footprint exactly — inside the caps' region,
    // at its 30° edge, on either side of it, with a rotation, at the pole, with the footprint too
    // large for the cap, with non-finite differentials, and with the other filters (which the
    // caps serve too).
    const EnvironmentMap map = test::env_noise_map(EnvLayout::latlong, 64, 26);
    ASSERT_NE(map.polar_cap(0), nullptr);
    const Mat3 rotation = rotation_xyz_degrees(10, 20, 30);
    std::mt19937 rng(27);
    std::uniform_real_distribution<float> u(0, 1);
    int compared = 0;
    for (int i = 0; i < 400; ++i) {
        const float colatitude = (i % 4 == 0 ? 30.0f : 40.0f * u(rng)) * 3.14159265f / 180;
        const float phi = 2 * 3.14159265f * u(rng), pole = i % 2 ? 1.0f : -1.0f;
        const Vec3 r{std::sin(colatitude) * std::cos(phi), pole * std::cos(colatitude),
                     std::sin(colatitude) * std::sin(phi)};
        Vec3 dx, dy;
        test::isotropic_differentials(r, 0.3f * u(rng) * u(rng), dx, dy);  // up to ~12 texels
        if (i % 50 == 7) dx.x = NAN;
        const Mat3& a = i % 3 == 0 ? rotation : Mat3{};
        LookupOptions options;
        if (i % 5 == 1) options.filter = TextureFilter::ewa;
        if (i % 5 == 3) options.filter = TextureFilter::trilinear;
        float direct, via_footprint;
        environment_lookup(map, r, dx, dy, EnvLookupOptions{options, a}, &direct);
        environment_lookup(map,
                           compute_env_footprint(map.layout(), map.texel_scale(), r, dx, dy, a),
                           options, &via_footprint);
        ASSERT_EQ(direct, via_footprint) << "lookup " << i;
        ++compared;
    }
    EXPECT_EQ(compared, 400);
}

TEST(EnvironmentMap, PolarCapFootprintsFourAtOnceAreTheScalarOnes) {
    // polar_cap_footprints4() against in_polar_cap_region(), polar_cap_footprint() and
    // single_probe_lod() ray by ray, bit for bit: near both poles, at the region's 30° edge, with
    // a rotation, footprints up to too large for the cap, non-finite differentials and directions,
    // directions at 2^±110.
    const EnvironmentMap map = test::env_noise_map(EnvLayout::latlong, 64, 26);
    ASSERT_NE(map.polar_cap(0), nullptr);
    std::mt19937 rng(29);
    std::uniform_real_distribution<float> u(0, 1);
    int valid = 0;
    for (const Mat3& rotation : {Mat3{}, rotation_xyz_degrees(10, 20, 30)}) {
        const IdentitySkippingRotation to_map(rotation);
        for (int first = 0; first < 2000; first += 4) {
            EnvRayDifferential rays[4];
            for (int lane = 0; lane < 4; ++lane) {
                const int i = first + lane;
                const float colatitude = (i % 7 == 0 ? 30.0f : 45.0f * u(rng)) * 3.14159265f / 180;
                const float phi = 2 * 3.14159265f * u(rng), pole = i % 2 ? 1.0f : -1.0f;
                EnvRayDifferential& ray = rays[lane];
                ray.direction = {std::sin(colatitude) * std::cos(phi), pole * std::cos(colatitude),
                                 std::sin(colatitude) * std::sin(phi)};
                test::isotropic_differentials(ray.direction, 0.5f * u(rng) * u(rng), ray.d_dx,
                                              ray.d_dy);
                if (i % 41 == 3) ray.d_dy.z = INFINITY;
                if (i % 43 == 5) ray.direction.x = NAN;
                if (i % 13 == 9) ray.direction = 0x1p-110f * ray.direction;
                if (i % 17 == 2) ray.direction = 0x1p101f * ray.direction;
            }
            PolarCapFootprints4 four;
            polar_cap_footprints4(map, rays, to_map, LookupOptions{}, four);
            for (int lane = 0; lane < 4; ++lane) {
                const auto& [r, dx, dy] = rays[lane];
                const Vec3 m = to_map(r);
                SCOPED_TRACE(testing::Message() << "ray " << first + lane << " (" << r.x << ", "
                                                << r.y << ", " << r.z << ")");
                EXPECT_EQ(four.region >> lane & 1, in_polar_cap_region(m));
                const bool spread = is_finite(dx) && is_finite(dy);
                const PolarCapFootprint cap =
                    is_finite(r) ? polar_cap_footprint(map, m, spread ? to_map(dx) : Vec3{},
                                                       spread ? to_map(dy) : Vec3{})
                                 : PolarCapFootprint{};
                if (!(four.valid >> lane & 1)) {
                    // Left to the scalar path: not the caps', or prepare()'s rare case.
                    const float big = max_abs_component(m);
                    EXPECT_TRUE(!(in_polar_cap_region(m) && cap.valid) || big < 0x1p-100f ||
                                big > 0x1p100f);
                    continue;
                }
                ++valid;
                ASSERT_TRUE(in_polar_cap_region(m) && cap.valid);
                const PolarCapFootprint f = four.footprint(map, lane);
                EXPECT_EQ(f.cap, cap.cap);
                EXPECT_EQ(f.coords.face, cap.coords.face);
                EXPECT_EQ(f.coords.s, cap.coords.s);
                EXPECT_EQ(f.coords.t, cap.coords.t);
                EXPECT_EQ(f.matrix.xx, cap.matrix.xx);
                EXPECT_EQ(f.matrix.xy, cap.matrix.xy);
                EXPECT_EQ(f.matrix.yy, cap.matrix.yy);
                EXPECT_EQ(four.lod[lane],
                          single_probe_lod(cap.matrix, LookupOptions{}, cap.cap->max_level()));
            }
        }
    }
    EXPECT_GT(valid, 2 * 2000 / 4);  // the rays within 30° of a pole, their footprints on the cap
}

TEST(EnvironmentMap, BatchedLookupsEqualSingleLookups) {
    // environment_lookup_batch computes each group's footprints and requests their texels before
    // filtering: the results must be bit-identical to one call per ray, in every layout, for every
    // footprint size (one probe, probe lines, polar caps, the pole itself), with a rotation, and
    // for batch sizes that leave a partial last group. The overloads without a rotation must equal
    // those given the identity.
    std::mt19937 rng(77);
    std::normal_distribution<float> normal;
    std::uniform_real_distribution<float> u(0, 1);
    const Mat3 rotation = rotation_xyz_degrees(20, -35, 50);
    for (EnvLayout layout : test::kAllEnvLayouts) {
        const EnvironmentMap map = test::env_noise_map(layout, 32, 5);
        std::vector<EnvRayDifferential> rays(73);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            EnvRayDifferential& ray = rays[i];
            ray.direction = i % 9 == 0 ? Vec3{0, i % 2 ? 1.0f : -1.0f, 0}
                                       : Vec3{normal(rng), normal(rng), normal(rng)};
            if (i % 3 == 1) ray.direction.y = 4 * std::copysign(1.0f, normal(rng));  // a polar cap
            const float angle = 0.002f * std::exp2(8 * u(rng));  // 0.1 … 30 texels
            test::isotropic_differentials(ray.direction, angle, ray.d_dx, ray.d_dy);
            ray.d_dx = ray.d_dx * (1 + 15 * u(rng));                     // anisotropy up to 16:1
            if (i % 11 == 4) ray.direction = 0x1p-110f * ray.direction;  // the careful paths
            if (i % 11 == 7) ray.direction = 0x1p101f * ray.direction;
            if (i % 13 == 6) ray.d_dy.x = std::nanf("");
        }
        // Rule B (whose near-isotropic lookups are one probe, decided four at a time on a cube
        // map), Rule A, and another filter.
        LookupOptions rule_a, trilinear;
        rule_a.probe_rule = ProbeRule::ext;
        trilinear.filter = TextureFilter::trilinear;
        for (const LookupOptions& options : {LookupOptions{}, rule_a, trilinear})
            for (const Mat3& a : {Mat3{}, rotation}) {
                std::vector<float> single(rays.size()), batched(rays.size());
                for (std::size_t i = 0; i < rays.size(); ++i)
                    environment_lookup(map, rays[i].direction, rays[i].d_dx, rays[i].d_dy,
                                       EnvLookupOptions{options, a}, &single[i]);
                environment_lookup_batch(map, rays, EnvLookupOptions{options, a}, batched.data());
                for (std::size_t i = 0; i < rays.size(); ++i)
                    EXPECT_EQ(single[i], batched[i]) << test::layout_name(layout) << " ray " << i;
            }
        std::vector<float> identity(rays.size()), unrotated(rays.size()), batched(rays.size());
        for (std::size_t i = 0; i < rays.size(); ++i) {
            environment_lookup(map, rays[i].direction, rays[i].d_dx, rays[i].d_dy,
                               EnvLookupOptions{LookupOptions{}, Mat3{}}, &identity[i]);
            environment_lookup(map, rays[i].direction, rays[i].d_dx, rays[i].d_dy, LookupOptions{},
                               &unrotated[i]);
        }
        environment_lookup_batch(map, rays, LookupOptions{}, batched.data());
        for (std::size_t i = 0; i < rays.size(); ++i) {
            EXPECT_EQ(identity[i], unrotated[i]) << test::layout_name(layout) << " ray " << i;
            EXPECT_EQ(identity[i], batched[i]) << test::layout_name(layout) << " ray " << i;
        }
    }
}

TEST(EnvironmentMap, FootprintBatchEqualsSingleLookups) {
    // environment_lookup_batch of computed footprints (form (b)) requests the texels of a group's
    // centre probes and cube lines before filtering: bit-identical to one call per footprint, in
    // every layout, for mirror and bumped, rough reflections and for ray differentials towards
    // the poles, of every size (one probe, lines on a face and across its edges, polar caps),
    // degenerate input, and a partial last group.
    std::mt19937 rng(78);
    std::normal_distribution<float> normal;
    std::uniform_real_distribution<float> u(0, 1);
    for (EnvLayout layout : test::kAllEnvLayouts) {
        const EnvironmentMap map = test::env_noise_map(layout, 32, 5);
        std::vector<EnvFootprint> footprints(83);
        for (std::size_t i = 0; i < footprints.size(); ++i) {
            ReflectionGeometry g;
            g.v = {normal(rng), normal(rng), normal(rng)};
            if (i % 9 == 0) g.v = {0.01f * normal(rng), 1, 0.01f * normal(rng)};  // near a pole
            g.n = {normal(rng), normal(rng), normal(rng)};
            if (dot(g.n, g.v) < 0) g.n = -g.n;
            const float scale = 0.003f * std::exp2(7 * u(rng));  // about 0.1 … 30 texels
            g.dv_dx = scale * Vec3{normal(rng), normal(rng), normal(rng)};
            g.dv_dy = scale * Vec3{normal(rng), normal(rng), normal(rng)};
            g.dn_dx = scale * (1 + 8 * u(rng)) * Vec3{normal(rng), normal(rng), normal(rng)};
            g.dn_dy = scale * Vec3{normal(rng), normal(rng), normal(rng)};
            if (i % 3 == 1) {  // bumped and rough
                g.bump_slope = {0.2f * normal(rng), 0.2f * normal(rng)};
                g.roughness = roughness_factor(Sym2{0.01f * u(rng), 0, 0.002f * u(rng)});
            }
            if (i % 13 == 6) g.dn_dy.x = std::nanf("");
            if (i % 17 == 8) g.v = {INFINITY, 0, 1};
            footprints[i] = compute_env_footprint(layout, map.texel_scale(), g);
            if (i % 2 == 0) {  // reflected towards a pole (a lat-long map's polar caps)
                const Vec3 r{normal(rng), 4 * std::copysign(1.0f, normal(rng)), normal(rng)};
                Vec3 dr_dx, dr_dy;
                test::isotropic_differentials(r, 0.02f * std::exp2(3.5f * u(rng)), dr_dx, dr_dy);
                if (i % 4 == 0) dr_dx = dr_dx * (1 + 7 * u(rng));  // a line
                footprints[i] = compute_env_footprint(layout, map.texel_scale(), r, dr_dx, dr_dy);
            }
        }
        LookupOptions rule_a, trilinear, near_isotropic;
        rule_a.probe_rule = ProbeRule::ext;
        trilinear.filter = TextureFilter::trilinear;
        near_isotropic.isotropic_ratio = 1.5f;  // one probe on the caps' slightly distorted texels
        for (const LookupOptions& options : {LookupOptions{}, rule_a, trilinear, near_isotropic}) {
            std::vector<float> single(footprints.size()), batched(footprints.size());
            for (std::size_t i = 0; i < footprints.size(); ++i)
                environment_lookup(map, footprints[i], options, &single[i]);
            environment_lookup_batch(map, footprints, options, batched.data());
            for (std::size_t i = 0; i < footprints.size(); ++i)
                EXPECT_EQ(std::bit_cast<std::uint32_t>(single[i]),
                          std::bit_cast<std::uint32_t>(batched[i]))
                    << test::layout_name(layout) << " footprint " << i;
        }
    }
}

TEST(EnvironmentMap, SphereAndParaboloidImagesAreChecked) {
    EXPECT_FALSE(EnvironmentMap::from_sphere(Image(8, 4, 3)).ok());
    EXPECT_FALSE(EnvironmentMap::from_sphere(Image()).ok());
    EXPECT_TRUE(EnvironmentMap::from_sphere(Image(8, 8, 3)).ok());
    EXPECT_FALSE(EnvironmentMap::from_paraboloid(Image(8, 8, 3), Image(8, 8, 1)).ok());
    EXPECT_FALSE(EnvironmentMap::from_paraboloid(Image(8, 8, 3), Image(16, 16, 3)).ok());
    EXPECT_FALSE(EnvironmentMap::from_paraboloid(Image(8, 4, 3), Image(8, 4, 3)).ok());
    EXPECT_TRUE(EnvironmentMap::from_paraboloid(Image(8, 8, 3), Image(8, 8, 3)).ok());
}

TEST(EnvironmentMap, BadFacesAreErrors) {
    std::array<Image, 6> faces;
    for (Image& f : faces) f = Image(8, 8, 3);
    faces[3] = Image(8, 4, 3);
    const Result<EnvironmentMap> r = EnvironmentMap::from_cube_faces(faces);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("-Y"), std::string::npos) << r.error().message;
    EXPECT_FALSE(EnvironmentMap::from_latlong(Image()).ok());
}

}  // namespace
}  // namespace footprint
