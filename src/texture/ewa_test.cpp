#include "texture/ewa.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

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

        // Brute force: every level-0 texel of the wrap-extended image within reach.
        const Sym2 sigma =
            (1.0f / ewa_truncation_variance()) * ewa_gaussian_covariance(e, 0.0f, 1.0f);
        const double det = double(sigma.xx) * sigma.yy - double(sigma.xy) * sigma.xy;
        const double cx = double(s) * size - 0.5, cy = double(t) * size - 0.5;
        double sum[3] = {}, wsum = 0;
        for (int y = int(cy) - 100; y <= int(cy) + 100; ++y)
            for (int x = int(cx) - 100; x <= int(cx) + 100; ++x) {
                const double dx = x - cx, dy = y - cy;
                const double r2 =
                    (sigma.yy * dx * dx - 2 * sigma.xy * dx * dy + sigma.xx * dy * dy) / det;
                if (r2 >= 9) continue;
                const double w = std::exp(-0.5 * r2) - std::exp(-4.5);
                const float* texel = image.at(wrap_index(x, size, WrapMode::repeat),
                                              wrap_index(y, size, WrapMode::mirror));
                for (int c = 0; c < 3; ++c) sum[c] += w * texel[c];
                wsum += w;
            }
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], sum[c] / wsum, kLevel0RelTolerance)
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

}  // namespace
}  // namespace footprint
