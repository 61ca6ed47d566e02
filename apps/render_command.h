// apps/render_command.h — `footprint render`: a scene file rendered with one filter mode.
//
//   footprint render SCENE.json --filter MODE [--spp N] [--threads N] [--exposure E] [--json]
//                    [--frames N] [--quiet] -o OUT.png|OUT.exr
//
// --frames N renders N frames along the scene's camera_path (scene/scene.h; an error without
// one) into OUT with the frame number before the extension: out.png → out_0000.png … (4 digits,
// more if N needs them).
//
// Returns the process exit status: 0, or 1 after one line "footprint: <what is wrong>" on stderr
// naming the file, key or value at fault (scene errors come from scene/scene_file.h and
// render/render_scene.h). The output path is checked before any work, and the image is written
// atomically (image/image_io.h's save_image). PNG/JPEG/TIFF outputs are sRGB-encoded after
// multiplying by 2^exposure; EXR/HDR outputs hold the linear radiance as rendered (exposure is not
// applied: HDR stays HDR). A progress bar on stderr when it is a terminal and not --quiet; --json
// prints one summary line to stdout:
//   {"scene": …, "output": …, "filter": …, "spp": …, "threads": …, "width": …, "height": …,
//    "pixels": …, "seconds": …, "lookups": …, "frames": …}   (pixels, seconds, lookups: all frames)
#pragma once

#include <filesystem>
#include <string>

namespace footprint {

struct RenderCommandOptions {
    std::filesystem::path scene;
    std::filesystem::path output;
    std::string filter = "fa-rough";  // render/renderer.h's FilterMode names
    int spp = 0;                      // 0: 1, or 64 for the reference
    int threads = 0;                  // 0: all cores
    float exposure = 0;               // stops, for integer outputs
    int frames = 0;                   // 0: one image (the scene's camera); N ≥ 1: a sequence
    bool json = false;
    bool quiet = false;
};
int run_render_command(const RenderCommandOptions& options);

// The file of frame `frame` of a sequence of `frame_count` written to `output`
// (out.png → out_0007.png).
std::filesystem::path frame_file(const std::filesystem::path& output, int frame, int frame_count);

}  // namespace footprint
