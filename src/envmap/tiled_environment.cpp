// The environment lookups through tiles (tiled_environment.h): env_lookup_general.h's steps,
// compiled here for TiledEnvironment, apart from environment_map.cpp's in-memory instance (whose
// inlining a second instance in the same file could change).
#include "envmap/tiled_environment.h"

#include "envmap/env_lookup_general.h"

namespace footprint::detail {

TiledEnvShape tiled_env_shape(const EnvironmentMap& map, int tile_log2) {
    TiledEnvShape shape;
    shape.layout = map.layout();
    for (int f = 0; f < map.face_count(); ++f)
        shape.parts.push_back(tiled_shape(map.face(f), tile_log2));
    shape.polar_caps = map.polar_cap(0) != nullptr;
    for (int pole = 0; pole < 2 && shape.polar_caps; ++pole)
        shape.parts.push_back(tiled_shape(*map.polar_cap(pole), tile_log2));
    return shape;
}

void environment_lookup(const TiledEnvironment& map, const EnvFootprint& footprint,
                        const LookupOptions& options, float* out) {
    env_route::lookup(map, footprint, options, out);
}

void environment_lookup(const TiledEnvironment& map, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                        const EnvLookupOptions& options, float* out) {
    env_route::lookup(map, r, dr_dx, dr_dy, options, out);
}

void environment_bilinear(const TiledEnvironment& map, Vec3 r, int level, float* out) {
    env_route::bilinear(map, r, level, out);
}

}  // namespace footprint::detail
