#include "texture/footprint_assembly_lanes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "texture/kernel_moments.h"

namespace footprint {
namespace {

// check.py's tolerance for Rule B's kernel covariance ([FAB]: relative Frobenius error < 3 %). The
// residual comes from averaging the bilinear phase over a finite 8×8 grid and from the box
// pyramid's discrete taps; a wrong axis (r2 for r1), a transposed K or Rule A's spacing all miss by
// more than 30 %.
constexpr double kKernelCovarianceTolerance = 0.03;
// The kernel mean must sit on the lookup centre: probes are placed symmetrically (float rounding of
// offsets up to ~1000 texels).
constexpr double kKernelMeanTolerance = 2e-3;

FootprintEllipse random_footprint(std::mt19937& rng, float min_size, float max_size,
                                  float max_aniso) {
    std::uniform_real_distribution<float> u(0, 1);
    const float major = min_size * std::pow(max_size / min_size, u(rng));
    const float aniso = std::pow(max_aniso, u(rng));
    const float angle = u(rng) * float(M_PI);
    return make_footprint_ellipse(major, major / aniso, angle);
}

// Phase-averaged kernel moments of footprint assembly for one footprint: the bilinear weights of a
// probe depend on where it falls inside a texel, so (like check.py) average over a 16×16 grid of
// centre offsets spanning one texel of the coarser level the probes read.
KernelMoments averaged_fa_moments(const MomentPyramids& moments, const FootprintEllipse& e,
                                  const LookupOptions& options, float* mean_error) {
    const ProbePlan plan = plan_probes(e, options.probe_rule, options.max_probes,
                                       moments.first().max_level(), 0.0f, options.isotropic_ratio);
    const float period = std::exp2(std::floor(plan.lod) + 1);
    KernelMoments avg{};
    *mean_error = 0;
    constexpr int kPhases = 16;  // 8 phases per texel of the finer level
    for (int i = 0; i < kPhases * kPhases; ++i) {
        const float ox = period * ((i % kPhases) + 0.5f - 0.5f * kPhases) / kPhases,
                    oy = period * ((i / kPhases) + 0.5f - 0.5f * kPhases) / kPhases;
        const KernelMoments m =
            moments.measure(ox, oy, [&](const MipPyramid& p, float s, float t, float* out) {
                texture_lookup(p, s, t, e, options, out);
            });
        *mean_error = std::max({*mean_error, std::fabs(m.mean.x - ox), std::fabs(m.mean.y - oy)});
        avg.covariance = avg.covariance + (1.0f / (kPhases * kPhases)) * m.covariance;
    }
    return avg;
}

const MomentPyramids& moment_pyramids() {
    static const MomentPyramids pyramids(2048);
    return pyramids;
}

TEST(FootprintAssembly, RuleBPlansMatchTheSpecExamples) {
    // The spec's four Rule B cases (N_max = 16), planned on Λ = √(λ² + 1): a line of 7 probes of
    // T_p = Λ2; a line beyond the budget, whose T_p rises to Λ1·√(3/258); a nearly round
    // footprint of two probes; a thin one whose probes read level 0.17 rather than level 0.
    struct Case {
        float l1, l2;
        int n;
        float texel_size;
    };
    for (const Case c :
         {Case{14.8f, 4, 7, 4.12311f}, Case{4 * std::sqrt(258.0f / 3), 2, 16, 4.00145f},
          Case{9, 8, 2, 8.06226f}, Case{7, 0.6f, 11, 1.16619f}}) {
        const ProbePlan plan = plan_probes(make_footprint_ellipse(c.l1, c.l2, 0.3f),
                                           ProbeRule::moment_matched, 16, 12);
        EXPECT_EQ(plan.count, c.n) << c.l1 << "," << c.l2;
        EXPECT_NEAR(plan.texel_size, c.texel_size, 1e-3f) << c.l1 << "," << c.l2;
        EXPECT_NEAR(plan.lod, std::log2(c.texel_size), 1e-4f);
        // Spacing never exceeds the probe size: no gaps between probes.
        EXPECT_LE(length(plan.step), plan.texel_size * (1 + 1e-5f));
    }
}

TEST(FootprintAssembly, FootprintsBeyondAnyBudgetTakeTheBudgetAtTheCoarsestLevel) {
    // λ1 of 1e12 texels (a huge finite K), infinite or NaN: more probes than any budget, whose
    // count no int holds (undefined before; found by fuzz_lookup, tests/data/bad/fuzz/lookup/).
    // Both weightings take N_max probes on the coarsest level.
    constexpr int kMaxProbes = 16, kMaxLevel = 12;
    for (const ProbeRule rule : {ProbeRule::moment_matched, ProbeRule::gaussian}) {
        for (const float l1 : {1e12f, std::numeric_limits<float>::infinity()}) {
            const ProbePlan plan =
                plan_probes(make_footprint_ellipse(l1, 2, 0.3f), rule, kMaxProbes, kMaxLevel);
            EXPECT_EQ(plan.count, kMaxProbes) << l1;
            EXPECT_EQ(plan.lod, static_cast<float>(kMaxLevel)) << l1;
        }
        FootprintEllipse nan = make_footprint_ellipse(8, 2, 0.3f);
        nan.major_radius = std::numeric_limits<float>::quiet_NaN();
        const ProbePlan plan = plan_probes(nan, rule, kMaxProbes, kMaxLevel);
        EXPECT_GE(plan.count, 1);
        EXPECT_LE(plan.count, kMaxProbes);
    }
    // A NaN minor axis is planned as rank one (Rule A divided by it: its count was undefined).
    for (const ProbeRule rule :
         {ProbeRule::moment_matched, ProbeRule::gaussian, ProbeRule::ext, ProbeRule::texram}) {
        FootprintEllipse nan_minor = make_footprint_ellipse(8, 2, 0.3f);
        nan_minor.minor_radius = std::numeric_limits<float>::quiet_NaN();
        const ProbePlan plan = plan_probes(nan_minor, rule, kMaxProbes, kMaxLevel);
        FootprintEllipse rank_one = make_footprint_ellipse(8, 0, 0.3f);
        const ProbePlan expected = plan_probes(rank_one, rule, kMaxProbes, kMaxLevel);
        EXPECT_EQ(plan.count, expected.count);
        EXPECT_EQ(plan.lod, expected.lod);
    }
}

TEST(FootprintAssembly, RuleAAndTexramPlans) {
    const FootprintEllipse e = make_footprint_ellipse(32, 2, 0);
    const ProbePlan a = plan_probes(e, ProbeRule::ext, 16, 12);
    EXPECT_EQ(a.count, 16);
    EXPECT_NEAR(a.lod, 1.0f, 1e-6f);           // log2(λ1/N) = log2(2)
    EXPECT_NEAR(a.step.x, 32.0f / 17, 1e-5f);  // o_i = (i/(N+1) − ½)·λ1 r1
    const ProbePlan t = plan_probes(make_footprint_ellipse(32, 3, 0), ProbeRule::texram, 16, 12);
    EXPECT_EQ(t.count, 8);               // ⌈32/3⌉ = 11 → power of two 8
    EXPECT_NEAR(t.step.x, 4.0f, 1e-6f);  // λ1/N
    EXPECT_NEAR(t.offset(0).x, (0.5f / 8 - 0.5f) * 32, 1e-5f);
}

// Λ = max(√(λ² + ρ), 1), ρ = clamp(λ1² + λ2² − 1, 0, 1): footprint e's semi-axis l as Rule B
// plans it (footprint_assembly.h).
float big_lambda(float l, const FootprintEllipse& e) {
    const float rho = std::clamp(
        e.major_radius * e.major_radius + e.minor_radius * e.minor_radius - 1, 0.0f, 1.0f);
    return std::max(std::sqrt(l * l + rho), 1.0f);
}

// The kernel covariance spec §2.8 predicts for Rule B, in the moments' measure (kernel_moments.h:
// texel-centre covariance + I/12, where a probe of texel size T measures T²/4):
// ¼[(Λ1'² − T_p² + T_eff²) r1r1ᵀ + T_eff² r2r2ᵀ], Λ1' = max(Λ1, T_p). T_eff² is the probes' own
// variance ×4: T_p² with the variance-matched level blend, 4^L(1 + 3w) for GL's linear blend at
// lod L + w ([FAT]). With the remap and no clamping this is exactly (K + I)/4 from tr K = 2 on: the
// ground truth's kernel in this measure, K/4 about the bilinear reconstruction f, whose tent adds
// I/6 to the texel-centre covariance, and the measure's I/12 (below, (K + ρI)/4 with each axis
// at least the bilinear probe's ¼).
Sym2 predicted_kernel(const FootprintEllipse& e, const ProbePlan& plan, LodBlend blend) {
    const float tp = plan.texel_size;
    const float level = std::floor(plan.lod), w = plan.lod - level;
    const float t_eff_sq =
        blend == LodBlend::variance_matched ? tp * tp : std::exp2(2 * level) * (1 + 3 * w);
    const float major = std::max(big_lambda(e.major_radius, e), tp);
    return outer(e.major_axis, 0.25f * (major * major - tp * tp + t_eff_sq)) +
           outer(e.minor_axis(), 0.25f * t_eff_sq);
}

TEST(FootprintAssembly, ProbeWeightsAreTheGaussianAtEachProbe) {
    // probe_weights() builds exp(−½(a·k)²), k = i − (N−1)/2, by a recurrence from one ratio
    // q = e^{−a²/8}: tabulated for the fall-offs plan_probes() gives (a = 2κ_g/(N − 1)), an exp for
    // any other. Both: within float rounding of the Gaussian (a rounding per power of q), exactly
    // symmetric, and the tabulated q is the exp bit for bit (it is the weight at k = ½ of an even
    // line).
    std::vector<float> w(kMaxProbeCount);
    for (int n = 1; n <= 64; ++n)
        for (const bool planned : {true, false}) {
            ProbePlan plan;
            plan.count = n;
            plan.weight_falloff = planned && n > 1
                                      ? 2 * kGaussianProbeExtent / static_cast<float>(n - 1)
                                      : 0.37f + 0.01f * static_cast<float>(n);
            probe_weights(plan, w.data());
            const float a = plan.weight_falloff;
            for (int i = 0; i < n; ++i) {
                const double k = i - 0.5 * (n - 1);
                const double want =
                    n <= 2 ? 1.0 : std::exp(-0.5 * (double(a) * k) * (double(a) * k));
                // The recurrence raises q to the power 4k²: so many roundings of its relative
                // error. (Weights under 1e−37 may underflow to zero.)
                ASSERT_NEAR(w[i], want, (4 * k * k + 4) * 1.2e-7 * want + 1e-37)
                    << n << " probes, planned " << planned << ", i " << i;
                ASSERT_EQ(w[i], w[n - 1 - i]) << n << " probes, planned " << planned;
            }
            if (n > 2 && n % 2 == 0) {
                EXPECT_EQ(w[n / 2], std::exp(-0.125f * (a * a))) << n;
            }
        }
}

TEST(FootprintAssembly, GaussianPlansKeepRuleBsMomentsAndSpacing) {
    for (float l1 : {3.0f, 10.0f, 40.0f, 300.0f})
        for (int max_probes : {4, 16, 30, 128}) {
            const FootprintEllipse e = make_footprint_ellipse(l1, 1.5f, 0.9f);
            const ProbePlan plan = plan_probes(e, ProbeRule::gaussian, max_probes, 12);
            ASSERT_LE(plan.count, max_probes);
            // No gaps: spacing ≤ T_p.
            EXPECT_LE(length(plan.step), plan.texel_size * (1 + 1e-4f));
            // Σw o² / Σw + T_p²/4 = Λ1²/4 along r1 (the weights as filter_footprint_assembly makes
            // them).
            double sw = 0, swo = 0;
            for (int i = 0; i < plan.count; ++i) {
                const double k = i - 0.5 * (plan.count - 1),
                             w = std::exp(-0.5 * std::pow(plan.weight_falloff * k, 2));
                sw += w;
                swo += w * std::pow(k * length(plan.step), 2);
            }
            const double major = std::max(big_lambda(l1, e), plan.texel_size);
            EXPECT_NEAR(swo / sw + plan.texel_size * plan.texel_size / 4, major * major / 4,
                        1e-3 * major * major)
                << "λ1 = " << l1 << ", N_max = " << max_probes;
        }
}

// The spacing factor a/√v of n Gaussian-weighted probes from its definition (footprint_assembly.h):
// weights exp(−½u²) on n even nodes over [−2, 2], Δ = σ_g · a/√v.
double spacing_factor_by_definition(int n) {
    const double a = 4.0 / (n - 1);
    double sw = 0, swu = 0;
    for (int i = 0; i < n; ++i) {
        const double u = (i - 0.5 * (n - 1)) * a, w = std::exp(-0.5 * u * u);
        sw += w;
        swu += w * u * u;
    }
    return a / std::sqrt(swu / sw);
}

TEST(FootprintAssembly, GaussianPlansTakeTheFewestProbes) {
    // No count from 2 to N − 1 closes the gaps (σ_g·c(n) ≤ T_p). The factor is not monotonic,
    // c(3) = 2.17 > c(2) = 2: a search down from above that stopped at the first count too few
    // would take four probes where two do, for 1.36 < λ1/T_p ≤ √2.
    int lines = 0;
    for (float l1 = 2.01f; l1 < 80; l1 *= 1.01f) {
        const FootprintEllipse e = make_footprint_ellipse(l1, 2.0f, 0.4f);
        const ProbePlan plan = plan_probes(e, ProbeRule::gaussian, kMaxProbeCount, 12);
        if (plan.count == 1) continue;
        ++lines;
        const double tp = plan.texel_size, big_l1 = big_lambda(l1, e),
                     sigma = 0.5 * std::sqrt(big_l1 * big_l1 - tp * tp);
        for (int n = 2; n < plan.count; ++n)
            EXPECT_GT(sigma * spacing_factor_by_definition(n), tp * (1 - 1e-5))
                << "λ1 = " << l1 << ": " << n << " probes would do, the plan takes " << plan.count;
    }
    EXPECT_GT(lines, 300);
    EXPECT_EQ(
        plan_probes(make_footprint_ellipse(2.8f, 2.0f, 0.4f), ProbeRule::gaussian, 30, 12).count,
        2);  // Λ1/T_p = 1.33
}

TEST(FootprintAssembly, KernelCovarianceIsQuarterK) {
    // Hundreds of random footprints: all orientations, anisotropy 1–64, major semi-axis 0.1–500
    // texels, with a probe budget that never clamps (⌈√(3·64²)⌉ = 111 probes), for both weightings
    // (equal and Gaussian: the same moments by construction) and both level blends.
    const MomentPyramids& moments = moment_pyramids();
    for (ProbeRule rule : {ProbeRule::moment_matched, ProbeRule::gaussian})
        for (LodBlend blend : {LodBlend::variance_matched, LodBlend::linear}) {
            LookupOptions options;
            options.max_probes = 128;
            options.probe_rule = rule;
            options.lod_blend = blend;
            std::mt19937 rng(2024);
            for (int i = 0; i < 300; ++i) {
                const FootprintEllipse e = random_footprint(rng, 0.1f, 500, 64);
                const ProbePlan plan = plan_probes(e, options.probe_rule, options.max_probes,
                                                   moments.first().max_level());
                float mean_error = 0;
                const KernelMoments m = averaged_fa_moments(moments, e, options, &mean_error);
                const Sym2 expected = predicted_kernel(e, plan, blend);
                EXPECT_LT(relative_error(m.covariance, expected), kKernelCovarianceTolerance)
                    << "footprint " << i << ": λ = (" << e.major_radius << ", " << e.minor_radius
                    << ")";
                EXPECT_LT(mean_error, kKernelMeanTolerance * std::max(1.0f, e.major_radius))
                    << "footprint " << i;
                if (blend == LodBlend::variance_matched) {
                    // ... which is (K + ρI)/4 itself: from tr K = 2 on, the ground truth's kernel.
                    const float major = big_lambda(e.major_radius, e),
                                minor = big_lambda(e.minor_radius, e);
                    const Sym2 quarter_k = outer(e.major_axis, 0.25f * major * major) +
                                           outer(e.minor_axis(), 0.25f * minor * minor);
                    EXPECT_LT(relative_error(m.covariance, quarter_k), kKernelCovarianceTolerance)
                        << "footprint " << i;
                }
            }
        }
}

TEST(FootprintAssembly, IsotropicRatioTakesOneProbeOfTheGeometricMean) {
    // LookupOptions::isotropic_ratio = 1.25: footprints with Λ1 ≤ 1.25·Λ2 take one probe of
    // T_p = √(Λ1·Λ2), whose measured kernel is T_p²/4·I (each σ within √1.25 of (K + I)/4's);
    // longer ones keep Rule B's probe lines and (K + I)/4.
    const MomentPyramids& moments = moment_pyramids();
    for (ProbeRule rule : {ProbeRule::moment_matched, ProbeRule::gaussian}) {
        LookupOptions options;
        options.probe_rule = rule;
        options.lod_blend = LodBlend::variance_matched;
        options.isotropic_ratio = 1.25f;
        std::mt19937 rng(7);
        for (int i = 0; i < 150; ++i) {
            const FootprintEllipse e = random_footprint(rng, 0.5f, 200, 1.6f);
            const ProbePlan plan =
                plan_probes(e, rule, options.max_probes, moments.first().max_level(), 0.0f, 1.25f);
            const float major = big_lambda(e.major_radius, e),
                        minor = big_lambda(e.minor_radius, e);
            float mean_error = 0;
            const KernelMoments m = averaged_fa_moments(moments, e, options, &mean_error);
            EXPECT_LT(mean_error, kKernelMeanTolerance * major) << "footprint " << i;
            if (major <= 1.25f * minor) {
                ASSERT_EQ(plan.count, 1) << "footprint " << i;
                EXPECT_NEAR(plan.texel_size, std::sqrt(major * minor), 1e-4f * major);
                const Sym2 single =
                    footprint_matrix({0.5f * plan.texel_size, 0}, {0, 0.5f * plan.texel_size});
                EXPECT_LT(relative_error(m.covariance, single), kKernelCovarianceTolerance)
                    << "footprint " << i << ": λ = (" << e.major_radius << ", " << e.minor_radius
                    << ")";
                // single_probe_lod (texture_lookup's and the environment's shortcut) agrees.
                const Sym2 k = outer(e.major_axis, e.major_radius * e.major_radius) +
                               outer(e.minor_axis(), e.minor_radius * e.minor_radius);
                EXPECT_NEAR(single_probe_lod(k, 0, moments.first().max_level(), 1.25f), plan.lod,
                            1e-3f);
            } else {
                EXPECT_GT(plan.count, 1) << "footprint " << i;
                const Sym2 quarter_k = outer(e.major_axis, 0.25f * major * major) +
                                       outer(e.minor_axis(), 0.25f * minor * minor);
                EXPECT_LT(relative_error(m.covariance, quarter_k), kKernelCovarianceTolerance)
                    << "footprint " << i;
            }
        }
    }
}

TEST(FootprintAssembly, FourSingleProbeLodsAreTheScalarOnesBitForBit) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1, 1), log_size(-8, 70);
    const float nan = std::nanf(""), inf = INFINITY;
    // Footprints of every kind: magnified, one probe, several, at the ratio's edge, negative or
    // indefinite, overflowing, NaN and infinite.
    auto random_k = [&](int i) -> Sym2 {
        const float size = std::exp2(log_size(rng) * (i % 3 == 0 ? 0.1f : 1.0f));
        switch (i % 8) {
            case 0:
                return make_footprint_ellipse(size, size / std::fabs(1 + 0.002f * u(rng)),
                                              3 * u(rng))
                    .matrix;  // near the isotropic ratio
            case 1:
                return {nan, 0, 1};
            case 2:
                return {inf, u(rng), 1};
            case 3:
                return {size * u(rng), size * u(rng), size * u(rng)};  // maybe indefinite
            case 4:
                return {0, 0, 0};
            default:
                return make_footprint_ellipse(size, size * std::fabs(u(rng)), 3 * u(rng)).matrix;
        }
    };
    for (const float bias : {0.0f, 0.5f, -1.0f})
        for (const int max_level : {0, 3, 11})
            for (const float ratio : {kIsotropicRatio, 1.3f})
                for (int i = 0; i < 4000; i += 4) {
                    Sym2 k[4];
                    for (int lane = 0; lane < 4; ++lane) k[lane] = random_k(i + lane);
                    if (i == 0) {
                        // λ1² = ratio²·T_p² exactly: one probe, at the rule's edge.
                        const float tie = ratio * ratio;
                        k[1] = {tie, 0, 1};
                        k[2] = {4 * tie, 0, 4};
                        k[3] = {std::nextafter(tie, 2.0f), 0, 1};
                    }
                    float lods[4];
                    single_probe_lod(Float4(k[0].xx, k[1].xx, k[2].xx, k[3].xx),
                                     Float4(k[0].xy, k[1].xy, k[2].xy, k[3].xy),
                                     Float4(k[0].yy, k[1].yy, k[2].yy, k[3].yy), bias, max_level,
                                     ratio)
                        .store(lods);
                    for (int lane = 0; lane < 4; ++lane) {
                        const float expected = single_probe_lod(k[lane], bias, max_level, ratio);
                        ASSERT_TRUE(std::isnan(expected)
                                        ? std::isnan(lods[lane])
                                        : std::memcmp(&expected, &lods[lane], sizeof(float)) == 0)
                            << "K = (" << k[lane].xx << ", " << k[lane].xy << ", " << k[lane].yy
                            << ") bias " << bias << " max level " << max_level << " ratio " << ratio
                            << ": " << lods[lane] << " vs " << expected;
                    }
                }
}

TEST(FootprintAssembly, FourShortPlansAreTheScalarOnesBitForBit) {
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> u(0, 1);
    auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; };
    int planned = 0, scalar_short = 0;
    for (const ProbeRule rule : {ProbeRule::moment_matched, ProbeRule::gaussian, ProbeRule::ext})
        for (const int max_probes : {30, 8, 5, 3, 2})
            for (const float ratio : {kIsotropicRatio, 1.25f})
                for (int i = 0; i < 4000; i += 4) {
                    // Anisotropies from one probe to beyond kShortLineProbes (up to 12:1), any
                    // size and angle; every 7th footprint degenerate.
                    Sym2 k[4];
                    for (int lane = 0; lane < 4; ++lane) {
                        const float major = std::exp2(12 * u(rng) - 2);
                        const float minor = major / std::exp2(3.6f * u(rng) * u(rng));
                        k[lane] = (i + lane) % 7 == 0
                                      ? Sym2{major, 0, 0}
                                      : make_footprint_ellipse(major, minor, 6.3f * u(rng)).matrix;
                    }
                    if (i < 400) {
                        // At the rule's edges exactly: λ1 = ratio·T_p (one probe or two), and
                        // λ1/T_p ulps around √2, where Rule B's ⌈√(3(λ1/T_p)² − 2)⌉ turns 3.
                        // (√(x·x) rounds back to x, so λ1 of diag(x², 1) is x.)
                        k[0] = {ratio * ratio, 0, 1};
                        float r = std::sqrt(2.0f);
                        for (int step = 0; step < i / 4; ++step) r = std::nextafter(r, 2.0f);
                        for (int lane = 1; lane < 4; ++lane) {
                            k[lane] = {r * r, 0, 1};
                            r = std::nextafter(r, 0.0f);
                        }
                    }
                    ShortPlans4 plans;
                    short_plans4(Float4(k[0].xx, k[1].xx, k[2].xx, k[3].xx),
                                 Float4(k[0].xy, k[1].xy, k[2].xy, k[3].xy),
                                 Float4(k[0].yy, k[1].yy, k[2].yy, k[3].yy), rule, max_probes, 9,
                                 0.25f, ratio, plans);
                    for (int lane = 0; lane < 4; ++lane) {
                        const ProbePlan expected = plan_probes(make_footprint_ellipse(k[lane]),
                                                               rule, max_probes, 9, 0.25f, ratio);
                        // Short lines within the budget (below it: at N_max a plan may be
                        // clamped).
                        const bool short_line = expected.count >= 2 &&
                                                expected.count <= kShortLineProbes &&
                                                expected.count < max_probes;
                        scalar_short += short_line;
                        if (!(plans.planned >> lane & 1)) {
                            // Left to plan_probes(): only other lines, or another rule.
                            EXPECT_TRUE(!short_line || rule == ProbeRule::ext)
                                << expected.count << " probes, N_max " << max_probes;
                            continue;
                        }
                        ++planned;
                        const ProbePlan plan = plans.plan(lane);
                        ASSERT_EQ(plan.count, expected.count);
                        EXPECT_TRUE(same(plan.step.x, expected.step.x) &&
                                    same(plan.step.y, expected.step.y));
                        EXPECT_TRUE(same(plan.lod, expected.lod));
                        EXPECT_TRUE(same(plan.texel_size, expected.texel_size));
                        EXPECT_TRUE(same(plan.weight_falloff, expected.weight_falloff));
                    }
                }
    EXPECT_GT(planned, 8000);
    EXPECT_GT(scalar_short, planned);  // Rule A's are the scalar's
}

TEST(FootprintAssembly, ClampedProbeBudgetRaisesTheMinorAxisOnly) {
    // With N_max = 16 the spec's kernel is ¼(Λ1² r1r1ᵀ + max(Λ2, T_p)² r2r2ᵀ): the major axis keeps
    // its full length, the minor one grows to the raised probe size T_p.
    const MomentPyramids& moments = moment_pyramids();
    for (ProbeRule rule : {ProbeRule::moment_matched, ProbeRule::gaussian}) {
        LookupOptions options;
        options.max_probes = 16;
        options.probe_rule = rule;
        options.lod_blend = LodBlend::variance_matched;
        std::mt19937 rng(99);
        for (int i = 0; i < 100; ++i) {
            const FootprintEllipse e = random_footprint(rng, 8, 400, 64);
            const ProbePlan plan =
                plan_probes(e, options.probe_rule, options.max_probes, moments.first().max_level());
            float mean_error = 0;
            const KernelMoments m = averaged_fa_moments(moments, e, options, &mean_error);
            const float minor = std::max(big_lambda(e.minor_radius, e), plan.texel_size);
            const float major = std::max(big_lambda(e.major_radius, e), plan.texel_size);
            const Sym2 expected = outer(e.major_axis, 0.25f * major * major) +
                                  outer(e.minor_axis(), 0.25f * minor * minor);
            EXPECT_LT(relative_error(m.covariance, expected), kKernelCovarianceTolerance)
                << "footprint " << i << ": λ = (" << e.major_radius << ", " << e.minor_radius
                << "), N = " << plan.count;
        }
    }
}

TEST(FootprintAssembly, RuleAIntegratesOnePixelStep) {
    // Spec §2.8: Rule A's kernel along r1 is about a one-pixel-step box, σ²_major → λ1²/12 + T²/4
    // ([FAX]: λ = (32, 2) gives σ_major = 8.7 instead of Rule B's 16).
    const MomentPyramids& moments = moment_pyramids();
    LookupOptions options;
    options.probe_rule = ProbeRule::ext;
    options.max_probes = 16;
    const FootprintEllipse e = make_footprint_ellipse(32, 2, 0.4f);
    float mean_error = 0;
    const KernelMoments m = averaged_fa_moments(moments, e, options, &mean_error);
    const float sigma_major = std::sqrt(m.covariance.quadratic_form(e.major_axis));
    const int n = 16;
    const float t = 2;
    const float predicted =
        std::sqrt(t * t / 4 + 32.0f * 32 * (n - 1) / (12.0f * (n + 1)));  // check.py [FAX]
    EXPECT_NEAR(sigma_major, predicted, 0.03f * predicted);
    EXPECT_NEAR(predicted, 8.73f, 0.01f);
}

}  // namespace
}  // namespace footprint
