// texture/texture_lookup.h — filtered texture lookups: one call, every filter.
//
// Conventions (spec §1):
//   (s, t)                 normalised coordinates; s grows with the column, t with the row
//                          (t = 0 is the top row of the image). At level l the texel coordinate
//                          is X = s·W_l − ½: texel i has its centre at X = i.
//   ∂s/∂x, ∂t/∂x, ∂s/∂y, ∂t/∂y
//                          derivatives of (s, t) per pixel step in x and in y, in normalised
//                          units (like OpenImageIO's dsdx…dtdy). Zero derivatives mean "no
//                          antialiasing": a point (bilinear) sample.
//   footprint              D = S·∂(s,t)/∂(x,y), S = diag(W_0, H_0), in level-0 texels per pixel;
//                          K = D Dᵀ (math/footprint_ellipse.h). Filters that honour K have a
//                          kernel covariance of K/4 (spec §2.6: a σ = ½-pixel Gaussian pixel
//                          filter).
//
// Filters (TextureFilter):
//   nearest             the nearest level-0 texel (the aliased baseline)
//   bilinear            bilinear at level 0 (no MIP)
//   trilinear           isotropic MIP (GL rule: ρ = max(|∂X/∂x|, |∂X/∂y|), lod = log2 ρ, linear
//                       blend between the two nearest levels) — the 1997 hardware baseline
//   brilinear           trilinear's level, blended only within brilinear_band of a level
//                       transition and one bilinear probe of the nearer level elsewhere: what
//                       drivers' "trilinear optimisation" does, one level's texels instead of two
//                       for most lookups, at the price of visible level transitions
//   footprint_assembly  several trilinear probes along the major axis r1 of the footprint ellipse
//                       [S97a §5, lecture notes]; probe count, spacing and level by spec §2.8:
//                       Rule B (moment-matched, kernel covariance K/4) by default, Rule A (EXT) and
//                       Texram's power-of-two rule as options, at most max_probes probes
//   ewa                 elliptical weighted average (Heckbert 1989; as in pbrt-v4): a Gaussian of
//                       covariance K/4 summed over the texels of the level chosen from the minor
//                       axis, blended between two levels; anisotropy clamped to max_anisotropy by
//                       growing the minor axis. The high-quality reference filter.
//   summed_area         box mean over the footprint ellipse's bounding rectangle from a summed-area
//                       table (needs MipPyramidOptions::summed_area_table)
//
// Robustness: non-finite or zero derivatives give a bilinear sample at level 0; a non-finite
// position gives the coarsest level (the texture mean); footprints larger than the texture are read
// from the coarsest levels. No input produces NaN from finite texels.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include <footprint/math/footprint_ellipse.h>
#include <footprint/texture/mip_pyramid.h>

namespace footprint {

enum class TextureFilter {
    nearest,
    bilinear,
    trilinear,
    brilinear,
    footprint_assembly,
    ewa,
    summed_area
};

// How footprint assembly places its probes (spec §2.8).
enum class ProbeRule {
    moment_matched,  // Rule B: kernel covariance K/4, no gaps between probes, equal weights
    gaussian,        // Rule B's moments with Gaussian probe weights (footprint_assembly.h)
    ext,             // Rule A: EXT_texture_filter_anisotropic's rule on the ellipse axes
    texram,          // Texram: power-of-two probe counts, probes at ((i − ½)/N − ½)·λ1 r1
};

// How a probe between two MIP levels blends them.
enum class LodBlend {
    linear,  // GL: weight w = frac(lod); kernel variance 4^L(1+3w)/4, up to 12 % wide in σ
    variance_matched,  // w' = (4^w − 1)/3 makes the blended variance 4^{L+w}/4 exactly (spec §2.8)
    // footprint assembly's default: linear for a single probe, variance_matched for several.
    // A lone trilinear probe is a box-prefiltered tent whose side lobes alias, and linear's extra
    // blur hides that; a line of probes keeps the minor axis at T_p only with the remap (both seen
    // in footprint-bench texture's errors against the Gaussian ground truth, docs/performance.md).
    // Either way the kernel covariance stays within [FAT]'s 12 % of K/4.
    automatic,
};

struct LookupOptions {
    TextureFilter filter = TextureFilter::footprint_assembly;
    ProbeRule probe_rule = ProbeRule::gaussian;
    int max_probes = 30;  // footprint assembly: N_max (1..1024); more anisotropy raises the lod
    LodBlend lod_blend = LodBlend::automatic;  // footprint assembly's level blend
    float max_anisotropy = 16;  // EWA: λ1/λ2 clamp (grows λ2), as pbrt-v4's maxAnisotropy
    float lod_bias = 0;         // added to the level of trilinear, footprint assembly and EWA
    // Footprint assembly: a footprint with λ1 ≤ isotropic_ratio·max(λ2, 1) takes one probe of
    // size √(λ1·max(λ2, 1)) instead of a line (footprint_assembly.h). Each kernel σ is then off by
    // up to √ratio (11 % at 1.25, about the linear lod blend's own error), and the near-isotropic
    // footprints of cube faces and polar caps cost one probe instead of two or three. The default,
    // 1, is Rule B exactly (spec §2.8); what 1.25 gains and costs: footprint-bench env
    // --isotropic-ratio 1.25 (docs/performance.md).
    float isotropic_ratio = 1.0f;
    // Footprint assembly of a lat-long environment map: a footprint more anisotropic than
    // max_probes probes can cover is filtered by EWA instead of raising the probes' level
    // (environment_map.h). Off: spec §2.8's rule. The renderer's fa modes turn it on.
    bool ewa_beyond_probes = false;
    // brilinear: the width, in levels (0 … 1), of the band around each level transition where two
    // levels are blended. 1 is trilinear, 0 the nearest level (GL's NEAREST_MIPMAP_LINEAR).
    float brilinear_band = 0.25f;
};

// Where and how large a lookup is: position and derivatives in normalised units (see above).
struct TextureCoords {
    float s = 0, t = 0;
    float dsdx = 0, dtdx = 0;
    float dsdy = 0, dtdy = 0;
};

// Filters `pyramid` over the footprint of `coords`, writing pyramid.channels() floats to `out`.
// Thread-safe: lookups only read the pyramid.
void texture_lookup(const MipPyramid& pyramid, const TextureCoords& coords,
                    const LookupOptions& options, float* out);

// texture_lookup() of every lookup of `coords`, lookup i's pyramid.channels() floats written from
// out[i·channels]: bit for bit the single calls' results, faster where lookups are scattered. A
// single call waits on memory for its texels before it returns; the batch requests the texels of
// its lookups that are one probe (magnification, bilinear, trilinear, near-isotropic footprint
// assembly) or a short line of probes, 16 lookups at a time, and reads them once all 16 are
// routed, so that their misses to memory overlap. (OpenImageIO's batched texture() plays the same
// role.)
void texture_lookup_batch(const MipPyramid& pyramid, std::span<const TextureCoords> coords,
                          const LookupOptions& options, float* out);

// The same, with the footprint given directly as an ellipse in level-0 texels around (s, t).
void texture_lookup(const MipPyramid& pyramid, float s, float t, const FootprintEllipse& footprint,
                    const LookupOptions& options, float* out);

// The footprint ellipse of a lookup: K = D Dᵀ with D = diag(W0, H0)·∂(s,t)/∂(x,y).
FootprintEllipse footprint_of(const MipPyramid& pyramid, const TextureCoords& coords);

std::optional<TextureFilter> parse_texture_filter(std::string_view name);
const char* to_string(
    TextureFilter filter);  // "nearest", "bilinear", "trilinear", "brilinear", "fa", "ewa", "sat"

}  // namespace footprint
