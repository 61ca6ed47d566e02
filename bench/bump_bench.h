// bench/bump_bench.h — `footprint-bench bump`: building bump/roughness pyramids and filtered bump
// lookups.
//
// Build: a size² height map (default 4096², procedural, 1 channel) → slope map
// (slopes_from_height_map) → BumpPyramid (5 moment channels computed in double), timed separately,
// with 1 and 2 threads (oneTBB global_control), best of 3.
// Lookups: bump_lookup() on a 2048² bump map for nearest, bilinear, trilinear, footprint assembly
// and EWA at the texture benchmark's regimes (bench_lookups.h), 1 and 2 threads; beside each, the
// rate of a plain RGB texture_lookup() on the same footprints, as the baseline in the same run.
#pragma once

#include <string>

namespace footprint::bench {

struct BumpBenchOptions {
    int build_size = 4096;
    int lookup_size = 2048;
    std::size_t lookups_per_regime = 200000;
    std::string json_path;
    bool quiet = false;
};

int run_bump_bench(const BumpBenchOptions& options);

}  // namespace footprint::bench
