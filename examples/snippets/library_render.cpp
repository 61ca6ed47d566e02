// docs/library.md's snippets of scenes and rendering, the renderer's maps, the GPU path and
// footprint behind OpenImageIO's TextureSystem, each as written between its markers, around them
// the declarations they take from the text. The scene is examples/scenes/quickstart.json, read
// from the repository (its maps are in assets/). The GPU snippet needs an EGL device with OpenGL
// 4.5 (Mesa's llvmpipe is one): where GpuDevice::headless() finds none, the program says so and
// only its compilation was checked. Built and run against the installed package by
// cmake/test_snippets.cmake; check_snippets.py holds docs/library.md to these regions.
#include <footprint/footprint.h>
#include <footprint/oiio/texture_system.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>

#include "support.h"

// The GPU snippet's own #include lines stand inside a function below: the headers were included
// above, so there they add nothing (#pragma once).

namespace {

using namespace footprint;
using snippets::check;

// What a program does with an error.
int fail(const std::string& message) {
    std::fprintf(stderr, "%s\n", message.c_str());
    return 1;
}

int scenes() {
    // clang-format off
    // snippet begin: docs/library.md
    Result<SceneDesc> desc = load_scene_file("examples/scenes/quickstart.json");
    Result<RenderScene> scene = prepare_render_scene(*desc);   // loads images and meshes, builds pyramids
    RenderOptions options;                                      // fa-rough, 1 spp, all cores
    RenderStats stats;
    Image image = render(*scene, options, &stats);
    // snippet end
    // clang-format on
    check(desc.ok() && scene.ok(), "docs/library.md: the scene");
    check(image.width == 640 && image.height == 360 && stats.non_finite_pixels == 0,
          "docs/library.md: the render");
    return 0;
}

int renderer_maps() {
    Result<SceneDesc> desc = load_scene_file("examples/scenes/quickstart.json");
    check(desc.ok(), "examples/scenes/quickstart.json");
    TextureSystemOptions options;
    options.max_memory_mb = 64;
    // clang-format off
    // snippet begin: docs/library.md
    Result<std::unique_ptr<TextureSystem>> made = TextureSystem::create(options);
    if (!made) return fail(made.error().message);
    std::shared_ptr<TextureSystem> textures = std::move(*made);
    Result<RenderScene> scene = prepare_render_scene(*desc, textures);
    Image image = render(*scene, RenderOptions{});
    if (Status s = scene->take_texture_errors(); !s) std::fprintf(stderr, "%s\n", s.error().message.c_str());
    // snippet end
    // clang-format on
    check(scene.ok() && image.width == 640 && scene->take_texture_errors().ok(),
          "docs/library.md: the renderer's maps");
    return 0;
}

int gpu() {
    if (!GpuDevice::headless()) {
        std::printf("no EGL device with OpenGL 4.5: the GPU snippet was compiled, not run\n");
        return 0;
    }
    Result<SceneDesc> desc = load_scene_file("examples/scenes/quickstart.json");
    check(desc.ok(), "examples/scenes/quickstart.json");
    desc->width = 160;  // small enough for llvmpipe
    desc->height = 90;
    Result<RenderScene> scene = prepare_render_scene(*desc);
    check(scene.ok(), "the GPU snippet's scene");
    const CameraDesc camera = desc->camera;
    const int width = 160, height = 90;
    // clang-format off
    // snippet begin: docs/library.md
    Result<GpuDevice> device = GpuDevice::headless();      // OpenGL 4.5 core through EGL, current now
    Result<GpuRenderer> gpu = GpuRenderer::create(*scene);  // uploads the scene's pyramids as built
    GpuRenderOptions options;                               // fa-rough, κ = 2, N_max = 30
    GpuFrameStats stats;
    Result<Image> image = gpu->render(options, &stats);     // read back; stats.gpu_ms, stats.wall_ms
    gpu->draw(camera, width, height, options);              // into the bound framebuffer (a viewer)
    // snippet end
    // clang-format on
    check(device.ok() && gpu.ok() && image.ok() && image->width == 160,
          "docs/library.md: the GPU renderer");
    return 0;
}

int oiio_drop_in() {
    // clang-format off
    // snippet begin: docs/library.md
    #include <footprint/oiio/texture_system.h>   // links footprint::oiio (in footprint::footprint)

    OIIO::TextureSystem* ts = footprint::oiio::create_texture_system();   // was TextureSystem::create()
    // ... every call as before: ustring names, TextureOpt, handles, per-thread info, geterror() ...
    footprint::oiio::destroy_texture_system(ts);                          // was TextureSystem::destroy()
    // snippet end
    // clang-format on
    check(footprint::oiio::create_error().empty(), "docs/library.md: the adapter");
    return 0;
}

}  // namespace

int main() {
    // The scene file and its maps are the repository's; the snippets' own files are written here.
    const std::filesystem::path here = std::filesystem::current_path();
    std::filesystem::current_path(SNIPPETS_SOURCE_ROOT);
    if (scenes() != 0 || renderer_maps() != 0 || gpu() != 0) return 1;
    std::filesystem::current_path(here);
    if (oiio_drop_in() != 0) return 1;
    std::printf("docs/library.md's rendering snippets ran\n");
    return 0;
}
