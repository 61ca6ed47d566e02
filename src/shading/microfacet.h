// shading/microfacet.h — microfacet highlights (Beckmann, GGX) whose distribution of normals is
// widened by the bump slopes' covariance K_b: the same filtered moments that the rough Blinn-Phong
// of shading/blinn_phong.h takes, in a BRDF of the form every current engine shades with.
//
// Sources. [CT82] Cook & Torrance, "A reflectance model for computer graphics" (the BRDF
// D·G·F/(4 cos_l cos_v)); [W07] Walter, Marschner, Li & Torrance, "Microfacet models for refraction
// through rough surfaces" (GGX: D eq. 33, G1 eq. 34; Beckmann); [H14] Heitz, "Understanding the
// masking-shadowing function in microfacet-based BRDFs" (the slope distribution P22, anisotropy as
// a linear map of the slopes, Smith's Λ with the roughness of the projected direction, the
// height-correlated G2); [OB10] Olano & Baker, "LEAN mapping" (Gaussian slopes: covariances add);
// [TK19] Tokuyoshi & Kaplanyan, "Improved geometric specular antialiasing" (after Kaplanyan et al.
// 2016: a GGX lobe widened as if it were Beckmann, α² = 2σ²).
//
// Frame and slopes. n̂ is the unit shading (mean, bumped) normal and (e1, e2) an orthonormal
// tangent frame with (e1, e2, n̂) right-handed, as in blinn_phong.h. A unit direction ω has local
// coordinates (ω·e1, ω·e2, ω·n̂) = (t, z); a microfacet normal ĥ has the slope s = t/z (the bump
// convention n_m = n̂ + s1 e1 + s2 e2; every distribution here is even in s, so the sign of the
// slope does not matter). K_b is the covariance of the bump slopes in (e1, e2), dimensionless
// (blinn_phong.h's "Roughness").
//
// The roughness matrix. Both models take one symmetric positive definite 2×2 matrix
//     M = α² I + 2 K_b                                              (α: the model's roughness)
// and are then, for a unit ĥ = (t, z) with Q = tᵀM⁻¹t (= z² sᵀM⁻¹s), [H14] D = P22(s)/z⁴:
//   Beckmann  P22(s) = exp(−sᵀM⁻¹s) / (π √det M),   D = exp(−Q/z²) / (π √det M z⁴)
//   GGX       P22(s) = 1 / (π √det M (1 + sᵀM⁻¹s)²), D = 1 / (π √det M (z² + Q)²)
// For K_b = 0 they are the textbook isotropic distributions: exp(−tan²θ/α²)/(π α² cos⁴θ) and
// α²/(π cos⁴θ (α² + tan²θ)²) [W07 eq. 33]; either integrates to ∫ D cos θ_h dω = 1.
//   * Beckmann's slopes are Gaussian with covariance Σ = M/2 = (α²/2) I + K_b: filtering by slopes
//     N(0, K_b) convolves two Gaussians, which is exact [OB10] (LEAN mapping's Σ' = Σ + K_b).
//   * GGX's slopes have infinite variance, so no covariance can be added exactly. M = α² I + 2 K_b
//     is the moment match of [TK19]: K_b enters as the Beckmann lobe of the same slope covariance
//     (α² = 2σ²). It is exact for K_b = 0, keeps the unit integral, and gives the right peak in
//     both limits (K_b ≪ α²: the lobe itself; K_b ≫ α²: the Gaussian N(0, K_b), whose peak 1/(2π
//     σ²) equals GGX's 1/(π α²) at α² = 2σ²). Between them it is too peaked: measured against the
//     numerical convolution of GGX with N(0, K_b) (microfacet_test.cpp; the error depends on K_b/α²
//     only, as slope space scales), for isotropic K_b = σ² I the widened lobe's peak is too high by
//         σ²/α² = 0.125: 14.5 %,   0.25: 20 %,   0.7: 24.3 % (the worst),   2: 20 %,   8: 11 %
//     of the true peak, and its largest deviation anywhere is at most 24.3 % of the true peak (at
//     the peak, up to σ²/α² = 4; beyond, the true lobe turns Gaussian while the widened one keeps
//     GGX's long tails: 14–15 % of the peak at |s| ≈ 0.75 √(α² + 2σ²), and an L1 distance that
//     grows towards that between a Gaussian and a GGX lobe, 34 % of the unit mass at σ²/α² = 8).
//     Anisotropic K_b measure the same (at most 22 % in the tests).
//
// Masking-shadowing: Smith's, height-correlated [H14], G2 = 1/(1 + Λ(l̂) + Λ(v̂)), with Λ of the
// same M. A direction ω = (t, z) sees the roughness α_ω² = t̂ᵀM t̂ of its projected azimuth (t̂ =
// t/|t|, [H14]: exact for any linear map of the slopes), so with q = α_ω² tan²θ = tᵀM t / z²:
//   Beckmann  Λ = (e^{−a²}/(a √π) − erfc a)/2,   a = 1/√q
//   GGX       Λ = (√(1 + q) − 1)/2 = q/(2(1 + √(1 + q)))       [W07 eq. 34: G1 = 1/(1 + Λ)]
// (Height-correlated rather than separable G1(l̂)G1(v̂): it is the exact Smith form for a
// microsurface of uncorrelated heights and slopes, and loses less energy at grazing angles.)
//
// The highlight. f_r = D(ĥ)·G2·F(v̂·ĥ) / (4 cos_l cos_v) [CT82], ĥ = normalize(l̂ + v̂), F Schlick's
// (shading/fresnel.h) at the microfacet's angle v̂·ĥ; microfacet_highlight() returns
//     f_r · cos_l = D G2 F / (4 cos_v)
// the reflected radiance per unit irradiance of a light from l̂ (a directional light's irradiance
// on a plane facing it), to be multiplied by the light and the material's `specular` weight. It is
// reciprocal (f_r(l̂, v̂) = f_r(v̂, l̂)) and its directional albedo ∫ f_r cos_l dω_l is ≤ 1 for F = 1.
// Single scattering loses energy, to masking (G2 < 1) and, with GGX's long tails, to facets that
// reflect below the horizon: facing the light GGX keeps 88 % at α = 0.3, 59 % at α = 0.6, 31 % at
// α = 1; Beckmann 99.97 %, 86 %, 46 % (microfacet_test.cpp).
//
// Conventions for degenerate input. Every function is pure and returns a finite value ≥ 0 for
// finite input; the formulas are evaluated in double.
//   * l̂ or v̂ at or below the horizon of n̂ (cos ≤ 0) gives 0; ĥ is then never degenerate.
//   * α is clamped to [kMinMicrofacetAlpha, 1] (NaN counts as the minimum): the glTF range, and a
//     floor that keeps the peak D = 1/(π α²) ≤ 3.2e5 finite in float.
//   * K_b is clamped to be PSD (negative variances to 0, |k12| to √(k11 k22); NaN to 0), so M is
//     positive definite with eigenvalues ≥ α².
//   * f0 is clamped to [0, 1] (schlick_fresnel() clamps the angle).
#pragma once

#include <array>

#include <footprint/math/footprint_ellipse.h>

namespace footprint {

enum class MicrofacetModel {
    beckmann,  // Gaussian slopes: filtering by the bump slopes is exact
    ggx,       // Trowbridge-Reitz: long tails; filtered by the moment match above
};

// The smallest α microfacet functions use (see "Conventions").
constexpr float kMinMicrofacetAlpha = 1e-3f;

// M = α² I + 2 K_b for α clamped to [kMinMicrofacetAlpha, 1] and K_b clamped to be PSD (above).
Sym2 microfacet_roughness_matrix(float alpha, const Sym2& k_b);

// D(ĥ) for the local coordinates h = (ĥ·e1, ĥ·e2, ĥ·n̂) of a unit ĥ and M (as returned by
// microfacet_roughness_matrix()); ĥ at or below the horizon (h[2] ≤ 0) gives 0, and so does an M
// that is not positive definite and finite.
float microfacet_distribution(MicrofacetModel model, const std::array<float, 3>& h, const Sym2& m);

// Smith's Λ(ω) for the local coordinates of a unit ω (as for ĥ): 0 along n̂, growing towards the
// horizon; ω at or below it, or an M that is not positive definite and finite, give the largest
// float (G2 = 0).
float smith_lambda(MicrofacetModel model, const std::array<float, 3>& w, const Sym2& m);

// The height-correlated G2 = 1/(1 + Λ(l̂) + Λ(v̂)); 0 if either is at or below the horizon.
float smith_masking_shadowing(MicrofacetModel model, const std::array<float, 3>& l,
                              const std::array<float, 3>& v, const Sym2& m);

// f_r · cos_l = D G2 F / (4 cos_v) (above) for unit n̂, (e1, e2), l̂ (towards the light) and v̂
// (towards the eye), the slope covariance K_b in (e1, e2), the model's roughness α and Schlick's
// F0. K_b = 0 gives the unfiltered highlight.
float microfacet_highlight(MicrofacetModel model, const std::array<float, 3>& n,
                           const std::array<float, 3>& e1, const std::array<float, 3>& e2,
                           const std::array<float, 3>& l, const std::array<float, 3>& v,
                           const Sym2& k_b, float alpha, float f0);

// The same highlight split where F0 enters it: Schlick's F = F0 + (1 − F0)(1 − v̂·ĥ)⁵ is linear in
// F0, so a coloured F0 (a metal's) takes one evaluation for its three channels:
//     f_r · cos_l = dg · (f0 + (1 − f0) · schlick)
struct MicrofacetTerms {
    float dg = 0;                 // D G2 / (4 cos_v)
    float schlick = 0;            // (1 − v̂·ĥ)⁵
    float times(float f0) const;  // dg · F(f0), f0 clamped to [0, 1]
};
MicrofacetTerms microfacet_terms(MicrofacetModel model, const std::array<float, 3>& n,
                                 const std::array<float, 3>& e1, const std::array<float, 3>& e2,
                                 const std::array<float, 3>& l, const std::array<float, 3>& v,
                                 const Sym2& k_b, float alpha);

}  // namespace footprint
