// render/renderer.h — rendering a scene with one of the filter modes, or its ground truth.
//
// One pixel's journey (README "Architecture"; every step is a plain call into the modules below):
//   camera ray with differentials (render/camera.h)
//   → nearest hit: p, n, ∂p/∂(u,v), ∂n/∂(u,v), (u, v)           scene/shapes.h, scene/mesh.h
//   → ray differentials: ∂p, ∂n, ∂(u,v) per pixel step           scene/ray_differentials.h
//   → texture footprint D = S ∂(s,t)/∂(x,y)                      texture/texture_lookup.h
//       → base colour = filter(colour pyramid, (s,t), D)
//       → mean slope b and roughness K_b = filter(bump pyramid)  bump/bump_pyramid.h
//   → perturbed normal n_m = n + |n| T b (frame T per material)  bump/local_frame.h
//   → environment footprint K = D Dᵀ + κ² B'B'ᵀ (form (b))        envmap/env_footprint.h
//       → reflection = filter(environment, v_r, K)               envmap/environment_map.h
//   → Fresnel mirror + Lambert + (rough) Blinn-Phong or microfacet highlights   shading/
//
// Filter modes (FilterMode; the CLI's --filter names, the same names as texture_lookup.h's
// TextureFilter wherever both have the filter):
//   bilinear   bilinear lookups at the finest level with no footprint — the aliased baseline (and,
//              with --spp N, an unbiased estimate of the reference)
//   trilinear  isotropic MIP for textures, bumps and the environment (the 1997 hardware baseline)
//   fa         footprint assembly for textures, bumps and the environment; the bump map's mean
//              slope only (roughness ignored: plain Blinn-Phong, K3 = 0)
//   fa-rough   Schilling's full method: footprint assembly plus the roughness pyramid, which
//              widens the environment footprint (κ² K3) and the highlights (rough Blinn-Phong)
//   ewa-rough  EWA for textures, bumps and the environment, with roughness
//   reference  the ground truth: spp samples per pixel, each a finest-level bilinear lookup of
//              every map, the micro-roughness sampled as random slopes
// Peers (what engines ship, for the evaluation; sources and how each is built here in
// docs/rendering.md#peers and render/peer_filters.h). Textures, bumps and the environment are
// filtered as a GPU's 16× anisotropic filter does (footprint assembly with the EXT rule), and
// Fresnel is taken at the mean normal:
//   lean         LEAN mapping (Olano & Baker 2010): the pyramid's slope moments, K_b in the
//                highlights and the environment footprint — fa-rough's model at a GPU's filter
//   toksvig      Toksvig (2005): a pyramid of unit normals, K_b = (1 − |n̄|)/|n̄| I
//   specular-aa  geometric specular antialiasing (Kaplanyan et al. 2016, Tokuyoshi & Kaplanyan
//                2019): the mean slope, K_b from its change across the pixel
//   stochastic   stochastic texture filtering (Pharr et al. 2024): each lookup reads one random
//                position the filter picks, shading at the slope it reads (unbiased, noisy)
// Pixel filter: a Gaussian of σ = ½ pixel (truncated at ±3σ) — the filter whose texel-space image
// has the covariance K/4 every footprint filter implements (spec §2.6), so that filtered modes and
// the reference measure the same thing. With spp = 1 the filtered modes sample the pixel centre;
// with spp = N > 1 the reference takes N samples placed by a Gaussian-warped R2 sequence, each
// with its ray differentials scaled by 1/√N, and a filtered mode N samples whose own kernels
// (α/4 pixel²) and spread (σ = ½√(1 − α)) add up to the same pixel filter: for N = m² the m × m
// grid of Gaussian quantiles with α = 1/m, else R2 points with α = 1/N (supersampling on top of
// filtering; docs/rendering.md).
//
// Shading (linear RGB). At a hit with base colour c, mean normal n̂_m, view direction v̂:
//   L = Σ_lights E_i [ diffuse·c·max(0, n̂_m·l̂) + specular·S(n̂_m, ĥ, K_b, m)·[n̂_m·l̂ > 0] ]
//     + diffuse·c·E(n̂_m, K_b)/π  (the environment's irradiance, envmap/irradiance.h: nine
//                                 spherical harmonics, averaged over K_b in the rough modes)
//     + mirror·F(n̂_m·v̂)·env(v_r)
// E_i = colour (directional) or colour/d² (point), no shadows; S = shading/blinn_phong.h's
// specular() (plain for bilinear/trilinear/fa, gaussian with the filtered K_b for the rough modes),
// or for a material whose highlight is beckmann or ggx shading/microfacet.h's
// microfacet_highlight() with α = roughness² and K_b likewise;
// F = Schlick's Fresnel with fresnel_f0. A metallic-roughness material (glTF's) is the same sum
// with its diffuse colour c(1 − m), diffuse 1/π for the lights and 1 for E/π, F0 per channel, and
// its roughness in K_b (render/material_model.h). Reflections show the environment only (no
// inter-reflections), as in the papers. Rays that miss show the environment (filtered over the
// camera ray's own differentials) or the background colour.
//
// Determinism: every sample position and random number is a hash of (pixel, sample, seed), and
// every pixel is computed independently, so images are bit-identical for any thread count.
// Non-finite samples never reach a pixel: a pixel is the mean of its finite samples, and a pixel
// without any is written as 0 (both counted in RenderStats).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>

#include <footprint/image/image.h>
#include <footprint/render/render_scene.h>

namespace footprint {

enum class FilterMode {
    bilinear,
    trilinear,
    fa,
    fa_rough,
    ewa_rough,
    reference,
    lean,
    toksvig,
    specular_aa,
    stochastic
};

std::optional<FilterMode> parse_filter_mode(std::string_view name);
// "bilinear", "trilinear", "fa", "fa-rough", "ewa-rough", "reference", "lean", "toksvig",
// "specular-aa", "stochastic"
const char* filter_mode_name(FilterMode mode);
// Every mode, in the order above.
std::span<const FilterMode> all_filter_modes();
// The peers, in the order above.
std::span<const FilterMode> peer_filter_modes();

struct RowBand {
    int begin = 0, end = 0;
};

struct RenderOptions {
    FilterMode filter = FilterMode::fa_rough;
    int spp = 1;      // samples per pixel, ≥ 1 (the reference's default is set by the caller)
    int threads = 0;  // 0: all cores
    float kappa = 2;  // κ of the environment footprint (spec §2.6)
    // N_max of footprint assembly's probe lines in fa, fa-rough and the budget's hybrids (1 …
    // kMaxProbeCount; LookupOptions::max_probes): more anisotropy raises the probes' level.
    int max_probes = 30;
    // The sample positions and random numbers of every pixel are a hash of (pixel, sample, seed):
    // renders with different seeds have independent samples.
    std::uint32_t seed = 1;
    // Animation: frame_count ≥ 1 renders frame `frame` of `frame_count` along the scene's
    // camera_path (scene/scene.h's camera_for_frame); 0 (or no path): the scene's camera. Every
    // frame uses the same seed.
    int frame = 0;
    int frame_count = 0;
    // A band of rows [begin, end) of the image (0 ≤ begin < end ≤ height), for renders split
    // across machines: render() returns width × (end − begin) pixels, each bit for bit the whole
    // image's (a pixel's samples depend on its place only). None: the whole image.
    std::optional<RowBand> rows = std::nullopt;
};

struct RenderStats {
    double seconds = 0;
    std::uint64_t pixels = 0;
    std::uint64_t samples = 0;
    std::uint64_t lookups = 0;             // texture + bump + environment lookups
    std::uint64_t non_finite_samples = 0;  // samples whose colour was not finite (dropped)
    std::uint64_t non_finite_pixels = 0;   // pixels without a finite sample (written as 0)
};

// Renders desc().width × desc().height linear RGB (or the band of RenderOptions::rows) in tiles of
// 16 × 16 pixels on oneTBB.
// `tile_done` (optional) is called once per finished tile, from the worker threads (a progress
// bar: render_tile_count() calls in all).
Image render(const RenderScene& scene, const RenderOptions& options, RenderStats* stats = nullptr,
             const std::function<void()>& tile_done = {});

int render_tile_count(int width, int height);

// The interior of the scene's image at its still camera: 1 where the pixel filter (±3σ = ±1.5
// pixels around the centre) sees one object only — no silhouette, no object/background edge —
// else 0 (one channel). Texture filters can remove the aliasing there; at silhouettes only more
// samples can. The mask of `footprint eval`'s interior errors.
Image interior_mask(const RenderScene& scene);

}  // namespace footprint
