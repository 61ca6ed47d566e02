#include "math/fast_log2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace footprint {
namespace {

// Float rounding of a result up to ~40: a few ulps of 32 (3.8e−6 each) plus the series' 5e−8.
constexpr float kLog2Tolerance = 1e-5f;

TEST(FastLog2, MatchesStdLog2) {
    for (int k = -100; k <= 100; ++k) EXPECT_EQ(fast_log2(std::ldexp(1.0f, k)), float(k));  // exact
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(-30, 40);
    for (int i = 0; i < 100000; ++i) {
        const float x = std::exp2(u(rng));
        ASSERT_NEAR(fast_log2(x), std::log2(x), kLog2Tolerance) << x;
    }
}

}  // namespace
}  // namespace footprint
