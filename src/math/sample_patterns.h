// math/sample_patterns.h — deterministic random numbers and the Gaussian pixel filter's samples,
// shared by every supersampled render (the plane demo's reference, the renderer).
//
// Randomness is a hash of integers (pixel, sample index, seed), never a stateful generator: any
// pixel can be computed alone, in any order, on any thread, with the same result.
#pragma once

#include <cstdint>

namespace footprint {

// PCG's output permutation as a hash (Jarzynski & Olano 2020, "Hash functions for GPU rendering").
constexpr std::uint32_t hash32(std::uint32_t v) {
    v = v * 747796405u + 2891336453u;
    v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    return (v >> 22u) ^ v;
}

// The top 24 bits as a double in [0, 1).
constexpr double unit_float(std::uint32_t bits) {
    return (bits >> 8) * (1.0 / 16777216.0);
}

// Φ⁻¹(p) for p ∈ (0, 1) (Acklam's rational approximation, relative error < 1.2e-9); p ≤ 0 gives
// −∞, p ≥ 1 +∞.
double inverse_normal_cdf(double p);

// The Gaussian pixel filter of σ = ½ pixel truncated at ±3σ (texture/texture_lookup.h: the pixel
// filter whose texel-space image has covariance K/4): maps u ∈ [0, 1) to an offset from the pixel
// centre, in pixels, through Φ⁻¹ on [Φ(−3), Φ(3)]. A stratified u gives stratified offsets.
double gaussian_pixel_offset(double u);

}  // namespace footprint
