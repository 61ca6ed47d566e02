// footprint/bump.glsl — the bump + roughness lookup by moments (docs/method.md, "Bump maps and the
// roughness pyramid"; bump/bump_pyramid.h, bump/roughness.h).
//
// A bump map is its moment pyramid: per texel of every level the mean μ' of the finest-level
// slopes it covers and their second moment M2' = K_b + μ'μ'ᵀ, five channels (μ'1, μ'2, M2'11,
// M2'12, M2'22), μ' centred on the map's mean slope (slope_offset()). Any filter blends the
// moments with its weights; K_b = M2 − μμᵀ is then the covariance of every finest slope under the
// filter's kernel — the roughness the bumps too small to see leave behind.
#ifndef FOOTPRINT_GLSL_BUMP
#define FOOTPRINT_GLSL_BUMP

#include "footprint/common.glsl"
#include "footprint/texture.glsl"

// The slopes of a filtered region: b = (b1, b2) in the bump map's frame T = (t1, t2), with the
// perturbed normal n_m = n + |n|(b1 t1 + b2 t2) (docs/method.md, "Slopes and frames").
struct FpSlopeStats {
    vec2 mean;  // μ, the mean slope
    vec3 k;     // K_b = (xx, xy, yy), the slopes' covariance (slope units², PSD)
};

// μ and K_b from the filtered moments: m0 = (μ'1, μ'2, M2'11, M2'12), m22 = M2'22, slope_offset
// the map's mean slope (μ = μ' + slope_offset). K_b = M2' − μ'μ'ᵀ, clamped to PSD (bump_pyramid.h's
// from_moments()).
FpSlopeStats fp_slope_stats(vec4 m0, float m22, vec2 slope_offset) {
    float m1 = m0.x, m2 = m0.y;
    return FpSlopeStats(vec2(m1, m2) + slope_offset,
                        fp_clamp_to_psd(vec3(m0.z - m1 * m1, m0.w - m1 * m2, m22 - m2 * m2)));
}

// The factor B = [[d1, d2], [0, d3]] with B Bᵀ = K as (d1, d2, d3) (docs/method.md, "The factor";
// bump/roughness.h's roughness_factor()): an upper factor, d1 from the determinant so that rank-1
// K gives no NaN. Non-finite K gives 0.
vec3 fp_roughness_factor(vec3 k) {
    if (!fp_is_finite(k.x + k.y + k.z)) return vec3(0.0);
    float scale = max(0.0, k.x) + max(0.0, k.z);
    if (k.z > 1e-12 * scale && k.z > 0.0) {
        float d3 = sqrt(k.z);
        float bound = sqrt(max(0.0, k.x));
        return vec3(sqrt(max(0.0, k.x * k.z - k.y * k.y) / k.z), clamp(k.y / d3, -bound, bound),
                    d3);
    }
    return vec3(sqrt(max(0.0, k.x)), 0.0, 0.0);
}

// The bump + roughness lookup (bump_lookup() with the default LookupOptions but max_probes):
// footprint assembly over the five moment channels, each probe reading both textures with the
// same weights.
//   moments0:      (μ'1, μ'2, M2'11, M2'12) per texel, every level (BumpPyramid::moments()'s first
//                  four channels), trilinear-filtered, its whole chain down to 1×1
//   moments1:      M2'22 in its red channel, the same size, levels and wrap
//   uv, duv_dx/dy: as fp_texture() (normalised; derivatives per pixel step)
//   slope_offset:  the map's mean slope (BumpPyramid::slope_offset())
//   max_probes:    N_max ≥ 1, as fp_texture()
// Returns μ and K_b in the bump map's frame, slope units (per unit of world length along t1, t2).
FpSlopeStats fp_bump(sampler2D moments0, sampler2D moments1, vec2 uv, vec2 duv_dx, vec2 duv_dy,
                     vec2 slope_offset, int max_probes) {
    ivec2 texels = textureSize(moments0, 0);
    vec2 size = vec2(texels);
    FpPlan plan = fp_texture_plan(size, fp_full_chain_max_level(texels), duv_dx * size,
                                  duv_dy * size, max_probes);
    mat2x4 m;  // the two textures' texels as columns
#define FP_SAMPLE_MOMENTS(i, at, lod) \
    mat2x4(textureLod(moments0, at, lod), textureLod(moments1, at, lod))
    FP_ASSEMBLE(mat2x4, m, plan, uv, size, FP_SAMPLE_MOMENTS)
#undef FP_SAMPLE_MOMENTS
    return fp_slope_stats(m[0], m[1].x, slope_offset);
}

#endif  // FOOTPRINT_GLSL_BUMP
