#include "env_lookups.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "envmap/env_layout.h"

namespace footprint::bench {

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- The environment: a function of direction with content at every scale.

std::uint32_t hash3(std::int64_t x, std::int64_t y, std::int64_t z, std::uint32_t seed) {
    std::uint32_t h = static_cast<std::uint32_t>(x) * 0x8da6b343u ^
                      static_cast<std::uint32_t>(y) * 0xd8163841u ^
                      static_cast<std::uint32_t>(z) * 0xcb1ab31fu ^ seed;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return h;
}

double lattice3(std::int64_t x, std::int64_t y, std::int64_t z, std::uint32_t seed) {
    return double(hash3(x, y, z, seed) & 0xffffffu) / double(0x1000000);
}

// Smooth (C¹) value noise in 3-D with unit cells, in [0, 1).
double value_noise3(double x, double y, double z, std::uint32_t seed) {
    const double fx0 = std::floor(x), fy0 = std::floor(y), fz0 = std::floor(z);
    const auto ix = static_cast<std::int64_t>(fx0), iy = static_cast<std::int64_t>(fy0),
               iz = static_cast<std::int64_t>(fz0);
    auto smooth = [](double f) { return f * f * (3 - 2 * f); };
    const double sx = smooth(x - fx0), sy = smooth(y - fy0), sz = smooth(z - fz0);
    auto lerp = [](double a, double b, double w) { return a + w * (b - a); };
    double face[2];
    for (int k = 0; k < 2; ++k) {
        const double a =
            lerp(lattice3(ix, iy, iz + k, seed), lattice3(ix + 1, iy, iz + k, seed), sx);
        const double b =
            lerp(lattice3(ix, iy + 1, iz + k, seed), lattice3(ix + 1, iy + 1, iz + k, seed), sx);
        face[k] = lerp(a, b, sy);
    }
    return lerp(face[0], face[1], sz);
}

// Linear-light RGB of the unit direction d; `texel` is the angle of one lat-long texel (π/H).
// red: octaves of value noise (cells of 256…4 texels) plus hard-edged cells of 8 texels (the
// parity of a 3-D lattice on the sphere); green: two plane-wave gratings of period 3.3 texels (near
// the lat-long Nyquist rate, so under-filtering aliases); blue: fine noise (2-texel cells) over a
// gradient in y. The angular content is the same everywhere on the sphere: only its lat-long image
// is stretched towards the poles.
void environment_colour(const Vec3d& d, double texel, float* rgb) {
    double noise = 0, amplitude = 0.5;
    for (int cells = 256; cells >= 4; cells /= 4, amplitude *= 0.6) {
        const double k = 1.0 / (cells * texel);
        noise += amplitude * value_noise3(d.x * k, d.y * k, d.z * k, 17u + cells);
    }
    const double c = 1.0 / (8 * texel);
    const auto parity =
        static_cast<std::int64_t>(std::floor(d.x * c) + std::floor(d.y * c) + std::floor(d.z * c));
    rgb[0] = float(0.45 * noise + ((parity & 1) ? 0.4 : 0.0));
    const double k = 2 * kPi / (3.3 * texel);
    const Vec3d a = normalize(Vec3d{0.48, 0.6, 0.64}), b = normalize(Vec3d{-0.8, 0.1, 0.59});
    rgb[1] = float(0.5 + 0.225 * (std::sin(k * dot(a, d)) + std::sin(k * dot(b, d) + 1.0)));
    const double fine = 1.0 / (2 * texel);
    rgb[2] = float(0.2 + 0.25 * (d.y + 1) +
                   0.25 * (value_noise3(d.x * fine, d.y * fine, d.z * fine, 99u) - 0.5));
}

Vec3 to_float(const Vec3d& v) {
    return {float(v.x), float(v.y), float(v.z)};
}

// The lat-long direction of (s, t) and its derivatives ∂/∂s, ∂/∂t (env_layout.h §3.4's inverse:
// φ = 2π(s − ½), θ = πt, r = (sin θ sin φ, cos θ, −sin θ cos φ)).
struct LatlongFrame {
    Vec3d r, d_ds, d_dt;
};
LatlongFrame latlong_frame(double s, double t) {
    const double phi = 2 * kPi * (s - 0.5), theta = kPi * t;
    const double sp = std::sin(phi), cp = std::cos(phi), st = std::sin(theta), ct = std::cos(theta);
    return {{st * sp, ct, -st * cp},
            {2 * kPi * st * cp, 0, 2 * kPi * st * sp},
            {kPi * ct * sp, -kPi * st, -kPi * ct * cp}};
}

}  // namespace

Image make_latlong_image(int width, int height) {
    Image image(width, height, 3);
    const double texel = kPi / height;
    tbb::parallel_for(0, height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const Vec3d d = latlong_direction((x + 0.5) / width, (y + 0.5) / height);
            environment_colour(normalize(d), texel, image.at(x, y));
        }
    });
    return image;
}

std::vector<EnvLookup> make_env_lookups(const EnvRegime& regime, std::size_t n, int width,
                                        int height, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<EnvLookup> lookups(n);
    for (EnvLookup& q : lookups) {
        const double angle = 2 * kPi * unit(rng);
        const double scale = std::exp2(unit(rng) - 0.5);
        const double ca = std::cos(angle), sa = std::sin(angle);
        const double s = unit(rng);
        double latitude = regime.lat_min + (regime.lat_max - regime.lat_min) * unit(rng);
        if (unit(rng) < 0.5) latitude = -latitude;  // both hemispheres
        const double t = 0.5 - latitude / 180.0;
        const LatlongFrame f = latlong_frame(s, t);
        Vec3d dx, dy;
        if (regime.isotropic_on_sphere) {
            const double rho = regime.major * (kPi / height) * scale;
            const Vec3d e_s = normalize(f.d_ds), e_t = normalize(f.d_dt);
            dx = rho * (ca * e_s + sa * e_t);
            dy = rho * (ca * e_t - sa * e_s);
        } else {
            // Columns of D in texels, then in (s, t) units.
            const double xs = regime.major * scale * ca, xt = regime.major * scale * sa;
            const double ys = -regime.minor * scale * sa, yt = regime.minor * scale * ca;
            dx = (xs / width) * f.d_ds + (xt / height) * f.d_dt;
            dy = (ys / width) * f.d_ds + (yt / height) * f.d_dt;
        }
        q = {to_float(f.r), to_float(dx), to_float(dy)};
    }
    return lookups;
}

}  // namespace footprint::bench
