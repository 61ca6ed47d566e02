// envmap/polar_caps.h — (private to envmap) a lat-long map's polar caps: the two gnomonic faces
// (a cube's ±Y faces) that EnvironmentMap keeps beside a lat-long pyramid and filters footprints
// near the poles on (environment_map.h, "Lat-long polar caps", explains why). A footprint comes
// onto a cap from its map-space direction differentials (EnvFootprint::map_dr_dx …), so its
// anisotropy survives even where the lat-long footprint fell back to an isotropic one (§3.4).
#pragma once

#include <type_traits>
#include <utility>

#include "envmap/env_footprint.h"
#include "envmap/environment_map.h"
#include "image/image.h"
#include "texture/filters.h"
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
// lat-long footprint fell back to an isotropic one. `Cap` is the caps' texel source: a MipPyramid
// (an EnvironmentMap's) or TiledTexels (a TiledEnvironment's, tiled_environment.h).
template <class Cap>
struct PolarCapFootprintOn {
    bool valid = false;  // the caps filter it: centre within 30° of a pole, probes on the face
    const Cap* cap = nullptr;
    EnvCoords coords;  // on the cap (cube face 2 or 3)
    Sym2 matrix;       // K in the cap's level-0 texels
};
using PolarCapFootprint = PolarCapFootprintOn<MipPyramid>;
// The caps' texel source of a map type.
template <class Map>
using CapOf = std::remove_cvref_t<decltype(*std::declval<const Map&>().polar_cap(0))>;

// Explicitly instantiated (polar_caps.cpp) for EnvironmentMap and TiledEnvironment.
template <class Map>
PolarCapFootprintOn<CapOf<Map>> polar_cap_footprint(const Map& map, const EnvFootprint& footprint);
// The same for form (a) (a direction and its differentials, in map space; no roughness), without
// an EnvFootprint, for a direction the caller found in the caps' region (in_polar_cap_region()).
template <class Map>
PolarCapFootprintOn<CapOf<Map>> polar_cap_footprint(const Map& map, Vec3 map_direction,
                                                    Vec3 map_dr_dx, Vec3 map_dr_dy);

// Filters a valid cap footprint into out.
template <class Cap>
void polar_cap_filter(const PolarCapFootprintOn<Cap>& footprint, const LookupOptions& options,
                      float* out);

// polar_cap_footprint() (form (a)) for four rays at once on a lat-long map with caps, in
// structure-of-arrays form (math/float4.h), for the batch. Bit i of `region` is set where ray i's
// map direction A r lies in the caps' region (in_polar_cap_region()). Where bit i of `valid` is
// set, the caps take it (polar_cap_footprint() valid, r and its differentials as the single lookup
// passes them), and lane i holds exactly (bit for bit) that footprint's cap, coords and K, and
// `lod` its single_probe_lod() for `options`. A clear bit leaves the ray to the scalar functions.
struct PolarCapFootprints4 {
    int region = 0, valid = 0;
    int cap[4];  // 0: +Y, 1: −Y
    float s[4], t[4];
    float xx[4], xy[4], yy[4];
    float lod[4];

    PolarCapFootprint footprint(const EnvironmentMap& map, int i) const {
        return {true, map.polar_cap(cap[i]), {2 + cap[i], s[i], t[i]}, {xx[i], xy[i], yy[i]}};
    }
};
void polar_cap_footprints4(const EnvironmentMap& map, const EnvRayDifferential* rays,
                           const IdentitySkippingRotation& to_map, const LookupOptions& options,
                           PolarCapFootprints4& out);

// polar_cap_filter() for callers that request many lookups before reading any (the batch), given
// the footprint's single_probe_lod(): a lookup of one probe is requested into `probe`, a line of
// probes on the cap as request_footprint_assembly() requests it into `line`; any other lookup is
// filtered into out at once.
detail::Requested polar_cap_request(const PolarCapFootprint& footprint, float lod,
                                    const LookupOptions& options, float* out,
                                    detail::RequestedProbe& probe,
                                    detail::RequestedLine<detail::kRequestedLineProbes>& line);

}  // namespace footprint
