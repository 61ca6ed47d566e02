#include "math/float4.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "math/fast_log2.h"

namespace footprint {
namespace {

// Values where a vector operation may part from the scalar one: signed zeros, NaN, infinities,
// subnormals, ties, the largest finite values and ordinary numbers.
std::vector<float> edge_values() {
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    return {0.0f,  -0.0f, 1.0f,   -1.0f, 0.5f, 1.41421356f, 3.0f, -7.25f, 1e-40f,    -1e-40f,
            1e30f, 3e38f, -3e38f, inf,   -inf, nan,         -nan, 2.0f,   0x1p-100f, 0x1p100f};
}

// Bit-for-bit equal, NaN included (any NaN matches any NaN: the payload is not specified).
bool same(float a, float b) {
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
    return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

// Runs `vector_op` on the pairs (a, b) of edge values four at a time and compares every lane with
// `scalar_op`.
template <class Vector, class Scalar>
void expect_lanes_match(const char* name, Vector vector_op, Scalar scalar_op) {
    const std::vector<float> v = edge_values();
    std::vector<float> a, b;
    for (float x : v)
        for (float y : v) a.push_back(x), b.push_back(y);
    while (a.size() % 4) a.push_back(1.0f), b.push_back(1.0f);
    for (std::size_t i = 0; i < a.size(); i += 4) {
        float out[4];
        vector_op(Float4(a[i], a[i + 1], a[i + 2], a[i + 3]),
                  Float4(b[i], b[i + 1], b[i + 2], b[i + 3]))
            .store(out);
        for (int k = 0; k < 4; ++k)
            EXPECT_TRUE(same(out[k], scalar_op(a[i + k], b[i + k])))
                << name << "(" << a[i + k] << ", " << b[i + k] << ") = " << out[k];
    }
}

TEST(Float4, ArithmeticIsTheScalarArithmeticLaneByLane) {
    expect_lanes_match(
        "+", [](Float4 a, Float4 b) { return a + b; }, [](float a, float b) { return a + b; });
    expect_lanes_match(
        "-", [](Float4 a, Float4 b) { return a - b; }, [](float a, float b) { return a - b; });
    expect_lanes_match(
        "*", [](Float4 a, Float4 b) { return a * b; }, [](float a, float b) { return a * b; });
    expect_lanes_match(
        "/", [](Float4 a, Float4 b) { return a / b; }, [](float a, float b) { return a / b; });
    expect_lanes_match(
        "neg", [](Float4 a, Float4) { return -a; }, [](float a, float) { return -a; });
    expect_lanes_match(
        "abs", [](Float4 a, Float4) { return abs(a); },
        [](float a, float) { return std::fabs(a); });
    expect_lanes_match(
        "sqrt", [](Float4 a, Float4) { return sqrt(a); },
        [](float a, float) { return std::sqrt(a); });
}

TEST(Float4, MinMaxClampFollowTheStandardLibrary) {
    // std::max returns its first argument unless the second is greater: max(NaN, 1) is NaN, max(1,
    // NaN) is 1, max(0, −0) is 0 and max(−0, 0) is −0. _mm_max_ps alone orders them the other way.
    expect_lanes_match(
        "max", [](Float4 a, Float4 b) { return max_like_std(a, b); },
        [](float a, float b) { return std::max(a, b); });
    expect_lanes_match(
        "min", [](Float4 a, Float4 b) { return min_like_std(a, b); },
        [](float a, float b) { return std::min(a, b); });
    expect_lanes_match(
        "clamp(·, −1, b≥−1)",
        [](Float4 a, Float4 b) {
            return clamp_like_std(a, Float4(-1.0f), max_like_std(b, Float4(-1.0f)));
        },
        [](float a, float b) { return std::clamp(a, -1.0f, std::max(b, -1.0f)); });
}

TEST(Float4, ComparisonsAndSelectsAreOrdered) {
    auto as_float = [](bool x) { return x ? 1.0f : 0.0f; };
    auto pick = [](Mask4 m) { return select(m, Float4(1.0f), Float4(0.0f)); };
    expect_lanes_match(
        "<", [&](Float4 a, Float4 b) { return pick(a < b); },
        [&](float a, float b) { return as_float(a < b); });
    expect_lanes_match(
        "<=", [&](Float4 a, Float4 b) { return pick(a <= b); },
        [&](float a, float b) { return as_float(a <= b); });
    expect_lanes_match(
        ">", [&](Float4 a, Float4 b) { return pick(a > b); },
        [&](float a, float b) { return as_float(a > b); });
    expect_lanes_match(
        ">=", [&](Float4 a, Float4 b) { return pick(a >= b); },
        [&](float a, float b) { return as_float(a >= b); });
    expect_lanes_match(
        "!(a < b) & ordered(a)",
        [&](Float4 a, Float4 b) {
            const Mask4 not_less = !(a < b);
            return pick(not_less & is_not_nan(a));
        },
        [&](float a, float b) { return as_float(!(a < b) && !std::isnan(a)); });
    expect_lanes_match(
        "(a < b) | (a > b)", [&](Float4 a, Float4 b) { return pick((a < b) | (a > b)); },
        [&](float a, float b) { return as_float(a < b || a > b); });
    const Mask4 m = Float4(1, -1, 2, -2) > Float4(0.0f);
    EXPECT_EQ(m.bits(), 0b0101);
}

TEST(Float4, IntegerLanesAndBits) {
    const Float4 x(1.0f, 0.75f, 1e-30f, 6e20f);
    int exponent[4];
    ((shift_right<23>(bits_of(x)) & Int4(0xff)) - Int4(127)).store(exponent);
    EXPECT_EQ(exponent[0], 0);
    EXPECT_EQ(exponent[1], -1);
    EXPECT_EQ(exponent[2], std::ilogb(1e-30f));
    EXPECT_EQ(exponent[3], std::ilogb(6e20f));
    float back[4];
    float_from_bits(shift_left<23>(Int4(127) - Int4(3))).store(back);  // 2^-3
    EXPECT_EQ(back[0], 0.125f);
    to_float(Int4(-5) + Int4(2)).store(back);
    EXPECT_EQ(back[3], -3.0f);
    int picked[4];
    select(Float4(1, -1, 1, -1) > Float4(0.0f), Int4(7), Int4(9)).store(picked);
    EXPECT_EQ(picked[0], 7);
    EXPECT_EQ(picked[1], 9);
}

TEST(Float4, FastLog2OfFourIsTheScalarFastLog2) {
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-120, 120);
    for (int i = 0; i < 20000; ++i) {
        float x[4], out[4];
        for (float& v : x) v = std::exp2(u(rng));
        if (i == 0) x[0] = 1.41421356f, x[1] = std::nextafter(1.41421356f, 2.0f), x[2] = 1.0f;
        fast_log2(Float4(x[0], x[1], x[2], x[3])).store(out);
        for (int k = 0; k < 4; ++k) ASSERT_TRUE(same(out[k], fast_log2(x[k]))) << x[k];
    }
}

}  // namespace
}  // namespace footprint
