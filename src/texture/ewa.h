// texture/ewa.h — the elliptical weighted average (Heckbert 1989; pbrt-v4's MIPMap::EWA).
//
// EWA is footprint's high-quality reference filter: a truncated Gaussian over the footprint
// ellipse, summed texel by texel. Like pbrt-v4 it (1) orders the axes, (2) clamps the anisotropy
// to max_anisotropy by growing the minor axis, (3) picks the level from the minor axis and
// (4) blends the sums of two adjacent levels. It differs where footprint's measure convention
// (spec §2.6) asks for it: the kernel covariance is K/4 exactly, on every level:
//
//   magnify     λ1 ≤ 1 level-0 texel: a bilinear sample (like footprint assembly), not a blur.
//   level       lod = log2(λ2) − 1.5 + lod_bias, clamped to [0, L_max]; levels ⌊lod⌋ and ⌊lod⌋+1
//               blended linearly. Texels of size T ≤ λ2/√2 keep the Gaussian ≥ 0.64 texels wide
//               across the minor axis, where a sampled Gaussian keeps its variance to 1 %.
//   Gaussian    Σ = K/4 − (v_l + 1/12)·I, v_l = the level's prefilter variance
//               (MipPyramid::prefilter_variance), so prefilter + Gaussian = K/4; each eigenvalue
//               is floored at (kEwaMinSigma·T)².
//   weights     w(ξ) = exp(−½ q) − exp(−½·9) for q = ξᵀΣ'⁻¹ξ < 9 (3σ; continuous at the cut, as
//               pbrt's), Σ' = Σ / ewa_truncation_variance() so that the truncated kernel has
//               covariance Σ; texels are visited row by row over the exact span of the truncation
//               ellipse, with the pyramid's wrap modes.
//   thin levels a level one texel high (wide) reads the same row (column) at every y (x), so the
//               Gaussian's spread that way is squeezed to kEwaThinLevelSigma: the rows visited
//               would otherwise grow with the texture's aspect ratio (ewa_squeeze_thin_level).
#pragma once

#include <cmath>

#include <footprint/math/footprint_ellipse.h>

namespace footprint {

// Radius of the truncation in σ units.
constexpr float kEwaTruncationSigmas = 3.0f;
// Smallest Gaussian σ in texels of the level summed. A sampled Gaussian reproduces a linear ramp
// up to its aliasing term ≈ 4πσ²·e^{−2π²σ²}: 4e−3 texel at σ = 0.6.
constexpr float kEwaMinSigma = 0.6f;
// Largest σ, in texels of the level summed, across a level one texel thick. Rows of a sampled
// Gaussian this wide sum to its continuous marginal to float rounding, so squeezing a wider one
// to it leaves the weights along the level as they were.
constexpr float kEwaThinLevelSigma = 4.0f;
// The variance the truncated, shifted 2-D Gaussian w(r) = e^{−r²/2} − c (r < R, c = e^{−R²/2})
// keeps relative to the untruncated one:
//   E[r²]/2 = (2 − (R² + 2)c − cR⁴/4) / (2((1 − c) − cR²/2)) = 0.88020 for R = 3.
inline float ewa_truncation_variance() {
    const double r2 = double(kEwaTruncationSigmas) * kEwaTruncationSigmas;
    const double c = std::exp(-0.5 * r2);
    return static_cast<float>((2 - (r2 + 2) * c - c * r2 * r2 / 4) / (2 * ((1 - c) - c * r2 / 2)));
}

// The Gaussian covariance EWA sums on a level (level-0 texels²) for footprint matrix K:
// K/4 − (prefilter variance + 1/12)·I with eigenvalues floored at (kEwaMinSigma·texel_size)².
// Exposed so that tests can rebuild the exact weights by brute force.
Sym2 ewa_gaussian_covariance(const FootprintEllipse& footprint, float prefilter_variance,
                             float texel_size);

// Σ' (the level's texels²) with its spread across a level one texel high (or wide) scaled down to
// kEwaThinLevelSigma, the covariance along the level kept; unchanged on any other level. Every
// wrap mode maps all rows of a one-texel level to its one row, so only the number of rows summed
// changes: on the coarse levels of a W × 1 texture it would otherwise grow with W.
Sym2 ewa_squeeze_thin_level(Sym2 sigma, int width, int height);

}  // namespace footprint
