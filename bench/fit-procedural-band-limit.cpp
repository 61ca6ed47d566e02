// footprint-fit-procedural-band-limit — derives the procedural textures' band limit
// (texture/procedural.h, docs/method.md#procedural-textures) from the noise itself, then checks it
// on grazing planes that nothing was fitted to.
//
//   footprint-fit-procedural-band-limit [--pairs N] [--reference-spp N] [--views-only]
//                                       [--curves-only]
//
// 1. Curves. Clamping replaces octave i by a_i·o(p) + (1 − a_i)·E o, o = n or |n| at the pixel's
//    centre p. Against the footprint's mean B(p) = E_q o(q), q ~ N(p, Σ) (Σ the pixel filter's
//    Gaussian over the footprint, in lattice units), the error E(B − a·o)² is least at
//    a* = Cov(B, o)/Var o = Cov(o(x), o(x + d))/Var o, d ~ N(0, Σ): the octave's autocorrelation
//    averaged over the footprint's own Gaussian, C(Σ). (The variance the blur keeps, Var B/Var o,
//    is C(2Σ); its square root, the weight the band limit had, keeps too much where C is small:
//    1/√(σ_1σ_2) against 1/(σ_1σ_2).) C is measured here by Monte Carlo over random points and
//    footprint planes of random orientation, for round, 4:1 and line footprints, and the closed
//    form of an isotropic Gaussian spectrum of σ_f = c/λ per axis, C = Π_k (1 + 4π² σ_k² c²)^(−1/2)
//    (λ = 1), is fitted to it by least squares in a (a wrong a costs (a − a*)² Var o).
// 2. Views. A plane seen at grazing angles (75°–88° from the normal at the image's centre) at
//    several scales, as the renderer draws it: band-limited at one sample per pixel (the pixel's
//    centre ray and its differentials), 16 point samples and 1024 point samples (the reference),
//    both R2 points warped to the σ = ½-pixel Gaussian pixel filter, as `--filter reference`
//    takes them. Prints the RMSE of the value v ∈ [0, 1] against the reference for noise,
//    turbulence and marble, with the library as built.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "math/sample_patterns.h"
#include "texture/grazing_views.h"
#include "texture/procedural.h"

namespace {

using namespace footprint;

constexpr double kPi = 3.14159265358979323846;

// ---- 1. the octave's autocorrelation under the footprint's Gaussian ----

struct Shape {
    const char* name;
    double ratio;  // σ_2/σ_1
};

double model(double s1, double s2, double c) {
    const double k = 4 * kPi * kPi * c * c;
    return 1 / std::sqrt((1 + k * s1 * s1) * (1 + k * s2 * s2));
}

// The weight the band limit had: the square root of the variance kept, Gaussian spectrum of
// σ_f = 0.7/λ.
double old_weight(double s1, double s2) {
    const double k = 8 * kPi * kPi * 0.49;
    return std::pow((1 + k * s1 * s1) * (1 + k * s2 * s2), -0.25);
}

void curves(int pairs) {
    const double sigmas[] = {0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.7, 1.0, 1.4, 2.0, 3.0};
    const Shape shapes[] = {{"round", 1.0}, {"4:1", 0.25}, {"line", 0.0}};
    // Common random numbers: the same points, planes and offsets for every σ.
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(-1000, 1000);
    std::normal_distribution<double> g(0, 1);
    struct Pair {
        Vec3d x, u, v;
        double q1, q2, n;
    };
    std::vector<Pair> samples(pairs);
    double sum = 0, sum_sq = 0, sum_abs = 0;
    for (Pair& s : samples) {
        s.x = {u(rng), u(rng), u(rng)};
        const Vec3d axis = normalize(Vec3d{g(rng), g(rng), g(rng)});
        Vec3d a, b;
        tangent_basis(axis, a, b);
        const double phi = 2 * kPi * std::uniform_real_distribution<double>(0, 1)(rng);
        s.u = std::cos(phi) * a + std::sin(phi) * b;
        s.v = cross(axis, s.u);
        s.q1 = g(rng), s.q2 = g(rng);
        s.n = gradient_noise(s.x);
        sum += s.n, sum_sq += s.n * s.n, sum_abs += std::abs(s.n);
    }
    const double mean = sum / pairs, var = sum_sq / pairs - mean * mean;
    const double mean_abs = sum_abs / pairs, var_abs = sum_sq / pairs - mean_abs * mean_abs;
    std::printf(
        "one octave of gradient noise over %d points: E n %.5f, E n^2 %.5f, E|n| %.5f, "
        "Var|n| %.5f\n\n",
        pairs, mean, sum_sq / pairs, mean_abs, var_abs);
    struct Row {
        double s1, s2, c_n, c_abs;
    };
    std::vector<Row> rows;
    for (const Shape& shape : shapes)
        for (double s1 : sigmas) {
            const double s2 = shape.ratio * s1;
            double cn = 0, ca = 0;
            for (const Pair& s : samples) {
                const double m = gradient_noise(s.x + s1 * s.q1 * s.u + s2 * s.q2 * s.v);
                cn += (s.n - mean) * (m - mean);
                ca += (std::abs(s.n) - mean_abs) * (std::abs(m) - mean_abs);
            }
            rows.push_back({s1, s2, cn / pairs / var, ca / pairs / var_abs});
        }
    // Least squares in a over every row, for n and for |n|, c on a grid of 0.001.
    auto fit = [&](bool absolute) {
        double best_c = 0, best = INFINITY;
        for (double c = 0.2; c <= 2.0; c += 0.001) {
            double e = 0;
            for (const Row& r : rows) {
                const double d = (absolute ? r.c_abs : r.c_n) - model(r.s1, r.s2, c);
                e += d * d;
            }
            if (e < best) best = e, best_c = c;
        }
        return std::pair{best_c, std::sqrt(best / rows.size())};
    };
    const auto [c_n, rms_n] = fit(false);
    const auto [c_abs, rms_abs] = fit(true);
    // One c for both (the octave weight is shared): the least squares over both sets.
    double c_both = 0, best = INFINITY;
    for (double c = 0.2; c <= 2.0; c += 0.001) {
        double e = 0;
        for (const Row& r : rows) {
            const double m = model(r.s1, r.s2, c);
            e += (r.c_n - m) * (r.c_n - m) + (r.c_abs - m) * (r.c_abs - m);
        }
        if (e < best) best = e, c_both = c;
    }
    std::printf(
        "the footprint's mean against the point value, C(sigma) = Cov(B, o)/Var o "
        "(MC ±%.3f), against the closed form of c = %.3f and the old weight:\n",
        1 / std::sqrt(double(pairs)), c_both);
    std::printf("%-6s %7s %7s | %8s %8s | %8s %8s | %8s\n", "shape", "sigma1", "sigma2", "C(n)",
                "C(|n|)", "model", "err max", "old a");
    double old_sq = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
        const Row& r = rows[i];
        const double m = model(r.s1, r.s2, c_both), o = old_weight(r.s1, r.s2);
        old_sq += (r.c_n - o) * (r.c_n - o) + (r.c_abs - o) * (r.c_abs - o);
        std::printf("%-6s %7.3f %7.3f | %8.4f %8.4f | %8.4f %8.4f | %8.4f\n",
                    shapes[i / std::size(sigmas)].name, r.s1, r.s2, r.c_n, r.c_abs, m,
                    std::max(std::abs(r.c_n - m), std::abs(r.c_abs - m)), o);
    }
    double largest_n = 0, largest_abs = 0, largest_old = 0;
    for (const Row& r : rows) {
        largest_n = std::max(largest_n, std::abs(r.c_n - model(r.s1, r.s2, c_n)));
        largest_abs = std::max(largest_abs, std::abs(r.c_abs - model(r.s1, r.s2, c_abs)));
        const double o = old_weight(r.s1, r.s2);
        largest_old = std::max({largest_old, std::abs(r.c_n - o), std::abs(r.c_abs - o)});
    }
    std::printf(
        "\nfitted c: n %.3f (RMS residual %.4f, largest %.4f), |n| %.3f (%.4f, largest "
        "%.4f), both %.3f (%.4f); the old weight's RMS residual %.4f, largest %.4f\n",
        c_n, rms_n, largest_n, c_abs, rms_abs, largest_abs, c_both,
        std::sqrt(best / (2 * rows.size())), std::sqrt(old_sq / (2 * rows.size())), largest_old);
}

// ---- 2. grazing planes ----

void views(int reference_spp) {
    // 75°–88° at the image's centre, scales from a minor axis of a tenth of a cell to a few.
    const double angles[] = {75, 80, 84, 86, 88};
    const double scales[] = {2, 5, 12};
    const struct {
        ProceduralPattern pattern;
        const char* name;
    } patterns[] = {{ProceduralPattern::noise, "noise"},
                    {ProceduralPattern::turbulence, "turbulence"},
                    {ProceduralPattern::marble, "marble"}};
    std::printf(
        "\ngrazing planes, 48x32 pixels, fov 20 deg, 6 octaves: RMSE of v against %d spp "
        "(band-limited 1 spp / 16 spp)\n",
        reference_spp);
    std::printf("%6s %6s", "angle", "scale");
    for (const auto& p : patterns) std::printf(" | %-10s %15s", p.name, "");
    std::printf("\n");
    int wins = 0, total = 0;
    double worst_ratio = 0;
    for (double angle : angles)
        for (double scale : scales) {
            std::printf("%6.0f %6.0f", angle, scale);
            for (const auto& pat : patterns) {
                ProceduralTexture texture;
                texture.pattern = pat.pattern;
                texture.scale = scale;
                texture.octaves = 6;
                const test::GrazingError e =
                    test::grazing_error(texture, {angle, scale, 20, 48, 32}, reference_spp);
                const double ratio = e.filtered / e.sixteen;
                worst_ratio = std::max(worst_ratio, ratio);
                wins += ratio < 1, ++total;
                std::printf(" | %8.5f / %8.5f %s", e.filtered, e.sixteen, ratio < 1 ? "  " : " L");
            }
            std::printf("\n");
        }
    std::printf("band-limited below 16 spp in %d of %d; worst ratio %.3f\n", wins, total,
                worst_ratio);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"footprint-fit-procedural-band-limit: the procedural band limit from the noise"};
    int pairs = 2000000, reference_spp = 1024;
    bool views_only = false, curves_only = false;
    app.add_option("--pairs", pairs, "Monte-Carlo point pairs per curve point")
        ->check(CLI::Range(1000, 100000000));
    app.add_option("--reference-spp", reference_spp, "the views' reference samples per pixel")
        ->check(CLI::Range(16, 65536));
    app.add_flag("--views-only", views_only, "only the grazing views");
    app.add_flag("--curves-only", curves_only, "only the curves and the fit");
    CLI11_PARSE(app, argc, argv);
    if (!views_only) curves(pairs);
    if (!curves_only) views(reference_spp);
    return 0;
}
