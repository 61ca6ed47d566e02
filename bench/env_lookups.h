// bench/env_lookups.h — the environment and the lookups the environment benchmarks share
// (`footprint-bench env`, env_bench.h; the instruction counts of bench/env-instructions.sh).
//
// The environment is a procedural function of direction with content at every scale (noise
// octaves, hard-edged cells, a grating near the lat-long Nyquist rate), sampled at texel centres.
// A regime is a footprint shape in lat-long texels (pole_band: on the sphere) and a latitude band;
// a lookup puts it at a random position and orientation, scaled by 2^u, u ∈ [−½, ½], as a
// direction with ray differentials (environment_lookup's form (a)).
#pragma once

#include <cstddef>
#include <vector>

#include "envmap/environment_map.h"
#include "image/image.h"

namespace footprint::bench {

using EnvLookup = EnvRayDifferential;  // the library's batch element

struct EnvRegime {
    const char* name;
    float major,
        minor;  // lat-long texel lengths of the pixel-step images (pole_band: on the sphere)
    double lat_min, lat_max;  // |latitude| range, degrees
    bool isotropic_on_sphere;
};
inline constexpr EnvRegime kEnvRegimes[] = {{"tiny", 0.25f, 0.25f, 0, 60, false},
                                            {"moderate", 4, 4, 0, 60, false},
                                            {"aniso32", 32, 1, 0, 60, false},
                                            {"pole_band", 4, 4, 60, 85, true}};

// The environment as a width × height float RGB lat-long image (texel centres).
Image make_latlong_image(int width, int height);

// n random lookups of a regime, with footprints sized in texels of a width × height lat-long map.
// Lat-long regimes: the footprint's texel-space columns D = R(α)·diag(major, minor)·2^u are mapped
// to ray differentials through the inverse map, dr = ∂r/∂s·D_s/W + ∂r/∂t·D_t/H, so
// compute_env_footprint recovers D (to first order). pole_band: ∂r/∂x, ∂r/∂y orthogonal tangent
// vectors of length major·(π/H)·2^u.
std::vector<EnvLookup> make_env_lookups(const EnvRegime& regime, std::size_t n, int width,
                                        int height, unsigned seed);

}  // namespace footprint::bench
