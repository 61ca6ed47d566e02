// Tests of the irradiance from nine spherical-harmonic coefficients (envmap/irradiance.h) against
// brute-force cosine integrals: of a radiance field of bands ≤ 2 (which nine coefficients hold
// exactly), of an environment map with a sun (which they approximate), and of the irradiance
// averaged over Gaussian slopes (the roughness widening).
#include <footprint/envmap/irradiance.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "envmap/env_test_maps.h"

namespace footprint {
namespace {

constexpr double kPi = std::numbers::pi;

// A radiance of bands 0…2 only, different per channel, with every one of the nine harmonics and
// no symmetry that would hide a wrong sign or a swapped axis.
Vec3 band_two_radiance(Vec3 w) {
    const float x = w.x, y = w.y, z = w.z;
    const float common = 0.3f * x * y - 0.2f * y * z + 0.25f * x * z + 0.15f * (x * x - y * y) -
                         0.1f * (3 * z * z - 1);
    return {1.0f + 0.6f * x + common, 0.8f - 0.5f * y + 0.2f * z + common,
            0.6f + 0.4f * z - 0.3f * x + 0.5f * common};
}

// ∫ L(ω) max(0, n·ω) dω by the midpoint rule on a fine (θ, φ) grid.
template <class Radiance>
Vec3 brute_force_irradiance(const Radiance& radiance, Vec3 n, int rows = 720) {
    double e[3] = {0, 0, 0};
    const int columns = 2 * rows;
    for (int i = 0; i < rows; ++i) {
        const double theta = (i + 0.5) * kPi / rows;
        const double d_omega = std::sin(theta) * (kPi / rows) * (2 * kPi / columns);
        for (int j = 0; j < columns; ++j) {
            const double phi = (j + 0.5) * 2 * kPi / columns;
            const Vec3 w{static_cast<float>(std::sin(theta) * std::cos(phi)),
                         static_cast<float>(std::sin(theta) * std::sin(phi)),
                         static_cast<float>(std::cos(theta))};
            const double c = dot(n, w);
            if (c <= 0) continue;
            const Vec3 l = radiance(w);
            e[0] += l.x * c * d_omega, e[1] += l.y * c * d_omega, e[2] += l.z * c * d_omega;
        }
    }
    return {static_cast<float>(e[0]), static_cast<float>(e[1]), static_cast<float>(e[2])};
}

std::vector<Vec3> test_normals() {
    std::vector<Vec3> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}};
    std::mt19937 rng(7);
    std::normal_distribution<float> gauss;
    for (int i = 0; i < 12; ++i)
        normals.push_back(normalize(Vec3{gauss(rng), gauss(rng), gauss(rng)}));
    return normals;
}

float max_abs_difference(Vec3 a, Vec3 b) {
    return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)});
}

// A radiance of bands ≤ 2 has its irradiance exactly in nine coefficients: what is left is the
// two quadratures' error. A harmonic's sign or axis wrong would be off by ≥ 0.05.
TEST(Irradiance, IsExactForARadianceOfBandsUpToTwo) {
    constexpr float kTolerance = 2e-3f;  // the midpoint rules' error on E ≈ 3
    const IrradianceSH sh =
        project_radiance([](Vec3 w, Vec3, Vec3) { return band_two_radiance(w); });
    for (Vec3 n : test_normals()) {
        const Vec3 want = brute_force_irradiance(band_two_radiance, n);
        const Vec3 got = irradiance(sh, n);
        EXPECT_LT(max_abs_difference(got, want), kTolerance)
            << "n = " << n.x << ' ' << n.y << ' ' << n.z << ": " << got.x << " vs " << want.x;
    }
    // A constant radiance L gives E = πL everywhere.
    const IrradianceSH constant = project_radiance([](Vec3, Vec3, Vec3) {
        return Vec3{1, 2, 0.5f};
    });
    const Vec3 e = irradiance(constant, normalize(Vec3{0.3f, -0.2f, 0.9f}));
    EXPECT_NEAR(e.x, kPi, 1e-4);
    EXPECT_NEAR(e.y, 2 * kPi, 2e-4);
    EXPECT_NEAR(e.z, 0.5 * kPi, 1e-4);
}

// A lat-long map of a sky (blue above, brown ground) with a sun of a few texels, projected through
// its filtered lookups: against the cosine integral over its texels, the nine coefficients' error
// is the truncation's (bands ≥ 3 of a near-point source), far below the mean colour's.
TEST(Irradiance, ApproximatesAnEnvironmentMapWithASun) {
    const Vec3 sun = normalize(Vec3{0.4f, 0.3f, 0.85f});
    auto sky = [&](Vec3 w, float* out) {
        const bool in_sun = dot(w, sun) > std::cos(0.06f);
        const float up = std::max(0.0f, w.z);
        out[0] = in_sun ? 200.0f : (w.z > 0 ? 0.3f + 0.2f * up : 0.25f);
        out[1] = in_sun ? 180.0f : (w.z > 0 ? 0.5f + 0.2f * up : 0.18f);
        out[2] = in_sun ? 150.0f : (w.z > 0 ? 0.9f + 0.3f * up : 0.1f);
    };
    constexpr int kSize = 128;
    const std::vector<Image> images = test::env_images(EnvLayout::latlong, kSize, 3, sky);
    const EnvironmentMap map = test::env_map_from_images(EnvLayout::latlong, images);
    const IrradianceSH sh = project_radiance([&](Vec3 w, Vec3 d1, Vec3 d2) {
        float out[3];
        environment_lookup(map, w, d1, d2, EnvLookupOptions{}, out);
        return Vec3{out[0], out[1], out[2]};
    });

    // The brute force: every texel's radiance × its solid angle (the parametrisation's area
    // element, by central differences) × the clamped cosine.
    const Image& image = images[0];
    const int width = image.width, height = image.height;
    std::vector<std::pair<Vec3, float>> texels;  // direction, solid angle
    double total = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double u = (x + 0.5) / width, v = (y + 0.5) / height, h = 1e-4;
            auto dir = [](double s, double t) {
                return normalize(env_direction(EnvLayout::latlong, 0, s, t));
            };
            const Vec3d du = (dir(u + h, v) - dir(u - h, v)) / (2 * h);
            const Vec3d dv = (dir(u, v + h) - dir(u, v - h)) / (2 * h);
            const double omega = length(cross(du, dv)) / (double(width) * height);
            const Vec3d w = dir(u, v);
            texels.emplace_back(Vec3{float(w.x), float(w.y), float(w.z)},
                                static_cast<float>(omega));
            total += omega;
        }
    ASSERT_NEAR(total, 4 * kPi, 1e-3);
    Vec3 mean{0, 0, 0};
    for (std::size_t i = 0; i < texels.size(); ++i) {
        const float* l = image.at(static_cast<int>(i) % width, static_cast<int>(i) / width);
        mean = mean + (texels[i].second / float(4 * kPi)) * Vec3{l[0], l[1], l[2]};
    }

    double worst = 0, worst_mean = 0;
    for (Vec3 n : test_normals()) {
        double e[3] = {0, 0, 0};
        for (std::size_t i = 0; i < texels.size(); ++i) {
            const double c = dot(n, texels[i].first);
            if (c <= 0) continue;
            const float* l = image.at(static_cast<int>(i) % width, static_cast<int>(i) / width);
            for (int k = 0; k < 3; ++k) e[k] += l[k] * c * texels[i].second;
        }
        const Vec3 want{float(e[0]), float(e[1]), float(e[2])};
        const double scale = std::max({want.x, want.y, want.z, 1.0f});
        worst = std::max(worst, max_abs_difference(irradiance(sh, n), want) / scale);
        worst_mean = std::max(worst_mean, max_abs_difference(float(kPi) * mean, want) / scale);
    }
    std::printf("largest relative error: nine coefficients %.4f, the mean colour %.4f\n", worst,
                worst_mean);
    constexpr double kTruncation = 0.10;  // bands ≥ 3 of a sun of 0.06 rad
    EXPECT_LT(worst, kTruncation);
    EXPECT_LT(worst * 5, worst_mean);
}

// Averaged over slopes of variance σ² per axis about n, the irradiance is the nine coefficients'
// bands scaled by g_1, g_2: against a quadrature of E at the tilted normals. A heat kernel's
// exp(−l(l+1)σ²/2) in their place is off by 0.028 at σ² = 0.1.
TEST(Irradiance, RoughnessWidensAsTheAverageOverTheSlopes) {
    const IrradianceSH sh =
        project_radiance([](Vec3 w, Vec3, Vec3) { return band_two_radiance(w); });
    for (float variance : {0.01f, 0.1f, 0.5f, 1.0f}) {
        constexpr float kTolerance = 1e-3f;  // the quadrature's error, E ≈ 1…4
        for (Vec3 n : test_normals()) {
            Vec3 t1, t2;
            tangent_basis(n, t1, t2);
            // The slopes' Gaussian by a square grid over ±6σ (midpoint rule, weights normalised).
            constexpr int kNodes = 121;
            const float step = 12.0f / kNodes;
            double sum[3] = {0, 0, 0}, weights = 0;
            for (int i = 0; i < kNodes; ++i)
                for (int j = 0; j < kNodes; ++j) {
                    const float u = -6 + (i + 0.5f) * step, v = -6 + (j + 0.5f) * step;
                    const double w = std::exp(-0.5 * (u * u + v * v));
                    const float a = std::sqrt(variance) * u, b = std::sqrt(variance) * v;
                    const Vec3 e = irradiance(sh, normalize(n - a * t1 - b * t2));
                    sum[0] += w * e.x, sum[1] += w * e.y, sum[2] += w * e.z, weights += w;
                }
            const Vec3 want{float(sum[0] / weights), float(sum[1] / weights),
                            float(sum[2] / weights)};
            const Vec3 widened = irradiance(sh, n, variance);
            const Vec3 sharp = irradiance(sh, n);
            EXPECT_LT(max_abs_difference(widened, want), kTolerance) << "σ² " << variance;
            // …and the widening is not nothing: E(n) itself is further off.
            if (variance >= 0.1f) {
                EXPECT_LT(max_abs_difference(widened, want),
                          0.5f * max_abs_difference(sharp, want) + 1e-3f);
            }
        }
    }
}

}  // namespace
}  // namespace footprint
