// README.md's snippet of the GPU path, as written between its markers, around it the scene it
// renders. It needs an EGL device with OpenGL 4.5 (Mesa's llvmpipe is one): where
// GpuDevice::headless() finds none, the program says so and only its compilation was checked.
// Built and run against the installed package by cmake/test_snippets.cmake; check_snippets.py
// holds the README to this region.
#include <footprint/footprint.h>

#include <cstdio>

#include "support.h"

// The snippet's own #include line stands inside the function below: the header was included
// above, so there it adds nothing (#pragma once).

namespace {

using namespace footprint;

// A lit, textured sphere in front of a lat-long sky, small enough for llvmpipe.
const char* const kScene = R"({
    "image": {"width": 48, "height": 27},
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
    "environment": {"file": "sky.exr"},
    "lights": [{"type": "directional", "direction": [0, -1, -1]}],
    "objects": [{"shape": "sphere", "radius": 0.8,
                 "material": {"base_color": "bricks.png",
                              "bump": {"normal_map": "bricks_normal.png", "strength": 0.5}}}]
})";

int gpu() {
    if (!GpuDevice::headless()) {
        std::printf("no EGL device with OpenGL 4.5: the GPU snippet was compiled, not run\n");
        return 0;
    }
    Result<SceneDesc> desc = parse_scene(kScene, "snippet-scene.json");
    snippets::check(desc.ok(), "the GPU snippet's scene: " + (desc ? "" : desc.error().message));
    // clang-format off
    // snippet begin: README.md
    #include <footprint/gpu/gpu_renderer.h>

    Result<GpuDevice> device = GpuDevice::headless();              // EGL: llvmpipe, or any vendor's GPU
    Result<RenderScene> scene = prepare_render_scene(*desc);        // the CPU's pyramids, uploaded as built
    Result<GpuRenderer> gpu = GpuRenderer::create(*scene);
    GpuFrameStats stats;
    Result<Image> frame = gpu->render(GpuRenderOptions{GpuFilter::fa_rough}, &stats);  // or hw_aniso, the GPU's own
    // snippet end
    // clang-format on
    snippets::check(device.ok() && scene.ok() && gpu.ok(), "README: the GPU renderer");
    snippets::check(frame.ok() && frame->width == 48 && frame->height == 27,
                    "README: the GPU frame");
    return 0;
}

}  // namespace

int main() {
    snippets::write_files();
    if (gpu() != 0) return 1;
    std::printf("README.md's GPU snippet ran\n");
    return 0;
}
