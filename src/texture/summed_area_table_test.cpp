#include "texture/summed_area_table.h"

#include <gtest/gtest.h>

#include <random>

#include "image/test_images.h"
#include "texture/texture_lookup.h"

namespace footprint {
namespace {

// Double-precision table, float result: the mean of values in [0, 1] is exact to float rounding.
constexpr float kBoxMeanTolerance = 2e-6f;

// Length of [a, b) ∩ [lo, hi).
double overlap(double a, double b, double lo, double hi) {
    return std::max(0.0, std::min(b, hi) - std::max(a, lo));
}

TEST(SummedAreaTable, BoxMeanEqualsBruteForceForEveryWrapMode) {
    const int w = 37, h = 23;  // odd sizes
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0, 1);
    const Image image = random_image(w, h, 2, 1234u);
    for (WrapMode ws : {WrapMode::repeat, WrapMode::clamp, WrapMode::mirror})
        for (WrapMode wt : {WrapMode::repeat, WrapMode::clamp, WrapMode::mirror}) {
            const SummedAreaTable sat = SummedAreaTable::build(image, ws, wt);
            for (int i = 0; i < 200; ++i) {
                // Boxes up to two texture sizes wide, anywhere in [−1.5, 2.5] textures.
                const double x0 = (4 * u(rng) - 1.5) * w, y0 = (4 * u(rng) - 1.5) * h;
                const double x1 = x0 + 0.01 + 2 * w * u(rng) * u(rng),
                             y1 = y0 + 0.01 + 2 * h * u(rng) * u(rng);
                float got[2];
                sat.box_mean(x0, y0, x1, y1, got);
                double sum[2] = {};
                for (int y = int(std::floor(y0)); y < int(std::ceil(y1)); ++y) {
                    const double oy = overlap(y, y + 1, y0, y1);
                    for (int x = int(std::floor(x0)); x < int(std::ceil(x1)); ++x) {
                        const double o = overlap(x, x + 1, x0, x1) * oy;
                        const float* t = image.at(wrap_index(x, w, ws), wrap_index(y, h, wt));
                        sum[0] += o * t[0];
                        sum[1] += o * t[1];
                    }
                }
                const double area = (x1 - x0) * (y1 - y0);
                EXPECT_NEAR(got[0], sum[0] / area, kBoxMeanTolerance)
                    << to_string(ws) << "/" << to_string(wt);
                EXPECT_NEAR(got[1], sum[1] / area, kBoxMeanTolerance)
                    << to_string(ws) << "/" << to_string(wt);
            }
        }
}

TEST(SummedAreaTable, LookupUsesTheEllipseBoundingRectangle) {
    const int size = 32;
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> u(0, 1);
    const Image image = random_image(size, size, 1, 1234u);
    MipPyramidOptions po;
    po.summed_area_table = true;
    const MipPyramid pyramid = MipPyramid::build(image, po);
    const SummedAreaTable& sat = *pyramid.summed_area_table();
    LookupOptions options;
    options.filter = TextureFilter::summed_area;
    const FootprintEllipse e = make_footprint_ellipse(6, 2, 0.5f);
    float got, want;
    texture_lookup(pyramid, 0.3f, 0.6f, e, options, &got);
    const double hx = std::sqrt(double(e.matrix.xx)), hy = std::sqrt(double(e.matrix.yy));
    sat.box_mean(0.3 * size - hx, 0.6 * size - hy, 0.3 * size + hx, 0.6 * size + hy, &want);
    EXPECT_NEAR(got, want, kBoxMeanTolerance);
}

}  // namespace
}  // namespace footprint
