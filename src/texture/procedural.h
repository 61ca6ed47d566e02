// texture/procedural.h — solid (3D) procedural textures, band-limited by the pixel's footprint.
//
// The patterns (the lectures' "Texturing, part 2"), evaluated at a point p in world units, in the
// lattice coordinates x = scale·p, and u = R x, R a fixed rotation: the octaves' lattice,
// oblique to the pattern's axes, so that a plane at a whole coordinate (a floor at y = 0) is no
// lattice plane of the noise, whose moments differ there:
//   noise       fBm of gradient noise:  Σ_{i<N} n(2^i u)/2^i, over Σ 2^−i, mapped to [0, 1]
//   turbulence  Σ_{i<N} |n(2^i u)|/2^i, over Σ 2^−i
//   marble      ½ + ½ sin(x₀ + T(u)), T = Σ_{i<N} |n(2^i u)|/2^i (unnormalised), x₀ = x's first
//               axis
//   checker     the parity of ⌊x₀⌋ + ⌊x₁⌋ + ⌊x₂⌋
// n is gradient noise on the integer lattice (Perlin's improved noise: a quintic blend of the
// eight corners' gradients, chosen from Perlin's twelve cube-edge directions by a hash of the
// corner), in about [−1, 1] with mean 0. The value v ∈ [0, 1] blends the two colours:
// colour = (1 − v)·colours[0] + v·colours[1].
//
// Antialiasing (clamping, Norton, Rome & Fiume 1982: the octaves a pixel cannot hold fade to their
// mean; docs/method.md#procedural-textures). The pixel filter's Gaussian over the footprint
// (σ = ½ pixel along ∂p/∂x and ∂p/∂y) has, in lattice units, the variances σ_1², σ_2² along its
// principal axes. Octave i, of lattice spacing λ_i = 2^−i, becomes a_i·octave + (1 − a_i)·its mean
// (0 for n, E|n| = kMeanAbsNoise for |n|), with the a_i closest to the octave's mean over the
// footprint: its autocorrelation averaged over the footprint's Gaussian. For a spectrum taken as
// isotropic Gaussian of σ_f = c/λ_i per axis that is a_i = Π_k (1 + 4π² σ_k² σ_f²)^(−1/2), with c
// the noise's own: 0.448 for n, 0.677 for |n|, fitted to its autocorrelation measured over random
// points and footprints (bench/fit-procedural-band-limit.sh; no scene enters), and checked on
// grazing planes nothing was fitted to (ProceduralGrazing). A footprint long in one direction
// only, as at a grazing angle, thus keeps what its short axis resolves. The marble's stripes
// sin(x₀ + T) are attenuated as a sinusoid by the variance σ_x² along x₀, exp(−σ_x²/2), and by the
// variance the clamped octaves leave in its phase T, exp(−½ Var|n| Σ_i 4^−i (1 − a_i²)). The
// checker is box-filtered exactly: over an axis-aligned box of half-widths
// (√3/2)·scale·(|∂p/∂x| + |∂p/∂y|) per axis (a box of the σ = ½-pixel Gaussian's variance along
// each derivative), the mean of the product of three square waves is the product of their means,
// each a difference of the square wave's integral (a triangle wave) over the box. Zero
// derivatives: the point value.
#pragma once

#include <array>

#include <footprint/math/vec3.h>

namespace footprint {

enum class ProceduralPattern { noise, turbulence, marble, checker };

struct ProceduralTexture {
    ProceduralPattern pattern = ProceduralPattern::noise;
    double scale = 1;  // lattice cells per world unit
    int octaves = 4;   // 1 … kMaxProceduralOctaves (the checker has none)
    std::array<Vec3, 2> colors{Vec3{0, 0, 0}, Vec3{1, 1, 1}};  // linear RGB at v = 0 and v = 1
};

inline constexpr int kMaxProceduralOctaves = 16;

// E|n(x)| over the lattice, for uniformly distributed x (ProceduralTexture's test measures it).
inline constexpr double kMeanAbsNoise = 0.2200;

// Var|n| = E n² − (E|n|)² over the lattice, for uniformly distributed x (ProceduralTexture's test
// measures it): the marble's phase variance per unit of clamped octave.
inline constexpr double kAbsNoiseVariance = 0.0244;

// Var(∂n/∂x_k) over the lattice, the mean of the three axes, for uniformly distributed x
// (ProceduralTexture's test measures it: 0.48 along x and z, 0.52 along y, whose gradients
// Perlin's table repeats).
inline constexpr double kNoiseGradientVariance = 0.496;

// Gradient noise n(x) on the integer lattice, and with its gradient ∇n(x).
double gradient_noise(Vec3d x);
struct NoiseSample {
    double value = 0;
    Vec3d gradient;
};
NoiseSample gradient_noise_sample(Vec3d x);

// The pattern's value v ∈ [0, 1] at p, band-limited to the footprint spanned by ∂p/∂x and ∂p/∂y
// (world units per pixel; zero: the point value).
double procedural_value(const ProceduralTexture& texture, Vec3d p, Vec3d dpdx = {},
                        Vec3d dpdy = {});

// The pattern as a height field (bump: {"procedural": …}): the gradient ∇v of its value per world
// unit, band-limited as procedural_value() (each octave's a_i), and the covariance of ∇v that the
// band limit removed (the roughness the footprint filtered away: (1 − a_i²) of each octave's
// gradient variance kNoiseGradientVariance, isotropic; in the marble, the turbulence's under the
// stripes' (½ cos)², and the stripes' own (1 − s²) along x₀, s the stripes' attenuation above). The
// checker, a sum of steps, has none.
struct ProceduralSlopes {
    Vec3d gradient;
    std::array<double, 6> covariance{};  // xx, yy, zz, xy, xz, yz
};
ProceduralSlopes procedural_slopes(const ProceduralTexture& texture, Vec3d p, Vec3d dpdx = {},
                                   Vec3d dpdy = {});

// The colour of the value at p: the two colours blended by procedural_value().
Vec3 procedural_color(const ProceduralTexture& texture, Vec3d p, Vec3d dpdx = {}, Vec3d dpdy = {});

}  // namespace footprint
