#include "texture/reference_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace footprint {
namespace {

// The quadrature's relative error on the kernel moments: midpoint rule at ≥ 8 nodes per σ on a
// Gaussian times a piecewise-bilinear function (kinks at texel edges) and the 4σ cut (the
// truncated Gaussian keeps 99.7 % of its variance per axis).
constexpr double kMomentTolerance = 4e-3;

// Moments of the reference kernel, through the textures x, y, x², xy, y² (see kernel_moments.h).
TEST(ReferenceFilter, KernelIsTheQuarterKGaussianOnTheBilinearReconstruction) {
    const int size = 256;
    Image poly(size, size, 5);
    const double c = 0.5 * (size - 1);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const double dx = x - c, dy = y - c;
            float* p = poly.at(x, y);
            p[0] = float(dx), p[1] = float(dy), p[2] = float(dx * dx), p[3] = float(dx * dy),
            p[4] = float(dy * dy);
        }
    ReferenceOptions options;
    options.wrap_s = options.wrap_t = WrapMode::clamp;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0, 1);
    for (int i = 0; i < 60; ++i) {
        // σ_minor ≥ 1 texel, so that the bilinear interpolation error of x² (f(1−f) at phase f)
        // averages to exactly 1/6 over the kernel.
        const float major = 2 + 18 * u(rng), minor = 2 + (major - 2) * u(rng);
        const FootprintEllipse e = make_footprint_ellipse(major, minor, 3.2f * u(rng));
        const double ox = 3 * u(rng), oy = 3 * u(rng);
        float m[5];
        reference_lookup(poly, (0.5 * size + ox) / size, (0.5 * size + oy) / size, e, options, m);
        EXPECT_NEAR(m[0], ox, 1e-4);
        EXPECT_NEAR(m[1], oy, 1e-4);
        const double cxx = m[2] - double(m[0]) * m[0], cxy = m[3] - double(m[0]) * m[1],
                     cyy = m[4] - double(m[1]) * m[1];
        const Sym2 want = 0.25f * e.matrix;
        const double scale = want.trace();
        EXPECT_NEAR(cxx, want.xx + 1.0 / 6, kMomentTolerance * scale) << i;
        EXPECT_NEAR(cxy, want.xy, kMomentTolerance * scale) << i;
        EXPECT_NEAR(cyy, want.yy + 1.0 / 6, kMomentTolerance * scale) << i;
    }
}

TEST(ReferenceFilter, ZeroFootprintIsTheBilinearReconstruction) {
    Image image(3, 3, 1);
    for (int i = 0; i < 9; ++i) image.pixels[i] = float(i * i);
    float v;
    // Between texels (0,0)=0, (1,0)=1, (0,1)=9, (1,1)=16 at fractions (0.25, 0.5).
    reference_lookup(image, (0.25 + 0.5) / 3, (0.5 + 0.5) / 3, FootprintEllipse{},
                     ReferenceOptions{}, &v);
    EXPECT_NEAR(v, 0.75 * 0.5 * 0 + 0.25 * 0.5 * 1 + 0.75 * 0.5 * 9 + 0.25 * 0.5 * 16, 1e-5);
}

}  // namespace
}  // namespace footprint
