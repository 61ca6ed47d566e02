#include "demo_assets.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "math/sample_patterns.h"
#include "scene/terrain.h"

namespace footprint {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

std::uint32_t hash3(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return hash32(a ^ hash32(b ^ hash32(c)));
}

// A uniform number in [0, 1) from (stream, index, component).
double uniform01(std::uint32_t stream, std::uint32_t index, std::uint32_t component) {
    return (hash3(stream, index, component) >> 8) * (1.0 / 16777216.0);
}

struct Rgb {
    double r = 0, g = 0, b = 0;
};
Rgb operator+(Rgb a, Rgb b) {
    return {a.r + b.r, a.g + b.g, a.b + b.b};
}
Rgb operator*(double s, Rgb a) {
    return {s * a.r, s * a.g, s * a.b};
}
Rgb lerp(Rgb a, Rgb b, double f) {
    return (1.0 - f) * a + f * b;
}

void store(Image& image, int x, int y, Rgb c) {
    float* p = image.at(x, y);
    p[0] = static_cast<float>(c.r);
    p[1] = static_cast<float>(c.g);
    p[2] = static_cast<float>(c.b);
}

double smoothstep(double e0, double e1, double x) {
    const double f = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return f * f * (3.0 - 2.0 * f);
}

Vec3d direction_from_elevation_azimuth(double elevation_deg, double azimuth_deg) {
    const double e = elevation_deg * kDeg, a = azimuth_deg * kDeg;
    return {std::cos(e) * std::sin(a), std::sin(e), -std::cos(e) * std::cos(a)};
}

// The per-row and per-column factors of the lat-long inverse (env_layout.h §3.4) at texel centres:
// r = (sin θ sin φ, cos θ, −sin θ cos φ), θ = π(y + ½)/H, φ = 2π((x + ½)/W − ½).
struct LatlongGrid {
    std::vector<double> sin_theta, cos_theta, sin_phi, cos_phi;
    LatlongGrid(int width, int height) {
        for (int y = 0; y < height; ++y) {
            const double theta = kPi * (y + 0.5) / height;
            sin_theta.push_back(std::sin(theta));
            cos_theta.push_back(std::cos(theta));
        }
        for (int x = 0; x < width; ++x) {
            const double phi = 2.0 * kPi * ((x + 0.5) / width - 0.5);
            sin_phi.push_back(std::sin(phi));
            cos_phi.push_back(std::cos(phi));
        }
    }
    Vec3d direction(int x, int y) const {
        return {sin_theta[y] * sin_phi[x], cos_theta[y], -sin_theta[y] * cos_phi[x]};
    }
};

// Fraction of row y (θ from πy/H to π(y+1)/H) above the horizon θ = π/2.
double row_sky_coverage(int y, int height) {
    return std::clamp(0.5 * height - y, 0.0, 1.0);
}

// Angle between unit vectors, accurate for small angles.
double angle_between(Vec3d a, Vec3d b) {
    return std::atan2(length(cross(a, b)), dot(a, b));
}

// Splats a gaussian dot of peak `peak` (per channel) and standard deviation sigma (texels) centred
// at texel coordinates (cx, cy) = (sW, tH) into a lat-long image; columns wrap, rows clip.
void splat_gaussian(Image& image, double cx, double cy, double sigma, Rgb peak) {
    const int x0 = static_cast<int>(std::floor(cx)), y0 = static_cast<int>(std::floor(cy));
    const double inv = 1.0 / (2.0 * sigma * sigma);
    for (int dy = -2; dy <= 2; ++dy) {
        const int y = y0 + dy;
        if (y < 0 || y >= image.height) continue;
        for (int dx = -2; dx <= 2; ++dx) {
            const int xu = x0 + dx;
            const int x = ((xu % image.width) + image.width) % image.width;
            const double ex = xu + 0.5 - cx, ey = y + 0.5 - cy;
            const double w = std::exp(-(ex * ex + ey * ey) * inv);
            float* p = image.at(x, y);
            p[0] += static_cast<float>(w * peak.r);
            p[1] += static_cast<float>(w * peak.g);
            p[2] += static_cast<float>(w * peak.b);
        }
    }
}

}  // namespace

// ---- Night sky ---------------------------------------------------------------------------------

Vec3 night_sky_moon_direction() {
    const Vec3d m =
        direction_from_elevation_azimuth(kNightSkyMoonElevationDeg, kNightSkyMoonAzimuthDeg);
    return vec3_cast<float>(m);
}

Image make_night_sky_latlong(int width) {
    width = std::max(width, 16);
    const int height = width / 2;
    Image image(width, height, 3);
    const LatlongGrid grid(width, height);
    const Vec3d moon =
        direction_from_elevation_azimuth(kNightSkyMoonElevationDeg, kNightSkyMoonAzimuthDeg);
    const double moon_radius = kNightSkyMoonRadiusDeg * kDeg;
    const double row_angle = kPi / height;  // angular height of one texel row
    // The moon's tangent frame: e1 horizontal, e2 "up" across its face.
    const Vec3d e1 = normalize(Vec3d{-moon.z, 0.0, moon.x});
    const Vec3d e2 = cross(e1, moon);

    const Rgb zenith{0.0015, 0.0022, 0.0070}, horizon{0.012, 0.016, 0.030};
    const Rgb sea_horizon{0.008, 0.010, 0.016}, sea_deep{0.0025, 0.0030, 0.0045};
    const Rgb glow{0.10, 0.10, 0.12};
    const Rgb moon_colour{1.0, 0.96, 0.88};
    constexpr double kMoonBrightness = 30.0;
    // The glow about the moon, cut off at kGlowReach (and lowered by its value there, so it ends
    // without a step; outside it costs nothing).
    const auto glow_profile = [](double angle) {
        return 0.6 * std::exp(-angle / (3 * kDeg)) + 0.4 * std::exp(-angle / (10 * kDeg));
    };
    const double kGlowReach = 40 * kDeg, kGlowCos = std::cos(kGlowReach);
    struct Mare {
        double a, b, r, darkness;
    };
    // In units of the moon's radius; none covers the centre, so the centre stays the brightest.
    constexpr std::array<Mare, 6> kMaria{{{-0.38, 0.30, 0.30, 0.45},
                                          {0.12, 0.45, 0.22, 0.40},
                                          {0.36, -0.02, 0.17, 0.35},
                                          {-0.18, -0.30, 0.20, 0.40},
                                          {0.50, 0.40, 0.12, 0.35},
                                          {-0.55, -0.10, 0.14, 0.38}}};

    for (int y = 0; y < height; ++y) {
        const double elevation = kPi / 2 - kPi * (y + 0.5) / height;  // at the row's centre
        const double cover = row_sky_coverage(y, height);
        const Rgb sky = lerp(zenith, horizon, std::exp(-std::max(elevation, 0.0) / 0.3));
        const Rgb sea = lerp(sea_deep, sea_horizon, std::exp(-std::max(-elevation, 0.0) / 0.15));
        const Rgb base = lerp(sea, sky, cover);
        for (int x = 0; x < width; ++x) {
            Rgb c = base;
            if (cover > 0) {
                const Vec3d r = grid.direction(x, y);
                const double cos_angle = dot(r, moon);
                if (cos_angle > kGlowCos) {  // within 40°: the glow, and maybe the disk
                    const double angle = angle_between(r, moon);
                    c = c + (cover * (glow_profile(angle) - glow_profile(kGlowReach))) * glow;
                    const double disk =
                        std::clamp((moon_radius - angle) / row_angle + 0.5, 0.0, 1.0) * cover;
                    if (disk > 0) {
                        const double a = dot(r, e1) / std::sin(moon_radius);
                        const double b = dot(r, e2) / std::sin(moon_radius);
                        const double rho2 = std::min(a * a + b * b, 1.0);
                        double shade = 0.8 + 0.2 * std::sqrt(1.0 - rho2);  // limb darkening
                        for (const Mare& m : kMaria) {
                            const double d = std::hypot(a - m.a, b - m.b);
                            shade *= 1.0 - m.darkness * (1.0 - smoothstep(0.7 * m.r, m.r, d));
                        }
                        c = lerp(c, kMoonBrightness * shade * moon_colour, disk);
                    }
                }
            }
            store(image, x, y, c);
        }
    }

    // Stars: uniform over the upper hemisphere (sin elevation uniform), none near the moon.
    const double area = (width / 2048.0) * (width / 2048.0);
    const int star_count = std::max(64, static_cast<int>(std::lround(4000 * area)));
    constexpr std::uint32_t kStarStream = 0x5747u;
    for (int i = 0; i < star_count; ++i) {
        const auto u = [&](std::uint32_t k) { return uniform01(kStarStream, i, k); };
        const double sin_elev = u(0), azimuth = 2 * kPi * u(1);
        const double elev = std::asin(sin_elev);
        if (elev < 1 * kDeg) continue;
        const Vec3d dir{std::cos(elev) * std::sin(azimuth), sin_elev,
                        -std::cos(elev) * std::cos(azimuth)};
        if (angle_between(dir, moon) < 3 * moon_radius) continue;
        // Many faint stars, few bright ones: 0.05 · 100^(u³) ∈ [0.05, 5).
        const double v = u(2);
        const double brightness = 0.05 * std::pow(100.0, v * v * v);
        const double sigma = 0.45 + 0.35 * u(3);
        const double kind = u(4);
        const Rgb tint = kind < 0.15   ? Rgb{0.75, 0.85, 1.15}     // blue-white
                         : kind < 0.3  ? Rgb{1.15, 0.85, 0.55}     // orange
                         : kind < 0.33 ? Rgb{1.25, 0.55, 0.40}     // red
                                       : Rgb{1.0, 0.98, 0.95};     // white
        const double fade = smoothstep(1 * kDeg, 6 * kDeg, elev);  // extinction near the horizon
        // Texel coordinates of the direction: s = ½ + φ/(2π) with φ = azimuth, t = θ/π.
        const double s = 0.5 + azimuth / (2 * kPi), t = (kPi / 2 - elev) / kPi;
        splat_gaussian(image, s * width, t * height, sigma, (brightness * fade) * tint);
    }
    return image;
}

// ---- Zebra -------------------------------------------------------------------------------------

Image make_zebra_latlong(int width) {
    width = std::max(width, 8);
    const int height = width / 2;
    Image image(width, height, 3);
    const double period = kZebraPeriodDeg * kDeg;
    // ∫₀^θ white: full periods contribute half their length, the last partial one up to half.
    const auto white_integral = [period](double theta) {
        const double n = std::floor(theta / period);
        return n * 0.5 * period + std::min(theta - n * period, 0.5 * period);
    };
    for (int y = 0; y < height; ++y) {
        const double t0 = kPi * y / height, t1 = kPi * (y + 1) / height;
        const double v =
            std::clamp((white_integral(t1) - white_integral(t0)) / (t1 - t0), 0.0, 1.0);
        for (int x = 0; x < width; ++x) store(image, x, y, {v, v, v});
    }
    return image;
}

// ---- Daylight sky ------------------------------------------------------------------------------

Vec3 sky_gradient_sun_direction() {
    const Vec3d d =
        direction_from_elevation_azimuth(kSkyGradientSunElevationDeg, kSkyGradientSunAzimuthDeg);
    return vec3_cast<float>(d);
}

Image make_sky_gradient_latlong(int width) {
    width = std::max(width, 16);
    const int height = width / 2;
    Image image(width, height, 3);
    const LatlongGrid grid(width, height);
    const Vec3d sun =
        direction_from_elevation_azimuth(kSkyGradientSunElevationDeg, kSkyGradientSunAzimuthDeg);
    const Rgb zenith{0.10, 0.22, 0.60}, horizon{0.65, 0.75, 0.90};
    const Rgb ground_near{0.30, 0.27, 0.23}, ground_far{0.11, 0.10, 0.08};
    const Rgb sun_colour{1.0, 0.95, 0.85};
    const double sigma = 1.2 * kDeg;
    for (int y = 0; y < height; ++y) {
        const double elevation = kPi / 2 - kPi * (y + 0.5) / height;
        const double cover = row_sky_coverage(y, height);
        const Rgb sky = lerp(horizon, zenith, std::pow(std::max(elevation, 0.0) / (kPi / 2), 0.6));
        const Rgb ground =
            lerp(ground_far, ground_near, std::exp(-std::max(-elevation, 0.0) / 0.3));
        const Rgb base = lerp(ground, sky, cover);
        for (int x = 0; x < width; ++x) {
            Rgb c = base;
            const double cos_angle = dot(grid.direction(x, y), sun);
            if (cover > 0 && cos_angle > 0.5) {
                const double angle = angle_between(grid.direction(x, y), sun);
                const double blob = 40.0 * std::exp(-0.5 * (angle / sigma) * (angle / sigma)) +
                                    0.8 * std::exp(-angle / (8 * kDeg));
                c = c + (cover * blob) * sun_colour;
            }
            store(image, x, y, c);
        }
    }
    return image;
}

// ---- Water -------------------------------------------------------------------------------------

Image make_water_height_map(int size) {
    size = std::max(size, 16);
    Image image(size, size, 1);
    std::vector<double> h(static_cast<std::size_t>(size) * size, 0.0);
    constexpr std::uint32_t kWaterStream = 0xa7e5u;
    constexpr double kWind = 30 * kDeg;
    std::vector<double> sx(size), cx(size), sy(size), cy(size);
    int wave = 0;
    for (int octave = 0; octave < 5; ++octave) {
        const double k = 2 << octave;  // cycles per tile: 2, 4, 8, 16, 32
        for (int j = 0; j < 3; ++j, ++wave) {
            const auto u = [&](std::uint32_t c) { return uniform01(kWaterStream, wave, c); };
            const double angle = kWind + (u(0) * 2 - 1) * 50 * kDeg;
            int kx = static_cast<int>(std::lround(k * std::cos(angle)));
            int ky = static_cast<int>(std::lround(k * std::sin(angle)));
            if (kx == 0 && ky == 0) kx = static_cast<int>(k);
            if (2 * std::max(std::abs(kx), std::abs(ky)) >= size) continue;  // above Nyquist
            const double amplitude = std::pow(0.55, octave) * (0.7 + 0.6 * u(1));
            const double phase = 2 * kPi * u(2);
            // sin(αx + βy + φ) = sin(αx) cos(βy + φ) + cos(αx) sin(βy + φ): separable.
            for (int i = 0; i < size; ++i) {
                const double ax = 2 * kPi * ((static_cast<long>(kx) * i) % size) / size;
                const double by = 2 * kPi * ((static_cast<long>(ky) * i) % size) / size + phase;
                sx[i] = std::sin(ax);
                cx[i] = std::cos(ax);
                sy[i] = std::sin(by);
                cy[i] = std::cos(by);
            }
            for (int y = 0; y < size; ++y) {
                double* row = h.data() + static_cast<std::size_t>(y) * size;
                const double a = amplitude * cy[y], b = amplitude * sy[y];
                for (int x = 0; x < size; ++x) row[x] += sx[x] * a + cx[x] * b;
            }
        }
    }
    double peak = 0;
    for (double v : h) peak = std::max(peak, std::abs(v));
    const double scale = peak > 0 ? 1.0 / peak : 0.0;
    for (std::size_t i = 0; i < h.size(); ++i) image.pixels[i] = static_cast<float>(h[i] * scale);
    return image;
}

// ---- Brushed metal -----------------------------------------------------------------------------

Image make_brushed_metal_height_map(int size) {
    size = std::max(size, 16);
    const std::size_t n = static_cast<std::size_t>(size) * size;
    std::vector<double> h(n, 0.0);
    constexpr std::uint32_t kMetalStream = 0xb705u;

    // Groove layers: periodic value noise with nx × ny lattice cells over the tile (long along u).
    // Every lattice row is shifted along u by its own random offset, so cells do not line up.
    struct Layer {
        int cell_u, cell_v;  // cell size in texels at size 512 (scaled with the size)
        double amplitude;
    };
    constexpr std::array<Layer, 4> kLayers{
        {{128, 1, 1.0}, {64, 2, 0.6}, {256, 4, 0.4}, {32, 8, 0.25}}};
    const auto quintic = [](double f) { return f * f * f * (f * (f * 6 - 15) + 10); };
    for (std::size_t li = 0; li < kLayers.size(); ++li) {
        const Layer& layer = kLayers[li];
        const int nx = std::max(1, static_cast<int>(std::lround(512.0 / layer.cell_u)));
        const int ny = std::max(1, static_cast<int>(std::lround(size / (layer.cell_v * 1.0))));
        const std::uint32_t stream = kMetalStream + static_cast<std::uint32_t>(li) * 7919u;
        const auto lattice = [&](int ix, int iy) {  // value in [−1, 1]
            ix = ((ix % nx) + nx) % nx;
            iy = ((iy % ny) + ny) % ny;
            return 2.0 * uniform01(stream, static_cast<std::uint32_t>(iy * nx + ix), 1) - 1.0;
        };
        const auto along_u = [&](int iy, double fx) {  // 1-D noise of lattice row iy
            fx += nx * uniform01(stream, static_cast<std::uint32_t>(iy), 2);
            const double fl = std::floor(fx);
            const int ix = static_cast<int>(fl);
            const double w = quintic(fx - fl);
            return (1 - w) * lattice(ix, iy) + w * lattice(ix + 1, iy);
        };
        for (int y = 0; y < size; ++y) {
            const double fy = static_cast<double>(y) * ny / size;
            const double fly = std::floor(fy);
            const int iy = static_cast<int>(fly);
            const double wy = quintic(fy - fly);
            double* row = h.data() + static_cast<std::size_t>(y) * size;
            for (int x = 0; x < size; ++x) {
                const double fx = static_cast<double>(x) * nx / size;
                const double a = along_u(iy, fx);
                const double v = wy > 0 ? (1 - wy) * a + wy * along_u(iy + 1, fx) : a;
                row[x] += layer.amplitude * v;
            }
        }
    }
    // Grooves to a standard deviation of 0.3.
    double mean = 0, var = 0;
    for (double v : h) mean += v;
    mean /= n;
    for (double v : h) var += (v - mean) * (v - mean);
    const double groove_scale = var > 0 ? 0.3 / std::sqrt(var / n) : 0.0;
    for (double& v : h) v = (v - mean) * groove_scale;

    // Scratches: straight segments, a rounded groove profile, drawn with wrap-around.
    constexpr int kScratches = 8;
    for (int i = 0; i < kScratches; ++i) {
        const auto u = [&](std::uint32_t c) { return uniform01(kMetalStream + 1, i, c); };
        const double px = u(0) * size, py = u(1) * size, angle = u(2) * kPi;
        const double half_length = 0.5 * (0.15 + 0.3 * u(3)) * size;
        const double half_width = 0.6 + 0.4 * u(4);
        const double depth = 0.5 + 0.4 * u(5);
        const double dx = std::cos(angle), dy = std::sin(angle);
        const double reach = half_width + 1;
        const int x0 = static_cast<int>(std::floor(px - std::abs(dx) * half_length - reach));
        const int x1 = static_cast<int>(std::ceil(px + std::abs(dx) * half_length + reach));
        const int y0 = static_cast<int>(std::floor(py - std::abs(dy) * half_length - reach));
        const int y1 = static_cast<int>(std::ceil(py + std::abs(dy) * half_length + reach));
        for (int y = y0; y <= y1; ++y) {
            for (int x = x0; x <= x1; ++x) {
                const double ex = x + 0.5 - px, ey = y + 0.5 - py;
                const double along = std::clamp(ex * dx + ey * dy, -half_length, half_length);
                const double d = std::hypot(ex - along * dx, ey - along * dy) / half_width;
                if (d >= 1) continue;
                const int wx = ((x % size) + size) % size, wy = ((y % size) + size) % size;
                h[static_cast<std::size_t>(wy) * size + wx] -= depth * (1 - d * d);
            }
        }
    }

    mean = 0;
    for (double v : h) mean += v;
    mean /= n;
    double peak = 0;
    for (double& v : h) {
        v -= mean;
        peak = std::max(peak, std::abs(v));
    }
    const double scale = 1.0 / std::max(1.0, peak);
    Image image(size, size, 1);
    for (std::size_t i = 0; i < n; ++i) image.pixels[i] = static_cast<float>(h[i] * scale);
    return image;
}

// ---- Secret writing ----------------------------------------------------------------------------

namespace {

struct Glyph {
    char c;
    std::array<const char*, 7> rows;
};

// A 5 × 7 bitmap font: '#' is ink.
constexpr std::array<Glyph, 31> kFont{{
    {'A', {".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'B', {"####.", "#...#", "#...#", "####.", "#...#", "#...#", "####."}},
    {'C', {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."}},
    {'D', {"####.", "#...#", "#...#", "#...#", "#...#", "#...#", "####."}},
    {'E', {"#####", "#....", "#....", "####.", "#....", "#....", "#####"}},
    {'F', {"#####", "#....", "#....", "####.", "#....", "#....", "#...."}},
    {'G', {".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".####"}},
    {'H', {"#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'I', {".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'J', {"..###", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."}},
    {'K', {"#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"}},
    {'L', {"#....", "#....", "#....", "#....", "#....", "#....", "#####"}},
    {'M', {"#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"}},
    {'N', {"#...#", "#...#", "##..#", "#.#.#", "#..##", "#...#", "#...#"}},
    {'O', {".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'P', {"####.", "#...#", "#...#", "####.", "#....", "#....", "#...."}},
    {'Q', {".###.", "#...#", "#...#", "#...#", "#.#.#", "#..#.", ".##.#"}},
    {'R', {"####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"}},
    {'S', {".####", "#....", "#....", ".###.", "....#", "....#", "####."}},
    {'T', {"#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."}},
    {'U', {"#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'V', {"#...#", "#...#", "#...#", "#...#", "#...#", ".#.#.", "..#.."}},
    {'W', {"#...#", "#...#", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#."}},
    {'X', {"#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#"}},
    {'Y', {"#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#.."}},
    {'Z', {"#####", "....#", "...#.", "..#..", ".#...", "#....", "#####"}},
    {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
    {',', {".....", ".....", ".....", ".....", ".##..", "..#..", ".#..."}},
    {'?', {".###.", "#...#", "....#", "...#.", "..#..", ".....", "..#.."}},
    {'!', {"..#..", "..#..", "..#..", "..#..", "..#..", ".....", "..#.."}},
    {'-', {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
}};

const Glyph* find_glyph(char c) {
    for (const Glyph& g : kFont)
        if (g.c == c) return &g;
    return nullptr;  // a space, or a character the font lacks: left blank
}

constexpr std::string_view kSecretText =
    "CAN YOU READ THE SECRET WRITING? LOOK AT IT FROM A FLAT ANGLE AND THE LETTERS GROW SHORT "
    "ENOUGH TO READ. A MIP MAP FILTERS ISOTROPICALLY, SO AT A GRAZING ANGLE IT PICKS ITS LEVEL "
    "FROM "
    "THE LONG AXIS OF THE FOOTPRINT AND THE THIN STROKES MELT INTO GREY. FOOTPRINT ASSEMBLY TAKES "
    "SEVERAL SMALLER SAMPLES ALONG THAT AXIS, AND THE WRITING STAYS SHARP. THE QUICK BROWN FOX "
    "JUMPS OVER THE LAZY DOG, WHILE THE ZEBRAS WATCH THE MOON RISE OVER THE DARK SEA! ";

}  // namespace

Image make_secret_writing_texture(int size) {
    size = std::max(size, 64);
    const int unit_u = std::max(1, size / 1024);  // stroke width along u, texels
    const int unit_v = 6 * unit_u;                // the 6× stretch along v
    const int advance = 6 * unit_u, line_pitch = 9 * unit_v;
    const int margin_u = 2 * advance, margin_v = line_pitch / 2;
    const int columns = std::max(1, (size - 2 * margin_u) / advance);
    const int lines = std::max(1, (size - 2 * margin_v) / line_pitch);

    // Word-wrap the text (cycled) into lines of `columns` characters.
    std::vector<std::string> text(lines);
    std::size_t pos = 0;
    for (std::string& line : text) {
        while (true) {
            const std::size_t end = kSecretText.find(' ', pos);
            const std::string_view word = kSecretText.substr(pos, end - pos);
            const std::size_t needed = line.size() + (line.empty() ? 0 : 1) + word.size();
            if (!line.empty() && needed > static_cast<std::size_t>(columns)) break;
            if (!line.empty()) line += ' ';
            line += word.substr(0, columns);
            pos = end + 1 >= kSecretText.size() ? 0 : end + 1;
        }
    }

    const Rgb paper{0.85, 0.82, 0.72}, rule{0.62, 0.70, 0.82};
    const Rgb ink{0.02, 0.025, 0.06}, red_ink{0.55, 0.04, 0.03};
    Image image(size, size, 3);
    for (int y = 0; y < size; ++y) {
        const int ly = y - margin_v;
        const int line = ly >= 0 ? ly / line_pitch : -1;
        const int gy = ly >= 0 ? (ly % line_pitch) / unit_v : -1;  // glyph row 0…8
        const bool in_text = line >= 0 && line < lines;
        // A 1-texel ruled line one unit below each line of text.
        const bool ruled = in_text && (ly % line_pitch) == 8 * unit_v;
        for (int x = 0; x < size; ++x) {
            Rgb c = ruled ? rule : paper;
            const int lx = x - margin_u;
            if (in_text && gy < 7 && lx >= 0 && lx < columns * advance) {
                const int col = lx / advance, gx = (lx % advance) / unit_u;
                const std::string& s = text[line];
                if (gx < 5 && col < static_cast<int>(s.size())) {
                    const Glyph* g = find_glyph(s[col]);
                    if (g && g->rows[gy][gx] == '#') c = line % 5 == 3 ? red_ink : ink;
                }
            }
            store(image, x, y, c);
        }
    }
    return image;
}

Image make_topographic_texture(const TerrainShape& terrain, double contour, int size) {
    size = std::max(size, 16);
    const std::vector<double> h = terrain_heights(terrain);
    const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(h.size()))));
    const auto [low, high] = std::minmax_element(h.begin(), h.end());
    const double range = std::max(*high - *low, 1e-12);
    // The height at (x, y) in texels of the texture, bilinear between the samples.
    auto height = [&](double x, double y) {
        const double i = std::clamp(x / size * (n - 1), 0.0, n - 1.0);
        const double j = std::clamp(y / size * (n - 1), 0.0, n - 1.0);
        const int i0 = std::min(static_cast<int>(i), n - 2),
                  j0 = std::min(static_cast<int>(j), n - 2);
        const double fi = i - i0, fj = j - j0;
        auto at = [&](int a, int b) { return h[static_cast<std::size_t>(b) * n + a]; };
        return (1 - fj) * ((1 - fi) * at(i0, j0) + fi * at(i0 + 1, j0)) +
               fj * ((1 - fi) * at(i0, j0 + 1) + fi * at(i0 + 1, j0 + 1));
    };
    struct Stop {
        double at;
        std::array<float, 3> colour;
    };
    static constexpr Stop ramp[] = {{0.0, {0.16f, 0.32f, 0.10f}},
                                    {0.35, {0.34f, 0.44f, 0.16f}},
                                    {0.6, {0.45f, 0.35f, 0.24f}},
                                    {0.8, {0.50f, 0.49f, 0.47f}},
                                    {1.0, {0.92f, 0.93f, 0.95f}}};
    Image image(size, size, 3);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const double px = x + 0.5, py = y + 0.5, value = height(px, py);
            const double a = (value - *low) / range;
            std::size_t k = 1;
            while (k + 1 < std::size(ramp) && a > ramp[k].at) ++k;
            const double w =
                std::clamp((a - ramp[k - 1].at) / (ramp[k].at - ramp[k - 1].at), 0.0, 1.0);
            // Distance to the nearest contour in texels: its height distance over the slope.
            const double slope = std::hypot(height(px + 0.5, py) - height(px - 0.5, py),
                                            height(px, py + 0.5) - height(px, py - 0.5));
            const double to_line =
                std::abs(value / contour - std::round(value / contour)) * contour;
            const double line = std::clamp(1 - to_line / std::max(slope, 1e-12) / 0.75, 0.0, 1.0);
            for (int c = 0; c < 3; ++c) {
                const double colour = (1 - w) * ramp[k - 1].colour[c] + w * ramp[k].colour[c];
                image.at(x, y, c) = static_cast<float>(colour * (1 - 0.7 * line));
            }
        }
    }
    return image;
}

}  // namespace footprint
