#include "math/fast_atan2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

namespace footprint {
namespace {

// 6e−8 rad is the polynomial's fit; float rounding of the quotient and of the π/2 and π folds adds
// up to 2 ulps of π (2.4e−7 each). A texel of a 16k-wide lat-long map spans 4e−4 rad.
constexpr float kAtan2Tolerance = 6e-7f;

TEST(FastAtan2, MatchesStdAtan2EverywhereToFloatRounding) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> angle(-3.14159265f, 3.14159265f);
    std::uniform_real_distribution<float> scale(-30, 30);
    for (int i = 0; i < 1000000; ++i) {
        const float phi = angle(rng), r = std::exp2(scale(rng));
        const float y = r * std::sin(phi), x = r * std::cos(phi);
        ASSERT_NEAR(fast_atan2(y, x), std::atan2(y, x), kAtan2Tolerance) << y << " " << x;
    }
}

TEST(FastAtan2, AxesSignsAndZerosFollowStdAtan2) {
    const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-30f, -1e30f, INFINITY, -INFINITY};
    for (float y : values)
        for (float x : values) {
            if (std::isinf(x) && std::isinf(y)) continue;  // not used by the maps
            EXPECT_NEAR(fast_atan2(y, x), std::atan2(y, x), kAtan2Tolerance) << y << " " << x;
            EXPECT_EQ(std::signbit(fast_atan2(y, x)), std::signbit(std::atan2(y, x)))
                << y << " " << x;
        }
    EXPECT_TRUE(std::isnan(fast_atan2(NAN, 1.0f)));
    EXPECT_TRUE(std::isnan(fast_atan2(1.0f, NAN)));
}

TEST(FastAtan2, FourAtOnceIsTheScalarFastAtan2BitForBit) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> angle(-3.14159265f, 3.14159265f), scale(-30, 30);
    const float special[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-30f, -1e30f, INFINITY, -INFINITY, NAN};
    for (int i = 0; i < 200000; ++i) {
        float y[4], x[4], out[4];
        for (int k = 0; k < 4; ++k) {
            const float phi = angle(rng), r = std::exp2(scale(rng));
            y[k] = r * std::sin(phi), x[k] = r * std::cos(phi);
            if (i < 81 && k == 0) y[k] = special[i % 9], x[k] = special[i / 9];
            if (k == 1) x[k] = std::fabs(y[k]) * (i % 2 ? 1.0f : -1.0f);  // |y| = |x|
        }
        fast_atan2(Float4(y[0], y[1], y[2], y[3]), Float4(x[0], x[1], x[2], x[3])).store(out);
        for (int k = 0; k < 4; ++k) {
            const float expected = fast_atan2(y[k], x[k]);
            ASSERT_TRUE(std::isnan(expected) ? std::isnan(out[k])
                                             : std::memcmp(&expected, &out[k], sizeof(float)) == 0)
                << y[k] << " " << x[k] << ": " << out[k] << " vs " << expected;
        }
    }
}

}  // namespace
}  // namespace footprint
