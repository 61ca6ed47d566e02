#include "texture/footprint_assembly_lanes.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "math/fast_log2.h"
#include "math/footprint_ellipse_lanes.h"
#include "math/lanes.h"

#include "texture/filters.h"
#include "texture/footprint_assembly_filter.h"
#include "texture/sampling.h"

namespace footprint {

namespace {

// The lod for a probe texel size, biased and clamped to the pyramid (any lane type).
template <class F>
F probe_lod(F texel_size, float lod_bias, int max_level) {
    return clamp_like_std(fast_log2(max_like_std(texel_size, F(1))) + F(lod_bias), F(0),
                          F(static_cast<float>(max_level)));
}

// The Gaussian fall-off a = 2κ_g/(N − 1) that plan_probes() gives a line of N probes, and the
// ratio q = e^{−a²/8} that probe_weights() builds its weights from, for every count a plan may
// hold: tabulated once, so that a short line's weights cost no exp beside its few probes.
struct GaussianFalloff {
    float falloff, ratio;
};
const GaussianFalloff& gaussian_falloff(int n) {
    constexpr int kTableSize = kMaxProbeCount + 1;
    static const std::array<GaussianFalloff, kTableSize> table = [] {
        std::array<GaussianFalloff, kTableSize> t{};
        for (int m = 2; m < kTableSize; ++m) {
            const float a = 2 * kGaussianProbeExtent / static_cast<float>(m - 1);
            t[m] = {a, std::exp(-0.125f * (a * a))};
        }
        return t;
    }();
    return table[std::clamp(n, 2, kTableSize - 1)];
}

int floor_power_of_two(int n) {
    int p = 1;
    while (p * 2 <= n) p *= 2;
    return p;
}

// ρ, the share of the reconstruction's texel Rule B plans (footprint_assembly.h; docs/method.md,
// "Footprint assembly"), from the squared axes: 0 inside one texel (tr K = λ1² + λ2² ≤ 1,
// magnification), 1 from tr K = 2, for any lane type.
template <class F>
F reconstruction_share(F l1_sq, F l2_sq) {
    return clamp_like_std(l1_sq + l2_sq - F(1), F(0), F(1));
}
// Λ = max(√(λ² + ρ), 1): a semi-axis as Rule B plans it.
template <class F>
F planned_axis(F l, F rho) {
    using std::sqrt;
    return max_like_std(sqrt(l * l + rho), F(1));
}

// Rule B's arithmetic (footprint_assembly.h), for any lane type: plan_probes() and the batches'
// short_plans4() share it, and differ only in how they find the count N.
// √(max(1, 3(λ1/T_p)² − 2)), whose ceiling is Rule B's N.
template <class F>
F rule_b_root(F l1, F tp) {
    using std::sqrt;
    const F ratio = l1 / tp;
    return sqrt(max_like_std(F(1), F(3) * ratio * ratio - F(2)));
}
// Δ = √(3(λ1² − T_p²)/(N² − 1)) for N > 1 moment-matched probes.
template <class F>
F rule_b_spacing(F l1, F tp, F n) {
    using std::sqrt;
    return sqrt(max_like_std(F(0), F(3) * (l1 * l1 - tp * tp)) / (n * n - F(1)));
}
// σ_g = √(λ1² − T_p²)/2 of the Gaussian-weighted line.
template <class F>
F gaussian_sigma(F l1, F tp) {
    using std::sqrt;
    return F(0.5f) * sqrt(l1 * l1 - tp * tp);
}

}  // namespace

// a/√v_N, v_N the variance, in u units, of the weights exp(−½u²) on N even nodes over [−κ, κ].
// Tabulated on first use (so that programs that never plan a Gaussian line do not pay for it),
// since a plan may look several up.
float gaussian_spacing_factor(int n) {
    constexpr int kTableSize = kMaxProbeCount + 1;  // every count a plan may hold
    static const std::array<float, kTableSize> table = [] {
        std::array<float, kTableSize> t{};
        for (int m = 2; m < kTableSize; ++m) {
            const double a = 2.0 * kGaussianProbeExtent / (m - 1);
            double sw = 0, swu = 0;
            for (int i = 0; i < m; ++i) {
                const double u = (i - 0.5 * (m - 1)) * a, w = std::exp(-0.5 * u * u);
                sw += w;
                swu += w * u * u;
            }
            t[m] = static_cast<float>(a / std::sqrt(swu / sw));
        }
        return t;
    }();
    return table[std::clamp(n, 2, kTableSize - 1)];
}

void probe_weights(const ProbePlan& plan, float* weights) {
    // From the centre out by the recurrence w_{k+1} = w_k·r_k, r_{k+1} = r_k·e^{−a²}, mirrored, so
    // that the weights are exactly symmetric (the kernel mean stays on the centre), from one
    // ratio per plan: q = e^{−a²/8} (tabulated for plan_probes()' fall-offs, an exp for any other),
    // e^{−a²/2} = q⁴, e^{−a²} = q⁸.
    if (plan.count <= 2) {  // one probe, or two of equal weight: no ratio
        weights[0] = weights[plan.count - 1] = 1.0f;
        return;
    }
    const float a2 = plan.weight_falloff * plan.weight_falloff;
    const int half = plan.count / 2;  // probes on each side of the centre
    const GaussianFalloff& planned = gaussian_falloff(plan.count);  // the same q, without the exp
    const float q = plan.weight_falloff == planned.falloff ? planned.ratio : std::exp(-0.125f * a2),
                q4 = (q * q) * (q * q), q8 = q4 * q4;
    float wk = plan.count % 2 ? 1.0f : q;  // k = 0 or ½
    float rk = plan.count % 2 ? q4 : q8;   // w_{k+1}/w_k
    const float r_step = q8;
    if (plan.count % 2) weights[half] = 1.0f;
    for (int j = 0; j < half; ++j) {
        if (j > 0 || plan.count % 2) {
            wk *= rk;
            rk *= r_step;
        }
        weights[half - 1 - j] = weights[plan.count - half + j] = wk;
    }
}

namespace {

// single_probe_lod() for any lane type (math/lanes.h): one footprint, or four at once for the
// batches.
template <class F>
inline F single_probe_lod_lanes(F xx, F xy, F yy, float lod_bias, int max_level,
                                float isotropic_ratio) {
    const F zero(0), one(1);
    const F bias_lod(std::clamp(lod_bias, 0.0f, static_cast<float>(max_level)));
    // Magnification (λ1² ≤ tr K ≤ 1): one probe at level 0, no eigenvalues needed.
    const MaskOf<F> magnified = (xx + yy <= one) & (xx >= zero) & (yy >= zero);
    if (none(!magnified)) return bias_lod;
    const AxesSquared<F> a = axes_squared(xx, xy, yy);
    // Λ1², Λ2² = max(λ² + ρ, 1), as planned_axis() squared.
    const F rho = reconstruction_share(a.major_sq, a.minor_sq);
    const F major_sq = max_like_std(a.major_sq + rho, one),
            minor_sq = max_like_std(a.minor_sq + rho, one);
    const float ratio = std::max(isotropic_ratio, kIsotropicRatio);
    const MaskOf<F> one_probe = major_sq <= F(ratio * ratio) * minor_sq;
    // log2 √(Λ1·Λ2) = ¼ log2(Λ1² Λ2²).
    const F lod = clamp_like_std(F(0.25f) * fast_log2(major_sq * minor_sq) + F(lod_bias), zero,
                                 F(static_cast<float>(max_level)));
    return select(magnified, bias_lod, select(one_probe, lod, F(-1)));
}

}  // namespace

float single_probe_lod(const Sym2& k, float lod_bias, int max_level, float isotropic_ratio) {
    return single_probe_lod_lanes(k.xx, k.xy, k.yy, lod_bias, max_level, isotropic_ratio);
}

Float4 single_probe_lod(Float4 xx, Float4 xy, Float4 yy, float lod_bias, int max_level,
                        float isotropic_ratio) {
    return single_probe_lod_lanes(xx, xy, yy, lod_bias, max_level, isotropic_ratio);
}

// make_footprint_ellipse() and plan_probes()' short lines by Rule B, lane by lane in the same order
// of operations, with selects for the branches. Gaussian weighting: N is the fewest probes from 3
// on whose spacing σ·c(N) is at most T_p (plan_probes()' search ends there from any first guess),
// which is 3 plus the number of N ≥ 3 with σ·c(N) > T_p, as c(N) falls with N (checked once).
void short_plans4(Float4 xx, Float4 xy, Float4 yy, ProbeRule rule, int max_probes, int max_level,
                  float lod_bias, float isotropic_ratio, ShortPlans4& out) {
    out.planned = 0;
    max_probes = std::clamp(max_probes, 1, kMaxProbeCount);
    static const bool spacing_falls = [] {
        for (int n = 3; n < kMaxProbeCount; ++n)
            if (!(gaussian_spacing_factor(n + 1) < gaussian_spacing_factor(n))) return false;
        return true;
    }();
    if (rule != ProbeRule::moment_matched && (rule != ProbeRule::gaussian || !spacing_falls))
        return;
    const Float4 zero(0.0f), one(1.0f);
    const EllipseLanes<Float4> ellipse = footprint_ellipse_lanes(xx, xy, yy);
    // plan_probes(): more than one probe, N ≤ kShortLineProbes and within the budget; axes beyond
    // kMaxPlannedRadius, or not finite (a NaN λ2 too), go plan_probes()' way (bounded there).
    Mask4 planned = (ellipse.major_radius <= Float4(kMaxPlannedRadius)) &
                    (ellipse.minor_radius >= zero) & is_finite(ellipse.major_axis.x) &
                    is_finite(ellipse.major_axis.y);
    const Float4 rho = reconstruction_share(ellipse.major_radius * ellipse.major_radius,
                                            ellipse.minor_radius * ellipse.minor_radius);
    const Float4 l1 = planned_axis(ellipse.major_radius, rho),  // Λ1
        tp = planned_axis(ellipse.minor_radius, rho);           // T_p = Λ2
    const float ratio = std::max(isotropic_ratio, kIsotropicRatio);
    planned = planned & !(l1 <= tp * Float4(ratio));  // anisotropic
    Int4 n(2);
    Float4 spacing, falloff(0.0f);
    if (rule == ProbeRule::moment_matched) {
        // N = ⌈√(max(1, 3(λ1/T_p)² − 2))⌉: 1 + the number of k = 1 … 7 below the root.
        const Float4 root = rule_b_root(l1, tp);
        n = Int4(1);
        for (int k = 1; k < kShortLineProbes; ++k)
            n = select(root > Float4(static_cast<float>(k)), n + Int4(1), n);
        planned = planned & (root > one) &
                  (root <= Float4(static_cast<float>(std::min(kShortLineProbes, max_probes))));
        spacing = rule_b_spacing(l1, tp, to_float(n));
    } else {
        const Float4 sigma = gaussian_sigma(l1, tp);
        const Float4 c2(gaussian_spacing_factor(2));
        const Mask4 two = sigma * c2 <= tp;
        if (((!two) & planned).bits() == 0) {  // two probes wherever a line (the commonest case)
            spacing = sigma * c2;
            falloff = Float4(2 * kGaussianProbeExtent);
        } else {
            Int4 more(3);  // N ≥ 3: 3 + the count of N with σ·c(N) > T_p
            for (int k = 3; k <= kShortLineProbes; ++k)
                more =
                    select(sigma * Float4(gaussian_spacing_factor(k)) > tp, more + Int4(1), more);
            n = select(two, Int4(2), more);
            Float4 factor = c2;
            for (int k = 3; k <= kShortLineProbes; ++k)
                factor = select(n == Int4(k), Float4(gaussian_spacing_factor(k)), factor);
            spacing = sigma * factor;
            falloff = Float4(2 * kGaussianProbeExtent) / to_float(n - Int4(1));
        }
        // Within kShortLineProbes, and N < N_max (plan_probes() clamps N ≥ N_max).
        planned = planned & (n <= Int4(std::min(kShortLineProbes, max_probes - 1)));
    }
    out.planned = planned.bits();
    if (out.planned == 0) return;
    n.store(out.count);
    (spacing * ellipse.major_axis.x).store(out.step_x);
    (spacing * ellipse.major_axis.y).store(out.step_y);
    tp.store(out.texel_size);
    falloff.store(out.weight_falloff);
    probe_lod(tp, lod_bias, max_level).store(out.lod);
}

float planned_minor_axis(const FootprintEllipse& e) {
    const float rho =
        reconstruction_share(e.major_radius * e.major_radius, e.minor_radius * e.minor_radius);
    return planned_axis(e.minor_radius, rho);
}

float single_probe_lod(const Sym2& k, const LookupOptions& options, int max_level) {
    if (!has_single_probe_rule(options)) return -1.0f;
    return single_probe_lod(k, options.lod_bias, max_level, options.isotropic_ratio);
}

ProbePlan plan_probes(const FootprintEllipse& footprint, ProbeRule rule, int max_probes,
                      int max_level, float lod_bias, float isotropic_ratio) {
    isotropic_ratio = std::max(isotropic_ratio, kIsotropicRatio);
    float l1 = footprint.major_radius, l2 = footprint.minor_radius;
    Vec2 r1 = footprint.major_axis;
    if (!(l1 <= kMaxPlannedRadius) || !is_finite(r1)) {  // also NaN
        l1 = kMaxPlannedRadius;
        l2 = std::isfinite(l2) ? std::min(l2, l1) : l1;
        if (!is_finite(r1)) r1 = {1, 0};
    }
    if (!(l2 >= 0)) l2 = 0;  // NaN: planned as rank one
    max_probes = std::clamp(max_probes, 1, kMaxProbeCount);
    ProbePlan plan;
    // Rule B plans the axes Λ (footprint_assembly.h), the others λ.
    const float rho = reconstruction_share(l1 * l1, l2 * l2);
    const float big_l1 = planned_axis(l1, rho), big_l2 = planned_axis(l2, rho);

    switch (rule) {
        case ProbeRule::moment_matched: {  // Rule B
            l1 = big_l1;
            float tp = big_l2;
            int n = 1;
            if (l1 <= tp * isotropic_ratio) {
                tp = std::sqrt(tp * l1);  // one probe, √(Λ1 Λ2)
            } else {
                // Bounded as a float: a footprint beyond INT_MAX texels (or a NaN one) holds
                // more probes than any budget, and no int holds its count.
                n = static_cast<int>(std::fmin(std::ceil(rule_b_root(l1, tp)),
                                               static_cast<float>(kMaxProbeCount + 1)));
                if (n > max_probes) {
                    n = max_probes;
                    tp = std::max(tp, l1 * std::sqrt(3.0f / static_cast<float>(n * n + 2)));
                }
                if (n > 1) {
                    plan.step = rule_b_spacing(l1, tp, static_cast<float>(n)) * r1;
                } else {
                    tp = std::max(tp, l1);  // N_max = 1: one isotropic probe covering λ1
                }
            }
            plan.count = n;
            plan.texel_size = tp;
            break;
        }
        case ProbeRule::gaussian: {
            l1 = big_l1;
            float tp = big_l2;
            if (l1 <= tp * isotropic_ratio) {
                plan.texel_size = std::sqrt(tp * l1);  // one probe, √(Λ1 Λ2)
                break;
            }
            auto spacing_factor = [](int n) { return gaussian_spacing_factor(n); };
            float sigma = gaussian_sigma(l1, tp);
            int n = 2;
            // Two probes (c = 2) first: c(3) = 2.17 > c(2) (the ends' weights e^−2), so the descent
            // below, which stops where c(N − 1) is too large, would stop at four.
            if (!(sigma * spacing_factor(2) <= tp)) {
                // First guess from the continuous truncated Gaussian (v ≈ 0.774 at κ = 2), then
                // exact.
                // (Bounded as a float, as Rule B's, and so that c(N) stays in its table: a guess
                // of kMaxProbeCount is at least any budget, and the descent finds the same N.)
                n = std::max(3, static_cast<int>(std::fmin(
                                    std::ceil(2 * kGaussianProbeExtent * sigma / (tp * 0.88f)),
                                    static_cast<float>(kMaxProbeCount - 1))) +
                                    1);
                while (n < max_probes && sigma * spacing_factor(n) > tp) ++n;
                while (n > 3 && sigma * spacing_factor(n - 1) <= tp) --n;
            }
            if (n >= max_probes) {
                n = std::max(2, max_probes);
                if (max_probes == 1) {  // one isotropic probe covering λ1
                    plan.texel_size = std::max(tp, l1);
                    break;
                }
                // Raise T_p until the spacing closes the gaps: T = √(λ1² − T²)/2 · c.
                const float c = spacing_factor(n);
                tp = std::max(tp, l1 * 0.5f * c / std::sqrt(1 + 0.25f * c * c));
                sigma = 0.5f * std::sqrt(std::max(0.0f, l1 * l1 - tp * tp));
            }
            plan.count = n;
            plan.texel_size = tp;
            plan.step = (sigma * spacing_factor(n)) * r1;
            plan.weight_falloff = gaussian_falloff(n).falloff;
            break;
        }
        case ProbeRule::ext:
        case ProbeRule::texram: {
            constexpr float kMinMinor = 1e-6f;  // ε of Rule A: keeps ⌈λ1/λ2⌉ finite
            const float ratio = std::ceil(l1 / std::max(l2, kMinMinor));
            int n = static_cast<int>(std::clamp(ratio, 1.0f, static_cast<float>(max_probes)));
            if (rule == ProbeRule::texram) n = floor_power_of_two(n);
            plan.count = n;
            plan.texel_size = l1 / static_cast<float>(n);
            // Rule A: o_i = (i/(N+1) − ½)·λ1 r1 → spacing λ1/(N+1); Texram: spacing λ1/N.
            const float spacing = rule == ProbeRule::ext ? l1 / static_cast<float>(n + 1)
                                                         : l1 / static_cast<float>(n);
            if (n > 1) plan.step = spacing * r1;
            break;
        }
    }
    plan.lod = probe_lod(plan.texel_size, lod_bias, max_level);
    return plan;
}

namespace detail {

template void filter_footprint_assembly(const MipPyramid&, float, float, const FootprintEllipse&,
                                        const LookupOptions&, float*);

Requested request_footprint_assembly(const MipPyramid& pyramid, float s, float t,
                                     const FootprintEllipse& footprint,
                                     const LookupOptions& options, float* out,
                                     RequestedProbe& probe,
                                     RequestedLine<kRequestedLineProbes>& line) {
    return assemble(pyramid, s, t, plan_for(pyramid, footprint, options), options, out, &probe,
                    &line);
}

Requested request_footprint_assembly(const MipPyramid& pyramid, float s, float t,
                                     const ProbePlan& plan, const LookupOptions& options,
                                     float* out, RequestedProbe& probe,
                                     RequestedLine<kRequestedLineProbes>& line) {
    return assemble(pyramid, s, t, plan, options, out, &probe, &line);
}

}  // namespace detail
}  // namespace footprint
