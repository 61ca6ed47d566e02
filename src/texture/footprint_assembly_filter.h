// texture/footprint_assembly_filter.h — footprint assembly's filter on either texel source
// (private to texture/): footprint_assembly.cpp compiles it for MipPyramid, tiled_lookup.cpp for
// TiledTexels. Two translation units, so that the tiled instance's code does not change how GCC
// inlines the in-memory one (it did: lat-long pole_band lookups took 8 % more instructions).
#pragma once

#include <type_traits>

#include "texture/filters.h"
#include "texture/footprint_assembly.h"
#include "texture/sampling.h"
#include "texture/tiled_texels.h"

namespace footprint::detail {
// Internal linkage, as when these lived in footprint_assembly.cpp alone: each of the two files
// has its own copy, inlined by the same rules as before.
namespace {

// The plan of a footprint on `pyramid`.
template <class Texels>
inline ProbePlan plan_for(const Texels& pyramid, const FootprintEllipse& footprint,
                          const LookupOptions& options) {
    return plan_probes(footprint, options.probe_rule, options.max_probes, pyramid.max_level(),
                       options.lod_bias, options.isotropic_ratio);
}

// filter_footprint_assembly(), or given `probe` and `line`, request_footprint_assembly(), of a
// footprint planned (plan_for()), on a MipPyramid or TiledTexels (whose lines all take TiledLine,
// tiled_texels.h).
template <class Texels>
inline Requested assemble(const Texels& pyramid, float s, float t, const ProbePlan& plan,
                          const LookupOptions& options, float* out, RequestedProbe* probe,
                          RequestedLine<kRequestedLineProbes>* line) {
    // Offsets are in level-0 texels; divide by S = diag(W0, H0) for normalised units (spec §2.9).
    // Positions need no per-probe reduction: the footprint is bounded to a few texture sizes, and
    // sample_bilinear wraps taps outside the level.
    const float du = plan.step.x / static_cast<float>(pyramid.width(0));
    const float dv = plan.step.y / static_cast<float>(pyramid.height(0));
    const float first = -0.5f * static_cast<float>(plan.count - 1);
    const LodBlend blend = effective_lod_blend(plan, options.lod_blend);
    if (plan.count == 1) {  // one isotropic probe: both levels' taps issued together
        if (probe) {
            const TrilinearLevels levels = trilinear_levels(plan.lod, pyramid.max_level(), blend);
            *probe = {probe_taps(pyramid, s, t, levels), levels};
            probe->request(pyramid.stride());
            return Requested::probe;
        }
        dispatch_stride(pyramid.stride(), [&]<int S>() {
            store(sample_trilinear<S>(pyramid, s, t, plan.lod, blend), pyramid.channels(), out);
        });
        return Requested::done;
    }
    // C = Σ w_i trilinear(c + o_i) / Σ w_i (spec §2.9).
    float weights[kMaxProbeCount];
    probe_weights(plan, weights);
    const TrilinearLevels levels = trilinear_levels(plan.lod, pyramid.max_level(), blend);
    auto position = [&](int i) {
        const float k = first + static_cast<float>(i);
        return Vec2{s + k * du, t + k * dv};
    };
    constexpr bool in_memory = std::is_same_v<Texels, MipPyramid>;
    if constexpr (in_memory) {
        if (line && plan.count <= kRequestedLineProbes) {
            bool requested = false;
            dispatch_stride(pyramid.stride(), [&]<int S>() {
                requested =
                    line->template request<S>(pyramid, plan.count, weights, levels, position(0),
                                              position(plan.count - 1), position);
            });
            if (requested) return Requested::line;
        }
        // A line whose ends' taps lie on the levels needs no wrapping.
        if (blend_probe_line_inside(pyramid, plan.count, weights, levels, position, out))
            return Requested::done;
    } else {  // through tiles: every line one way, its probes at position(i)
        const ProbeLine line{{s, t}, {du, dv}, first};
        blend_probe_line_in_tiles(pyramid, plan.count, weights, levels, line, out);
        return Requested::done;
    }
    dispatch_stride(pyramid.stride(), [&]<int S>() {
        const Texel<S> result =
            blend_probe_line<S>(plan.count, weights, levels, pyramid.stride(), [&](int i) {
                const Vec2 p = position(i);
                return probe_taps(pyramid, p.x, p.y, levels);
            });
        store(result, pyramid.channels(), out);
    });
    return Requested::done;
}

}  // namespace

template <class Texels>
void filter_footprint_assembly(const Texels& pyramid, float s, float t,
                               const FootprintEllipse& footprint, const LookupOptions& options,
                               float* out) {
    assemble(pyramid, s, t, plan_for(pyramid, footprint, options), options, out, nullptr, nullptr);
}

}  // namespace footprint::detail
