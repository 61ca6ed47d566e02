// render/peer_filters.h — (private) the steps of the peers' methods that footprint's own modes do
// not have, for the renderer's peer modes (render/renderer.h; sources in docs/rendering.md#peers):
//
//   toksvig      Toksvig, "Mipmapping normal maps", JGT 10(3), 2005: the MIP pyramid filters unit
//                normals; the shorter their mean n̄, the rougher the region: the slope variance
//                σ² = (1 − |n̄|)/|n̄| (his shininess factor m' = m|n̄|/(|n̄| + m(1 − |n̄|)) is
//                exactly 1/m' = 1/m + σ²: the lobe's slope variance 1/m widened by σ²).
//   specular-aa  Kaplanyan, Hill, Patney & Lefohn, "Filtering distributions of normals for
//                shading antialiasing", HPG 2016; Tokuyoshi & Kaplanyan, "Improved geometric
//                specular antialiasing", I3D 2019: the slope covariance widened by the normal's
//                change across the pixel filter, σ_p² (δx δxᵀ + δy δyᵀ), δ the change of the
//                slope per pixel step (a GPU's quad derivative), σ_p² = ¼ (the variance of
//                the σ = ½-pixel filter), each variance clamped to κ/2 (κ = 0.18 clamps α² =
//                2σ², their recommended value).
//   stochastic   Pharr, Wronski, Salvi & Fajardo, "Filtering after shading with stochastic
//                texture filtering", I3D 2024: each lookup reads one place the filter picks at
//                random with the filter's weights, and the shading that follows is averaged by the
//                pixel's samples (unbiased, noisy).
#pragma once

#include <cmath>
#include <cstdint>

#include "bump/bump_pyramid.h"
#include "image/image.h"
#include "math/footprint_ellipse.h"
#include "math/sample_patterns.h"
#include "math/vec.h"
#include "math/vec3.h"
#include "texture/texture_lookup.h"

namespace footprint::detail {

// A stream of random numbers from one seed: the hash of a counter (math/sample_patterns.h), so a
// sample's draws depend only on the sample.
class RandomStream {
  public:
    explicit RandomStream(std::uint32_t seed) : state_(hash32(seed)) {}
    double uniform() {
        state_ = hash32(state_ + 0x9e3779b9u);
        return unit_float(state_);
    }
    // A standard normal pair (Box–Muller).
    Vec2 gaussian() {
        const double r = std::sqrt(-2.0 * std::log(std::max(1.0 - uniform(), 1e-12)));
        const double phi = 6.283185307179586 * uniform();
        return {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi))};
    }

  private:
    std::uint32_t state_;
};

// Toksvig: the mean slope and the covariance σ² I of a filtered mean `n` of unit normals in the
// slope frame (a slope b is the normal (b1, b2, 1)/√(1 + |b|²)): b̄ = (n_x, n_y)/n_z and
// σ² = (1 − |n̄|)/|n̄|. |n̄| = 0 or n_z ≤ 0 (normals that cancel) gives b̄ = 0 and the largest σ².
SlopeStatistics toksvig_slopes(Vec3 mean_normal);

// The unit normals (b1, b2, 1)/√(1 + |b|²) of a 2-channel slope map × strength: the image whose
// pyramid Toksvig's lookups filter.
Image unit_normals(const Image& slopes, float strength);

// Specular AA: the covariance σ_p² (δx δxᵀ + δy δyᵀ) of the slopes' change per pixel step δx, δy,
// each variance clamped to kMaxVariance (and the covariance with them, so that it stays PSD).
struct ScreenSpaceRoughness {
    static constexpr float kPixelFilterVariance = 0.25f;  // σ_p² of the σ = ½-pixel filter
    static constexpr float kMaxVariance = 0.09f;          // κ/2, κ = 0.18 on α² = 2σ²
};
Sym2 screen_space_roughness(Vec2 dslope_dx, Vec2 dslope_dy);

// Stochastic texture filtering of a lookup whose pixel filter covers the Gaussian of covariance
// K/4 (K = J Jᵀ, J = diag(width, height)·∂(s,t)/∂(x,y), level-0 texels): one bilinear lookup at
// level L, at a position drawn from that Gaussian less what the level's own kernel (box ⊗ tent,
// variance 4^L/4 per axis) already covers. L is the level whose kernel matches the footprint's
// minor axis, lod = log2(2σ_min), with the fraction of the lod drawn at random (stochastic
// trilinear): the expectation is the trilinear-prefiltered Gaussian of K/4. Returns the
// coordinates of a trilinear lookup that reads level L alone (isotropic derivatives of 2^L
// texels, the lod an integer); zero or non-finite derivatives give the position itself at level 0.
TextureCoords stochastic_probe(const TextureCoords& coords, int width, int height,
                               RandomStream& random);

// One slope from N(μ, K) (K's Cholesky factor times a standard normal pair).
Vec2 sample_slope(const SlopeStatistics& slopes, Vec2 standard_normal);

}  // namespace footprint::detail
