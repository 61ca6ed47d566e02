// footprint/texture.glsl — texture filtering by footprint assembly (docs/method.md, "Footprint
// assembly: the probe rules"): the pixel's elliptical footprint covered by a few trilinear probes
// along its major axis, Rule B with Gaussian weights (footprint's default), each probe one
// textureLod. The C++ counterpart is texture/footprint_assembly.h with texture/texture_lookup.h.
//
// The pieces are separate so that any sampler can use them: fp_texture_plan() plans the probes,
// fp_probe_offset()/fp_probe_weight() place and weigh probe i, and FP_ASSEMBLE() is the one loop
// that reads and blends them, given a macro that samples.
#ifndef FOOTPRINT_GLSL_TEXTURE
#define FOOTPRINT_GLSL_TEXTURE

#include "footprint/common.glsl"

// Where the Gaussian probe weights are cut, in σ of the weight Gaussian (kGaussianProbeExtent).
const float FP_GAUSSIAN_PROBE_EXTENT = 2.0;
// One probe where Λ1 ≤ ratio·Λ2 (kIsotropicRatio): a round footprint must not split into two
// coincident probes over rounding.
const float FP_ISOTROPIC_RATIO = 1.001;
// The most probes a plan holds (kMaxProbeCount); max_probes is clamped to it.
const int FP_MAX_PROBE_COUNT = 1024;

// c(N) of N ≥ 2 Gaussian-weighted probes (gaussian_spacing_factor()): the spacing of the probes is
// Δ = σ_g·c(N), σ_g the weights' standard deviation, so that the line's weighted second moment is
// σ_g² (docs/method.md, "Gaussian weights"). c(N) = a/√v_N, a = 2κ_g/(N − 1), v_N the variance,
// in units of u, of the weights exp(−½u²) on N even nodes over u ∈ [−κ_g, κ_g], κ_g =
// FP_GAUSSIAN_PROBE_EXTENT. Computed from that definition, N exps (the C++ tabulates it in
// double); counts outside [2, FP_MAX_PROBE_COUNT] read the nearest end.
float fp_gaussian_spacing(int n) {
    int m = clamp(n, 2, FP_MAX_PROBE_COUNT);
    float a = 2.0 * FP_GAUSSIAN_PROBE_EXTENT / float(m - 1);
    float sum_w = 0.0, sum_wu2 = 0.0;
    for (int i = 0; i < m; ++i) {
        float u = (float(i) - 0.5 * float(m - 1)) * a, w = exp(-0.5 * u * u);
        sum_w += w;
        sum_wu2 += w * u * u;
    }
    return a / sqrt(sum_wu2 / sum_w);
}

// The hardware lod that reads `lod`'s two levels with the blend weight w' = (4^w − 1)/3 instead of
// w (docs/method.md, "Level blend": LodBlend::variance_matched, a line's blend): textureLod at it
// blends linearly with that weight.
float fp_variance_matched_lod(float lod, int max_level) {
    float l0 = min(floor(lod), float(max_level));
    if (l0 >= float(max_level)) return l0;
    float w = lod - l0;
    return l0 + (exp2(2.0 * w) - 1.0) / 3.0;
}

// A plan of probes: N probes at o_i = (i − (N − 1)/2)·step, all at one lod.
struct FpPlan {
    int count;         // N ≥ 1
    vec2 step;         // level-0 texels between neighbouring probes, along r1
    float lod;         // the probes' level, as textureLod takes it (a line's blend already applied)
    float falloff;     // a: weights ∝ exp(−½(a·k)²), k = i − (N − 1)/2
    float texel_size;  // T_p, raised where the line needed more than max_probes probes
};

// lod = clamp(log2 T_p, 0, L_max).
float fp_probe_lod(float texel_size, int max_level) {
    return clamp(log2(max(texel_size, 1.0)), 0.0, float(max_level));
}

// Λ = max(√(λ² + ρ), 1), ρ = clamp(λ1² + λ2² − 1, 0, 1): a semi-axis of `e` with the share of the
// bilinear reconstruction that the ground truth filters (docs/method.md, Rule B).
float fp_planned_axis(FpEllipse e, float l) {
    float rho = clamp(e.l1 * e.l1 + e.l2 * e.l2 - 1.0, 0.0, 1.0);
    return max(sqrt(l * l + rho), 1.0);
}

// Rule B with Gaussian weights on the axes Λ (docs/method.md, "Footprint assembly: the probe
// rules" and "Gaussian weights"): T_p = Λ2; one probe of size √(Λ1 Λ2) where Λ1 ≤ 1.001·Λ2; else
// the fewest N whose spacing σ_g·c(N) is at most T_p (σ_g = √(Λ1² − T_p²)/2), two tried first; past
// max_probes, N = max_probes and T_p raised until the spacing closes the gaps. e in level-0
// texels, max_probes ≥ 1, max_level the coarsest level.
FpPlan fp_plan_probes(FpEllipse e, int max_probes, int max_level) {
    max_probes = min(max_probes, FP_MAX_PROBE_COUNT);
    float l1 = fp_planned_axis(e, e.l1), tp = fp_planned_axis(e, e.l2);  // Λ1, T_p = Λ2
    if (l1 <= tp * FP_ISOTROPIC_RATIO)
        return FpPlan(1, vec2(0.0), fp_probe_lod(sqrt(tp * l1), max_level), 0.0, sqrt(tp * l1));
    float sigma = 0.5 * sqrt(l1 * l1 - tp * tp);
    int n = 2;
    float c = 2.0;  // c(2): two probes at ±σ_g
    if (!(sigma * c <= tp)) {
        // c(N) is near 2κ_g·0.88/(N − 1) from N = 3 on: start there and step to the fewest N.
        n = max(3, int(ceil(2.0 * FP_GAUSSIAN_PROBE_EXTENT * sigma / (tp * 0.88))) + 1);
        c = fp_gaussian_spacing(n);
        while (n < max_probes && sigma * c > tp) c = fp_gaussian_spacing(++n);
        while (n > 3) {
            float fewer = fp_gaussian_spacing(n - 1);
            if (!(sigma * fewer <= tp)) break;
            c = fewer;
            --n;
        }
    }
    if (n >= max_probes) {
        n = max(2, max_probes);
        if (max_probes == 1)
            return FpPlan(1, vec2(0.0), fp_probe_lod(max(tp, l1), max_level), 0.0, max(tp, l1));
        // Raise T_p until the spacing closes the gaps.
        c = fp_gaussian_spacing(n);
        tp = max(tp, l1 * 0.5 * c / sqrt(1.0 + 0.25 * c * c));
        sigma = 0.5 * sqrt(max(0.0, l1 * l1 - tp * tp));
    }
    float lod = fp_variance_matched_lod(fp_probe_lod(tp, max_level), max_level);
    return FpPlan(n, (sigma * c) * e.r1, lod, 2.0 * FP_GAUSSIAN_PROBE_EXTENT / float(n - 1), tp);
}

// Whether `plan` raised its probes' level because the line needed more than its max_probes
// (exceeds_probe_budget(): the clamped anisotropy that blurs the minor axis).
bool fp_exceeds_probe_budget(FpPlan plan, FpEllipse e) {
    return plan.count > 1 && plan.texel_size > 1.0001 * fp_planned_axis(e, e.l2);  // beyond Λ2
}

// Probe i's offset from the footprint's centre, level-0 texels: o_i = (i − (N − 1)/2)·step.
vec2 fp_probe_offset(FpPlan plan, int i) {
    return (float(i) - 0.5 * float(plan.count - 1)) * plan.step;
}

// Probe i's (unnormalised) weight: exp(−½(a·k)²), k = i − (N − 1)/2; 1 for one or two probes.
float fp_probe_weight(FpPlan plan, int i) {
    float k = float(i) - 0.5 * float(plan.count - 1);
    return plan.count <= 2 ? 1.0 : exp(-0.5 * (plan.falloff * k) * (plan.falloff * k));
}

// The ellipse of K (level-0 texels) as the plans take it: a non-finite K reads as a point, and
// axes beyond 4 × the larger side read the coarsest levels anyway, so they are clamped there
// (which keeps the probes' positions and squares finite).
FpEllipse fp_planned_ellipse(vec3 k, vec2 size) {
    FpEllipse e = fp_is_finite(k.x + k.y + k.z) ? fp_ellipse_of(k) : FpEllipse(0.0, 0.0, vec2(1, 0));
    float limit = 4.0 * max(size.x, size.y);
    e.l1 = min(e.l1, limit);
    e.l2 = min(e.l2, limit);
    return e;
}

// The plan of a 2D lookup with footprint D = (d_dx, d_dy), the columns ∂X/∂x, ∂X/∂y in level-0
// texels, on a map of level-0 size `size` (texels) and coarsest level max_level. Magnification
// (tr K ≤ 1) and a non-finite D read the bilinear reconstruction itself: one probe of level 0
// (docs/method.md, "Magnification").
FpPlan fp_texture_plan(vec2 size, int max_level, vec2 d_dx, vec2 d_dy, int max_probes) {
    float trace = dot(d_dx, d_dx) + dot(d_dy, d_dy);
    if (!fp_is_finite(trace) || trace <= 1.0) return FpPlan(1, vec2(0.0), 0.0, 0.0, 1.0);
    return fp_plan_probes(fp_planned_ellipse(fp_footprint_matrix(d_dx, d_dy), size), max_probes,
                          max_level);
}

// The loop of footprint assembly, C = Σ w_i probe_i / Σ w_i (docs/method.md, "Footprint
// assembly"), written once for every sampler: `result`, a variable of type TYPE (vec3, vec4,
// mat2x4: anything float · TYPE adds up in), receives the blend of SAMPLE(i, at, lod) over the
// plan's probes, `at` = centre + o_i / size the probe's centre in normalised coordinates (size:
// level-0 texels per unit of `centre`), `lod` the plan's. SAMPLE is a function-like macro that
// reads one trilinear probe, e.g.
//     #define MY_SAMPLE(i, at, lod) textureLod(my_texture, at, lod)
//     vec4 c; FP_ASSEMBLE(vec4, c, plan, uv, size, MY_SAMPLE)
#define FP_ASSEMBLE(TYPE, result, plan, centre, size, SAMPLE)                                    \
    {                                                                                            \
        result = TYPE(0.0);                                                                      \
        float fp_weight_sum = 0.0;                                                               \
        for (int fp_i = 0; fp_i < (plan).count; ++fp_i) {                                        \
            float fp_w = fp_probe_weight(plan, fp_i);                                            \
            result += fp_w * SAMPLE(fp_i, (centre) + fp_probe_offset(plan, fp_i) / (size),       \
                                    (plan).lod);                                                 \
            fp_weight_sum += fp_w;                                                               \
        }                                                                                        \
        result *= 1.0 / fp_weight_sum;                                                           \
    }

// A texture filtered by footprint assembly (texture_lookup() with the default LookupOptions but
// max_probes).
//   tex:           trilinear-filtered (GL_LINEAR_MIPMAP_LINEAR) with its whole chain of levels down
//                  to 1×1, each the box-filtered level of footprint's MipPyramid (or the driver's);
//                  its wrap mode is the lookup's
//   uv:            the texture coordinates, normalised (textureLod's)
//   duv_dx/dy:     ∂uv/∂x and ∂uv/∂y per pixel step, normalised units (OpenImageIO's dsdx … dtdy;
//                  dFdx(uv) where nothing better is known; zero: a bilinear point sample)
//   max_probes:    N_max ≥ 1, the most probes along the major axis (footprint's default 30);
//                  beyond it the probes' level rises
// Returns the filtered texel, its kernel covariance K/4 about the bilinear reconstruction
// (docs/method.md, "The measure").
vec4 fp_texture(sampler2D tex, vec2 uv, vec2 duv_dx, vec2 duv_dy, int max_probes) {
    ivec2 texels = textureSize(tex, 0);
    vec2 size = vec2(texels);
    FpPlan plan = fp_texture_plan(size, fp_full_chain_max_level(texels), duv_dx * size,
                                  duv_dy * size, max_probes);
    vec4 result;
#define FP_SAMPLE_2D(i, at, lod) textureLod(tex, at, lod)
    FP_ASSEMBLE(vec4, result, plan, uv, size, FP_SAMPLE_2D)
#undef FP_SAMPLE_2D
    return result;
}

// The same with the Jacobian J = ∂uv/∂(x, y): its columns J[0] = ∂uv/∂x and J[1] = ∂uv/∂y (GLSL's
// mat2 is column-major: mat2(∂u/∂x, ∂v/∂x, ∂u/∂y, ∂v/∂y)).
vec4 fp_texture_jacobian(sampler2D tex, vec2 uv, mat2 J, int max_probes) {
    return fp_texture(tex, uv, J[0], J[1], max_probes);
}

#endif  // FOOTPRINT_GLSL_TEXTURE
