#include "texture/procedural.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace footprint {

namespace {

constexpr double kPi = 3.14159265358979323846;

// A lattice point's gradient index, 0 … 15: an integer hash of its coordinates (no table, so that a
// shader can draw the same noise with the same arithmetic).
std::uint32_t lattice_hash(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    std::uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ z * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h & 15u;
}

// The dot product of (x, y, z) with one of the twelve cube-edge directions (h's low four bits;
// four of them repeat, as in Perlin's improved noise).
double gradient_dot(std::uint32_t h, double x, double y, double z) {
    const double u = h < 8 ? x : y;
    const double v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

// A lattice coordinate ⌊x⌋ as the shader's int holds it, modulo 2^32: defined for any finite x
// (a cast of a double beyond the integer's range is not), the same integer where x is small.
std::uint32_t lattice_index(double floor_x) {
    return static_cast<std::uint32_t>(static_cast<std::int64_t>(std::fmod(floor_x, 4294967296.0)));
}

double quintic(double t) {
    return t * t * t * (t * (t * 6 - 15) + 10);
}

double quintic_slope(double t) {
    return 30 * t * t * (t - 1) * (t - 1);
}

// The octaves' lattice, rotated against the pattern's axes by 1 radian about (1, 2, 3)/√14: a
// plane at a whole lattice coordinate (a floor at y = 0) would otherwise be a lattice plane of
// every octave, where the gradients' third components drop out and the noise is not the noise
// whose moments (E|n|, Var|n|) and autocorrelation the band limit uses: on y = 0, E|n| = 0.196
// against 0.220 over space, a bias of every clamped octave. An oblique plane meets the lattice
// at every offset, as random points do (docs/method.md#procedural-textures).
constexpr double kLatticeRotation[3][3] = {
    {0.57313785544898699, -0.60900664213739331, 0.54829180960859991},
    {0.74034884046078198, 0.67164450419152844, -0.02787928294794625},
    {-0.35127851212351696, 0.42190587791811218, 0.83582225209576422}};

Vec3d to_lattice(Vec3d x) {
    const auto& r = kLatticeRotation;
    return {r[0][0] * x.x + r[0][1] * x.y + r[0][2] * x.z,
            r[1][0] * x.x + r[1][1] * x.y + r[1][2] * x.z,
            r[2][0] * x.x + r[2][1] * x.y + r[2][2] * x.z};
}

// A gradient in the rotated lattice's coordinates back in the pattern's: Rᵀ g.
Vec3d from_lattice(Vec3d g) {
    const auto& r = kLatticeRotation;
    return {r[0][0] * g.x + r[1][0] * g.y + r[2][0] * g.z,
            r[0][1] * g.x + r[1][1] * g.y + r[2][1] * g.z,
            r[0][2] * g.x + r[1][2] * g.y + r[2][2] * g.z};
}

// The pixel filter's Gaussian over the footprint (σ = ½ pixel along ∂p/∂x and ∂p/∂y) in lattice
// units: the variances along its two principal axes, the eigenvalues of ¼ scale² [a b]ᵀ[a b].
struct Spread {
    double major = 0, minor = 0;
};
Spread footprint_spread(Vec3d a, Vec3d b, double scale) {
    const double k = 0.25 * scale * scale;
    const double aa = k * dot(a, a), bb = k * dot(b, b), ab = k * dot(a, b);
    const double mean = 0.5 * (aa + bb), root = std::sqrt(0.25 * (aa - bb) * (aa - bb) + ab * ab);
    if (!std::isfinite(mean + root)) return {INFINITY, INFINITY};
    return {mean + root, std::max(0.0, mean - root)};
}

// Octave i's weight (docs/method.md#procedural-textures): clamping replaces the octave o (n, or
// |n|) by a·o(p) + (1 − a)·E o, and the a closest to the footprint's mean B(p) = E o(q), q drawn
// from the footprint's Gaussian around p, is a = Cov(B, o)/Var o: o's autocorrelation averaged over
// that Gaussian. For a spectrum taken as isotropic Gaussian of σ_f = c/λ per axis that is
// Π_k (1 + 4π² σ_k² σ_f²)^(−1/2) over the Gaussian's principal variances σ_k²; c is the noise's
// own, fitted to its measured autocorrelation (bench/fit-procedural-band-limit.sh): the folds of
// |n| put more of its variance at high frequencies than n has.
constexpr double kNoiseBandLimit = 0.448;     // c for n
constexpr double kAbsNoiseBandLimit = 0.677;  // c for |n|

double octave_weight(double spacing, Spread s, bool absolute) {
    const double c = absolute ? kAbsNoiseBandLimit : kNoiseBandLimit;
    const double k = 4 * kPi * kPi * (c / spacing) * (c / spacing);
    return 1 / std::sqrt((1 + k * s.major) * (1 + k * s.minor));
}

// Σ_{i<N} a_i f(n(2^i x))/2^i + (1 − a_i) mean/2^i, f the identity or |·|, and Σ 2^−i: the fractal
// sums. residual: Σ 4^−i (1 − a_i²), the variance, in units of one octave's (Var o = 1), by which
// the octaves at the footprint's points differ from the clamped sum: E_q (o(q) − a o(p))² =
// (1 − a²) Var o for the a above.
double fractal_sum(Vec3d x, int octaves, Spread w, bool absolute, double& norm,
                   double* residual = nullptr) {
    const double mean = absolute ? kMeanAbsNoise : 0.0;
    const Vec3d u = to_lattice(x);
    double sum = 0, amplitude = 1, left = 0;
    norm = 0;
    for (int i = 0; i < octaves; ++i, amplitude *= 0.5) {
        const double a = octave_weight(amplitude, w, absolute);
        double n = mean;
        if (a > 0) {
            n = gradient_noise(u / amplitude);
            if (absolute) n = std::abs(n);
        }
        sum += amplitude * (a * n + (1 - a) * mean);
        norm += amplitude;
        left += amplitude * amplitude * (1 - a * a);
    }
    if (residual) *residual = left;
    return sum;
}

// The marble's stripes sin(x₀ + T) averaged over the footprint's Gaussian, as a factor on the
// sinusoid of the clamped phase: exp(−σ_x²/2) for x₀'s variance σ_x² = ¼ scale² (a₀² + b₀²) along
// it, times exp(−V/2) for the variance V = Var|n| Σ 4^−i (1 − a_i²) the turbulence's octaves keep
// about the clamped phase (E cos r = exp(−Var r/2) for a Gaussian r).
double stripe_factor(double scale, Vec3d dpdx, Vec3d dpdy, double residual) {
    const double along = 0.25 * scale * scale * (dpdx.x * dpdx.x + dpdy.x * dpdy.x);
    const double exponent = -0.5 * (along + kAbsNoiseVariance * residual);
    return std::isfinite(exponent) ? std::exp(exponent) : 0.0;
}

// Σ_{i<N} a_i f'(n_i) ∇n(2^i x) (in lattice units: each octave's 1/2^i cancels its 2^i), f the
// identity or |·|, and Σ (1 − a_i²): the octaves' gradient variance that the band limit removed, in
// units of one octave's (kNoiseGradientVariance).
Vec3d fractal_gradient(Vec3d x, int octaves, Spread w, bool absolute, double& removed) {
    Vec3d sum{0, 0, 0};
    removed = 0;
    double amplitude = 1;
    for (int i = 0; i < octaves; ++i, amplitude *= 0.5) {
        const double a = octave_weight(amplitude, w, absolute);
        removed += 1 - a * a;
        if (!(a > 0)) continue;
        const NoiseSample n = gradient_noise_sample(to_lattice(x) / amplitude);
        sum = sum + (absolute && n.value < 0 ? -a : a) * from_lattice(n.gradient);
    }
    return sum;
}

// The mean of the square wave s(u) = (−1)^⌊u⌋ over [u − h, u + h]: its integral, a triangle wave
// S(u) = 1 − |(u mod 2) − 1|, differenced.
double square_wave_mean(double u, double h) {
    if (std::isnan(h) || std::isinf(h)) return 0;  // a box of any size beyond measure: the mean
    if (!(h > 1e-12)) return std::floor(u) == 2 * std::floor(u / 2) ? 1.0 : -1.0;
    auto integral = [](double v) {
        const double m = v - 2 * std::floor(v / 2);
        return 1 - std::abs(m - 1);
    };
    return (integral(u + h) - integral(u - h)) / (2 * h);
}

double checker_value(Vec3d x, Vec3d half_width) {
    const double product = square_wave_mean(x.x, half_width.x) *
                           square_wave_mean(x.y, half_width.y) *
                           square_wave_mean(x.z, half_width.z);
    return 0.5 * (1 - product);
}

}  // namespace

NoiseSample gradient_noise_sample(Vec3d x) {
    const double fx = std::floor(x.x), fy = std::floor(x.y), fz = std::floor(x.z);
    const std::uint32_t ix = lattice_index(fx), iy = lattice_index(fy), iz = lattice_index(fz);
    const Vec3d d{x.x - fx, x.y - fy, x.z - fz};
    const Vec3d fade{quintic(d.x), quintic(d.y), quintic(d.z)};
    const Vec3d fade_slope{quintic_slope(d.x), quintic_slope(d.y), quintic_slope(d.z)};
    // n = Σ_corners w_c (g_c · (d − c)), w_c the product of the three fades (or 1 − fade) of c;
    // ∂n/∂x_k = Σ_c ∂w_c/∂x_k (g_c · (d − c)) + w_c g_c,k.
    NoiseSample n{0, {0, 0, 0}};
    for (std::uint32_t c = 0; c < 8; ++c) {
        const std::uint32_t cx = c & 1, cy = (c >> 1) & 1, cz = c >> 2;
        const std::uint32_t h = lattice_hash(ix + cx, iy + cy, iz + cz);
        const Vec3d g{gradient_dot(h, 1, 0, 0), gradient_dot(h, 0, 1, 0), gradient_dot(h, 0, 0, 1)};
        const double value = dot(g, Vec3d{d.x - cx, d.y - cy, d.z - cz});
        const double wx = cx ? fade.x : 1 - fade.x, wy = cy ? fade.y : 1 - fade.y,
                     wz = cz ? fade.z : 1 - fade.z;
        const double sx = cx ? fade_slope.x : -fade_slope.x, sy = cy ? fade_slope.y : -fade_slope.y,
                     sz = cz ? fade_slope.z : -fade_slope.z;
        n.value += wx * wy * wz * value;
        n.gradient =
            n.gradient + wx * wy * wz * g + value * Vec3d{sx * wy * wz, wx * sy * wz, wx * wy * sz};
    }
    return n;
}

double gradient_noise(Vec3d x) {
    return gradient_noise_sample(x).value;
}

double procedural_value(const ProceduralTexture& texture, Vec3d p, Vec3d dpdx, Vec3d dpdy) {
    const double scale = texture.scale;
    const Vec3d x = scale * p;
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z)) return 0.5;
    const Spread w = footprint_spread(dpdx, dpdy, scale);
    const int octaves = std::clamp(texture.octaves, 1, kMaxProceduralOctaves);
    double norm = 0;
    switch (texture.pattern) {
        case ProceduralPattern::noise: {
            const double sum = fractal_sum(x, octaves, w, false, norm);
            return std::clamp(0.5 + 0.5 * sum / norm, 0.0, 1.0);
        }
        case ProceduralPattern::turbulence: {
            const double sum = fractal_sum(x, octaves, w, true, norm);
            return std::clamp(sum / norm, 0.0, 1.0);
        }
        case ProceduralPattern::marble: {
            double residual = 0;
            const double turbulence = fractal_sum(x, octaves, w, true, norm, &residual);
            const double stripes = stripe_factor(scale, dpdx, dpdy, residual);
            return 0.5 + 0.5 * stripes * std::sin(x.x + turbulence);
        }
        case ProceduralPattern::checker: {
            const double k = 0.5 * std::sqrt(3.0) * scale;
            const Vec3d half{k * (std::abs(dpdx.x) + std::abs(dpdy.x)),
                             k * (std::abs(dpdx.y) + std::abs(dpdy.y)),
                             k * (std::abs(dpdx.z) + std::abs(dpdy.z))};
            return checker_value(x, half);
        }
    }
    return 0.5;
}

ProceduralSlopes procedural_slopes(const ProceduralTexture& texture, Vec3d p, Vec3d dpdx,
                                   Vec3d dpdy) {
    const double scale = texture.scale;
    const Vec3d x = scale * p;
    ProceduralSlopes out;
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z)) return out;
    const Spread w = footprint_spread(dpdx, dpdy, scale);
    const int octaves = std::clamp(texture.octaves, 1, kMaxProceduralOctaves);
    double norm = 0;
    for (int i = 0; i < octaves; ++i) norm += std::ldexp(1.0, -i);
    double removed = 0;
    auto isotropic = [&](double k) {  // k·removed·κ I
        const double v = k * removed * kNoiseGradientVariance;
        out.covariance = {v, v, v, 0, 0, 0};
    };
    switch (texture.pattern) {
        case ProceduralPattern::noise: {  // v = ½ + ½ Σ/norm
            const double k = 0.5 * scale / norm;
            out.gradient = k * fractal_gradient(x, octaves, w, false, removed);
            isotropic(k * k);
            break;
        }
        case ProceduralPattern::turbulence: {  // v = Σ|n|/norm
            const double k = scale / norm;
            out.gradient = k * fractal_gradient(x, octaves, w, true, removed);
            isotropic(k * k);
            break;
        }
        case ProceduralPattern::marble: {  // v = ½ + ½ e^{−σ²/2} sin(x₀ + T)
            double unused = 0, residual = 0;
            const double turbulence = fractal_sum(x, octaves, w, true, unused, &residual);
            const Vec3d turbulence_gradient =
                scale * fractal_gradient(x, octaves, w, true, removed);
            const double stripes = stripe_factor(scale, dpdx, dpdy, residual);
            const double c = std::cos(x.x + turbulence);
            out.gradient = 0.5 * stripes * c * (Vec3d{scale, 0, 0} + turbulence_gradient);
            // The turbulence's removed octaves under (½ cos)²: the local cos² where the footprint
            // resolves the stripes, its mean ½ where it does not. The stripes' own removed share
            // lies along x₀.
            const double c2 = 0.5 + stripes * stripes * (c * c - 0.5);
            isotropic(0.25 * c2 * scale * scale);
            out.covariance[0] += 0.125 * scale * scale * (1 - stripes * stripes);
            break;
        }
        case ProceduralPattern::checker:  // steps: no slopes to take
            break;
    }
    return out;
}

Vec3 procedural_color(const ProceduralTexture& texture, Vec3d p, Vec3d dpdx, Vec3d dpdy) {
    const auto v = static_cast<float>(procedural_value(texture, p, dpdx, dpdy));
    const Vec3 a = texture.colors[0], b = texture.colors[1];
    return {a.x + v * (b.x - a.x), a.y + v * (b.y - a.y), a.z + v * (b.z - a.z)};
}

}  // namespace footprint
