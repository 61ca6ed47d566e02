// examples/filament/filament_renderer.h — one scene in Filament, rendered offscreen with one of
// the materials and read back as linear floats.
//
// Filament 1.9 (Debian's libfilament-dev) renders here through OpenGL under an X server (Xvfb with
// llvmpipe): Engine::create(OPENGL) makes a GLX context, a 16×16 headless swap chain satisfies
// beginFrame(), and every frame goes to an RGBA16F render target that readPixels() reads back as
// floats. Post-processing is off (it misrenders on llvmpipe, and it would tone-map): the target
// holds linear radiance at exposure 1 (aperture f/1, 1.2 s, ISO 100) with the IBL at intensity 1,
// so a pixel is in the environment's own units.
//
// Filament aborts the process on some misuse (a malformed material package, an unknown parameter,
// no display). Everything checkable is checked before Filament sees it: the display opens, each
// .filamat is a well-formed chunk container, every parameter set exists in the material.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <footprint/core/result.h>
#include <footprint/image/image.h>
#include "scenes.h"

namespace footprint::filament_example {

enum class MaterialKind {
    filament,   // Filament's best practice (materials/filament_best.mat)
    footprint,  // footprint's filtering in GLSL (materials/footprint.mat, when built)
    truth,      // level-0 maps, authored roughness (materials/truth.mat), rendered N× larger
};
const char* material_name(MaterialKind kind);

struct RendererOptions {
    std::filesystem::path materials_dir;  // the compiled .filamat files
    std::filesystem::path cache_dir;      // cmgen's and roughness-prefilter's output
    int ibl_size = 256;                   // cmgen --size: the IBL cube's level-0 face
};

struct RenderedFrame {
    Image image;          // RGB, linear, top row first
    double frame_ms = 0;  // the median time of the timed frames (render + GPU finish)
    double first_ms = 0;  // the first frame (shader compilation, uploads)
};

class FilamentRenderer {
  public:
    // Opens the X display, creates the engine and loads the materials. Errors name what is
    // missing: the display, a .filamat file.
    static Result<std::unique_ptr<FilamentRenderer>> create(const RendererOptions& options);
    ~FilamentRenderer();
    FilamentRenderer(const FilamentRenderer&) = delete;
    FilamentRenderer& operator=(const FilamentRenderer&) = delete;

    // Whether footprint's material was built (the GLSL library was there at build time).
    bool has_material(MaterialKind kind) const;

    // Builds a scene: each surface's textures for every material, the environment (cmgen), each
    // object's geometry. `environment`, when not empty, replaces the scene's own.
    Status load(const SceneSetup& scene, const MapSource& environment);

    // Renders width × height with one material (frames ≥ 1: the first is warm-up, the rest timed).
    Result<RenderedFrame> render(MaterialKind kind, int width, int height, int frames);

    // The object-id pass: channel 0 = 1 + the renderable's index, 0 for the background.
    Result<Image> render_object_ids(int width, int height);

  private:
    struct State;
    struct SurfaceTextures;
    explicit FilamentRenderer(std::unique_ptr<State> state);
    Result<SurfaceTextures> make_surface_textures(const SurfaceDesc& surface);
    void add_renderable(const Mesh& mesh, const SurfaceTextures& textures);
    std::unique_ptr<State> state_;
};

}  // namespace footprint::filament_example
