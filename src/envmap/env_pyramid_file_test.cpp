// Tests of environment pyramid files (envmap/env_pyramid_file.h): every layout is saved and loaded
// as the same map, whose lookups are bit for bit the original's; other files are refused naming
// them; a failed save leaves nothing.
#include "envmap/env_pyramid_file.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "core/test_temp_dir.h"
#include "envmap/env_test_maps.h"
#include "image/image_io.h"

namespace footprint {
namespace {

// Random directions with ray differentials from a pixel's to a hundredth of the sphere.
std::vector<EnvRayDifferential> rays(int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> normal;
    std::uniform_real_distribution<float> scale(-9, -2);
    std::vector<EnvRayDifferential> all;
    for (int i = 0; i < count; ++i) {
        const Vec3 r = normalize(Vec3{normal(rng), normal(rng), normal(rng)});
        const float s = std::exp2(scale(rng));
        all.push_back({r, s * Vec3{normal(rng), normal(rng), normal(rng)},
                       0.3f * s * Vec3{normal(rng), normal(rng), normal(rng)}});
    }
    return all;
}

void expect_same_lookups(const EnvironmentMap& a, const EnvironmentMap& b, const char* what) {
    ASSERT_EQ(a.layout(), b.layout());
    ASSERT_EQ(a.face_count(), b.face_count());
    ASSERT_EQ(a.polar_cap(0) != nullptr, b.polar_cap(0) != nullptr) << what;
    for (const EnvRayDifferential& ray : rays(400, 3)) {
        for (TextureFilter filter :
             {TextureFilter::footprint_assembly, TextureFilter::trilinear, TextureFilter::ewa}) {
            EnvLookupOptions options;
            options.filter = filter;
            float want[3], got[3];
            environment_lookup(a, ray.direction, ray.d_dx, ray.d_dy, options, want);
            environment_lookup(b, ray.direction, ray.d_dx, ray.d_dy, options, got);
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(std::bit_cast<std::uint32_t>(got[c]),
                          std::bit_cast<std::uint32_t>(want[c]))
                    << what << " " << to_string(filter) << ": " << got[c] << " against " << want[c];
        }
        float want[3], got[3];
        environment_bilinear(a, ray.direction, 0, want);
        environment_bilinear(b, ray.direction, 0, got);
        for (int c = 0; c < 3; ++c) ASSERT_EQ(got[c], want[c]) << what;
    }
}

TEST(EnvPyramidFile, EveryLayoutRoundTripsWithBitIdenticalLookups) {
    test::TempDir dir;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> noise(0, 4);
    for (EnvLayout layout :
         {EnvLayout::latlong, EnvLayout::cube, EnvLayout::sphere, EnvLayout::paraboloid}) {
        const std::vector<Image> images = test::env_images(layout, 32, 3, [&](Vec3 r, float* out) {
            out[0] = 1 + r.x + 0.3f * noise(rng);
            out[1] = 2 + r.y;
            out[2] = noise(rng);
        });
        const EnvironmentMap map = test::env_map_from_images(layout, images);
        const auto file = dir / (std::string(env_layout_name(layout)) + ".exr");
        const Status saved = save_environment_pyramid(map, file, 16);
        ASSERT_TRUE(saved) << saved.error().message;
        EXPECT_TRUE(is_environment_pyramid_file(file));
        Result<EnvironmentMap> loaded = load_environment_pyramid(file);
        ASSERT_TRUE(loaded) << loaded.error().message;
        expect_same_lookups(map, *loaded, env_layout_name(layout));
    }
    // A lat-long map without polar caps stays without them.
    LatLongOptions no_caps;
    no_caps.polar_caps = false;
    const EnvironmentMap plain =
        EnvironmentMap::from_latlong(test::env_images(EnvLayout::latlong, 16, 3,
                                                      [](Vec3 r, float* out) {
                                                          out[0] = r.x, out[1] = r.y, out[2] = r.z;
                                                      })[0],
                                     no_caps)
            .value();
    ASSERT_TRUE(save_environment_pyramid(plain, dir / "plain.exr"));
    expect_same_lookups(plain, load_environment_pyramid(dir / "plain.exr").value(), "no caps");
}

TEST(EnvPyramidFile, OtherFilesAreRefusedNamingThemAndAFailedSaveLeavesNothing) {
    test::TempDir dir;
    ASSERT_TRUE(save_image(Image(16, 8, 3, 0.5f), dir / "sky.exr"));
    EXPECT_FALSE(is_environment_pyramid_file(dir / "sky.exr"));
    EXPECT_FALSE(is_environment_pyramid_file(dir / "missing.exr"));
    for (const char* name : {"sky.exr", "missing.exr"}) {
        Result<EnvironmentMap> map = load_environment_pyramid(dir / name);
        ASSERT_FALSE(map);
        EXPECT_NE(map.error().message.find(name), std::string::npos) << map.error().message;
    }
    EXPECT_NE(load_environment_pyramid(dir / "sky.exr")
                  .error()
                  .message.find("not an environment pyramid"),
              std::string::npos);
    const EnvironmentMap map = test::env_map(EnvLayout::cube, 8, [](Vec3 r) { return r.x; });
    EXPECT_FALSE(save_environment_pyramid(map, dir / "no" / "dir.exr"));
    EXPECT_FALSE(save_environment_pyramid(map, dir / "cube.png"));
    EXPECT_EQ(dir.entries(), 1);  // sky.exr alone
}

}  // namespace
}  // namespace footprint
