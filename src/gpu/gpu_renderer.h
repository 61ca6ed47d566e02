// gpu/gpu_renderer.h — the whole method on the GPU: the scenes of render/ rendered at one sample
// per pixel by OpenGL 4.5 fragment shaders, each footprint-assembly probe one hardware trilinear
// lookup, against the GPU's own anisotropic filtering.
//
//   GpuDevice    a headless OpenGL 4.5 core context (EGL: Mesa's surfaceless platform, or a
//                vendor's EGL device), current on the calling thread while it lives (devices
//                nest: destroying one makes the previous context current again). A GpuRenderer
//                works on the context current when it was created (a device's, or the viewer's
//                window's) and must go while that context is current.
//   GpuRenderer  a RenderScene made ready for the GPU — its MIP, bump-moment and environment
//                pyramids uploaded level by level, exactly the levels the C++ code built (never
//                glGenerateMipmap; cube maps as cube textures with seamless filtering) — and its
//                frames, rendered to an image or into the current framebuffer.
//
// Every per-pixel step runs on the GPU (gpu/shaders/, one file per module of the CPU pipeline,
// README "Architecture"): the camera ray; the nearest hit — triangle meshes rasterised into a
// buffer of triangle ids, then the pixel's ray intersected with its triangle, and the analytic
// shapes (plane, sphere, cylinder, paraboloid, torus) ray-cast over a full-screen triangle; the
// exact ray differentials transferred to the hit (not screen-space derivatives: they break at
// silhouettes and (u, v) wraps); the texture footprint; footprint assembly by Rule B with
// Gaussian weights; the bump + roughness lookup by moments (in the mesh's tangent frame where a
// glTF part has one); the environment footprint K = D Dᵀ + κ² K3 and its lookup in each layout
// (lat-long with polar caps, cube, sphere, dual paraboloid); roughness-aware Blinn-Phong; Fresnel.
// Nothing per pixel is computed on the CPU.
//
// Filter modes (GpuFilter; the CLI's --filter names with --device gpu):
//   point      level-0 bilinear lookups, no footprint: the CPU's `bilinear`
//   trilinear  isotropic MIP, as the CPU's `trilinear`
//   fa         footprint assembly, mean slopes only, as the CPU's `fa`
//   fa-rough   Schilling's full method, as the CPU's `fa-rough`
//   hw-aniso   the GPU's own anisotropic filtering (textureGrad with the same exact derivatives,
//              at the driver's maximum anisotropy; trilinear on cube maps), no roughness: the
//              baseline every real-time engine ships
//
// Limits: a scene's colour and bump maps may come in at most 16 different shapes (size, level count
// and wrap; maps of one shape share an array texture, however many there are) — beyond that an
// Error names the object.
// Determinism: a frame depends only on the scene, the camera and the options; the same frame
// twice gives identical pixels.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <footprint/core/result.h>
#include <footprint/image/image.h>
#include <footprint/render/render_scene.h>
#include <footprint/render/renderer.h>

namespace footprint {

enum class GpuFilter { point, trilinear, fa, fa_rough, hw_aniso };

std::optional<GpuFilter> parse_gpu_filter(std::string_view name);
const char* gpu_filter_name(
    GpuFilter filter);  // "point", "trilinear", "fa", "fa-rough", "hw-aniso"
std::span<const GpuFilter> all_gpu_filters();

class GpuDevice {
  public:
    // A headless context; an Error saying why where there is none (no EGL, no OpenGL 4.5).
    static Result<GpuDevice> headless();
    GpuDevice(GpuDevice&&) noexcept;
    GpuDevice& operator=(GpuDevice&&) noexcept;
    ~GpuDevice();

    // The renderer and OpenGL version, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) | OpenGL 4.5 …".
    const std::string& description() const;

  private:
    GpuDevice();
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

struct GpuRenderOptions {
    GpuFilter filter = GpuFilter::fa_rough;
    float kappa = 2;      // κ of the environment footprint (spec §2.6)
    int max_probes = 30;  // footprint assembly's N_max, as LookupOptions::max_probes
    // Animation, as RenderOptions: frame `frame` of `frame_count` along the scene's camera_path;
    // frame_count 0: the scene's camera.
    int frame = 0;
    int frame_count = 0;
    // A band of rows, as RenderOptions::rows: render() shades and returns only those (scissored),
    // each pixel as the whole image's.
    std::optional<RowBand> rows = std::nullopt;
};

struct GpuFrameStats {
    double gpu_ms = 0;   // the frame's GPU time (timestamp queries around its draw)
    double wall_ms = 0;  // from issuing the draw until glFinish returns (not the read back): on
                         // a software rasteriser, which may record timestamps before it renders,
                         // the time that counts
};

class GpuRenderer {
  public:
    // Uploads `scene` (which must outlive the renderer) on the context current on this thread.
    // Errors name a scene beyond the limits above or what the driver refused.
    static Result<GpuRenderer> create(const RenderScene& scene);
    GpuRenderer(GpuRenderer&&) noexcept;
    GpuRenderer& operator=(GpuRenderer&&) noexcept;
    ~GpuRenderer();

    // A width × height linear RGB image of the scene's camera (or frame), read back.
    Result<Image> render(const GpuRenderOptions& options, GpuFrameStats* stats = nullptr);
    Result<Image> render(const CameraDesc& camera, int width, int height,
                         const GpuRenderOptions& options, GpuFrameStats* stats = nullptr);

    // The same frame drawn into the framebuffer bound now (the viewer's window), width × height
    // pixels with image row 0 at the framebuffer's row 0. Returns the GPU time of the previous
    // draw (timer queries are read a frame late, so that the CPU never waits on the GPU), or
    // a negative value while none is available.
    double draw(const CameraDesc& camera, int width, int height, const GpuRenderOptions& options);

    // The time of each filter's first draw, on one pixel before its first frame, so that no
    // frame's time holds it: where the driver compiles shaders at their first draw (Mesa's
    // llvmpipe does, seconds on a cold shader cache), the compilation; elsewhere about nothing.
    double warmup_ms() const;

  private:
    GpuRenderer();
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace footprint
