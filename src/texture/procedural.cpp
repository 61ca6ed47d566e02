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

// Octave i's weight: the share of its amplitude that the footprint's Gaussian keeps. An octave of
// lattice spacing λ is taken as isotropic with a Gaussian spectrum of σ_f = c/λ per axis; the
// Gaussian of variances σ_1², σ_2² keeps Π_k (1 + 8π² σ_k² σ_f²)^(−1/2) of its variance. c = 0.7 is
// fitted (ProceduralTexture.BandLimitedValuesApproachTheFootprintsMean; 0.35 to 1.4 were tried).
double octave_weight(double spacing, Spread s) {
    constexpr double c = 0.7;
    const double f2 = (c / spacing) * (c / spacing);
    const double kept =
        1 / std::sqrt((1 + 8 * kPi * kPi * s.major * f2) * (1 + 8 * kPi * kPi * s.minor * f2));
    return std::sqrt(kept);
}

// Σ_{i<N} a_i f(n(2^i x))/2^i + (1 − a_i) mean/2^i, and Σ 2^−i: the fractal sums.
template <class F>
double fractal_sum(Vec3d x, int octaves, Spread w, double mean, F&& f, double& norm) {
    double sum = 0, amplitude = 1;
    norm = 0;
    for (int i = 0; i < octaves; ++i, amplitude *= 0.5) {
        const double a = octave_weight(amplitude, w);
        const double n = a > 0 ? f(gradient_noise(x / amplitude)) : mean;
        sum += amplitude * (a * n + (1 - a) * mean);
        norm += amplitude;
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

double gradient_noise(Vec3d x) {
    const double fx = std::floor(x.x), fy = std::floor(x.y), fz = std::floor(x.z);
    const std::uint32_t ix = lattice_index(fx), iy = lattice_index(fy), iz = lattice_index(fz);
    const double dx = x.x - fx, dy = x.y - fy, dz = x.z - fz;
    auto corner = [&](std::uint32_t cx, std::uint32_t cy, std::uint32_t cz) {
        return gradient_dot(lattice_hash(ix + cx, iy + cy, iz + cz), dx - cx, dy - cy, dz - cz);
    };
    const double u = quintic(dx), v = quintic(dy), w = quintic(dz);
    auto lerp = [](double a, double b, double t) { return a + t * (b - a); };
    return lerp(lerp(lerp(corner(0, 0, 0), corner(1, 0, 0), u),
                     lerp(corner(0, 1, 0), corner(1, 1, 0), u), v),
                lerp(lerp(corner(0, 0, 1), corner(1, 0, 1), u),
                     lerp(corner(0, 1, 1), corner(1, 1, 1), u), v),
                w);
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
            const double sum = fractal_sum(
                x, octaves, w, 0, [](double n) { return n; }, norm);
            return std::clamp(0.5 + 0.5 * sum / norm, 0.0, 1.0);
        }
        case ProceduralPattern::turbulence: {
            const double sum = fractal_sum(
                x, octaves, w, kMeanAbsNoise, [](double n) { return std::abs(n); }, norm);
            return std::clamp(sum / norm, 0.0, 1.0);
        }
        case ProceduralPattern::marble: {
            const double turbulence = fractal_sum(
                x, octaves, w, kMeanAbsNoise, [](double n) { return std::abs(n); }, norm);
            // sin(x₀) under the Gaussian: exp(−σ²/2) for its variance σ² along x₀.
            const double along = 0.25 * scale * scale * (dpdx.x * dpdx.x + dpdy.x * dpdy.x);
            const double stripes = std::isfinite(along) ? std::exp(-0.5 * along) : 0.0;
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

Vec3 procedural_color(const ProceduralTexture& texture, Vec3d p, Vec3d dpdx, Vec3d dpdy) {
    const auto v = static_cast<float>(procedural_value(texture, p, dpdx, dpdy));
    const Vec3 a = texture.colors[0], b = texture.colors[1];
    return {a.x + v * (b.x - a.x), a.y + v * (b.y - a.y), a.z + v * (b.z - a.z)};
}

}  // namespace footprint
