// shading/blinn_phong.h — Blinn-Phong highlights on rough (filtered bump-mapped) surfaces:
// the modified Blinn-Phong model of [S97b] Appendix A as corrected by the spec (§7, errata 14–15).
//
// Geometry (spec §7). n̂ is the unit (bump-perturbed, mean) normal, (e1, e2) the orthonormal
// tangent frame of spec §6 with (e1, e2, n̂) right-handed, ĥ the unit half vector. Then
//     cos a = n̂·ĥ,      d = −(ĥ·e1, ĥ·e2)      (the tangential part of n̂ − ĥ in (e1, e2)),
// so |d| = sin a and cos²a = 1 − |d|². The slope of ĥ relative to n̂ is d/cos a, |d|/cos a = tan a.
//
// Roughness. K_b is the 2×2 covariance of the bump *slopes* inside the filtered region, in the
// same (e1, e2) frame (spec §5; dimensionless, slope units: a slope of 0.1 tilts the normal by
// atan 0.1 ≈ 5.7°). Its stored factor is the upper triangular B = [[d1, d2], [0, d3]] with
// B Bᵀ = K_b (spec §5.2), so |Bᵀd|² = dᵀK_b d. The variance of the slopes in direction d̂ is
// σ²(d̂) = d̂ᵀK_b d̂ (the support function, not the distance to the 1σ ellipse: erratum 14).
//
// The modified model replaces cos a by cos a' before raising to the power m:
//   paper (corrected)  cos²a' = cos²a / ( |d|⁴/|Bᵀd|² + cos²a ),  i.e. tan a' = tan a / σ(d̂)
//                      ([S97b] prints |Dd|; with D Dᵀ = K that is dᵀDᵀDd ≠ dᵀKd: erratum 15.
//                      D, not D⁻¹: K → 0 gives a mirror-sharp highlight, K → ∞ a flat one.)
//   isotropic          cos²a' = l1² cos²a / (1 − cos²a + l1² cos²a),  l1² = λ_max(K) (spec §5.5)
//   Gaussian           |d|⁴/|Bᵀd|² replaced by dᵀK⁻¹d (elliptical contours). The paper's term is
//                      ≤ this one (so its cos²a' ≥), equal for isotropic K or d on a principal
//                      axis.
// In these three σ = 1 means "unchanged Blinn-Phong": the K they take is roughness *relative to
// the base lobe*. Because (cos a)^m ≈ exp(−m tan²a / 2) is a slope Gaussian of covariance I/m,
// the slope covariance K_b of the surface enters as K_rel = I + m K_b (relative_roughness()).
// The recommended, energy-consistent form (rough_blinn_phong()) is
//     cos²a' = cos²a / ( dᵀ(I + m K_b)⁻¹d + cos²a ),   L = (cos²a')^{m/2} / sqrt(det(I + m K_b)),
// which equals the plain lobe (cos a)^m convolved with the slope distribution N(0, K_b) to within
// 0.13 % of the peak at m = 400 (spec [B7]; up to 0.14 % for the other K_b in the tests);
// roughness widens the lobe and keeps its integral.
//
// Conventions for degenerate input. Every function is pure and returns a finite value in [0, 1]
// (rough_blinn_phong: [0, 1] too, its peak being 1/sqrt(det) ≤ 1) for finite input:
//   * d = 0 (ĥ = n̂) gives cos²a' = 1: the 0/0 term |d|⁴/|Bᵀd|² (or dᵀK⁻¹d) is defined as 0.
//   * cos²a is clamped to [0, 1]; cos a ≤ 0 (ĥ at or below the horizon of n̂) gives L = 0.
//   * A direction of zero variance (K = 0, or rank-1 K and d off its range) is mirror-sharp: the
//     term is +∞ and cos²a' = 0. A slightly indefinite K (rounding) counts as singular.
//   * shininess m < 0 is treated as 0 (L = 1/sqrt(det) everywhere above the horizon).
#pragma once

#include <array>

#include <footprint/math/footprint_ellipse.h>
#include <footprint/math/vec.h>

namespace footprint {

// Plain Blinn-Phong lobe (cos a)^m for cos a > 0, else 0; cos a > 1 (rounding) counts as 1.
float blinn_phong(float cos_a, float shininess);

// Corrected paper form (spec §7, first bullet): cos²a / ( |d|⁴/(dᵀK_b d) + cos²a ). Here k_b is
// the roughness relative to the base lobe (σ = 1: unchanged); d = 0 gives 1.
float modified_cos2_paper(float cos2_a, Vec2 d, const Sym2& k_b);

// Isotropic form (spec §7, [B3]): l1² cos²a / (1 − cos²a + l1² cos²a), l1 = relative roughness
// (l1 = 1: unchanged). cos²a ≥ 1 gives 1; l1 = 0 gives 0 for cos²a < 1.
float modified_cos2_isotropic(float cos2_a, float l1);

// Gaussian-consistent form (spec §7, [B5]): cos²a / ( dᵀK⁻¹d + cos²a ) with K = k_rel, the
// relative roughness. Singular K (zero, rank-1, slightly indefinite) is handled as the limit of
// K + εI: a component of d along a zero-variance direction gives 0; d = 0 gives 1.
float modified_cos2_gaussian(float cos2_a, Vec2 d, const Sym2& k_rel);

// K_rel = I + m K_b: the slope covariance K_b of the surface expressed relative to the base lobe
// (cos a)^m of shininess m (spec §7, "Units / recommended use").
inline Sym2 relative_roughness(const Sym2& k_b, float shininess) {
    return Sym2{1, 0, 1} + shininess * k_b;
}

// The recommended energy-consistent rough Blinn-Phong lobe (spec §7, [B7]):
//   cos²a' = cos²a / ( dᵀ(I + m K_b)⁻¹d + cos²a ),   returns (cos²a')^{m/2} / sqrt(det(I + m K_b)).
// cos_a = n̂·ĥ (≤ 0 gives 0), d as above, k_b the absolute slope covariance (K_b = 0 gives
// blinn_phong(cos_a, m) up to rounding when |d|² = 1 − cos²a), m = shininess. K_b is first
// clamped to be PSD (negative variances to 0, |k12| to sqrt(k11 k22)).
float rough_blinn_phong(float cos_a, Vec2 d, const Sym2& k_b, float shininess);

// cos a and d of the unit half vector ĥ in the frame (e1, e2, n̂) (see the top of this file).
struct HalfVectorGeometry {
    float cos_a = 1;  // n̂·ĥ
    Vec2 d;           // −(ĥ·e1, ĥ·e2), |d| = sin a
};
HalfVectorGeometry half_vector_geometry(const std::array<float, 3>& n,
                                        const std::array<float, 3>& e1,
                                        const std::array<float, 3>& e2,
                                        const std::array<float, 3>& h);

// Which shape the rough highlight takes in specular(). All four agree with the plain lobe for
// K_b = 0, and paper = isotropic = gaussian for isotropic K_b.
enum class RoughShadingModel {
    plain,      // (cos a)^m; K_b ignored (what unfiltered bump mapping does)
    paper,      // modified_cos2_paper (directional σ) with K_rel = I + m K_b, × 2/tr K_rel
    isotropic,  // modified_cos2_isotropic, l1² = λ_max(I + m K_b) = 1 + m λ_max(K_b), × 1/l1²
    gaussian,   // rough_blinn_phong: the recommended form, × 1/sqrt(det K_rel)
};

// The specular lobe L (peak 1 for K_b = 0; multiply by k_s and the light) for unit vectors n̂,
// (e1, e2) and ĥ, the absolute slope covariance K_b in the (e1, e2) frame (dimensionless) and the
// Blinn-Phong exponent m; ĥ at or below the horizon of n̂ gives 0. The rough models use the spec's
// units (K_rel = I + m K_b) and are normalised so that their integral over the slope plane equals
// the plain lobe's, 2π/(m − 2), exactly: a lobe (1 + r²/σ²(θ))^{−m/2} integrates to
// ∫σ²(θ)dθ/(m − 2), which is π tr K (paper), 2π l1² (isotropic), 2π sqrt(det K) (gaussian).
// Only gaussian matches the convolution with N(0, K_b) pointwise ([B7]); paper and isotropic are
// kept for comparison (isotropic is conservative: before normalisation its lobe is at least as
// wide as the gaussian one in every direction).
float specular(RoughShadingModel model, const std::array<float, 3>& n,
               const std::array<float, 3>& e1, const std::array<float, 3>& e2,
               const std::array<float, 3>& h, const Sym2& k_b, float shininess);

}  // namespace footprint
