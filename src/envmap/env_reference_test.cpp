#include "envmap/env_reference.h"
#include "envmap/env_test_maps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace footprint {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- A smooth analytic environment f(d), d = r̂, with four channels of rising difficulty:
// linear, quadratic (its Gaussian average measures the footprint's second moments, so a wrong
// width or orientation shows), and two products of sinusoids, the last with wavelengths of
// 2π/20 ≈ 0.31 rad (≈ 20–25 texels at the map sizes below).
constexpr int kChannels = 4;
std::array<double, kChannels> analytic(Vec3d r) {
    const Vec3d d = normalize(r);
    return {0.5 + 0.3 * d.x + 0.2 * d.y - 0.1 * d.z,                      //
            d.x * d.y + 0.5 * d.z * d.z,                                  //
            0.5 + 0.5 * std::sin(6 * d.x + 4 * d.y) * std::cos(5 * d.z),  //
            0.5 + 0.5 * std::sin(20 * d.x + 3) * std::sin(17 * d.y)};
}

// Texels = f at the direction of each texel centre (env_direction), faces `size` texels high.
std::vector<Image> sampled_faces(EnvLayout layout, int size) {
    return test::env_images<double>(layout, size, kChannels, [](Vec3d d, float* out) {
        const auto v = analytic(d);
        for (int c = 0; c < kChannels; ++c) out[c] = static_cast<float>(v[c]);
    });
}

EnvironmentMap analytic_latlong(int width) {
    return std::move(
        EnvironmentMap::from_latlong(sampled_faces(EnvLayout::latlong, width / 2)[0]).value());
}
EnvironmentMap analytic_cube(int size) {
    const std::vector<Image> f = sampled_faces(EnvLayout::cube, size);
    return std::move(EnvironmentMap::from_cube_faces({f[0], f[1], f[2], f[3], f[4], f[5]}).value());
}

// ---- Gauss–Hermite nodes and weights for ∫ e^{−x²} g(x) dx (Numerical Recipes' gauher: Newton
// on the orthonormal Hermite recurrence), so that E[g(a)], a ~ N(0, 1), is
// Σ w_i g(√2 x_i)/√π. With n = 64 nodes it integrates a polynomial of degree 127 exactly; the
// integrands below (f over a footprint of ≤ 0.15 rad) converge far below 1e−10.
struct GaussHermite {
    std::vector<double> node, weight;
};
GaussHermite gauss_hermite(int n) {
    GaussHermite gh;
    gh.node.resize(n), gh.weight.resize(n);
    const double pi_m4 = 1 / std::pow(kPi, 0.25);
    double z = 0;
    for (int i = 0; i < (n + 1) / 2; ++i) {
        if (i == 0)
            z = std::sqrt(2.0 * n + 1) - 1.85575 * std::pow(2.0 * n + 1, -0.16667);
        else if (i == 1)
            z -= 1.14 * std::pow(double(n), 0.426) / z;
        else if (i == 2)
            z = 1.86 * z - 0.86 * gh.node[0];
        else if (i == 3)
            z = 1.91 * z - 0.91 * gh.node[1];
        else
            z = 2.0 * z - gh.node[i - 2];
        double pp = 0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p1 = pi_m4, p2 = 0;
            for (int j = 0; j < n; ++j) {
                const double p3 = p2;
                p2 = p1;
                p1 = z * std::sqrt(2.0 / (j + 1)) * p2 - std::sqrt(double(j) / (j + 1)) * p3;
            }
            pp = std::sqrt(2.0 * n) * p2;
            const double z1 = z;
            z = z1 - p1 / pp;
            if (std::abs(z - z1) <= 1e-15) break;
        }
        gh.node[i] = z, gh.node[n - 1 - i] = -z;
        gh.weight[i] = gh.weight[n - 1 - i] = 2.0 / (pp * pp);
    }
    return gh;
}

// E[f(normalize(r̂ + a·axis1 + b·axis2))], (a, b) ~ N(0, 1): straight on f, no map.
std::array<double, kChannels> gaussian_integral(const SphereGaussian& g) {
    static const GaussHermite gh = gauss_hermite(64);
    const Vec3d centre = normalize(g.direction);
    std::array<double, kChannels> sum{};
    for (std::size_t j = 0; j < gh.node.size(); ++j)
        for (std::size_t i = 0; i < gh.node.size(); ++i) {
            const double a = std::sqrt(2.0) * gh.node[i], b = std::sqrt(2.0) * gh.node[j];
            const double w = gh.weight[i] * gh.weight[j] / kPi;
            const auto v = analytic(centre + a * g.axis1 + b * g.axis2);
            for (int c = 0; c < kChannels; ++c) sum[c] += w * v[c];
        }
    return sum;
}

// A footprint at r with standard deviations sigma1 ≥ sigma2 (radians), major axis at `angle` in
// the tangent basis.
SphereGaussian gaussian_at(Vec3d r, double sigma1, double sigma2, double angle) {
    Vec3d u, v;
    const Vec3d n = normalize(r);
    tangent_basis(n, u, v);
    const Vec3d e1 = std::cos(angle) * u + std::sin(angle) * v;
    const Vec3d e2 = -std::sin(angle) * u + std::cos(angle) * v;
    return {n, sigma1 * e1, sigma2 * e2};
}

// ---- The reference of a constant map is that constant, for every layout, any footprint: point,
// tiny, wide (the per-axis cap), at the lat-long poles and the sphere-map rim.
TEST(EnvReference, ConstantMapGivesTheConstant) {
    const Image plain(32, 32, 3, 0.375f), wide(64, 32, 3, 0.375f);
    std::vector<EnvironmentMap> maps;
    maps.push_back(std::move(EnvironmentMap::from_latlong(wide).value()));
    maps.push_back(std::move(
        EnvironmentMap::from_cube_faces({plain, plain, plain, plain, plain, plain}).value()));
    maps.push_back(std::move(EnvironmentMap::from_sphere(plain).value()));
    maps.push_back(std::move(EnvironmentMap::from_paraboloid(plain, plain).value()));
    std::mt19937 rng(11);
    std::normal_distribution<double> g(0, 1);
    std::uniform_real_distribution<double> u(0, 1);
    const Vec3d special[] = {{0, 1, 0}, {0, -1, 0}, {0, 0, -1}, {1, 1, 1}, {1, 0, 0}};
    for (const EnvironmentMap& map : maps)
        for (int i = 0; i < 25; ++i) {
            const Vec3d r = i < 5 ? special[i] : Vec3d{g(rng), g(rng), g(rng)};
            const double sigma1 = i % 3 == 0 ? 0.0 : 0.3 * u(rng);
            const SphereGaussian f = gaussian_at(r, sigma1, sigma1 * u(rng), 6 * u(rng));
            float out[3];
            environment_reference(map, f, out);
            for (float v : out) ASSERT_NEAR(v, 0.375f, 2e-6f) << int(map.layout()) << " " << i;
        }
}

// ---- A zero-size footprint is the finest-level bilinear point sample, exactly.
TEST(EnvReference, ZeroFootprintIsTheBilinearPointSample) {
    const EnvironmentMap cube = analytic_cube(32);
    std::mt19937 rng(12);
    std::normal_distribution<double> g(0, 1);
    for (int i = 0; i < 50; ++i) {
        const Vec3d r{g(rng), g(rng), g(rng)};
        float want[kChannels], got[kChannels];
        environment_bilinear(cube, vec3_cast<float>(normalize(r)), 0, want);
        environment_reference(cube, SphereGaussian{r, {}, {}}, got);
        for (int c = 0; c < kChannels; ++c) ASSERT_EQ(got[c], want[c]);
    }
}

// ---- The reference against an independent integral of f itself (Gauss–Hermite, no map): the
// only difference is the map's reconstruction error — bilinear interpolation of f sampled at
// texel centres, about h²/8·|f''| for a point and ~h²/12 averaged over a footprint (h = texel
// angle ≈ 0.012 rad at lat-long 512×256 and 0.006–0.016 rad at cube 128; |f''| ≤ ~400 for the
// last channel) — plus the quadrature's (≲ 1e−6, see QuadratureHasConverged).
//
// Measured (default options) over 160 footprints per map, σ1 ∈ {0, ~0 … 0.15} rad, anisotropy up
// to 8:1, random directions plus cube corners and edges, poles, the seam: max |error| for
// point-like footprints (σ1 < 0.02 rad, reconstruction error of a near-point sample) 4.2e−3
// (lat-long 512×256) and 5.9e−3 (cube 128); for wider footprints 1.9e−3 and 2.4e−3 (averaged
// interpolation error plus the quadrature's ≤ 4e−4). Bounds ≈ 1.5×.
constexpr double kPointLikeBound = 9e-3;
constexpr double kFootprintBound = 3.5e-3;
// Swapping the axes (the "transposed" footprint) or doubling the covariance (K instead of K/4)
// changes the result by far more than the bound on the wide footprints (measured 0.24 and 0.084).
constexpr double kMistakeFactor = 5;

struct AgreementStats {
    double max_point = 0, max_footprint = 0, max_swapped = 0, max_doubled = 0;
};

AgreementStats agreement(const EnvironmentMap& map, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0, 1);
    std::uniform_real_distribution<double> u(0, 1);
    const Vec3d special[] = {{1, 1, 1},     {-1, 1, -1},  {1, 0.999, 0}, {0, 1, 0},
                             {0, -1, 0},    {0.01, 1, 0}, {0, 0.3, 1},   {-0.001, 0.2, 1},
                             {1, 1e-3, -1}, {0, 0, -1}};
    AgreementStats stats;
    for (int i = 0; i < 160; ++i) {
        const Vec3d r = i < 10 ? special[i] : Vec3d{g(rng), g(rng), g(rng)};
        const double sigma1 = i % 8 == 0 ? 0.0 : 0.15 * std::pow(u(rng), 2.0);
        const double sigma2 = sigma1 / (1 + 7 * u(rng));
        const SphereGaussian f = gaussian_at(r, sigma1, sigma2, 6.3 * u(rng));
        float got[kChannels];
        environment_reference(map, f, got);
        const auto want = gaussian_integral(f);
        double error = 0;
        for (int c = 0; c < kChannels; ++c) error = std::max(error, std::abs(got[c] - want[c]));
        double& group_max = sigma1 < 0.02 ? stats.max_point : stats.max_footprint;
        group_max = std::max(group_max, error);
        if (sigma1 >= 0.05 && sigma2 < 0.5 * sigma1) {
            // The mistakes: axes swapped (same sizes, orientation turned by 90°) and K for K/4.
            const auto swapped = gaussian_integral(SphereGaussian{
                f.direction, f.axis2 * (sigma1 / sigma2), f.axis1 * (sigma2 / sigma1)});
            const auto doubled = gaussian_integral(
                SphereGaussian{f.direction, std::sqrt(2.0) * f.axis1, std::sqrt(2.0) * f.axis2});
            double e_swapped = 0, e_doubled = 0;
            for (int c = 0; c < kChannels; ++c) {
                e_swapped = std::max(e_swapped, std::abs(got[c] - swapped[c]));
                e_doubled = std::max(e_doubled, std::abs(got[c] - doubled[c]));
            }
            stats.max_swapped = std::max(stats.max_swapped, e_swapped);
            stats.max_doubled = std::max(stats.max_doubled, e_doubled);
        }
    }
    return stats;
}

TEST(EnvReference, MatchesAnIndependentIntegralOfTheEnvironment) {
    const EnvironmentMap latlong = analytic_latlong(512);
    const EnvironmentMap cube = analytic_cube(128);
    for (const EnvironmentMap* map : {&latlong, &cube}) {
        const AgreementStats s = agreement(*map, 21);
        std::printf(
            "[ reference ] %s: max |err| point-like %.2e, footprints %.2e; "
            "swapped axes %.2e, doubled covariance %.2e\n",
            map == &latlong ? "lat-long 512x256" : "cube 128", s.max_point, s.max_footprint,
            s.max_swapped, s.max_doubled);
        EXPECT_LT(s.max_point, kPointLikeBound);
        EXPECT_LT(s.max_footprint, kFootprintBound);
        EXPECT_GT(s.max_swapped, kMistakeFactor * kFootprintBound);
        EXPECT_GT(s.max_doubled, kMistakeFactor * kFootprintBound);
    }
}

// ---- Lat-long and cube maps of the same f give the same reference: each within its
// reconstruction error of the true integral, so within the sum of the two of each other. Measured
// max |diff| 1.2e−3 over 60 footprints of σ1 ∈ [0.02, 0.12] rad; bound 2.5e−3.
TEST(EnvReference, LatLongAndCubeAgree) {
    const EnvironmentMap latlong = analytic_latlong(512);
    const EnvironmentMap cube = analytic_cube(128);
    std::mt19937 rng(31);
    std::normal_distribution<double> g(0, 1);
    std::uniform_real_distribution<double> u(0, 1);
    double max_error = 0;
    for (int i = 0; i < 60; ++i) {
        const double sigma1 = 0.02 + 0.1 * u(rng);
        const SphereGaussian f = gaussian_at({g(rng), g(rng), g(rng)}, sigma1,
                                             sigma1 * (0.2 + 0.8 * u(rng)), 6.3 * u(rng));
        float a[kChannels], b[kChannels];
        environment_reference(latlong, f, a);
        environment_reference(cube, f, b);
        for (int c = 0; c < kChannels; ++c)
            max_error = std::max(max_error, double(std::abs(a[c] - b[c])));
    }
    std::printf("[ reference ] lat-long vs cube: max |diff| %.2e\n", max_error);
    EXPECT_LT(max_error, 2.5e-3);
}

// ---- The quadrature's own error: the defaults (step ½ texel, cut at 3.5σ) against step 0.1 texel
// and a 5σ cut. Measured max 3.7e−4 on this high-contrast environment (channel 3, |f''| ≈ 400):
// ~1.3e−4 from the 3.5σ cut (0.05 % of the weight) and the rest from the ½-texel step over the
// reconstruction's kinks at texel edges (it falls as step²: 0.25 texel gives ~1e−4). Bound 6e−4 —
// far below the filters' errors that the reference is used to measure (≳ 3e−3, see
// env_accuracy_test.cpp).
constexpr double kQuadratureBound = 6e-4;

TEST(EnvReference, QuadratureHasConverged) {
    const EnvironmentMap cube = analytic_cube(64);
    EnvReferenceOptions fine;
    fine.step_texels = 0.1;
    fine.cutoff_sigma = 5;
    std::mt19937 rng(41);
    std::normal_distribution<double> g(0, 1);
    std::uniform_real_distribution<double> u(0, 1);
    double max_error = 0;
    for (int i = 0; i < 20; ++i) {
        const double sigma1 = 0.1 * u(rng);
        const SphereGaussian f =
            gaussian_at({g(rng), g(rng), g(rng)}, sigma1, sigma1 * u(rng), 6.3 * u(rng));
        float a[kChannels], b[kChannels];
        environment_reference(cube, f, a);
        environment_reference(cube, f, b, fine);
        for (int c = 0; c < kChannels; ++c)
            max_error = std::max(max_error, double(std::abs(a[c] - b[c])));
    }
    std::printf("[ reference ] default vs fine quadrature: max |diff| %.2e\n", max_error);
    EXPECT_LT(max_error, kQuadratureBound);
}

// ---- sphere_gaussian_from_ray_differentials: Σ = ¼ Σ_k P dr_k dr_kᵀ P / |r|² exactly, axes
// orthogonal, tangent and ordered, invariant under a common positive scale of (r, dr).
TEST(EnvReference, RayDifferentialFootprintHasTheQuarterCovariance) {
    std::mt19937 rng(51);
    std::normal_distribution<double> g(0, 1);
    for (int i = 0; i < 200; ++i) {
        const Vec3d r{g(rng), g(rng), g(rng)}, dx{g(rng), g(rng), g(rng)},
            dy{g(rng), g(rng), g(rng)};
        const double scale = std::exp(2 * g(rng));
        const SphereGaussian f = sphere_gaussian_from_ray_differentials(r, 0.1 * dx, 0.1 * dy);
        const Vec3d n = normalize(r);
        auto project = [&](Vec3d d) { return (d - dot(d, n) * n) / length(r); };
        const Vec3d px = project(0.1 * dx), py = project(0.1 * dy);
        const double want[3][3] = {
            {0.25 * (px.x * px.x + py.x * py.x), 0.25 * (px.x * px.y + py.x * py.y),
             0.25 * (px.x * px.z + py.x * py.z)},
            {0, 0.25 * (px.y * px.y + py.y * py.y), 0.25 * (px.y * px.z + py.y * py.z)},
            {0, 0, 0.25 * (px.z * px.z + py.z * py.z)}};
        const Vec3d a = f.axis1, b = f.axis2;
        const double got[3][3] = {
            {a.x * a.x + b.x * b.x, a.x * a.y + b.x * b.y, a.x * a.z + b.x * b.z},
            {0, a.y * a.y + b.y * b.y, a.y * a.z + b.y * b.z},
            {0, 0, a.z * a.z + b.z * b.z}};
        const double trace = want[0][0] + want[1][1] + want[2][2];
        for (int p = 0; p < 3; ++p)
            for (int q = p; q < 3; ++q) ASSERT_NEAR(got[p][q], want[p][q], 1e-12 * trace);
        EXPECT_NEAR(dot(a, n), 0, 1e-12 * length(a));
        EXPECT_NEAR(dot(b, n), 0, 1e-12 * length(a));
        EXPECT_NEAR(dot(a, b), 0, 1e-12 * trace);
        EXPECT_GE(length(a), length(b));
        EXPECT_NEAR(dot(f.direction, n), 1, 1e-14);
        const SphereGaussian scaled =
            sphere_gaussian_from_ray_differentials(scale * r, 0.1 * scale * dx, 0.1 * scale * dy);
        EXPECT_NEAR(length(scaled.axis1 - a), 0, 1e-12 * length(a) + 1e-300);
    }
    // Degenerate input: a point at +z, or a point in r's direction.
    const SphereGaussian zero = sphere_gaussian_from_ray_differentials({}, {1, 0, 0}, {0, 1, 0});
    EXPECT_EQ(zero.direction.z, 1);
    EXPECT_EQ(length(zero.axis1), 0);
    const SphereGaussian nan =
        sphere_gaussian_from_ray_differentials({0, 2, 0}, {std::nan(""), 0, 0}, {0, 1, 0});
    EXPECT_EQ(nan.direction.y, 1);
    EXPECT_EQ(length(nan.axis1), 0);
}

// Monte Carlo: pixel offsets (x, y) ~ N(0, ¼I) (the σ = ½-pixel pixel filter of spec §2.6) moved
// through r + x·∂r/∂x + y·∂r/∂y onto the sphere and centrally projected onto the tangent plane
// have the covariance Σ: with ∂r ⟂ r the projection is exactly linear, so only sampling noise is
// left (200 000 samples: ≈ 0.5 % of the trace; bound 2 %; a K-for-K/4 or transposed Σ misses by
// ≥ 100 % of some entry's scale).
TEST(EnvReference, RayDifferentialFootprintMatchesMonteCarlo) {
    std::mt19937 rng(61);
    std::normal_distribution<double> g(0, 1);
    for (int i = 0; i < 5; ++i) {
        const Vec3d r = 3.0 * normalize(Vec3d{g(rng), g(rng), g(rng)});
        const Vec3d n = normalize(r);
        auto tangent = [&](Vec3d d) { return d - dot(d, n) * n; };
        const Vec3d dx = 0.05 * tangent({g(rng), g(rng), g(rng)});
        const Vec3d dy = 0.02 * tangent({g(rng), g(rng), g(rng)});
        const SphereGaussian f = sphere_gaussian_from_ray_differentials(r, dx, dy);
        double m[3][3] = {};
        const int samples = 200000;
        for (int k = 0; k < samples; ++k) {
            const double x = 0.5 * g(rng), y = 0.5 * g(rng);
            const Vec3d d = normalize(r + x * dx + y * dy);
            const Vec3d t = d / dot(d, n) - n;
            const double c[3] = {t.x, t.y, t.z};
            for (int p = 0; p < 3; ++p)
                for (int q = 0; q < 3; ++q) m[p][q] += c[p] * c[q] / samples;
        }
        const Vec3d a = f.axis1, b = f.axis2;
        const double ca[3] = {a.x, a.y, a.z}, cb[3] = {b.x, b.y, b.z};
        const double trace = dot(a, a) + dot(b, b);
        for (int p = 0; p < 3; ++p)
            for (int q = 0; q < 3; ++q)
                EXPECT_NEAR(m[p][q], ca[p] * ca[q] + cb[p] * cb[q], 0.02 * trace) << i;
    }
}

// In texel space the sphere Gaussian is K/4: S J_P(r̂) Σ J_P(r̂)ᵀ S equals a quarter of
// compute_env_footprint's K (form (a)) for every layout (float K: relative 1e−4; a transposed or
// un-quartered Σ misses by ≥ 30 % of the trace).
TEST(EnvReference, RayDifferentialFootprintIsAQuarterOfTheTexelFootprint) {
    struct Case {
        EnvLayout layout;
        Vec2 scale;
    };
    const Case cases[] = {{EnvLayout::cube, {128, 128}},
                          {EnvLayout::latlong, {512, 256}},
                          {EnvLayout::sphere, {256, 256}},
                          {EnvLayout::paraboloid, {128, 128}}};
    std::mt19937 rng(71);
    std::normal_distribution<float> g(0, 1);
    for (const Case& c : cases)
        for (int i = 0; i < 100; ++i) {
            const Vec3 r{g(rng), g(rng), g(rng)}, dx{g(rng), g(rng), g(rng)},
                dy{g(rng), g(rng), g(rng)};
            if (c.layout == EnvLayout::sphere && r.z / std::sqrt(dot(r, r)) < -0.9f) continue;
            const EnvFootprint fp =
                compute_env_footprint(c.layout, c.scale, r, 0.01f * dx, 0.01f * dy);
            const SphereGaussian f = sphere_gaussian_from_ray_differentials(
                vec3_cast<double>(r), vec3_cast<double>(0.01f * dx), vec3_cast<double>(0.01f * dy));
            const Jacobian23d j = env_jacobian(c.layout, normalize(vec3_cast<double>(r)));
            const double u1 = c.scale.x * dot(j.ds, f.axis1), v1 = c.scale.y * dot(j.dt, f.axis1);
            const double u2 = c.scale.x * dot(j.ds, f.axis2), v2 = c.scale.y * dot(j.dt, f.axis2);
            const double trace = 0.25 * fp.matrix.trace();
            EXPECT_NEAR(u1 * u1 + u2 * u2, 0.25 * fp.matrix.xx, 1e-4 * trace);
            EXPECT_NEAR(u1 * v1 + u2 * v2, 0.25 * fp.matrix.xy, 1e-4 * trace);
            EXPECT_NEAR(v1 * v1 + v2 * v2, 0.25 * fp.matrix.yy, 1e-4 * trace);
        }
}

}  // namespace
}  // namespace footprint
