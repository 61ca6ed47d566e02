// texture/footprint_assembly_lanes.h — (private) footprint_assembly.h's decisions for four
// footprints at once (math/float4.h), for the batches (environment_map_batch.cpp, polar_caps.cpp):
// the same templates over a lane type as the single calls' (footprint_assembly.cpp), so that lane
// i is the scalar result bit for bit.
#pragma once

#include "math/float4.h"
#include "texture/footprint_assembly.h"

namespace footprint {

// single_probe_lod(k, lod_bias, max_level, isotropic_ratio) for four footprints K_i = [[xx_i,
// xy_i], [xy_i, yy_i]] at once (math/float4.h): lane i is the scalar result bit for bit.
Float4 single_probe_lod(Float4 xx, Float4 xy, Float4 yy, float lod_bias, int max_level,
                        float isotropic_ratio = kIsotropicRatio);

// plan_probes(make_footprint_ellipse(K_i), rule, …) for four footprints K_i at once where it is a
// line of 2 to kShortLineProbes probes by Rule B (either weighting): the common lines, footprints
// up to about 8:1. Where bit i of `planned` is set, plan(i) is that plan bit for bit; elsewhere
// plan_probes() decides (one probe, a longer line, another rule, a clamped probe budget).
constexpr int kShortLineProbes = 8;
struct ShortPlans4 {
    int planned = 0;
    int count[4];
    float step_x[4], step_y[4], lod[4], texel_size[4], weight_falloff[4];

    ProbePlan plan(int i) const {
        ProbePlan p;
        p.count = count[i];
        p.step = {step_x[i], step_y[i]};
        p.lod = lod[i];
        p.texel_size = texel_size[i];
        p.weight_falloff = weight_falloff[i];
        return p;
    }
};
void short_plans4(Float4 xx, Float4 xy, Float4 yy, ProbeRule rule, int max_probes, int max_level,
                  float lod_bias, float isotropic_ratio, ShortPlans4& out);

}  // namespace footprint
