// apps/view_command.h — `footprint view`: a scene in a window, rendered by the GPU path.
//
//   footprint view SCENE [--filter MODE] [--size WxH] [--exposure E] [--frames N]
//                  [--screenshot FILE]
//
// SCENE is a scene file (.json) or a built-in demo scene, demo:NAME (apps/demo_scenes.h). The
// window (GLFW, OpenGL 4.5 core; --size, 1280x720 by default, resizable) shows the scene at one
// sample per pixel with the GPU path (gpu/gpu_renderer.h), linear radiance × 2^E shown
// sRGB-encoded. Controls:
//   left drag       orbit the camera around its look-at point
//   wheel / right drag   zoom (move towards or away from the look-at point)
//   1 … 5           point, trilinear, fa, fa-rough, hw-aniso;  M: the next mode
//   R               the scene's camera again;  Esc or Q: quit
// The HUD (top left) shows the mode, the GPU time per frame (timestamp queries, averaged over the
// last half second) and the resolution. --frames N closes the window after N frames (scripted
// runs, tests); --screenshot FILE then writes the last frame as `footprint render` would (sRGB
// PNG/JPEG/TIFF with the exposure, linear EXR/HDR), atomically.
//
// Returns 0, or 1 after one line "footprint: …" naming what failed (the scene, no display, no
// OpenGL 4.5 context, a scene the GPU path does not draw yet).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace footprint {

struct ViewCommandOptions {
    std::string scene;  // a file, or demo:NAME
    std::string filter = "fa-rough";
    std::string size;  // "WxH"; empty: 1280x720
    float exposure = 0;
    std::optional<int> frames;  // 1 … 1000000
    std::filesystem::path screenshot;
};
int run_view_command(const ViewCommandOptions& options);

}  // namespace footprint
