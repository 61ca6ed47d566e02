// footprint/highlight.glsl — highlights widened by the filtered slope covariance K_b
// (docs/method.md, "Shading" and "Microfacet highlights from the slope moments";
// shading/blinn_phong.h, shading/microfacet.h, shading/fresnel.h), in float.
//
// Every function takes a shading frame: n the unit (mean, bumped) normal, (e1, e2) a unit tangent
// pair with e1 × e2 = n, and K_b (xx, xy, yy) in that frame (slope units², e.g. fp_bump()'s k
// carried into it). K_b = 0 gives the textbook lobes.
#ifndef FOOTPRINT_GLSL_HIGHLIGHT
#define FOOTPRINT_GLSL_HIGHLIGHT

#include "footprint/common.glsl"

// Schlick's Fresnel F = F0 + (1 − F0)(1 − cos θ)⁵, cos θ clamped to [0, 1].
float fp_schlick_fresnel(float f0, float cos_theta) {
    float c = clamp(1.0 - cos_theta, 0.0, 1.0);
    float c2 = c * c;
    return f0 + (1.0 - f0) * c2 * c2 * c;
}

// Per channel of a coloured F0 (a metal's).
vec3 fp_schlick_fresnel3(vec3 f0, float cos_theta) {
    float w = fp_schlick_fresnel(0.0, cos_theta);
    return f0 + (1.0 - f0) * w;
}

// The plain Blinn-Phong lobe cos^m a (cos a = n·h).
float fp_blinn_phong(float cos_a, float shininess) {
    if (!(cos_a > 0.0)) return 0.0;
    return pow(min(cos_a, 1.0), max(0.0, shininess));
}

// cos²a' = cos²a / (term + cos²a).
float fp_modified_cos2(float cos2, float term) {
    float den = term + cos2;
    return den > 0.0 ? cos2 / den : 0.0;
}

// The roughness-aware Blinn-Phong lobe, the Gaussian-consistent form (docs/method.md, "Shading"):
// cos²a' = cos²a / (dᵀ(I + m K_b)⁻¹ d + cos²a), lobe (cos a')^m / √det(I + m K_b), which is the
// plain lobe convolved with the slopes N(0, K_b): roughness widens the highlight and keeps its
// energy.
//   cos_a:      n·h, h the unit half vector
//   d:          −(h·e1, h·e2), the tangential part of n − h (|d| = sin a)
//   k_b:        the slope covariance in (e1, e2) (clamped to PSD here)
//   shininess:  m ≥ 0
float fp_rough_blinn_phong(float cos_a, vec2 d, vec3 k_b, float shininess) {
    if (!(cos_a > 0.0)) return 0.0;
    float c = min(cos_a, 1.0), c2 = c * c;
    float m = max(0.0, shininess);
    float xx = max(0.0, k_b.x), yy = max(0.0, k_b.z);
    float bound = sqrt(xx * yy), xy = clamp(k_b.y, -bound, bound);
    float det_rel = 1.0 + m * (xx + yy) + m * m * max(0.0, xx * yy - xy * xy);
    float adj_b = max(0.0, yy * d.x * d.x - 2.0 * xy * d.x * d.y + xx * d.y * d.y);
    float term = (d.x * d.x + d.y * d.y + m * adj_b) / det_rel;
    return pow(fp_modified_cos2(c2, term), 0.5 * m) / sqrt(det_rel);
}

// The Blinn-Phong highlight at half vector h in the frame (n, e1, e2): the rough lobe, or the plain
// one where `rough` is false.
float fp_specular_lobe(bool rough, vec3 n, vec3 e1, vec3 e2, vec3 h, vec3 k_b, float shininess) {
    float cos_a = dot(n, h);
    if (!(cos_a > 0.0)) return 0.0;
    if (!rough) return fp_blinn_phong(cos_a, shininess);
    return fp_rough_blinn_phong(cos_a, vec2(-dot(h, e1), -dot(h, e2)), k_b, shininess);
}

// ---- Microfacet highlights widened by K_b: M = α² I + 2 K_b. M's eigenvalues are ≥ α² ≥ 1e-6, so
// det M ≥ 1e-12 and D ≤ 3.2e5 stay in float's range.

const int FP_HIGHLIGHT_BLINN_PHONG = 0;  // MaterialDesc::Highlight's order
const int FP_HIGHLIGHT_BECKMANN = 1;
const int FP_HIGHLIGHT_GGX = 2;

// D(ĥ) for the local coordinates h = (ĥ·e1, ĥ·e2, ĥ·n) of a unit ĥ and M (xx, xy, yy):
// Q = tᵀM⁻¹t, Beckmann exp(−Q/z²)/(π √det M z⁴), GGX 1/(π √det M (z² + Q)²).
float fp_microfacet_distribution(int model, vec3 h, vec3 m) {
    if (!(h.z > 0.0)) return 0.0;
    float det = m.x * m.z - m.y * m.y;
    float q = max(0.0, m.z * h.x * h.x - 2.0 * m.y * h.x * h.y + m.x * h.y * h.y) / det;
    float z2 = h.z * h.z;
    if (model == FP_HIGHLIGHT_GGX) {
        float den = z2 + q;
        return 1.0 / (FP_PI * sqrt(det) * den * den);
    }
    float exponent = q / z2;
    if (!(exponent < 80.0)) return 0.0;  // e^{−80} ≈ 2e-35; z⁴ might underflow beyond
    return exp(-exponent) / (FP_PI * sqrt(det) * z2 * z2);
}

// Smith's Λ(ω) for local w = (ω·e1, ω·e2, ω·n), q = α_ω² tan²θ = tᵀM t / z²: Beckmann
// (e^{−a²}/(a√π) − erfc a)/2 with a = 1/√q, GGX q/(2(1 + √(1 + q))).
float fp_smith_lambda(int model, vec3 w, vec3 m) {
    float q = max(0.0, m.x * w.x * w.x + 2.0 * m.y * w.x * w.y + m.z * w.y * w.y) / (w.z * w.z);
    if (!(q > 0.0)) return 0.0;
    if (!(q < 1e30)) return 1e30;  // at the horizon (z² rounded to 0): G2 = 0
    if (model == FP_HIGHLIGHT_GGX) return q / (2.0 * (1.0 + sqrt(1.0 + q)));
    // erfc(a) = e^{−a²}·t·poly(t) by Abramowitz & Stegun 7.1.26 (absolute error < 1.5e-7, so Λ's
    // is < 1e-7).
    float a = inversesqrt(q);
    float t = 1.0 / (1.0 + 0.3275911 * a);
    float poly = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 +
                 t * (-1.453152027 + t * 1.061405429))));
    return max(0.0, 0.5 * exp(-a * a) * (1.0 / (a * sqrt(FP_PI)) - poly));
}

// The microfacet highlight f_r·cos_l = D G2 F / (4 cos_v) (docs/method.md, "Microfacet highlights
// from the slope moments"): D of M = α² I + 2 K_b, the height-correlated G2 = 1/(1 + Λ(l) + Λ(v)),
// Schlick's F at v·h per channel of F0.
//   model:     FP_HIGHLIGHT_BECKMANN or FP_HIGHLIGHT_GGX
//   n, e1, e2: the shading frame; l, v: unit directions to the light and to the eye
//   k_b:       the slope covariance in (e1, e2) (clamped to PSD here); alpha: the material's α
//              (r², clamped to [1e-3, 1]); f0: Schlick's F0 per channel
vec3 fp_microfacet_highlight(int model, vec3 n, vec3 e1, vec3 e2, vec3 l, vec3 v, vec3 k_b,
                             float alpha, vec3 f0) {
    float cos_l = dot(n, l), cos_v = dot(n, v);
    if (!(cos_l > 0.0) || !(cos_v > 0.0)) return vec3(0.0);
    vec3 h = normalize(l + v);
    float a = clamp(alpha, 1e-3, 1.0);
    float xx = max(0.0, k_b.x), yy = max(0.0, k_b.z);
    float bound = sqrt(xx * yy), xy = clamp(k_b.y, -bound, bound);
    vec3 m = vec3(a * a + 2.0 * xx, 2.0 * xy, a * a + 2.0 * yy);
    float d = fp_microfacet_distribution(model, vec3(dot(h, e1), dot(h, e2), dot(h, n)), m);
    float g = 1.0 / (1.0 + fp_smith_lambda(model, vec3(dot(l, e1), dot(l, e2), cos_l), m) +
                     fp_smith_lambda(model, vec3(dot(v, e1), dot(v, e2), cos_v), m));
    return d * g * fp_schlick_fresnel3(clamp(f0, 0.0, 1.0), dot(v, h)) / (4.0 * cos_v);
}

#endif  // FOOTPRINT_GLSL_HIGHLIGHT
