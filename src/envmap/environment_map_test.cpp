#include "envmap/environment_map.h"

#include <gtest/gtest.h>

#include <cmath>
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

// A footprint of angular radius `angle` (radians) around direction r, as ray differentials.
EnvFootprint footprint_around(const EnvironmentMap& map, Vec3 r, float angle) {
    r = r / std::sqrt(dot(r, r));
    Vec3 a = std::fabs(r.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    a = a - dot(a, r) * r;
    a = a / std::sqrt(dot(a, a));
    const Vec3 b = cross(r, a);
    return compute_env_footprint(map.layout(), map.texel_scale(), r, angle * a, angle * b);
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
                continue;  // poles: not yet
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
            texture_lookup(cube.face(a.coords.face), a.coords.s, a.coords.t,
                           make_footprint_ellipse(a.matrix), LookupOptions{}, &ca);
            texture_lookup(cube.face(b.coords.face), b.coords.s, b.coords.t,
                           make_footprint_ellipse(b.matrix), LookupOptions{}, &cb);
            confined += std::fabs(ca - cb);
            ++n;
        }
    seamless /= n;
    confined /= n;
    std::printf("mean |difference| across an edge: seamless %.4f, confined to a face %.4f\n",
                seamless, confined);
    // Measured 0.0031 vs 0.0231 (noise of σ = 0.29 per texel): the remaining difference is the
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
            texture_lookup(cube.face(a.coords.face), a.coords.s, a.coords.t, FootprintEllipse{},
                           LookupOptions{}, &ca);
            texture_lookup(cube.face(b.coords.face), b.coords.s, b.coords.t, FootprintEllipse{},
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
