// bench/texture_bench.h — `footprint-bench texture`: our filters against OpenImageIO's
// TextureSystem.
//
// On a 2048² float RGB mipmapped texture (bench_texture_content.h), for the footprint regimes
//   tiny      0.25 × 0.25 texels   (magnification)
//   moderate  4 × 4 texels
//   aniso32   1 × 32 texels
// (the texel-space images of one pixel step in x and in y), each lookup at a random position and
// orientation and scaled by a random factor 2^u, u ∈ [−½, ½] (±½ octave), it measures lookups per
// second with 1 and 2 threads for every filter of ours and, on the very same lookups, for
// OpenImageIO's TextureSystem::texture() with a default TextureOpt on a tiled, mipmapped .tx made
// by ImageBufAlgo::make_texture (what `maketx --wrap periodic` runs). On a subset it measures the
// RMS error of both against reference_lookup() (texture/reference_filter.h).
#pragma once

#include <string>
#include <vector>

namespace footprint::bench {

struct TextureBenchOptions {
    int texture_size = 2048;
    std::size_t lookups_per_regime = 200000;
    std::size_t error_subset = 1500;
    std::vector<int> thread_counts = {1, 2};
    std::vector<std::string> filters;  // empty: all
    std::vector<std::string> regimes;  // empty: all
    int tile_log2 = -1;                // -1: the library default
    int max_probes = -1;               // -1: the library default
    std::string probe_rule;            // "b" | "gaussian" | "ext" | "texram" | empty: default
    std::string lod_blend;             // "linear" | "variance" | empty: the library default
    float brilinear_band = 0.25f;      // LookupOptions::brilinear_band (its default)
    int rounds = 2;  // each rate is the best of this many timed passes (noise only slows)
    bool with_oiio = true;
    std::string json_path;  // empty: no JSON
    bool quiet = false;
};

int run_texture_bench(const TextureBenchOptions& options);

}  // namespace footprint::bench
