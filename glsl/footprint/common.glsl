// footprint/common.glsl — what every part of footprint's GLSL library shares: constants, the
// footprint ellipse of a matrix K and the nearest positive semi-definite matrix.
//
// The library implements Andreas Schilling's texture, bump and environment filtering as
// docs/method.md describes it, as GLSL functions that take everything as arguments: no uniforms,
// no buffers, no globals. Public names begin with fp_ (functions), Fp (types) and FP_ (constants,
// macros), so that they do not meet an engine's own. Include the parts you use:
//     #include "footprint/texture.glsl"      // fp_texture, fp_texture_jacobian
//     #include "footprint/bump.glsl"         // fp_bump, fp_slope_stats
//     #include "footprint/highlight.glsl"    // fp_rough_blinn_phong, fp_microfacet_highlight
//     #include "footprint/environment.glsl"  // fp_environment_footprint, fp_environment_cube
// (GL_ARB_shading_language_include style, relative to the folder that holds footprint/; each file
// includes what it needs once, behind its guard). docs/engine.md lists the functions.
//
// Conventions (docs/method.md, "Conventions"): a symmetric 2×2 matrix is a vec3 (xx, xy, yy);
// footprints are in level-0 texels: D = diag(W0, H0)·∂(s,t)/∂(x,y), K = D Dᵀ, whose ellipse
// ξᵀK⁻¹ξ = 1 is the image of one pixel step.
#ifndef FOOTPRINT_GLSL_COMMON
#define FOOTPRINT_GLSL_COMMON

#include "footprint/version.glsl"

const float FP_PI = 3.14159265358979323846;

bool fp_is_finite(float x) {
    return !isnan(x) && !isinf(x);
}

// The footprint ellipse of K (docs/method.md, "The footprint ellipse"): semi-axes l1 ≥ l2 ≥ 0 and
// the unit major axis r1, from the eigenvector form that is stable in float for every K (no
// cancellation in λ2², which the papers' (k11 + k22 − W)/2 suffers). K = 0 gives (0, 0, (1, 0)).
struct FpEllipse {
    float l1, l2;  // λ1, λ2: level-0 texels
    vec2 r1;       // the major axis, unit length
};

FpEllipse fp_ellipse_of(vec3 k) {
    float w = sqrt((k.x - k.z) * (k.x - k.z) + 4.0 * k.y * k.y);
    float major_sq = 0.5 * (k.x + k.z + w);
    float minor_sq = major_sq > 0.0 ? max(0.0, k.x * k.z - k.y * k.y) / major_sq : 0.0;
    float l1 = sqrt(max(0.0, major_sq));
    vec2 r = k.x >= k.z ? vec2(k.x - k.z + w, 2.0 * k.y) : vec2(2.0 * k.y, k.z - k.x + w);
    float len = length(r);
    return FpEllipse(l1, min(sqrt(minor_sq), l1),
                     len > 0.0 && !isinf(len) ? r / len : vec2(1.0, 0.0));
}

// K = D Dᵀ of D's columns d_dx = ∂X/∂x, d_dy = ∂X/∂y (docs/method.md: K = D Dᵀ, not the papers'
// DᵀD, whose eigenvectors are screen space's).
vec3 fp_footprint_matrix(vec2 d_dx, vec2 d_dy) {
    return vec3(d_dx.x * d_dx.x + d_dy.x * d_dy.x, d_dx.x * d_dx.y + d_dy.x * d_dy.y,
                d_dx.y * d_dx.y + d_dy.y * d_dy.y);
}

// The nearest positive semi-definite matrix to K (negative eigenvalues set to 0; non-finite K
// gives 0): a covariance recovered as M2 − μμᵀ may round below zero (docs/method.md, "The moment
// pyramid").
vec3 fp_clamp_to_psd(vec3 k) {
    if (!fp_is_finite(k.x + k.y + k.z)) return vec3(0.0);
    if (k.x >= 0.0 && k.z >= 0.0 && k.x * k.z - k.y * k.y >= 0.0) return k;
    float w = sqrt((k.x - k.z) * (k.x - k.z) + 4.0 * k.y * k.y);
    float major = max(0.0, 0.5 * (k.x + k.z + w)), minor = max(0.0, 0.5 * (k.x + k.z - w));
    vec2 r = k.x >= k.z ? vec2(k.x - k.z + w, 2.0 * k.y) : vec2(2.0 * k.y, k.z - k.x + w);
    float len = length(r);
    r = len > 0.0 ? r / len : vec2(1.0, 0.0);
    vec2 q = vec2(-r.y, r.x);
    return major * vec3(r.x * r.x, r.x * r.y, r.y * r.y) +
           minor * vec3(q.x * q.x, q.x * q.y, q.y * q.y);
}

// The coarsest level of a texture of level-0 size `size` that holds its whole chain down to 1×1
// (docs/method.md, "Conventions": W_l = max(1, ⌊W0/2^l⌋)): ⌊log2 max(W0, H0)⌋, counted in integers
// (GLSL ES 3.0 has neither textureQueryLevels nor findMSB, and log2 may round below an integer).
int fp_full_chain_max_level(ivec2 size) {
    int level = 0;
    for (int m = max(size.x, size.y); m > 1; m /= 2) ++level;
    return level;
}

#endif  // FOOTPRINT_GLSL_COMMON
