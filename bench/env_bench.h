// bench/env_bench.h — `footprint-bench env`: our environment-map lookups against OpenImageIO's
// TextureSystem::environment().
//
// The environment is a procedural function of direction with content at every scale (noise
// octaves, hard-edged cells, a grating near the lat-long Nyquist rate), sampled at texel centres
// into a 2048×1024 float RGB lat-long map; the cube map (1024² faces) is that map resampled by
// convert_environment (envmap/env_convert.h). Lookups are a direction r with ray differentials
// ∂r/∂x, ∂r/∂y, built so that the footprint in lat-long texels has the regime's axes:
//   tiny      0.25 × 0.25 lat-long texels   latitudes within ±60°
//   moderate  4 × 4                          latitudes within ±60°
//   aniso32   32 × 1                         latitudes within ±60°
//   pole_band isotropic on the sphere, 4 lat-long texel heights (4π/1024 rad) across, latitudes
//             60°–85° north or south (hence 4 × 8 up to 4 × 46 texels in the lat-long map)
// each at a random position and orientation and scaled by 2^u, u ∈ [−½, ½]. For every regime it
// measures lookups per second with 1 and 2 threads for our lat-long and cube lookups
// (environment_lookup form (a): the footprint computed from the ray differentials inside the call,
// as in OpenImageIO) and, on the very same lookups, for OpenImageIO's environment() with a default
// TextureOpt on a tiled, mipmapped .tx made by ImageBufAlgo::make_texture(MakeTxEnvLatl) (what
// `maketx --envlatl` runs). On a subset it measures the RMS error of all three against
// environment_reference() (envmap/env_reference.h) on the lat-long map.
#pragma once

#include <string>
#include <vector>

namespace footprint::bench {

struct EnvBenchOptions {
    int latlong_width = 2048;  // the height is half of it
    int cube_size = 1024;
    std::size_t lookups_per_regime = 200000;
    std::size_t error_subset = 1500;
    std::vector<int> thread_counts = {1, 2};
    std::vector<std::string> regimes;  // empty: all (tiny moderate aniso32 pole_band)
    // Also time environment_lookup() and environment_lookup_batch() of footprints computed before
    // the timing (compute_env_footprint() of the same rays): rows "<layout>-footprint" and
    // "<layout>-footprint-batch", without a peer (OpenImageIO takes no footprint).
    bool footprints = false;
    bool with_oiio = true;
    std::string json_path;                // empty: no JSON
    float isotropic_ratio = 1;            // LookupOptions::isotropic_ratio of our lookups
    std::string probe_rule = "gaussian";  // LookupOptions::probe_rule: "gaussian" or "b" (Rule B)
    std::string lod_blend = "automatic";  // LookupOptions::lod_blend: automatic, linear, variance
    int rounds = 3;  // each rate is the best of this many timed passes (noise only slows)
    bool quiet = false;
};

int run_env_bench(const EnvBenchOptions& options);

}  // namespace footprint::bench
