// bench/gpu_bench.h — `footprint-bench gpu`: GPU frame times of every mode on the demo scenes.
//
// Each demo scene (apps/demo_scenes.h), or each of --scenes (demo names or scene files, e.g.
// examples/scenes/showcase.json), is rendered at --size (1920x1080 by default) in every GPU
// mode (gpu/gpu_renderer.h): --warmup frames first, then --frames timed ones. A frame's time is
// its GPU time between two timestamp queries around its draw (not the read back); the median of
// the timed frames counts, and frames/s = 1000 / median ms. The wall time of the draw until
// glFinish returns is printed beside it: llvmpipe records timestamps before it rasterises, so
// there only the wall time is the frame's. Per scene the targets of the real-time
// path are checked: fa-rough ≥ 60 frames/s, and its frame time ≤ 2× hw-aniso's (the GPU's own
// anisotropic filtering, the peer in the same run). The device string is printed first: on a
// software rasteriser (llvmpipe) the figures only show that the path runs.
//
// --quality instead measures the images: per scene, the interior RMSE (render/renderer.h's
// interior_mask) against the CPU's reference mode at --reference-spp samples per pixel (1024) of
// CPU fa-rough and of every GPU mode — docs/performance.md's quality table. Its figures are the
// same on any GPU up to the bilinear weights' rounding.
#pragma once

#include <string>
#include <vector>

namespace footprint::bench {

struct GpuBenchOptions {
    std::string json_path;
    std::string size = "1920x1080";
    int frames = 20;
    int warmup = 3;
    std::vector<std::string> scenes;  // demo scene names or .json files; empty: every demo scene
    bool quality = false;
    int reference_spp = 1024;
};

int run_gpu_bench(const GpuBenchOptions& options);

}  // namespace footprint::bench
