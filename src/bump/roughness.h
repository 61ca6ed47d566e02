// bump/roughness.h — the slope covariance K_b of a filtered bump map and its stored forms.
//
// Spec §5 (corrects [S97b]): the roughness of a texel is the covariance K_b of the finest-level
// slopes it covers (population normalisation 1/n, §5.1). The papers store an upper-triangular
// factor B = [[d1, d2], [0, d3]] with B Bᵀ = K_b (§5.2; an *upper* factor, not Cholesky's L Lᵀ)
// and, for the isotropic variant, l1 = √λ_max(K_b) (§5.5). Both are derived quantities here:
// filtering blends second moments (bump_pyramid.h), never d1, d2, d3 or l1 (§5.4, [R3]).
#pragma once

#include <footprint/math/footprint_ellipse.h>

namespace footprint {

// B = [[d1, d2], [0, d3]], B Bᵀ = K_b.
struct RoughnessFactor {
    float d1 = 0, d2 = 0, d3 = 0;

    Sym2 covariance() const { return {d1 * d1 + d2 * d2, d2 * d3, d3 * d3}; }  // B Bᵀ
};

// Spec §5.2, robust: never NaN, also for rank-1 K (where the paper's d1 = √(a − b²/c) is NaN in
// 27 % of cases through rounding, [R1z]) and for c = k22 = 0:
//     k22 > ε:  d3 = √k22, d2 = k12/d3, d1 = √(max(0, k11 k22 − k12²)/k22)
//     else:     d1 = √max(0, k11), d2 = 0, d3 = 0
// with ε relative to the trace, and d2 bounded by √k11 (a PSD K has |k12| ≤ √(k11 k22)).
RoughnessFactor roughness_factor(const Sym2& k);

// l1 = √λ_max(K) = √(½(k11 + k22 + hypot(k11 − k22, 2 k12))) (§5.5): σ in every direction ≤ l1.
float isotropic_roughness(const Sym2& k);

// The nearest positive semi-definite matrix (negative eigenvalues set to 0); NaN/Inf give 0.
// Moment blending (K = M2 − μμᵀ) can leave rounding-sized negative eigenvalues.
Sym2 clamp_to_psd(const Sym2& k);

}  // namespace footprint
