// apps/render_command.h — `footprint render`: a scene rendered with one filter mode.
//
//   footprint render SCENE -o OUT [--filter MODE] [--spp N] [--seed N] [--size WIDTH]
//                    [--frames N|A-B/N] [--tile I/N] [--threads N] [--exposure E] [--device
//                    cpu|gpu]
//                    [--texture-memory-mb N] [--texture-cache-dir DIR] [--json] [--quiet]
//
// --device gpu renders on the GPU path (gpu/gpu_renderer.h), headless through EGL, one sample per
// pixel: MODE is then one of point, trilinear, fa, fa-rough, hw-aniso, --spp must be 1 and
// --seed and --threads do not apply. The outputs, --frames and --size are the same; a scene
// the GPU path does not draw yet, or a machine without an EGL device, is refused with an error.
//
// SCENE is a scene file (.json) or a built-in demo scene's name (apps/command_util.h's
// resolve_scene). MODE is one of the filter vocabulary's render filters (apps/cli_options.h).
// --size WIDTH renders WIDTH pixels wide, the height following the scene's aspect ratio (its image
// width and height). --seed N chooses the sample sequences (render/renderer.h's
// RenderOptions::seed): the same seed gives the same image, different seeds independent samples.
// --frames N renders N frames along the scene's camera_path (scene/scene.h; an error without one)
// into OUT with the frame number before the extension: out.png → out_0000.png … (4 digits, more if
// N needs them); --frames A-B/N only frames A … B of them, into the same files.
// --tile I/N renders the I-th of N bands of rows (tile_rows) into OUT, which must be .exr: the
// band's pixels as the whole image has them, its place in the image as the file's data window.
// `footprint merge` (merge_command.h) assembles the bands bit for bit into the whole image.
//
// Every map of the scene is read through one TextureSystem (texture_system.h): files that store
// MIP levels (maketx output) tile by tile through a cache of at most --texture-memory-mb MiB of
// texels (default 1024), others built in memory or, with --texture-cache-dir, once into that
// folder and then read like stored files.
//
// Returns the process exit status: 0, or 1 after one line "footprint: <what is wrong>" on stderr
// naming the file, key or value at fault (scene errors come from scene/scene_file.h and
// render/render_scene.h). The output path is checked before any work, and the image is written
// atomically (image/image_io.h's save_image); a sequence that fails part way removes the frames
// it had written. PNG/JPEG/TIFF outputs are sRGB-encoded after
// multiplying by 2^exposure; EXR/HDR outputs hold the linear radiance as rendered (exposure is not
// applied: HDR stays HDR). A progress bar on stderr when it is a terminal and not --quiet. When
// done, one line on stderr (not with --quiet or --json):
//   footprint: wrote OUT (WxH, MODE, N spp, T s)
// and a warning line when samples were not finite (dropped: a pixel is the mean of its finite
// samples, 0 if it has none). --json prints one summary line to stdout instead:
//   {"scene": …, "output": …, "filter": …, "spp": …, "seed": …, "threads": …, "width": …,
//    "height": …, "pixels": …, "seconds": …, "lookups": …, "non_finite_samples": …,
//    "non_finite_pixels": …, "frames": …, "texture_tiles_loaded": …, "texture_peak_bytes": …}
//   (pixels, seconds, lookups, non-finite: all frames; the texture system's stats() at the end)
//   with --device gpu: {"scene", "output", "device": "gpu", "gpu": the renderer's name, "filter",
//    "spp": 1, "width", "height", "pixels", "seconds", "gpu_ms", "frames"} (gpu_ms: the GPU time
//    of all frames, timer queries; seconds: the wall time of rendering and reading back)
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "core/result.h"
#include "render/renderer.h"

namespace footprint {

struct RenderCommandOptions {
    std::filesystem::path scene;
    std::filesystem::path output;
    std::string filter = "fa-rough";  // apps/cli_options.h's render filters
    std::optional<int> spp;           // 1 … 65536; not given: 1, or 64 for the reference
    std::optional<int> width;         // --size: 16 … 16384; not given: the scene's own size
    std::uint32_t seed = 1;
    int threads = 0;            // 0: all cores
    float exposure = 0;         // stops, for integer outputs
    std::optional<int> frames;  // 1 … 100000: a sequence; not given: one image (scene camera)
    // --frames A-B/N: frames A … B (0 ≤ A ≤ B < N, the files' numbers) of the sequence of N =
    // `frames`, each written to the file the whole sequence writes it to (one task of a farm).
    std::optional<std::pair<int, int>> frame_range;
    // --tile I/N: the I-th (1 ≤ I ≤ N) of N horizontal bands (tile_rows()), written as an OpenEXR
    // band of the full image, which `footprint merge` assembles.
    std::optional<std::pair<int, int>> tile;
    std::string device = "cpu";               // "cpu" or "gpu"
    int texture_memory_mb = 1024;             // the texture system's max_memory_mb, ≥ 1
    std::filesystem::path texture_cache_dir;  // its cache_dir; empty: built pyramids in memory
    bool json = false;
    bool quiet = false;
};
int run_render_command(const RenderCommandOptions& options);

// The command line's "--frames N" or "--frames A-B/N" into options.frames and .frame_range, and
// "--tile I/N" into options.tile; an Error quotes the text and says what it takes. The numbers'
// ranges are checked by run_render_command.
Status parse_frames_option(std::string_view text, RenderCommandOptions& options);
Status parse_tile_option(std::string_view text, RenderCommandOptions& options);

// The rows of band i (1 … n) of an image `height` rows tall: [⌊(i − 1)·H/n⌋, ⌊i·H/n⌋), so that the
// n bands cover every row once and differ in height by at most one.
RowBand tile_rows(int i, int n, int height);

// The file of frame `frame` of a sequence of `frame_count` written to `output`
// (out.png → out_0007.png).
std::filesystem::path frame_file(const std::filesystem::path& output, int frame, int frame_count);

}  // namespace footprint
