// envmap/polar_caps.h — (private to envmap) a lat-long map's polar caps: the two gnomonic faces
// (a cube's ±Y faces) that EnvironmentMap keeps beside a lat-long pyramid and filters footprints
// near the poles on (environment_map.h, "Lat-long polar caps", explains why). A footprint comes
// onto a cap from its map-space direction differentials (EnvFootprint::map_dr_dx …), so its
// anisotropy survives even where the lat-long footprint fell back to an isotropic one (§3.4).
#pragma once

#include "envmap/env_footprint.h"
#include "envmap/environment_map.h"
#include "image/image.h"
#include "texture/texture_lookup.h"

namespace footprint {

// Cap face size for a lat-long map of height H: ⌈resolution · 2H/π⌉ (a cap of n texels has n/2
// texels per radian at its centre, the lat-long map H/π).
int polar_cap_size(int latlong_height, float resolution);

// The cap face (2: +Y, 3: −Y) of `map` (a lat-long map whose level 0 is built), `size` texels
// wide: each texel the average of the map's bilinear reconstruction over it.
Image polar_cap_image(const EnvironmentMap& map, int face, int size);

// Whether a lookup in map-space direction r is one for a polar cap: r within 30° of a pole.
bool in_polar_cap_region(Vec3 r);

// A footprint carried onto the cap of its pole: K on the cap from the footprint's map-space
// direction differentials (EnvFootprint::map_dr_dx …), so its anisotropy survives even where the
// lat-long footprint fell back to an isotropic one.
struct PolarCapFootprint {
    bool valid = false;  // the caps filter it: centre within 30° of a pole, probes on the face
    const MipPyramid* cap = nullptr;
    EnvCoords coords;  // on the cap (cube face 2 or 3)
    Sym2 matrix;       // K in the cap's level-0 texels
};
PolarCapFootprint polar_cap_footprint(const EnvironmentMap& map, const EnvFootprint& footprint);
// The same for form (a) (a direction and its differentials, in map space; no roughness), without
// an EnvFootprint, for a direction the caller found in the caps' region (in_polar_cap_region()).
PolarCapFootprint polar_cap_footprint(const EnvironmentMap& map, Vec3 map_direction, Vec3 map_dr_dx,
                                      Vec3 map_dr_dy);

// Filters a valid cap footprint into out.
void polar_cap_filter(const PolarCapFootprint& footprint, const LookupOptions& options, float* out);

}  // namespace footprint
