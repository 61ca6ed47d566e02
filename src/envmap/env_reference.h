// envmap/env_reference.h — the brute-force ground truth for environment lookups: a dense quadrature
// of the finest level over the Gaussian footprint on the sphere.
//
// What it computes. The ideal antialiased environment lookup in footprint's measure (spec §2.6:
// a σ = ½-pixel Gaussian pixel filter, so a footprint K = D Dᵀ is honoured by a kernel of
// covariance K/4) is the map's finest-level reconstruction integrated against a Gaussian of
// directions around the lookup direction r̂:
//
//     C = E[ f(normalize(r̂ + a·axis1 + b·axis2)) ],   (a, b) ~ N(0, 1) independent,
//     f = environment_bilinear(map, ·, level 0)   (seamless across cube edges and the lat-long
//     seam)
//
// The footprint is a SphereGaussian: a Gaussian in the tangent plane at r̂ (axes ⟂ r̂, lengths =
// standard deviations in radians), mapped to the sphere by central projection. For the footprint of
// a pixel with ray differentials ∂r/∂x, ∂r/∂y its tangent covariance is
//
//     Σ = ¼ (P ∂r/∂x ∂r/∂xᵀ P + P ∂r/∂y ∂r/∂yᵀ P) / |r|²,   P = I − r̂ r̂ᵀ,
//
// the pixel step mapped onto the unit sphere with the ¼ of K/4 (spec §2.6, §2.8), so that in the
// texel space of any layout (to first order) S J_P(r̂) Σ J_P(r̂)ᵀ S = K/4, K the footprint of
// compute_env_footprint form (a) (env_footprint.h). Unlike the lookups it involves no texel-space
// linearisation, no pyramid and no per-layout special case: poles, cube edges and corners, seams,
// the sphere-map rim and the paraboloid equator are all just directions at which the level-0
// reconstruction is sampled. Different layouts of the same environment therefore give the same
// reference up to their reconstruction (bilinear interpolation) error.
//
// Quadrature. A square grid of nodes (a_i, b_j), i, j symmetric about 0 (the centre is a node),
// over |a|, |b| ≤ cutoff_sigma, with Gaussian weights exp(−(a² + b²)/2) normalised to sum 1, in
// double precision (the 3.5σ square drops 0.05 % of the weight, renormalised away). The steps are
// chosen per axis so that neighbouring nodes land ≤ step_texels level-0 texels apart on the map —
// texels per radian measured by the layout's Jacobian (env_jacobian × texel_scale) at the centre
// and on a 5×5 lattice over the grid's square, the largest of them — and so that there are at
// least two nodes per σ (which makes the Gaussian's own sum exact to ~1e−30 for smooth
// integrands); each axis has at most max_samples_per_axis nodes (then the step is larger than
// asked: near the lat-long poles, where the texels shrink in s without bound, and for footprints
// spanning hundreds of texels). A zero axis is one node, so a zero-size footprint is the bilinear
// point sample. Quadrature error with the defaults (env_reference_test.cpp): ≤ 4e−4 on a 0…1
// environment with wavelengths down to ~20 texels — ~1e−4 from the 3.5σ cut, the rest from the
// ½-texel step over the reconstruction's kinks at texel edges (it falls as step²).
//
// Cost: (nodes per axis)² bilinear taps — about (2·3.5·2σ_texels)² for a footprint of σ texels,
// 10⁴ for σ = 4 texels, 10⁶ at the cap: orders of magnitude more than a filtered lookup. For
// tests, benchmark error figures and reference renders; thread-safe (reads the map only).
#pragma once

#include <span>

#include <footprint/envmap/environment_map.h>
#include <footprint/math/vec3.h>

namespace footprint {

// A Gaussian footprint on the sphere: directions normalize(direction + a·axis1 + b·axis2) with
// (a, b) ~ N(0, 1) independent. `direction` has any nonzero length (it is normalised first); the
// axes lie in the tangent plane (⟂ direction; a component along it is removed) and their lengths
// are the standard deviations in radians. Zero axes: a point.
struct SphereGaussian {
    Vec3d direction{0, 0, 1};
    Vec3d axis1, axis2;  // principal axes, |axis1| ≥ |axis2| as built below
};

// The footprint of a lookup direction r with ray differentials ∂r/∂x, ∂r/∂y (any common scale of
// r, like compute_env_footprint form (a)): tangent covariance Σ = ¼(P dr_x dr_xᵀ P + P dr_y dr_yᵀ
// P)/|r|² with P = I − r̂r̂ᵀ, axes = its principal axes (√eigenvalue · eigenvector; axis1 the major).
// Non-finite or zero r gives direction +z; non-finite differentials give a point.
SphereGaussian sphere_gaussian_from_ray_differentials(Vec3d r, Vec3d dr_dx, Vec3d dr_dy);

// The same for any number of spread vectors s_i (changes of r, at r's scale): Σ = ¼ Σ_i P s_i s_iᵀ
// P/|r|². An EnvFootprint's map-space vectors (map_dr_dx, map_dr_dy, map_roughness1,
// map_roughness2 at map_direction) give its whole footprint K = K12 + κ² K3.
SphereGaussian sphere_gaussian_from_spread(Vec3d r, std::span<const Vec3d> spread);

struct EnvReferenceOptions {
    double step_texels = 0.5;         // largest distance between neighbouring nodes, level-0 texels
    double cutoff_sigma = 3.5;        // the grid covers |a|, |b| ≤ cutoff_sigma
    int max_samples_per_axis = 1024;  // cap on the nodes per axis (odd counts are used: ≤ this)
};

// C above for `footprint` on `map`: map.channels() floats to `out`.
void environment_reference(const EnvironmentMap& map, const SphereGaussian& footprint, float* out,
                           const EnvReferenceOptions& options = {});

}  // namespace footprint
