// bump/bump_pyramid.h — the bump pyramid (mean slopes) and the roughness pyramid (slope
// covariance) as one MIP pyramid of slope moments, and filtered bump lookups.
//
// Spec §5 (corrects [S97b] §3–4). For the finest-level slopes f_i (2-vectors b in the tangent
// frame, bump/slope_map.h) covered by a texel, the bump pyramid holds μ = (1/n) Σ f_i and the
// roughness pyramid K_b = (1/n) Σ (f_i − μ)(f_i − μ)ᵀ (population normalisation, §5.1), level by
// level through §5.3's recursion
//     μ_l = ¼ Σ μ_{l−1,n},   K_l = ¼ Σ K_{l−1,n} + ¼ Σ (μ_{l−1,n} − μ_l)(μ_{l−1,n} − μ_l)ᵀ
// (the "+" the paper texts lose). It is computed in its equivalent linear form ([R2m]): filter the
// first moments μ and the second moments M2 = K + μμᵀ with the same weights, then K = M2 − μμᵀ. For
// the 2×2 box this is the recursion exactly; for the tent and for odd sizes (fractional box
// weights) it is the covariance of the weighted mixture, which is what §5.3 prescribes for non-box
// filters. The finest level starts at K_0 = the optional micro-roughness (an artist-supplied
// constant covariance of the slopes below the map's resolution, plus an optional per-texel
// variance).
//
// Storage: one float MipPyramid with 5 channels (μ'1, μ'2, M2'11, M2'12, M2'22), where
// μ' = μ − slope_offset() is centred on the map's mean slope (so that M2' − μ'μ'ᵀ cancels only the
// slope *variation*, not the mean tilt). Levels are computed in double and rounded once; K is
// recovered to ~1e−7·(tr K + |μ'|²). The spec's stored factor B = (d1, d2, d3) and the isotropic l1
// are derived from K on demand (bump/roughness.h): filtering never blends them (§5.4, [R3]).
//
// Filtered lookups (§5.4): any texture filter (trilinear, footprint assembly, EWA, …) blends the
// five channels with its weights w_j, which is exactly
//     μ = Σ w_j μ_j,   M2 = Σ w_j M2_j,   K_b = M2 − μμᵀ  (clamped to PSD)
// = the mean and covariance of all finest-level slopes (plus micro-roughness) in the filtered
// region, weighted by the filter's kernel.
#pragma once

#include <footprint/bump/roughness.h>
#include <footprint/core/result.h>
#include <footprint/image/image.h>
#include <footprint/math/footprint_ellipse.h>
#include <footprint/texture/mip_pyramid.h>
#include <footprint/texture/texture_lookup.h>

namespace footprint {

struct SlopeStatistics {
    Vec2 mean;        // μ: mean slope (b1, b2)
    Sym2 covariance;  // K_b, slope units²
};

struct BumpPyramidOptions {
    WrapMode wrap_s = WrapMode::repeat;
    WrapMode wrap_t = WrapMode::repeat;
    DownsampleFilter downsample = DownsampleFilter::box;  // box: §5.3 exactly; tent: mixture form
    Sym2 micro_roughness;  // K_0 of every finest texel (PSD, slope units²); default none
    // Optional, added to K_0 texel by texel: an isotropic variance σ² I per finest texel (1
    // channel, the slope map's size, finite and ≥ 0), for a roughness that varies over the map
    // (a glTF roughness texture: α²/2 per texel, scene/material_model.h).
    Image micro_variance;
};

// A bump lookup's options: the filter's (LookupOptions), and how the slopes read are scaled —
//     mean = strength·μ,   K_b = strength²·K + micro_roughness
// — which is the lookup of a pyramid built from the slopes × strength with K_0 = micro_roughness
// (the moments are linear in both; equal up to float rounding). A pyramid built for one material
// has neither (1 and none); a stored one (bump_pyramid_file.h) gets a material's at lookup.
struct BumpLookupOptions : LookupOptions {
    float strength = 1;
    Sym2 micro_roughness;  // PSD, slope units²

    BumpLookupOptions() = default;
    BumpLookupOptions(const LookupOptions& lookup, float strength = 1, Sym2 micro_roughness = {})
        : LookupOptions(lookup), strength(strength), micro_roughness(micro_roughness) {}
};

class BumpPyramid {
  public:
    // From a 2-channel slope map (b1, b2) of any size ≥ 1×1. Errors name the problem: a wrong
    // channel count, a non-finite slope (with its texel), a micro-roughness that is not PSD.
    static Result<BumpPyramid> build(const Image& slopes, const BumpPyramidOptions& options = {});
    // From the moment levels a pyramid stored (moments() level by level, 5 channels, level 0 down
    // to 1×1 in MipPyramid's sizes) and its slope_offset(): the same pyramid, bit for bit.
    static Result<BumpPyramid> from_moment_levels(const std::vector<Image>& levels,
                                                  Vec2 slope_offset, WrapMode wrap_s,
                                                  WrapMode wrap_t);

    int level_count() const { return moments_.level_count(); }
    int width(int level) const { return moments_.width(level); }
    int height(int level) const { return moments_.height(level); }
    const BumpPyramidOptions& options() const { return options_; }

    // μ and K_b of one texel of one level (§5.1, §5.3).
    SlopeStatistics statistics(int level, int x, int y) const;

    // The moment pyramid the filters read (channels μ'1, μ'2, M2'11, M2'12, M2'22; see above) and
    // the offset μ = μ' + slope_offset().
    const MipPyramid& moments() const { return moments_; }
    Vec2 slope_offset() const { return offset_; }

    // μ and K_b from the 5 moment channels a lookup returned.
    SlopeStatistics from_moments(const float* m) const;

    // This pyramid's slopes × strength, with micro_roughness added to every K: what bump_lookup()
    // with BumpLookupOptions{…, strength, micro_roughness} reads, for a caller that needs the
    // scaled pyramid whole (a GPU upload).
    BumpPyramid scaled(float strength, Sym2 micro_roughness) const;

  private:
    MipPyramid moments_;
    Vec2 offset_;
    BumpPyramidOptions options_;
};

// μ and K_b from the 5 moment channels `m` of a pyramid whose slope_offset() is `offset`, scaled
// as `options` say (BumpLookupOptions): the last step of every bump lookup.
SlopeStatistics slope_statistics(const float* m, Vec2 offset, const BumpLookupOptions& options);

// Filtered bump lookup (§5.4): the mean slope and the slope covariance K_b of the whole filtered
// region, with any filter of texture_lookup() (LookupOptions::filter), in the same conventions,
// scaled as BumpLookupOptions say.
SlopeStatistics bump_lookup(const BumpPyramid& pyramid, const TextureCoords& coords,
                            const BumpLookupOptions& options);
SlopeStatistics bump_lookup(const BumpPyramid& pyramid, float s, float t,
                            const FootprintEllipse& footprint, const BumpLookupOptions& options);

}  // namespace footprint
