// envmap/irradiance.h — an environment's diffuse light: the irradiance map of the lecture's
// "diffuse map indexed by the normal", held as nine spherical-harmonic coefficients.
//
// The irradiance at a surface of unit normal n under a distant environment of radiance L(ω) is
//
//     E(n) = ∫ L(ω) max(0, n·ω) dω,
//
// and a Lambertian surface of albedo c reflects c·E(n)/π. The clamped cosine is a low-pass filter
// on the sphere: expanding L in real spherical harmonics, L = Σ L_lm Y_lm, the Funk–Hecke theorem
// gives E = Σ Â_l L_lm Y_lm(n) with Â_0 = π, Â_1 = 2π/3, Â_2 = π/4, Â_3 = 0, and Â_l falling as
// l^(−5/2) beyond (Ramamoorthi & Hanrahan 2001). Bands l ≤ 2, nine coefficients per channel, hold
// all but a few per cent of E for any environment; E of an environment with no energy above band 2
// is exact.
//
// Roughness. A filtered bump map's pixel holds a distribution of normals, not one: slopes of
// covariance K_b about the mean normal. The diffuse light it reflects is E averaged over those
// normals. By Funk–Hecke again, averaging over tilts that are symmetric about n scales band l by
// g_l = E[P_l(cos θ)], θ the tilt. Slopes s ~ N(0, σ² I) tilt by cos θ = (1 + |s|²)^(−½) with
// |s|² exponential of mean 2σ², which gives, with x = 1/(2σ²),
//
//     g_1 = E[cos θ]            = √(πx) e^x erfc(√x),
//     g_2 = E[(3 cos²θ − 1)/2]  = (3 x e^x E₁(x) − 1)/2
//
// (1 − σ² + 3σ⁴ and 1 − 3σ² + 12σ⁴ for small σ²). An anisotropic K_b is taken by its mean variance
// σ² = (K_xx + K_yy)/2: the average over K_b's orientations about n.
//
// Projection. L_lm = ∫ L(ω) Y_lm(ω) dω over `samples` directions of a spherical Fibonacci lattice
// (equal areas 4π/samples), each reading the environment filtered over its cell, so that a sun of
// a few texels contributes its energy wherever it lies between the lattice points.
#pragma once

#include <array>
#include <functional>

#include <footprint/math/vec3.h>

namespace footprint {

// The radiance's nine coefficients L_lm, l ≤ 2, in the order Y_00; Y_1−1, Y_10, Y_11; Y_2−2,
// Y_2−1, Y_20, Y_21, Y_22 (Y_1−1 ∝ y, Y_10 ∝ z, Y_11 ∝ x), per RGB channel.
struct IrradianceSH {
    std::array<Vec3, 9> coefficients{};
};

inline constexpr int kIrradianceSamples = 4096;

// The real spherical harmonics Y_lm(ω), l ≤ 2, of a unit ω, in IrradianceSH's order.
std::array<float, 9> sh9_basis(Vec3 omega);

// The environment's radiance L projected on the nine harmonics. radiance(ω, ∂ω₁, ∂ω₂) is the
// environment filtered over the cell around the unit direction ω spanned by the two tangent steps
// (as a pixel's ray differentials span its footprint: an environment lookup form (a)).
IrradianceSH project_radiance(const std::function<Vec3(Vec3 omega, Vec3 d1, Vec3 d2)>& radiance,
                              int samples = kIrradianceSamples);

// g_1 and g_2 above for slopes of variance σ² per axis (σ² ≤ 0: 1 and 1).
std::array<float, 2> slope_band_gains(float slope_variance);

// E(n) at the unit normal n, averaged over slopes of mean variance `slope_variance` about it
// (0: the irradiance at n itself). Negative lobes of the truncation are clamped to 0.
Vec3 irradiance(const IrradianceSH& sh, Vec3 n, float slope_variance = 0);

}  // namespace footprint
