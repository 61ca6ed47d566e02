// Tests of environment lookups through tiles (envmap/tiled_environment.h): on every layout, with
// tiles far smaller than a face, footprint assembly returns bit for bit what the map in memory
// returns — both forms, every footprint size from a point to a hemisphere, the lat-long poles and
// caps, cube edges and corners, the sphere map's rim — and so do point samples; the other filters
// too, away from a cube face's edge. Every texel read comes through the tiles.
#include "envmap/tiled_environment.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>

#include "envmap/env_test_maps.h"
#include "texture/test_pyramid_tiles.h"

namespace footprint {
namespace {

// A map's parts (faces, then polar caps) as tiles of 2^tile_log2 texels, and the TiledEnvironment
// that reads them.
struct TiledCopy {
    detail::TiledEnvShape shape;
    std::vector<std::unique_ptr<test::PyramidTiles>> tiles;
    std::array<detail::TiledEnvironment::Part, detail::TiledEnvironment::kMaxParts> sources{};

    TiledCopy(const EnvironmentMap& map, int tile_log2)
        : shape(detail::tiled_env_shape(map, tile_log2)) {
        for (int f = 0; f < map.face_count(); ++f)
            tiles.push_back(std::make_unique<test::PyramidTiles>(map.face(f), tile_log2));
        for (int pole = 0; pole < 2 && map.polar_cap(pole); ++pole)
            tiles.push_back(std::make_unique<test::PyramidTiles>(*map.polar_cap(pole), tile_log2));
        for (std::size_t i = 0; i < tiles.size(); ++i) sources[i] = {tiles[i].get(), nullptr};
    }
    std::size_t tiles_made() const {
        std::size_t n = 0;
        for (const auto& t : tiles) n += t->tiles_made();
        return n;
    }
};

EnvironmentMap noise_map(EnvLayout layout, int size) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> noise(0, 4);
    return test::env_map_from_images(layout,
                                     test::env_images(layout, size, 3, [&](Vec3 r, float* out) {
                                         out[0] = 1 + r.x + noise(rng);
                                         out[1] = 2 + r.y;
                                         out[2] = noise(rng);
                                     }));
}

// Directions of every kind: anywhere, near the poles (±y), near a cube edge or corner, and near
// the sphere map's rim (−z); ray differentials from a hundredth of a texel to a hemisphere, up to
// 64:1 anisotropic.
std::vector<EnvRayDifferential> rays(int count) {
    std::mt19937 rng(3);
    std::normal_distribution<float> normal;
    std::uniform_real_distribution<float> scale(-12, 0), aniso(0, 6);
    std::uniform_int_distribution<int> kind(0, 3);
    std::vector<EnvRayDifferential> all;
    for (int i = 0; i < count; ++i) {
        Vec3 r{normal(rng), normal(rng), normal(rng)};
        switch (kind(rng)) {
            case 1:
                r = Vec3{0.2f * r.x, r.y > 0 ? 1.0f : -1.0f, 0.2f * r.z};
                break;  // a pole
            case 2:
                r = Vec3{r.x > 0 ? 1.0f : -1.0f, r.y > 0 ? 1.0f : -1.0f, 0.1f * r.z};
                break;
            case 3:
                r = Vec3{0.3f * r.x, 0.3f * r.y, -1.0f};
                break;  // the sphere map's rim
            default:
                break;
        }
        r = normalize(r);
        const float s = std::exp2(scale(rng));
        const Vec3 dx = s * Vec3{normal(rng), normal(rng), normal(rng)};
        const Vec3 dy = std::exp2(-aniso(rng)) * s * Vec3{normal(rng), normal(rng), normal(rng)};
        all.push_back({r, dx, dy});
    }
    return all;
}

void expect_bits(const float* got, const float* want, int channels, const std::string& what) {
    for (int c = 0; c < channels; ++c)
        ASSERT_EQ(std::bit_cast<std::uint32_t>(got[c]), std::bit_cast<std::uint32_t>(want[c]))
            << what << " channel " << c << ": " << got[c] << " through tiles, " << want[c]
            << " in memory";
}

TEST(TiledEnvironment, FootprintAssemblyIsBitForBitTheMapInMemoryOnEveryLayout) {
    for (EnvLayout layout :
         {EnvLayout::latlong, EnvLayout::cube, EnvLayout::sphere, EnvLayout::paraboloid}) {
        const EnvironmentMap map = noise_map(layout, 48);
        const TiledCopy copy(map, 3);  // 8² tiles: most lines cross several
        const std::string name = env_layout_name(layout);
        int i = 0;
        for (const EnvRayDifferential& ray : rays(3000)) {
            const std::string what = name + " ray " + std::to_string(i++);
            const detail::TiledEnvironment tiled(copy.shape, copy.sources);
            EnvLookupOptions options;
            float want[3], got[3];
            environment_lookup(map, ray.direction, ray.d_dx, ray.d_dy, options, want);
            detail::environment_lookup(tiled, ray.direction, ray.d_dx, ray.d_dy, options, got);
            expect_bits(got, want, 3, what + " form (a)");
            // Form (b), with a rough surface: the roughness term and its polar-cap carry-over.
            ReflectionGeometry g;
            g.v = -ray.direction;
            g.n = normalize(Vec3{0.1f, 0.2f, 1.0f} - ray.direction);
            g.dn_dx = 40.0f * ray.d_dx;
            g.dn_dy = 40.0f * ray.d_dy;
            g.roughness = {0.02f * static_cast<float>(i % 7), 0.01f, 0.015f};
            const EnvFootprint f = compute_env_footprint(layout, map.texel_scale(), g);
            environment_lookup(map, f, options, want);
            detail::environment_lookup(tiled, f, options, got);
            expect_bits(got, want, 3, what + " form (b)");
            for (int level : {0, 2}) {
                environment_bilinear(map, ray.direction, level, want);
                detail::environment_bilinear(tiled, ray.direction, level, got);
                expect_bits(got, want, 3, what + " bilinear level " + std::to_string(level));
            }
        }
        // The lookups read every face (and cap) through tiles, and not each whole.
        EXPECT_GT(copy.tiles_made(), 6u) << name;
    }
}

TEST(TiledEnvironment, OtherFiltersAreTheMapInMemoryAwayFromCubeEdges) {
    for (EnvLayout layout :
         {EnvLayout::latlong, EnvLayout::cube, EnvLayout::sphere, EnvLayout::paraboloid}) {
        const EnvironmentMap map = noise_map(layout, 32);
        const TiledCopy copy(map, 4);
        for (const EnvRayDifferential& ray : rays(1000)) {
            if (layout == EnvLayout::cube) {  // a face's interior: its border is not read
                const EnvCoords c = env_coords(layout, ray.direction);
                if (std::min({c.s, c.t, 1 - c.s, 1 - c.t}) < 0.25f ||
                    dot(ray.d_dx, ray.d_dx) + dot(ray.d_dy, ray.d_dy) > 1e-3f)
                    continue;
            }
            const detail::TiledEnvironment tiled(copy.shape, copy.sources);
            for (TextureFilter filter : {TextureFilter::trilinear, TextureFilter::ewa,
                                         TextureFilter::bilinear, TextureFilter::nearest}) {
                EnvLookupOptions options;
                options.filter = filter;
                float want[3], got[3];
                environment_lookup(map, ray.direction, ray.d_dx, ray.d_dy, options, want);
                detail::environment_lookup(tiled, ray.direction, ray.d_dx, ray.d_dy, options, got);
                expect_bits(got, want, 3,
                            std::string(env_layout_name(layout)) + " " + to_string(filter));
            }
        }
    }
}

}  // namespace
}  // namespace footprint
