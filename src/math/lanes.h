// math/lanes.h — (private) a step of the lookups written once over a lane type F: float (or
// double) for one lookup, Float4 (math/float4.h) for four at once. This header gives the scalar
// types the spellings that float4.h gives Float4 (select, max_like_std, none, …) and names the
// types that go with a lane type, so that one template serves both and a lane's result is the
// scalar result bit for bit by construction, not by a second copy kept in step.
//
// In a template over F, comparisons give MaskOf<F> (bool or Mask4), combined with &, | and !;
// branches become select(); `if (none(mask)) return` leaves early where no lane is left. Call
// abs and sqrt unqualified after `using std::abs, std::sqrt;` (ADL finds Float4's).
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <concepts>
#include <type_traits>

#include "math/float4.h"
#include "math/mat3.h"
#include "math/vec.h"
#include "math/vec3.h"

namespace footprint {

template <class F>
struct LaneTypes {  // one lane: float or double
    using Mask = bool;
    using Int = int;
    using Scalar = F;
};
template <>
struct LaneTypes<Float4> {
    using Mask = Mask4;
    using Int = Int4;
    using Scalar = float;
};
template <class F>
using MaskOf = typename LaneTypes<F>::Mask;
template <class F>
using IntOf = typename LaneTypes<F>::Int;
template <class F>
using ScalarOf = typename LaneTypes<F>::Scalar;

// Float4's operations for one lane.
template <class T>
requires std::is_arithmetic_v<T> T select(bool m, T a, T b) {
    return m ? a : b;
}
template <std::floating_point T>
T max_like_std(T a, T b) {
    return std::max(a, b);
}
template <std::floating_point T>
T min_like_std(T a, T b) {
    return std::min(a, b);
}
template <std::floating_point T>
T clamp_like_std(T v, T lo, T hi) {
    return std::clamp(v, lo, hi);
}
template <std::floating_point T>
bool is_finite(T a) {
    return std::isfinite(a);
}
template <std::floating_point T>
bool is_not_nan(T a) {
    return !std::isnan(a);
}

// The sign bit (std::signbit), and |m| with s's sign.
inline bool sign_bit(float a) {
    return std::signbit(a);
}
inline float copysign(float magnitude, float sign) {
    return std::copysign(magnitude, sign);
}

// Int4's bit operations for one lane: the IEEE-754 bits of a float as a 32-bit integer, logical
// shifts, and the exact conversion back to float.
inline int bits_of(float a) {
    return std::bit_cast<int>(a);
}
inline float float_from_bits(int a) {
    return std::bit_cast<float>(a);
}
template <int N>
int shift_right(int a) {  // logical
    return static_cast<int>(static_cast<unsigned>(a) >> N);
}
template <int N>
int shift_left(int a) {
    return static_cast<int>(static_cast<unsigned>(a) << N);
}
inline float to_float(int a) {
    return static_cast<float>(a);
}

// Whether no lane of a mask is set.
inline bool none(bool m) {
    return !m;
}
inline bool none(Mask4 m) {
    return m.bits() == 0;
}

template <class M, class F>
Vec3T<F> select(M m, const Vec3T<F>& a, const Vec3T<F>& b) {
    return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}

// is_finite() of each component, lane by lane.
template <class F>
MaskOf<F> is_finite_lanes(const Vec3T<F>& v) {
    return is_finite(v.x) & is_finite(v.y) & is_finite(v.z);
}

// A v (Mat3::operator*'s order of operations), or v where A is the identity.
template <class F>
Vec3T<F> rotate(const IdentitySkippingRotation& a, const Vec3T<F>& v) {
    if (a.is_identity()) return v;
    const auto& m = a.matrix().m;
    auto row = [&](int i) { return F(m[i][0]) * v.x + F(m[i][1]) * v.y + F(m[i][2]) * v.z; };
    return {row(0), row(1), row(2)};
}

// The Vec3 `member` of items[0..3], one lane each.
template <class T>
Vec3T<Float4> gather(const T* items, Vec3 T::*member) {
    const Vec3 &a = items[0].*member, &b = items[1].*member, &c = items[2].*member,
               &d = items[3].*member;
    return {{a.x, b.x, c.x, d.x}, {a.y, b.y, c.y, d.y}, {a.z, b.z, c.z, d.z}};
}

// K = D Dᵀ (math/footprint_ellipse.h's footprint_matrix()) of D's columns, for any lane type.
template <class F>
struct Sym2Lanes {
    F xx, xy, yy;
};
template <class F>
Sym2Lanes<F> footprint_matrix_lanes(const Vec2T<F>& d_dx, const Vec2T<F>& d_dy) {
    return {d_dx.x * d_dx.x + d_dy.x * d_dy.x, d_dx.x * d_dx.y + d_dy.x * d_dy.y,
            d_dx.y * d_dx.y + d_dy.y * d_dy.y};
}

}  // namespace footprint
