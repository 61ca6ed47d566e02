#include "texture/footprint_assembly.h"

#include <algorithm>
#include <cmath>

#include "texture/filters.h"
#include "texture/sampling.h"

namespace footprint {

namespace {

// The lod for a probe texel size, biased and clamped to the pyramid.
float probe_lod(float texel_size, float lod_bias, int max_level) {
    return std::clamp(std::log2(std::max(texel_size, 1.0f)) + lod_bias, 0.0f,
                      static_cast<float>(max_level));
}

int floor_power_of_two(int n) {
    int p = 1;
    while (p * 2 <= n) p *= 2;
    return p;
}

}  // namespace

ProbePlan plan_probes(const FootprintEllipse& footprint, ProbeRule rule, int max_probes,
                      int max_level, float lod_bias) {
    constexpr float kMinTexelSize = 1.0f;  // T_min: smaller footprints are magnification
    const float l1 = footprint.major_radius, l2 = footprint.minor_radius;
    const Vec2 r1 = footprint.major_axis;
    max_probes = std::max(1, max_probes);
    ProbePlan plan;

    switch (rule) {
        case ProbeRule::moment_matched: {  // Rule B
            float tp = std::max(l2, kMinTexelSize);
            int n = 1;
            if (l1 > tp) {
                const float ratio = l1 / tp;
                n = static_cast<int>(std::ceil(std::sqrt(std::max(1.0f, 3 * ratio * ratio - 2))));
                if (n > max_probes) {
                    n = max_probes;
                    tp = std::max(tp, l1 * std::sqrt(3.0f / static_cast<float>(n * n + 2)));
                }
                if (n > 1) {
                    const float spacing = std::sqrt(std::max(0.0f, 3 * (l1 * l1 - tp * tp)) /
                                                    static_cast<float>(n * n - 1));
                    plan.step = spacing * r1;
                } else {
                    tp = std::max(tp, l1);  // N_max = 1: one isotropic probe covering λ1
                }
            }
            plan.count = n;
            plan.texel_size = tp;
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

void filter_footprint_assembly(const MipPyramid& pyramid, float s, float t,
                               const FootprintEllipse& footprint, const LookupOptions& options,
                               float* out) {
    const ProbePlan plan = plan_probes(footprint, options.probe_rule, options.max_probes,
                                       pyramid.max_level(), options.lod_bias);
    // Offsets are in level-0 texels; divide by S = diag(W0, H0) for normalised units (spec §2.9).
    const float inv_w = 1.0f / static_cast<float>(pyramid.width(0));
    const float inv_h = 1.0f / static_cast<float>(pyramid.height(0));
    const float weight = 1.0f / static_cast<float>(plan.count);
    dispatch_stride(pyramid.stride(), [&]<int S>() {
        float acc[S] = {};
        for (int i = 0; i < plan.count; ++i) {
            const Vec2 o = plan.offset(i);
            const float si = reduce_coordinate(s + o.x * inv_w, pyramid.wrap_s());
            const float ti = reduce_coordinate(t + o.y * inv_h, pyramid.wrap_t());
            accumulate_trilinear<S>(pyramid, si, ti, plan.lod, options.lod_blend, weight, acc);
        }
        std::copy_n(acc, pyramid.channels(), out);
    });
}

}  // namespace detail
}  // namespace footprint
