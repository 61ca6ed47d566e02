// shading/fresnel.h — Schlick's Fresnel, and Fresnel over a distribution of slopes.
//
// A filtered pixel knows its bump slopes only by their mean b̄ and covariance K (spec §5). Its
// mirror reflection is the mean over the slopes of F(n̂(b)·v̂) · R(b): Fresnel F and the
// reflected environment R both depend on the slope, and together. At grazing angles they are
// strongly correlated — a facet tilted away from the eye reflects both lower and more — so
// F(n̂(b̄)·v̂) · E[R] is biased, and more samples per pixel do not remove that bias
// (`footprint eval --budget`: the mirror term against fresnel and reflection, docs/method.md).
//
// Slopes that turn the normal away from the eye (c = n̂·v̂ < 0) are shaded with the surface's own
// normal (spec §4: the bump is dropped), so they are set apart: P(c < 0) is their share. Over the
// rest, the mean of the product is E[F] times the mean of R under the slopes weighted by F:
//     E[F·R; c ≥ 0] = E[F; c ≥ 0] · E_F[R],     E_F[·] = E[F ·; c ≥ 0]/E[F; c ≥ 0]
// With cos θ = n̂·v̂ linear in the slope near b̄, c(b) = c̄ + uᵀ(b − b̄) (u = ∂c/∂b), c is
// Gaussian with σ_c² = uᵀKu, and with z = (c − c̄)/σ_c ~ N(0, 1) the weighted distribution of the
// slopes has (exactly, for that linear c and Gaussian slopes)
//     mean        b̄ + K u · E[zF] / (σ_c E[F])
//     covariance  K − (1 − Var_F(z)) · K u uᵀ K / σ_c²,   Var_F(z) = E[z²F]/E[F] − (E[zF]/E[F])²
// The three scalar means E[F; c ≥ 0], E[zF; c ≥ 0], E[z²F; c ≥ 0] are exact: Schlick's F is a
// quintic in c on [0, 1] and F0 above, so each is a sum of incomplete moments of the normal
// distribution (erfc and the density). The reflection is then looked up with the weighted mean and
// covariance — the same one filtered lookup as before, at a shifted slope with a narrowed
// footprint.
#pragma once

#include <footprint/math/footprint_ellipse.h>
#include <footprint/math/vec.h>

namespace footprint {

// Schlick: f0 + (1 − f0)(1 − cos θ)⁵, cos θ clamped to [0, 1].
float schlick_fresnel(float f0, float cos_theta);

// Fresnel over Gaussian slopes (above).
struct FresnelOverSlopes {
    float mean = 0;         // E[F · (c ≥ 0)]: over the facets that face the eye
    float facing_away = 0;  // P(c < 0)
    Vec2 mean_slope_shift;  // the F-weighted mean slope − b̄
    Sym2 covariance;        // the F-weighted covariance of the slopes
    // E[(1 − c)⁵; 0 ≤ c ≤ 1], Schlick's angular factor over the facets that face the eye. F is
    // linear in F0, so this and facing_away give the mean of every F0 (mean_fresnel()): a colour's
    // three channels from one call.
    float schlick = 0;
};

// `cos_mean` = c̄ = n̂(b̄)·v̂, `dcos_dslope` = u = ∂(n̂·v̂)/∂b at b̄, `k` = the slopes' covariance K,
// all in the coordinates of b. K = 0 or u = 0 give F(c̄), no shift, K itself and none facing
// away.
FresnelOverSlopes fresnel_over_slopes(float f0, float cos_mean, Vec2 dcos_dslope, const Sym2& k);

// E[F; c ≥ 0] for Schlick's F of `f0` over the slopes `over` was computed for (with any F0):
// f0 (1 − facing_away) + (1 − f0) schlick.
float mean_fresnel(const FresnelOverSlopes& over, float f0);

}  // namespace footprint
