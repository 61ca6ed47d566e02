// texture/footprint_assembly.h — probe placement for footprint assembly (spec §2.8).
//
// Footprint assembly [S97a §5; the lecture notes] approximates the anisotropic footprint ellipse
// (semi-axes λ1 ≥ λ2, major direction r1, in level-0 texels) by N isotropic trilinear probes on a
// line through the centre along r1. All rules place the probes evenly and symmetrically:
// o_i = (i − (N−1)/2)·step, i = 0..N−1. The default rule, ProbeRule::gaussian, keeps Rule B's
// construction (below) but weights the probes by a Gaussian cut at ±kGaussianProbeExtent σ, its
// spacing solved so that the kernel keeps the covariance K/4; the other rules weight each 1/N.
//
// Rule B (ProbeRule::moment_matched; spec §2.8) on the axes Λ_i = max(√(λ_i² + ρ), 1),
// ρ = clamp(λ1² + λ2² − 1, 0, 1):
//     T_p = Λ2
//     Λ1 ≤ T_p:  N = 1
//     else:      N = ⌈√(3(Λ1/T_p)² − 2)⌉                 smallest N with spacing ≤ T_p (no gaps)
//                N > N_max:  N = N_max,  T_p = max(T_p, Λ1·√(3/(N_max² + 2)))  (raises the lod)
//                Δ = √(3(Λ1² − T_p²)/(N² − 1))            spacing, Δ ≤ T_p
//     lod = clamp(log2 T_p, 0, L_max)
//   The ground truth filters the bilinear reconstruction f of level 0 with K/4 (texture/
//   reference_filter.h); a probe of texel size T has the covariance (T² − 1)/4 about f (level 0
//   is f itself). With ρ = 1 (tr K ≥ 2), the line's (Λ1² − T_p²)/4 and the probes' (T_p² − 1)/4
//   add up to exactly K/4 about f unless clamped; planned on λ with T_p = max(λ2, 1) (ρ = 0), as
//   the papers do, a footprint of a few texels falls short by up to ¼ texel² along each axis,
//   which aliases (docs/method.md). Magnification (tr K ≤ 1) reads f itself, one bilinear probe
//   of level 0, as every filter does; ρ rises from 0 there to 1 at tr K = 2, so that the plan
//   stays continuous.
// Rule A (ProbeRule::ext; EXT_texture_filter_anisotropic on the ellipse axes):
//     N = min(⌈λ1/max(λ2, ε)⌉, N_max),  lod = log2(λ1/N),  o_i = (i/(N+1) − ½)·λ1 r1 (i = 1..N)
//   It integrates about one pixel step along r1 (σ_major → λ1/√12 instead of λ1/2).
// Texram (ProbeRule::texram): N a power of two ≤ N_max, o_i = ((i − ½)/N − ½)·λ1 r1, lod =
// log2(λ1/N).
#pragma once

#include <algorithm>

#include <footprint/math/footprint_ellipse.h>
#include <footprint/texture/texture_lookup.h>

namespace footprint {

// Where the Gaussian probe weights are cut, in σ of the weight Gaussian.
constexpr float kGaussianProbeExtent = 2.0f;

struct ProbePlan {
    int count = 1;             // N
    Vec2 step;                 // level-0 texels between neighbouring probes (along r1)
    float lod = 0;             // level of every probe, in [0, max_level]
    float texel_size = 1;      // T_p before the lod was clamped to the pyramid
    float weight_falloff = 0;  // a: weights ∝ exp(−½(a·(i − (N−1)/2))²); 0 = equal weights

    Vec2 offset(int i) const {
        return (static_cast<float>(i) - 0.5f * static_cast<float>(count - 1)) * step;
    }
};

// Rule B (both weightings) takes one probe when Λ1 ≤ ratio·Λ2, ratio =
// LookupOptions::isotropic_ratio (at least kIsotropicRatio), of size √(Λ1·Λ2) (the geometric mean
// of the axes: each kernel σ is off by at most √ratio). kIsotropicRatio is the exact rule: an
// isotropic footprint must not split into two coincident probes over rounding (kernel variance
// off < 0.2 %).
constexpr float kIsotropicRatio = 1.001f;

// For Rule B (both weightings): the lod of the single probe that footprint K takes, or a negative
// value when K needs several probes. Decided from K's eigenvalues alone — no axes, no square roots
// of λ — so texture_lookup() can skip the ellipse for the common near-isotropic case.
float single_probe_lod(const Sym2& k, float lod_bias, int max_level,
                       float isotropic_ratio = kIsotropicRatio);

// Whether `options` ask for footprint assembly by Rule B (either weighting), the filters whose
// near-isotropic footprints are one probe at the centre.
inline bool has_single_probe_rule(const LookupOptions& options) {
    return options.filter == TextureFilter::footprint_assembly &&
           (options.probe_rule == ProbeRule::moment_matched ||
            options.probe_rule == ProbeRule::gaussian);
}

// The same for a lookup with `options`: −1 unless has_single_probe_rule(options).
float single_probe_lod(const Sym2& k, const LookupOptions& options, int max_level);

// The most probes a plan holds (max_probes is clamped to it).
constexpr int kMaxProbeCount = 1024;

// c(N) of N ≥ 2 Gaussian-weighted probes: their spacing is Δ = σ_g·c(N), σ_g = √(Λ1² − T_p²)/2
// (the weights' standard deviation). Counts outside [2, kMaxProbeCount] read the nearest end. (The
// GPU path uploads it as a table.)
float gaussian_spacing_factor(int n);

// The (unnormalised) weight of each of plan.count probes: 1, or ∝ exp(−½(a·k)²), k = i − (N−1)/2
// (two probes weigh 1 each).
void probe_weights(const ProbePlan& plan, float* weights);

// LodBlend::automatic resolved for a single probe: linear.
inline LodBlend single_probe_blend(LodBlend blend) {
    return blend == LodBlend::automatic ? LodBlend::linear : blend;
}
// The same for a plan: linear for one probe, variance-matched for several.
inline LodBlend effective_lod_blend(const ProbePlan& plan, LodBlend blend) {
    if (plan.count == 1) return single_probe_blend(blend);
    return blend == LodBlend::automatic ? LodBlend::variance_matched : blend;
}

// Axes beyond this many texels are planned at this radius: such a footprint (64 times a 16K map)
// reads the coarsest level of any pyramid, whatever its size, and bounded so its probes' positions
// stay in int range and its squares finite (λ1² overflows from 1.8e19).
constexpr float kMaxPlannedRadius = 1e6f;

// The probes for a footprint ellipse (λ1 ≥ λ2 ≥ 0; a λ1 beyond kMaxPlannedRadius or not finite, as
// from a K near FLT_MAX, is planned at kMaxPlannedRadius). max_probes ≥ 1; max_level = the
// pyramid's coarsest level. lod_bias is added before clamping.
ProbePlan plan_probes(const FootprintEllipse& footprint, ProbeRule rule, int max_probes,
                      int max_level, float lod_bias = 0, float isotropic_ratio = kIsotropicRatio);

// Λ2, footprint `e`'s minor axis as Rule B plans it: the probe size of a line within its budget.
float planned_minor_axis(const FootprintEllipse& e);

// Whether `plan`, for footprint `e`, had to raise its probes' level because the line would have
// needed more than its max_probes (the clamped anisotropy that blurs the minor axis).
inline bool exceeds_probe_budget(const ProbePlan& plan, const FootprintEllipse& e) {
    return plan.count > 1 && plan.texel_size > 1.0001f * planned_minor_axis(e);
}

}  // namespace footprint
