// math/float4.h — four floats computed at once (one SSE register), for the footprints of four
// lookups in structure-of-arrays form (envmap/env_footprint.h, texture/footprint_assembly.h).
//
// Every operation is, lane by lane, exactly the scalar operation it stands for, so that a lane's
// result is the scalar code's bit for bit:
// clang-format off
//   +, −, ×, ÷, √           IEEE-754 single precision, correctly rounded (no FMA contraction)
//   max_like_std(a, b)      std::max(a, b) = (a < b) ? b : a, NaN and signed-zero cases included
//   min_like_std(a, b)      std::min(a, b) = (b < a) ? b : a
//   clamp_like_std(v, l, h) std::clamp(v, l, h) for l ≤ h (a NaN v stays NaN)
//   comparisons             ordered (false when either side is NaN), as in C++
// clang-format on
// Int4 holds the 32-bit integers of the bit tricks (exponents from the IEEE bits). Without SSE2 the
// same operations run on four scalars.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

// FOOTPRINT_FLOAT4_SCALAR forces the four-scalar form (to test it on an SSE2 machine).
#if defined(__SSE2__) && !defined(FOOTPRINT_FLOAT4_SCALAR)
#define FOOTPRINT_FLOAT4_SSE2 1
#include <emmintrin.h>
#endif

namespace footprint {

#if FOOTPRINT_FLOAT4_SSE2

struct Mask4 {
    __m128 v;
    // Bit i set where lane i is true.
    int bits() const { return _mm_movemask_ps(v); }
};
inline Mask4 operator&(Mask4 a, Mask4 b) {
    return {_mm_and_ps(a.v, b.v)};
}
inline Mask4 operator|(Mask4 a, Mask4 b) {
    return {_mm_or_ps(a.v, b.v)};
}
inline Mask4 operator!(Mask4 a) {
    return {_mm_xor_ps(a.v, _mm_castsi128_ps(_mm_set1_epi32(-1)))};
}

struct Float4 {
    __m128 v;
    Float4() : v(_mm_setzero_ps()) {}
    Float4(__m128 v) : v(v) {}
    Float4(float x) : v(_mm_set1_ps(x)) {}
    Float4(float a, float b, float c, float d) : v(_mm_setr_ps(a, b, c, d)) {}
    static Float4 load(const float* in) { return _mm_loadu_ps(in); }  // in[0..3]
    void store(float* out) const { _mm_storeu_ps(out, v); }
};
inline Float4 operator+(Float4 a, Float4 b) {
    return _mm_add_ps(a.v, b.v);
}
inline Float4 operator-(Float4 a, Float4 b) {
    return _mm_sub_ps(a.v, b.v);
}
inline Float4 operator*(Float4 a, Float4 b) {
    return _mm_mul_ps(a.v, b.v);
}
inline Float4 operator/(Float4 a, Float4 b) {
    return _mm_div_ps(a.v, b.v);
}
inline Float4 operator-(Float4 a) {
    return _mm_xor_ps(a.v, _mm_set1_ps(-0.0f));
}  // flips the sign
inline Mask4 operator<(Float4 a, Float4 b) {
    return {_mm_cmplt_ps(a.v, b.v)};
}
inline Mask4 operator<=(Float4 a, Float4 b) {
    return {_mm_cmple_ps(a.v, b.v)};
}
inline Mask4 operator>(Float4 a, Float4 b) {
    return {_mm_cmpgt_ps(a.v, b.v)};
}
inline Mask4 operator>=(Float4 a, Float4 b) {
    return {_mm_cmpge_ps(a.v, b.v)};
}
inline Mask4 operator==(Float4 a, Float4 b) {
    return {_mm_cmpeq_ps(a.v, b.v)};
}
inline Mask4 is_not_nan(Float4 a) {
    return {_mm_cmpord_ps(a.v, a.v)};
}
inline Float4 abs(Float4 a) {
    return _mm_andnot_ps(_mm_set1_ps(-0.0f), a.v);
}
inline Float4 sqrt(Float4 a) {
    return _mm_sqrt_ps(a.v);
}
// Where the sign bit is set (std::signbit), and |magnitude| with the sign of `sign`
// (std::copysign).
inline Mask4 sign_bit(Float4 a) {
    return {_mm_castsi128_ps(_mm_srai_epi32(_mm_castps_si128(a.v), 31))};
}
inline Float4 copysign(Float4 magnitude, Float4 sign) {
    const __m128 sign_mask = _mm_set1_ps(-0.0f);
    return _mm_or_ps(_mm_andnot_ps(sign_mask, magnitude.v), _mm_and_ps(sign_mask, sign.v));
}
// _mm_max_ps(x, y) = (x > y) ? x : y, so std::max(a, b) = (b > a) ? b : a is _mm_max_ps(b, a).
inline Float4 max_like_std(Float4 a, Float4 b) {
    return _mm_max_ps(b.v, a.v);
}
inline Float4 min_like_std(Float4 a, Float4 b) {
    return _mm_min_ps(b.v, a.v);
}
// Where m, a, else b.
inline Float4 select(Mask4 m, Float4 a, Float4 b) {
    return _mm_or_ps(_mm_and_ps(m.v, a.v), _mm_andnot_ps(m.v, b.v));
}

struct Int4 {
    __m128i v;
    Int4(__m128i v) : v(v) {}
    Int4(int x) : v(_mm_set1_epi32(x)) {}
    void store(int* out) const { _mm_storeu_si128(reinterpret_cast<__m128i*>(out), v); }
};
inline Int4 operator+(Int4 a, Int4 b) {
    return _mm_add_epi32(a.v, b.v);
}
inline Int4 operator-(Int4 a, Int4 b) {
    return _mm_sub_epi32(a.v, b.v);
}
inline Int4 operator&(Int4 a, Int4 b) {
    return _mm_and_si128(a.v, b.v);
}
inline Int4 operator|(Int4 a, Int4 b) {
    return _mm_or_si128(a.v, b.v);
}
template <int N>
Int4 shift_right(Int4 a) {  // logical
    return _mm_srli_epi32(a.v, N);
}
template <int N>
Int4 shift_left(Int4 a) {
    return _mm_slli_epi32(a.v, N);
}
inline Mask4 operator==(Int4 a, Int4 b) {
    return {_mm_castsi128_ps(_mm_cmpeq_epi32(a.v, b.v))};
}
inline Mask4 operator>(Int4 a, Int4 b) {
    return {_mm_castsi128_ps(_mm_cmpgt_epi32(a.v, b.v))};
}
inline Int4 select(Mask4 m, Int4 a, Int4 b) {
    const __m128i mi = _mm_castps_si128(m.v);
    return _mm_or_si128(_mm_and_si128(mi, a.v), _mm_andnot_si128(mi, b.v));
}
inline Int4 bits_of(Float4 a) {
    return _mm_castps_si128(a.v);
}
inline Float4 float_from_bits(Int4 a) {
    return _mm_castsi128_ps(a.v);
}
inline Float4 to_float(Int4 a) {
    return _mm_cvtepi32_ps(a.v);
}  // exact for |a| ≤ 2^24

#else  // four scalars

struct Mask4 {
    bool lane[4];
    int bits() const { return lane[0] | lane[1] << 1 | lane[2] << 2 | lane[3] << 3; }
};
template <class F>
Mask4 mask_each(F f) {
    return {{f(0), f(1), f(2), f(3)}};
}
inline Mask4 operator&(Mask4 a, Mask4 b) {
    return mask_each([&](int i) { return a.lane[i] && b.lane[i]; });
}
inline Mask4 operator|(Mask4 a, Mask4 b) {
    return mask_each([&](int i) { return a.lane[i] || b.lane[i]; });
}
inline Mask4 operator!(Mask4 a) {
    return mask_each([&](int i) { return !a.lane[i]; });
}

struct Float4 {
    float lane[4];
    Float4() : lane{} {}
    Float4(float x) : lane{x, x, x, x} {}
    Float4(float a, float b, float c, float d) : lane{a, b, c, d} {}
    static Float4 load(const float* in) { return {in[0], in[1], in[2], in[3]}; }
    void store(float* out) const {
        for (int i = 0; i < 4; ++i) out[i] = lane[i];
    }
};
template <class F>
Float4 float_each(F f) {
    return {f(0), f(1), f(2), f(3)};
}
inline Float4 operator+(Float4 a, Float4 b) {
    return float_each([&](int i) { return a.lane[i] + b.lane[i]; });
}
inline Float4 operator-(Float4 a, Float4 b) {
    return float_each([&](int i) { return a.lane[i] - b.lane[i]; });
}
inline Float4 operator*(Float4 a, Float4 b) {
    return float_each([&](int i) { return a.lane[i] * b.lane[i]; });
}
inline Float4 operator/(Float4 a, Float4 b) {
    return float_each([&](int i) { return a.lane[i] / b.lane[i]; });
}
inline Float4 operator-(Float4 a) {
    return float_each([&](int i) { return -a.lane[i]; });
}
inline Mask4 operator<(Float4 a, Float4 b) {
    return mask_each([&](int i) { return a.lane[i] < b.lane[i]; });
}
inline Mask4 operator<=(Float4 a, Float4 b) {
    return mask_each([&](int i) { return a.lane[i] <= b.lane[i]; });
}
inline Mask4 operator>(Float4 a, Float4 b) {
    return b < a;
}
inline Mask4 operator>=(Float4 a, Float4 b) {
    return b <= a;
}
inline Mask4 operator==(Float4 a, Float4 b) {
    return mask_each([&](int i) { return a.lane[i] == b.lane[i]; });
}
inline Mask4 is_not_nan(Float4 a) {
    return mask_each([&](int i) { return !std::isnan(a.lane[i]); });
}
inline Float4 abs(Float4 a) {
    return float_each([&](int i) { return std::fabs(a.lane[i]); });
}
inline Float4 sqrt(Float4 a) {
    return float_each([&](int i) { return std::sqrt(a.lane[i]); });
}
inline Mask4 sign_bit(Float4 a) {
    return mask_each([&](int i) { return std::signbit(a.lane[i]); });
}
inline Float4 copysign(Float4 magnitude, Float4 sign) {
    return float_each([&](int i) { return std::copysign(magnitude.lane[i], sign.lane[i]); });
}
inline Float4 max_like_std(Float4 a, Float4 b) {
    return float_each([&](int i) { return a.lane[i] < b.lane[i] ? b.lane[i] : a.lane[i]; });
}
inline Float4 min_like_std(Float4 a, Float4 b) {
    return float_each([&](int i) { return b.lane[i] < a.lane[i] ? b.lane[i] : a.lane[i]; });
}
inline Float4 select(Mask4 m, Float4 a, Float4 b) {
    return float_each([&](int i) { return m.lane[i] ? a.lane[i] : b.lane[i]; });
}

struct Int4 {
    std::int32_t lane[4];
    Int4(int x) : lane{x, x, x, x} {}
    Int4(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) : lane{a, b, c, d} {}
    void store(int* out) const {
        for (int i = 0; i < 4; ++i) out[i] = lane[i];
    }
};
template <class F>
Int4 int_each(F f) {
    return {f(0), f(1), f(2), f(3)};
}
inline Int4 operator+(Int4 a, Int4 b) {
    return int_each([&](int i) {
        return static_cast<std::int32_t>(static_cast<std::uint32_t>(a.lane[i]) +
                                         static_cast<std::uint32_t>(b.lane[i]));
    });
}
inline Int4 operator-(Int4 a, Int4 b) {
    return int_each([&](int i) {
        return static_cast<std::int32_t>(static_cast<std::uint32_t>(a.lane[i]) -
                                         static_cast<std::uint32_t>(b.lane[i]));
    });
}
inline Int4 operator&(Int4 a, Int4 b) {
    return int_each([&](int i) { return a.lane[i] & b.lane[i]; });
}
inline Int4 operator|(Int4 a, Int4 b) {
    return int_each([&](int i) { return a.lane[i] | b.lane[i]; });
}
template <int N>
Int4 shift_right(Int4 a) {
    return int_each([&](int i) {
        return static_cast<std::int32_t>(static_cast<std::uint32_t>(a.lane[i]) >> N);
    });
}
template <int N>
Int4 shift_left(Int4 a) {
    return int_each([&](int i) {
        return static_cast<std::int32_t>(static_cast<std::uint32_t>(a.lane[i]) << N);
    });
}
inline Mask4 operator==(Int4 a, Int4 b) {
    return mask_each([&](int i) { return a.lane[i] == b.lane[i]; });
}
inline Mask4 operator>(Int4 a, Int4 b) {
    return mask_each([&](int i) { return a.lane[i] > b.lane[i]; });
}
inline Int4 select(Mask4 m, Int4 a, Int4 b) {
    return int_each([&](int i) { return m.lane[i] ? a.lane[i] : b.lane[i]; });
}
inline Int4 bits_of(Float4 a) {
    return int_each([&](int i) { return std::bit_cast<std::int32_t>(a.lane[i]); });
}
inline Float4 float_from_bits(Int4 a) {
    return float_each([&](int i) { return std::bit_cast<float>(a.lane[i]); });
}
inline Float4 to_float(Int4 a) {
    return float_each([&](int i) { return static_cast<float>(a.lane[i]); });
}

#endif

inline Mask4 operator<=(Int4 a, Int4 b) {
    return !(a > b);
}

// std::isfinite: neither NaN nor ±∞.
inline Mask4 is_finite(Float4 a) {
    return abs(a) < Float4(std::numeric_limits<float>::infinity());
}

// std::clamp(v, lo, hi) = (v < lo) ? lo : (hi < v) ? hi : v.
inline Float4 clamp_like_std(Float4 v, Float4 lo, Float4 hi) {
    return select(v < lo, lo, min_like_std(v, hi));
}

}  // namespace footprint
