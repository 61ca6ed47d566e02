#include "texture/ewa.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <tuple>

#include "image/test_images.h"
#include "texture/kernel_moments.h"
#include "texture/texture_lookup.h"

namespace footprint {
namespace {

// EWA at level 0 is a plain weighted sum: it must equal the brute-force sum to float rounding of
// weights accumulated in double and returned as float.
constexpr float kLevel0RelTolerance = 1e-5f;
// Kernel covariance against K/4 (the clamped K where λ1/λ2 > max_anisotropy). Exact in expectation
// by construction (prefilter variance + Gaussian = K/4); the residual is the sampled Gaussian's
// deviation from its continuous variance (≤ 1 % at σ ≥ 0.6 texel) and the linear level blend.
constexpr double kEwaCovarianceTolerance = 0.03;

TEST(Ewa, TruncationVarianceConstant) {
    // Numerically: the 2-D radial moments of w(r) = e^{−r²/2} − e^{−4.5} on r < 3.
    double num = 0, den = 0;
    for (int i = 0; i < 300000; ++i) {
        const double r = (i + 0.5) * 3.0 / 300000, w = std::exp(-0.5 * r * r) - std::exp(-4.5);
        num += r * r * w * r;
        den += w * r;
    }
    EXPECT_NEAR(ewa_truncation_variance(), num / den / 2, 1e-6);
    EXPECT_NEAR(ewa_truncation_variance(), 0.88020, 1e-5);
}

// Brute force over level l of the whole Gaussian EWA sums there (unsqueezed on a thin level): every
// texel of the wrap-extended level within its 3σ bounding box.
std::array<double, 3> brute_force_level(const MipPyramid& pyramid, int l, float s, float t,
                                        const FootprintEllipse& e) {
    const MipPyramid::LevelView& level = pyramid.level(l);
    const double tx = double(pyramid.width(0)) / level.width,
                 ty = double(pyramid.height(0)) / level.height;
    const Vec2 pv = pyramid.prefilter_variance(l);
    const Sym2 g = ewa_gaussian_covariance(e, std::max(pv.x, pv.y), float(std::max(tx, ty)));
    const double enlarge = 1.0 / ewa_truncation_variance();
    const double xx = enlarge * g.xx / (tx * tx), xy = enlarge * g.xy / (tx * ty),
                 yy = enlarge * g.yy / (ty * ty), det = xx * yy - xy * xy;
    const double cx = double(s) * level.width - 0.5, cy = double(t) * level.height - 0.5;
    const int rx = int(3 * std::sqrt(xx)) + 2, ry = int(3 * std::sqrt(yy)) + 2;
    std::array<double, 3> sum{};
    double wsum = 0;
    for (int y = int(cy) - ry; y <= int(cy) + ry; ++y)
        for (int x = int(cx) - rx; x <= int(cx) + rx; ++x) {
            const double dx = x - cx, dy = y - cy;
            const double r2 = (yy * dx * dx - 2 * xy * dx * dy + xx * dy * dy) / det;
            if (r2 >= 9) continue;
            const double w = std::exp(-0.5 * r2) - std::exp(-4.5);
            const float* texel = pyramid.texel(l, wrap_index(x, level.width, pyramid.wrap_s()),
                                               wrap_index(y, level.height, pyramid.wrap_t()));
            for (int c = 0; c < 3; ++c) sum[c] += w * texel[c];
            wsum += w;
        }
    for (double& v : sum) v /= wsum;
    return sum;
}

TEST(Ewa, EqualsBruteForceGaussianSumAtLevel0) {
    const int size = 64;
    const Image image = random_image(size, size, 3, 5);
    MipPyramidOptions po;
    po.wrap_s = WrapMode::repeat;
    po.wrap_t = WrapMode::mirror;
    const MipPyramid pyramid = MipPyramid::build(image, po);
    LookupOptions options;
    options.filter = TextureFilter::ewa;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0, 1);
    for (int i = 0; i < 300; ++i) {
        // λ2 ≤ 2√2 keeps EWA on level 0 (lod = log2 λ2 − 1.5 ≤ 0); λ1 > 1 avoids the bilinear
        // magnification path; anisotropy ≤ 16 stays under the clamp.
        const float minor = 0.1f + 2.7f * u(rng);
        const float major = std::max(1.05f, minor * std::pow(16.0f, u(rng)));
        const FootprintEllipse e =
            make_footprint_ellipse(major, std::min(minor, major), u(rng) * float(M_PI));
        const float s = u(rng), t = u(rng);  // anywhere, including across the wrap edges
        float got[3];
        texture_lookup(pyramid, s, t, e, options, got);

        const std::array<double, 3> want = brute_force_level(pyramid, 0, s, t, e);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], want[c], kLevel0RelTolerance)
                << "footprint " << i << " channel " << c;
    }
}

TEST(Ewa, KernelCovarianceIsQuarterK) {
    static const MomentPyramids moments(2048);
    LookupOptions options;
    options.filter = TextureFilter::ewa;
    options.max_anisotropy = 16;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1);
    for (int i = 0; i < 200; ++i) {
        const float major = 1.5f * std::pow(300.0f / 1.5f, u(rng));
        const float minor = major / std::pow(64.0f, u(rng));
        const float angle = u(rng) * float(M_PI);
        const FootprintEllipse e = make_footprint_ellipse(major, minor, angle);
        const float ox = 4 * u(rng), oy = 4 * u(rng);
        const KernelMoments m =
            moments.measure(ox, oy, [&](const MipPyramid& p, float s, float t, float* out) {
                texture_lookup(p, s, t, e, options, out);
            });
        // The anisotropy clamp grows the minor axis to λ1/16; the floor keeps σ ≥ 0.6 texel.
        const float clamped_minor = std::max(minor, major / options.max_anisotropy);
        const float var_minor = std::max(0.25f * clamped_minor * clamped_minor,
                                         kEwaMinSigma * kEwaMinSigma + 1.0f / 12);
        const Sym2 expected =
            outer(e.major_axis, 0.25f * major * major) + outer(e.minor_axis(), var_minor);
        EXPECT_LT(relative_error(m.covariance, expected), kEwaCovarianceTolerance)
            << "footprint " << i << ": λ = (" << major << ", " << minor << ")";
        EXPECT_NEAR(m.mean.x, ox, 0.01f * std::max(1.0f, major));
        EXPECT_NEAR(m.mean.y, oy, 0.01f * std::max(1.0f, major));
    }
}

// Squeezing keeps the correlation (a scale of one axis) and the other axis' variance exactly, to
// float rounding of a square root.
constexpr float kSqueezeRelTolerance = 1e-6f;
// On a level one texel thick the squeezed sum must equal the sum over the whole Gaussian, to float
// rounding as at level 0 (the residuals are about 1e−6).
constexpr float kThinLevelRelTolerance = 1e-5f;

float correlation(const Sym2& m) {
    return m.xy / std::sqrt(m.xx * m.yy);
}

TEST(Ewa, ThinLevelSqueezeBoundsTheSpreadAcrossIt) {
    const Sym2 sigma{9.0f, 300.0f, 40000.0f};  // σ = 3 along a 16 × 1 level, 200 across it
    const float cap = kEwaThinLevelSigma * kEwaThinLevelSigma;

    const Sym2 high = ewa_squeeze_thin_level(sigma, 16, 1);
    EXPECT_EQ(high.xx, sigma.xx);
    EXPECT_NEAR(high.yy, cap, kSqueezeRelTolerance * cap);
    EXPECT_NEAR(correlation(high), correlation(sigma), kSqueezeRelTolerance);

    const Sym2 wide = ewa_squeeze_thin_level({sigma.yy, -sigma.xy, sigma.xx}, 1, 16);
    EXPECT_NEAR(wide.xx, cap, kSqueezeRelTolerance * cap);
    EXPECT_EQ(wide.yy, sigma.xx);
    EXPECT_NEAR(correlation(wide), correlation(sigma) * -1, kSqueezeRelTolerance);

    // A level two texels thick, or a Gaussian already within the cap, is summed as it is.
    for (const auto& [m, w, h] : {std::tuple{sigma, 16, 2}, std::tuple{Sym2{9, 2, 4}, 16, 1}}) {
        const Sym2 same = ewa_squeeze_thin_level(m, w, h);
        EXPECT_EQ(same.xx, m.xx);
        EXPECT_EQ(same.xy, m.xy);
        EXPECT_EQ(same.yy, m.yy);
    }
}

TEST(Ewa, EqualsBruteForceOnLevelsOneTexelHigh) {
    // A 4096 × 1 texture: from level 0 on, its levels are one texel high, and a footprint's spread
    // across them is hundreds of rows of the same texels.
    const Image image = random_image(4096, 1, 3, 7);
    for (const WrapMode wrap : {WrapMode::repeat, WrapMode::clamp, WrapMode::mirror}) {
        MipPyramidOptions po;
        po.wrap_s = po.wrap_t = wrap;
        const MipPyramid pyramid = MipPyramid::build(image, po);
        LookupOptions options;
        options.filter = TextureFilter::ewa;
        std::mt19937 rng(5);
        std::uniform_real_distribution<float> u(0, 1);
        for (int i = 0; i < 6; ++i) {
            // lod = log2 λ2 − 1.5 = 8.25: levels 8 (16 × 1) and 9 (8 × 1), weighted ¾ and ¼;
            // anisotropy 4, under the clamp.
            const int l = 8;
            const float lod_fraction = 0.25f, minor = std::exp2(float(l) + lod_fraction + 1.5f);
            const FootprintEllipse e =
                make_footprint_ellipse(4 * minor, minor, u(rng) * float(M_PI));
            const float s = u(rng), t = u(rng);
            float got[3];
            texture_lookup(pyramid, s, t, e, options, got);
            const std::array<double, 3> fine = brute_force_level(pyramid, l, s, t, e),
                                        coarse = brute_force_level(pyramid, l + 1, s, t, e);
            for (int c = 0; c < 3; ++c) {
                const double want = (1 - lod_fraction) * fine[c] + lod_fraction * coarse[c];
                EXPECT_NEAR(got[c], want, kThinLevelRelTolerance * std::abs(want))
                    << "wrap " << int(wrap) << " footprint " << i << " channel " << c;
            }
        }
    }
}

}  // namespace
}  // namespace footprint
