// bench/pyramid_bench.h — `footprint-bench pyramid`: how fast pyramids build, and which memory
// layout makes lookups fastest.
//
// Build: a size² RGBA float image (default 4096²), box and tent downsampling, with 1 and 2 threads
// (oneTBB global_control). Layout: footprint-assembly and trilinear lookups/s (1 thread) at the
// texture benchmark's three regimes on a 2048² RGB texture stored row-major (tile_log2 = 0) and in
// 2×2, 4×4 and 8×8 tiles; the library default is the fastest measured here.
#pragma once

#include <string>

namespace footprint::bench {

struct PyramidBenchOptions {
    int build_size = 4096;
    std::string json_path;
    bool quiet = false;
};

int run_pyramid_bench(const PyramidBenchOptions& options);

}  // namespace footprint::bench
