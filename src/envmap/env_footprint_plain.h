// envmap/env_footprint_plain.h — internal: form (a)'s footprint without its rare cases, one ray or
// four at a time, for the lookups' fast path and the batches (environment_map.cpp,
// environment_map_batch.cpp). Not part of the API: users call compute_env_footprint().
#pragma once

#include "envmap/env_footprint.h"
#include "math/mat3.h"

namespace footprint {

// Form (a)'s common case in one pass, for the lookups' fast path: a lat-long or cube map, r
// usable and within 2^±100, its differentials and D finite and, on a lat-long map, the footprint
// clear of the poles. There the footprint is D Dᵀ and nothing else, and this gives exactly (bit for
// bit) the fields compute_env_footprint() sets, without its handling of the rare cases. Returns
// false everywhere else (then `out` is unspecified and compute_env_footprint() decides).
struct PlainEnvFootprint {
    Vec3 reflected, map_direction, map_dr_dx, map_dr_dy;
    EnvCoords coords;
    Vec2 d_dx, d_dy;
    Sym2 matrix;                // K = D Dᵀ
    EnvFootprint full() const;  // compute_env_footprint()'s result
};
// `to_map` is the rotation A, made once per call or per batch by the caller.
bool plain_env_footprint(EnvLayout layout, Vec2 texel_scale, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                         const IdentitySkippingRotation& to_map, PlainEnvFootprint& out);

// plain_env_footprint() on a cube or lat-long map for four rays at once, in structure-of-arrays
// form (math/float4.h), for the batch: where bit i of `plain` is set, lane i holds exactly (bit
// for bit) the coords, K and map direction that plain_env_footprint(layout, …) sets for rays[i].
// A clear bit leaves the ray to the scalar functions: exactly the rays that plain_env_footprint()
// refuses (both are one template over the lane type).
struct PlainEnvFootprints4 {
    int plain = 0;
    int face[4];
    float s[4], t[4];                    // coords
    float xx[4], xy[4], yy[4];           // K = D Dᵀ
    float map_x[4], map_y[4], map_z[4];  // A r

    EnvCoords coords(int i) const { return {face[i], s[i], t[i]}; }
    Sym2 matrix(int i) const { return {xx[i], xy[i], yy[i]}; }
    Vec3 map_direction(int i) const { return {map_x[i], map_y[i], map_z[i]}; }
};
void plain_env_footprints4(EnvLayout layout, Vec2 texel_scale, const EnvRayDifferential* rays,
                           const IdentitySkippingRotation& to_map, PlainEnvFootprints4& out);

}  // namespace footprint
