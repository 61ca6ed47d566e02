// envmap/irradiance.cpp — nine spherical-harmonic coefficients of the radiance and the irradiance
// they give (irradiance.h).
#include <footprint/envmap/irradiance.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace footprint {

std::array<float, 9> sh9_basis(Vec3 w) {
    // The normalisations of Y_lm (Ramamoorthi & Hanrahan 2001, eq. 3).
    constexpr float c0 = 0.282095f, c1 = 0.488603f, c2 = 1.092548f, c20 = 0.315392f,
                    c22 = 0.546274f;
    return {c0,
            c1 * w.y,
            c1 * w.z,
            c1 * w.x,
            c2 * w.x * w.y,
            c2 * w.y * w.z,
            c20 * (3 * w.z * w.z - 1),
            c2 * w.x * w.z,
            c22 * (w.x * w.x - w.y * w.y)};
}

IrradianceSH project_radiance(const std::function<Vec3(Vec3, Vec3, Vec3)>& radiance, int samples) {
    samples = std::max(1, samples);
    const double cell = 4 * std::numbers::pi / samples;  // each direction's solid angle
    const double step = std::sqrt(cell);                 // its side, as a ray differential
    const double golden_angle = std::numbers::pi * (3 - std::sqrt(5.0));
    std::array<std::array<double, 3>, 9> sum{};
    for (int i = 0; i < samples; ++i) {
        // The spherical Fibonacci lattice: equal-area bands in z, turned by the golden angle.
        const double z = 1 - (2 * i + 1) / static_cast<double>(samples);
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        const double phi = golden_angle * i;
        const Vec3 w{static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                     static_cast<float>(z)};
        Vec3 e1, e2;
        tangent_basis(w, e1, e2);
        const Vec3 l = radiance(w, static_cast<float>(step) * e1, static_cast<float>(step) * e2);
        const std::array<float, 9> y = sh9_basis(w);
        for (int k = 0; k < 9; ++k) {
            sum[k][0] += double(y[k]) * l.x, sum[k][1] += double(y[k]) * l.y;
            sum[k][2] += double(y[k]) * l.z;
        }
    }
    IrradianceSH sh;
    for (int k = 0; k < 9; ++k) {
        sh.coefficients[k] = {static_cast<float>(cell * sum[k][0]),
                              static_cast<float>(cell * sum[k][1]),
                              static_cast<float>(cell * sum[k][2])};
    }
    return sh;
}

namespace {

// √π z e^{z²} erfc(z), z > 0: erfc by Abramowitz & Stegun 7.1.26 (its e^{−z²} cancelling) up to
// z = 2, where its error of 1.5e−7 is still 8e−6 after the e^{z²}; beyond, Laplace's continued
// fraction erfc(z) = e^{−z²}/√π · 1/(z + ½/(z + 1/(z + (3/2)/(z + …)))), eight deep (1e−5 there).
double root_pi_z_erfcx(double z) {
    if (z <= 2) {
        const double t = 1 / (1 + 0.3275911 * z);
        const double p =
            t * (0.254829592 +
                 t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429))));
        return std::sqrt(std::numbers::pi) * z * p;
    }
    double d = z;
    for (int k = 8; k >= 1; --k) d = z + 0.5 * k / d;
    return z / d;
}

// x e^x E₁(x), x > 0: Abramowitz & Stegun 5.1.53 (a series, x ≤ 1) and 5.1.56 (a rational
// function, x ≥ 1), both to about 1e−7 relative.
double x_ex_e1(double x) {
    if (x <= 1) {
        const double e1 =
            -std::log(x) - 0.57721566 +
            x * (0.99999193 +
                 x * (-0.24991055 + x * (0.05519968 + x * (-0.00976004 + x * 0.00107857))));
        return x * std::exp(x) * e1;
    }
    return (x * x + 2.334733 * x + 0.250621) / (x * x + 3.330657 * x + 1.681534);
}

}  // namespace

std::array<float, 2> slope_band_gains(float slope_variance) {
    if (!(slope_variance > 0)) return {1, 1};
    // A slope s ~ N(0, σ² I) tilts the normal by θ, cos θ = (1 + |s|²)^(−½), |s|² ~ Exp(2σ²).
    const double x = 1 / (2 * double(slope_variance));
    const double g1 = root_pi_z_erfcx(std::sqrt(x));  // E[cos θ]
    const double g2 = (3 * x_ex_e1(x) - 1) / 2;       // E[(3 cos²θ − 1)/2]
    return {static_cast<float>(g1), static_cast<float>(g2)};
}

Vec3 irradiance(const IrradianceSH& sh, Vec3 n, float slope_variance) {
    constexpr float pi = std::numbers::pi_v<float>;
    // Â_l (the clamped cosine's band gains) × the slopes' attenuation of band l.
    const auto [g1, g2] = slope_band_gains(slope_variance);
    const float a[3] = {pi, 2 * pi / 3 * g1, pi / 4 * g2};
    constexpr int band[9] = {0, 1, 1, 1, 2, 2, 2, 2, 2};
    const std::array<float, 9> y = sh9_basis(n);
    Vec3 e{0, 0, 0};
    for (int k = 0; k < 9; ++k) e = e + (a[band[k]] * y[k]) * sh.coefficients[k];
    return {std::max(0.0f, e.x), std::max(0.0f, e.y), std::max(0.0f, e.z)};
}

}  // namespace footprint
