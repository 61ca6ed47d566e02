// Accuracy of the filtered environment lookups (environment_lookup form (a), default
// LookupOptions = footprint assembly, spec §2.8–2.9 and §3) against the brute-force reference
// (env_reference.h: the finest level integrated over the footprint's Gaussian on the sphere,
// covariance K/4, spec §2.6).
//
// The environment is band-limited but textured: per channel a sum of six sinusoids of direction
// projections, 0.5 ± 0.45, wavelengths 0.2–1 rad (≥ ~16 level-0 texels on every map below), so
// footprints of 2–32 texels attenuate its components anywhere between not at all and completely —
// a filter of the wrong size, shape or orientation shows. Maps: cube 128², lat-long 512×256,
// sphere 256², paraboloid 2 × 256² (level-0 texels of 0.006–0.03 rad).
//
// Each group states its bounds on RMSE (over lookups × channels) and max |error|, measured first
// and set with a modest margin, and checks that a mistake — the footprint transposed (its ellipse
// turned by 90°), a point sample, or a footprint 4× too large — would exceed the bound by far.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "envmap/env_reference.h"
#include "envmap/env_test_maps.h"
#include "envmap/environment_map.h"

namespace footprint {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kChannels = 3;

// ---- The test environment.
struct Wave {
    Vec3d k;  // unit direction
    double frequency, phase, amplitude;
};
const std::vector<Wave>& waves(int channel) {
    static const std::array<std::vector<Wave>, kChannels> table = [] {
        std::array<std::vector<Wave>, kChannels> t;
        std::mt19937 rng(2024);
        std::normal_distribution<double> g(0, 1);
        std::uniform_real_distribution<double> u(0, 1);
        const double amplitude[6] = {0.12, 0.1, 0.08, 0.06, 0.05, 0.04};  // Σ = 0.45
        for (auto& channel_waves : t)
            for (int i = 0; i < 6; ++i)
                channel_waves.push_back({normalize(Vec3d{g(rng), g(rng), g(rng)}), 10 + 40 * u(rng),
                                         2 * kPi * u(rng), amplitude[i]});
        return t;
    }();
    return table[channel];
}
float environment(Vec3d r, int channel) {
    const Vec3d d = normalize(r);
    double v = 0.5;
    for (const Wave& w : waves(channel))
        v += w.amplitude * std::sin(w.frequency * dot(w.k, d) + w.phase);
    return static_cast<float>(v);
}
// Texels = the environment at the direction of each texel centre, faces `size` texels high.
std::vector<Image> sampled_faces(EnvLayout layout, int size) {
    return test::env_images<double>(layout, size, kChannels, [](Vec3d d, float* out) {
        for (int c = 0; c < kChannels; ++c) out[c] = environment(d, c);
    });
}

const EnvironmentMap& cube_map() {
    static const EnvironmentMap map = [] {
        const std::vector<Image> f = sampled_faces(EnvLayout::cube, 128);
        return std::move(
            EnvironmentMap::from_cube_faces({f[0], f[1], f[2], f[3], f[4], f[5]}).value());
    }();
    return map;
}
const EnvironmentMap& latlong_map() {
    static const EnvironmentMap map =
        std::move(EnvironmentMap::from_latlong(sampled_faces(EnvLayout::latlong, 256)[0]).value());
    return map;
}
const EnvironmentMap& sphere_map() {
    static const EnvironmentMap map =
        std::move(EnvironmentMap::from_sphere(sampled_faces(EnvLayout::sphere, 256)[0]).value());
    return map;
}
const EnvironmentMap& paraboloid_map() {
    static const EnvironmentMap map = [] {
        const std::vector<Image> f = sampled_faces(EnvLayout::paraboloid, 256);
        return std::move(EnvironmentMap::from_paraboloid(f[0], f[1]).value());
    }();
    return map;
}

// ---- Lookups: a direction and ray differentials ⟂ it (dr_dx along the major axis).
struct Lookup {
    Vec3 r, dr_dx, dr_dy;
};

// Angular footprint: standard deviations sigma1 ≥ sigma2 (radians, K/4 measure: |dr|/2 for unit
// r), major axis at `angle` in the tangent plane.
Lookup angular_lookup(Vec3d r, double sigma1, double sigma2, double angle) {
    Vec3d u, v;
    const Vec3d n = normalize(r);
    tangent_basis(n, u, v);
    const Vec3d e1 = std::cos(angle) * u + std::sin(angle) * v;
    const Vec3d e2 = -std::sin(angle) * u + std::cos(angle) * v;
    return {vec3_cast<float>(n), vec3_cast<float>(2 * sigma1 * e1),
            vec3_cast<float>(2 * sigma2 * e2)};
}

// Texel footprint: the angular shape (anisotropy `ratio`, `angle`) scaled so that the ellipse of K
// (compute_env_footprint form (a)) has major semi-axis λ1 = lambda1 level-0 texels.
Lookup texel_lookup(const EnvironmentMap& map, Vec3d r, double lambda1, double ratio,
                    double angle) {
    const Lookup unit = angular_lookup(r, 1e-3, 1e-3 / ratio, angle);
    const EnvFootprint f =
        compute_env_footprint(map.layout(), map.texel_scale(), unit.r, unit.dr_dx, unit.dr_dy);
    const double scale = lambda1 / make_footprint_ellipse(f.matrix).major_radius;
    return angular_lookup(r, 1e-3 * scale, 1e-3 * scale / ratio, angle);
}

// The mistakes the bounds must catch.
enum class Mistake { none, transposed, point, four_times_larger };
Lookup with_mistake(const Lookup& l, Mistake m) {
    const float a = std::sqrt(dot(l.dr_dx, l.dr_dx)), b = std::sqrt(dot(l.dr_dy, l.dr_dy));
    switch (m) {
        case Mistake::transposed:  // the ellipse turned by 90° (axes swapped)
            return {l.r, (b > 0 ? a / b : 0.0f) * l.dr_dy, (a > 0 ? b / a : 0.0f) * l.dr_dx};
        case Mistake::point:
            return {l.r, {}, {}};
        case Mistake::four_times_larger:
            return {l.r, 4.0f * l.dr_dx, 4.0f * l.dr_dy};
        case Mistake::none:
            break;
    }
    return l;
}

struct Errors {
    double rmse = 0, max = 0;
};

// RMSE over lookups × channels and max |error| of environment_lookup (with `mistake` applied)
// against the reference of the correct footprint.
Errors measure(const EnvironmentMap& map, const std::vector<Lookup>& lookups,
               Mistake mistake = Mistake::none, const EnvReferenceOptions& reference = {},
               const LookupOptions& options = {}) {
    Errors e;
    double sum_sq = 0;
    for (const Lookup& l : lookups) {
        float want[kChannels], got[kChannels];
        environment_reference(
            map,
            sphere_gaussian_from_ray_differentials(
                vec3_cast<double>(l.r), vec3_cast<double>(l.dr_dx), vec3_cast<double>(l.dr_dy)),
            want, reference);
        const Lookup m = with_mistake(l, mistake);
        environment_lookup(map, m.r, m.dr_dx, m.dr_dy, options, got);
        for (int c = 0; c < kChannels; ++c) {
            const double d = double(got[c]) - want[c];
            sum_sq += d * d;
            e.max = std::max(e.max, std::abs(d));
        }
    }
    e.rmse = std::sqrt(sum_sq / (kChannels * static_cast<double>(lookups.size())));
    return e;
}

struct Bounds {
    double rmse, max;
};

// Checks one group: the lookups within `bounds`, the mistaken ones with RMSE ≥ 2× the bound.
void check_group(const char* name, const EnvironmentMap& map, const std::vector<Lookup>& lookups,
                 Bounds bounds, Mistake mistake, const EnvReferenceOptions& reference = {},
                 const LookupOptions& options = {}) {
    const Errors e = measure(map, lookups, Mistake::none, reference, options);
    const Errors wrong = measure(map, lookups, mistake, reference, options);
    std::printf(
        "[ accuracy ] %-34s n=%3zu  RMSE %.4f (bound %.4f)  max %.4f (bound %.4f)  "
        "mistake RMSE %.4f\n",
        name, lookups.size(), e.rmse, bounds.rmse, e.max, bounds.max, wrong.rmse);
    EXPECT_LT(e.rmse, bounds.rmse) << name;
    EXPECT_LT(e.max, bounds.max) << name;
    EXPECT_GT(wrong.rmse, 2 * bounds.rmse) << name << ": the bound would not catch the mistake";
}

Vec3d random_direction(std::mt19937& rng) {
    std::normal_distribution<double> g(0, 1);
    return normalize(Vec3d{g(rng), g(rng), g(rng)});
}

// Random footprints on `map` at random directions: λ1 ∈ [lo, hi] texels (log-uniform),
// anisotropy ∈ [1, max_ratio] (log-uniform).
std::vector<Lookup> random_lookups(const EnvironmentMap& map, int count, double lo, double hi,
                                   double max_ratio, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Lookup> lookups;
    for (int i = 0; i < count; ++i) {
        const Vec3d r = random_direction(rng);
        const double lambda1 = lo * std::pow(hi / lo, u(rng));
        const double ratio = std::pow(max_ratio, u(rng));
        lookups.push_back(texel_lookup(map, r, lambda1, ratio, 2 * kPi * u(rng)));
    }
    return lookups;
}

// Bounds (RMSE, max |error|). Measured with the library of 2026-11-29 (cube | lat-long where a
// group has both), bound ≈ 1.4× RMSE and 1.5× max; the mistake's RMSE in brackets, each ≥ 2× the
// RMSE bound (checked):
//   tiny λ1 ≤ 1 texel         0.0010 | 0.0009, max 0.0058 | 0.0043   [footprint ×4: 0.010 | 0.008]
//   moderate λ1 2–16          0.0049 | 0.0043, max 0.024 | 0.026     [point: 0.053 | 0.051]
//   anisotropic 4–32:1        0.0044 | 0.0045, max 0.017 | 0.019     [transposed: 0.063 | 0.061]
//   cube edges                0.0033, max 0.013                      [transposed: 0.030]
//   cube corners              0.0053, max 0.031                      [transposed: 0.028]
//   lat-long seam             0.0036, max 0.017                      [transposed: 0.036]
//   sphere r̂_z > −0.5         0.0061, max 0.030                      [transposed: 0.036]
//   paraboloid equator        0.0024, max 0.014                      [transposed: 0.028]
//   paraboloid random         0.0057, max 0.036                      [point: 0.045]
// Lat-long footprints centred within 30° of a pole are filtered on the map's polar caps
// (environment_map.h): 60°–85° 0.0045 / 0.021 [transposed: 0.029], 85°–89.9° 0.0062 / 0.042
// [transposed: 0.025], exactly at ±Y 0.0044 / 0.020 [point: 0.053] — on a par with ordinary
// footprints (without the caps: 0.0073, 0.032 and 0.036, spec §3.4's isotropic probe at the pole
// covering a narrow wedge of azimuths only). The sphere map near its rim: 0.0095 / 0.057
// [transposed: 0.039]. There a round footprint is 6.7:1 to 67:1 in texels, and N_max is scaled by
// that distortion (environment_map.h); with N_max = 30 as elsewhere the group's RMSE was 0.017,
// its bound no better than a regression guard. What remains is at the map's sampling limit: at
// r̂_z = −0.97 the rim leaves the shortest waves about one texel each radially, and footprints
// under a texel across are bilinear samples (T_min), not the reference's Gaussian.
constexpr Bounds kTinyBounds{0.0015, 0.009};
constexpr Bounds kModerateBounds{0.007, 0.04};
constexpr Bounds kAnisotropicBounds{0.0065, 0.028};
constexpr Bounds kCubeEdgeBounds{0.005, 0.02};
constexpr Bounds kCubeCornerBounds{0.0075, 0.045};
constexpr Bounds kSeamBounds{0.0055, 0.026};
constexpr Bounds kPoleBandBounds{0.0065, 0.032};
constexpr Bounds kNearPoleBounds{0.009, 0.063};
constexpr Bounds kSphereRimBounds{0.013, 0.085};
constexpr Bounds kSphereBounds{0.0085, 0.045};
constexpr Bounds kEquatorBounds{0.0035, 0.021};
constexpr Bounds kParaboloidBounds{0.008, 0.05};
// Beyond the probe budget, measured 2026-12-03: EWA 0.024, the raised level 0.190, EWA transposed
// 0.26 (RMSE).
constexpr double kBeyondBudgetBound = 0.035;
constexpr double kBeyondBudgetGain = 4;  // the clamped line's RMSE over EWA's, at least

// ---- Random footprints on the cube and lat-long maps.
TEST(EnvAccuracy, TinyFootprints) {
    for (const EnvironmentMap* map : {&cube_map(), &latlong_map()})
        check_group(map == &cube_map() ? "cube tiny (<=1 texel)" : "latlong tiny (<=1 texel)", *map,
                    random_lookups(*map, 80, 0.2, 1.0, 4, 101), kTinyBounds,
                    Mistake::four_times_larger);
}

TEST(EnvAccuracy, ModerateFootprints) {
    for (const EnvironmentMap* map : {&cube_map(), &latlong_map()})
        check_group(map == &cube_map() ? "cube moderate (2-16)" : "latlong moderate (2-16)", *map,
                    random_lookups(*map, 80, 2, 16, 4, 102), kModerateBounds, Mistake::point);
}

TEST(EnvAccuracy, AnisotropicFootprints) {
    for (const EnvironmentMap* map : {&cube_map(), &latlong_map()}) {
        // Anisotropy 4:1 to 32:1, λ1 from 4 to 32 texels.
        std::mt19937 rng(103);
        std::uniform_real_distribution<double> u(0, 1);
        std::vector<Lookup> lookups;
        for (int i = 0; i < 60; ++i)
            lookups.push_back(texel_lookup(*map, random_direction(rng), 4 * std::pow(8.0, u(rng)),
                                           4 * std::pow(8.0, u(rng)), 2 * kPi * u(rng)));
        check_group(
            map == &cube_map() ? "cube anisotropic (4-32:1)" : "latlong anisotropic (4-32:1)", *map,
            lookups, kAnisotropicBounds, Mistake::transposed);
    }
}

// ---- Cube edges and corners: the centre within ~1° of an edge or a corner, so that probes and
// bilinear taps cross onto neighbouring faces (spec §3.1).
TEST(EnvAccuracy, CubeEdgesAndCorners) {
    std::mt19937 rng(104);
    std::uniform_real_distribution<double> u(0, 1);
    std::normal_distribution<double> g(0, 1);
    std::vector<Lookup> edges, corners;
    auto sign = [&] { return u(rng) < 0.5 ? -1.0 : 1.0; };
    for (int i = 0; i < 60; ++i) {
        double c[3] = {sign(), sign(), -0.9 + 1.8 * u(rng)};
        std::shuffle(c, c + 3, rng);
        const Vec3d edge = Vec3d{c[0], c[1], c[2]} + 0.01 * Vec3d{g(rng), g(rng), g(rng)};
        const Vec3d corner = Vec3d{sign(), sign(), sign()} + 0.01 * Vec3d{g(rng), g(rng), g(rng)};
        edges.push_back(texel_lookup(cube_map(), edge, 2 * std::pow(8.0, u(rng)),
                                     std::pow(16.0, u(rng)), 2 * kPi * u(rng)));
        corners.push_back(texel_lookup(cube_map(), corner, 2 * std::pow(8.0, u(rng)),
                                       std::pow(16.0, u(rng)), 2 * kPi * u(rng)));
    }
    check_group("cube edges (2-16, <=16:1)", cube_map(), edges, kCubeEdgeBounds,
                Mistake::transposed);
    check_group("cube corners (2-16, <=16:1)", cube_map(), corners, kCubeCornerBounds,
                Mistake::transposed);
}

// ---- The lat-long seam s = 0 ≡ 1 (around +Z).
TEST(EnvAccuracy, LatLongSeam) {
    std::mt19937 rng(105);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Lookup> lookups;
    for (int i = 0; i < 60; ++i) {
        const Vec3d r{0.02 * (2 * u(rng) - 1), 1.6 * u(rng) - 0.8, 1};
        lookups.push_back(texel_lookup(latlong_map(), r, 2 * std::pow(8.0, u(rng)),
                                       std::pow(16.0, u(rng)), 2 * kPi * u(rng)));
    }
    check_group("latlong seam (2-16, <=16:1)", latlong_map(), lookups, kSeamBounds,
                Mistake::transposed);
}

// ---- The lat-long poles: latitudes 60°–89.9° and exactly ±Y. Footprints are sized by angle —
// σ1 = 1…8 t-texels (π/256 rad each), anisotropy ≤ 8:1 — since λ in s-texels grows without
// bound there (spec §3.4). The reference caps its grid at 256 nodes per axis here (the s-texels
// shrink towards the pole; 256 nodes still space ≤ 0.06 t-texels over the footprint).
TEST(EnvAccuracy, LatLongPoles) {
    EnvReferenceOptions reference;
    reference.max_samples_per_axis = 256;
    const double t_texel = kPi / 256;
    std::mt19937 rng(106);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Lookup> band[2], exact;  // band[0]: 60°–85°, band[1]: 85°–89.9°
    for (int i = 0; i < 60; ++i) {
        const int which = i % 3 == 2;
        const double degrees = which ? 85 + 4.9 * u(rng) : 60 + 25 * u(rng);
        const double latitude = degrees * kPi / 180, azimuth = 2 * kPi * u(rng);
        const double y = (i % 2 ? 1 : -1) * std::sin(latitude);
        const Vec3d r{std::cos(latitude) * std::sin(azimuth), y,
                      std::cos(latitude) * std::cos(azimuth)};
        const double sigma1 = t_texel * std::pow(8.0, u(rng));
        band[which].push_back(
            angular_lookup(r, sigma1, sigma1 / std::pow(8.0, u(rng)), 2 * kPi * u(rng)));
        if (i < 16) {
            const double s1 = t_texel * std::pow(8.0, u(rng));
            exact.push_back(angular_lookup({0, i % 2 ? 1.0 : -1.0, 0}, s1,
                                           s1 / std::pow(4.0, u(rng)), 2 * kPi * u(rng)));
        }
    }
    check_group("latlong latitude 60-85 deg", latlong_map(), band[0], kPoleBandBounds,
                Mistake::transposed, reference);
    check_group("latlong latitude 85-89.9 deg", latlong_map(), band[1], kNearPoleBounds,
                Mistake::transposed, reference);
    check_group("latlong exactly at +-Y", latlong_map(), exact, kNearPoleBounds, Mistake::point,
                reference);
}

// ---- Sphere map: away from the rim (r̂_z > −0.5) and near, not at, the rim (r̂_z ∈ [−0.97,
// −0.7]), where the map squeezes a footprint radially and stretches it along the rim (6.7:1 to 67:1
// for a round one) and λ1 is clamped ≤ W/2 (spec §3.2).
// Sized by angle: σ1 = 1…8 × 4/W rad (the mean texel angle of the equal-area map), ≤ 8:1.
TEST(EnvAccuracy, SphereMap) {
    const double texel = 4.0 / 256;
    std::mt19937 rng(107);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Lookup> inner, rim;
    for (int i = 0; i < 50; ++i) {
        Vec3d r = random_direction(rng);
        if (r.z < -0.5) r.z = -r.z;
        const double sigma1 = texel * std::pow(8.0, u(rng));
        inner.push_back(angular_lookup(r, sigma1, sigma1 / std::pow(8.0, u(rng)), 6.3 * u(rng)));
        const double z = -0.7 - 0.27 * u(rng), phi = 2 * kPi * u(rng);
        const Vec3d near_rim{std::sqrt(1 - z * z) * std::cos(phi),
                             std::sqrt(1 - z * z) * std::sin(phi), z};
        const double s1 = texel * std::pow(8.0, u(rng));
        rim.push_back(angular_lookup(near_rim, s1, s1 / std::pow(8.0, u(rng)), 6.3 * u(rng)));
    }
    check_group("sphere r_z > -0.5", sphere_map(), inner, kSphereBounds, Mistake::transposed);
    check_group("sphere near rim r_z -0.97..-0.7", sphere_map(), rim, kSphereRimBounds,
                Mistake::transposed);
}

// ---- Dual paraboloid: footprints across the equator (r̂_z ∈ [−0.1, 0.1]), so that probes and
// taps pass between the front and back faces (spec §3.3); and random directions.
TEST(EnvAccuracy, ParaboloidAcrossTheEquator) {
    std::mt19937 rng(108);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Lookup> equator;
    for (int i = 0; i < 60; ++i) {
        const double z = 0.2 * u(rng) - 0.1, phi = 2 * kPi * u(rng);
        const Vec3d r{std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi),
                      z};
        equator.push_back(texel_lookup(paraboloid_map(), r, 2 * std::pow(8.0, u(rng)),
                                       std::pow(8.0, u(rng)), 2 * kPi * u(rng)));
    }
    check_group("paraboloid equator (2-16, <=8:1)", paraboloid_map(), equator, kEquatorBounds,
                Mistake::transposed);
    check_group("paraboloid random (2-16, <=4:1)", paraboloid_map(),
                random_lookups(paraboloid_map(), 60, 2, 16, 4, 109), kParaboloidBounds,
                Mistake::point);
}

// ---- Beyond the probe budget: the mirror cylinder's case (docs/performance.md), footprints 16 to
// 64 texels long and under a texel wide, read along bands of latitude 6 texels apart. N_max = 30
// probes cannot cover them; spec §2.8 raises the probes' level until they do (T_p ≈ λ1/14.5),
// which blurs the minor axis across the bands. LookupOptions::ewa_beyond_probes filters such
// footprints by EWA instead (environment_map.h). On smooth content (the waves above) the two agree.
TEST(EnvAccuracy, BeyondTheProbeBudget) {
    constexpr double kBandTexels = 6;
    const EnvironmentMap map = test::env_map(EnvLayout::latlong, 256, [&](Vec3 r) {
        const double theta = std::acos(std::clamp(double(r.y), -1.0, 1.0));
        return static_cast<float>(0.5 + 0.45 * std::sin(theta * 512 / kBandTexels));
    });
    const double texel = kPi / 256;
    std::mt19937 rng(110);
    std::uniform_real_distribution<double> u(0, 1);
    LookupOptions ewa;
    ewa.ewa_beyond_probes = true;
    double clamped_sq = 0, ewa_sq = 0, transposed_sq = 0;
    constexpr int kLookups = 40;
    for (int i = 0; i < kLookups; ++i) {
        const double latitude = (u(rng) - 0.5) * kPi / 90, phi = 2 * kPi * u(rng);
        const Vec3d r{std::cos(latitude) * std::sin(phi), std::sin(latitude),
                      std::cos(latitude) * std::cos(phi)};
        const Vec3d along{std::cos(phi), 0, -std::sin(phi)};  // ∂r/∂φ: along the bands
        const Vec3d across{-std::sin(latitude) * std::sin(phi), std::cos(latitude),
                           -std::sin(latitude) * std::cos(phi)};
        const double sigma1 = texel * 8 * std::pow(4.0, u(rng));
        const double sigma2 = texel * 0.1 * std::pow(5.0, u(rng));
        const Vec3d dx = 2 * sigma1 * along, dy = 2 * sigma2 * across;
        float want = 0, got = 0, got_ewa = 0, got_transposed = 0;
        environment_reference(map, sphere_gaussian_from_ray_differentials(r, dx, dy), &want);
        const Vec3 rf = vec3_cast<float>(r), dxf = vec3_cast<float>(dx), dyf = vec3_cast<float>(dy);
        environment_lookup(map, rf, dxf, dyf, LookupOptions{}, &got);
        environment_lookup(map, rf, dxf, dyf, ewa, &got_ewa);
        environment_lookup(map, rf, float(sigma1 / sigma2) * dyf, float(sigma2 / sigma1) * dxf, ewa,
                           &got_transposed);
        clamped_sq += (got - want) * (got - want);
        ewa_sq += (got_ewa - want) * (got_ewa - want);
        transposed_sq += (got_transposed - want) * (got_transposed - want);
    }
    const double clamped = std::sqrt(clamped_sq / kLookups),
                 with_ewa = std::sqrt(ewa_sq / kLookups),
                 transposed = std::sqrt(transposed_sq / kLookups);
    std::printf(
        "[ accuracy ] latlong bands beyond the budget: RMSE spec 2.8 %.4f, EWA %.4f "
        "(bound %.4f), transposed %.4f\n",
        clamped, with_ewa, kBeyondBudgetBound, transposed);
    EXPECT_LT(with_ewa, kBeyondBudgetBound);
    EXPECT_GT(clamped, kBeyondBudgetGain * with_ewa);
    EXPECT_GT(transposed, 2 * kBeyondBudgetBound);
}

}  // namespace
}  // namespace footprint
