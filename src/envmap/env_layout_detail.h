// envmap/env_layout_detail.h — (private to envmap) the inline pieces of the lat-long and cube
// mappings of env_layout.h: a direction prepared for evaluation (an exact power-of-two rescaling),
// the cube's face table, and (s, t) with the Jacobian for both layouts. Each piece is written once
// over a lane type (math/lanes.h): env_layout.cpp builds its public float and double functions from
// them, and form (a)'s plain footprint (env_footprint_plain.h) and the polar caps use them for one
// ray or four at once, so that every result is the public functions' bit for bit.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "envmap/env_layout.h"
#include "math/fast_atan2.h"
#include "math/float4.h"
#include "math/lanes.h"

namespace footprint::env_detail {

template <class T>
inline constexpr T kPi = T(3.14159265358979323846);

// The common case of prepare(), for any lane type (math/lanes.h): where `common` (max |component|
// within 2^±100, no component NaN), r = (input)·scale has its largest |component| in [1, 2), and
// scale = 2^-⌊log2 max⌋ is exact, so nothing below under- or overflows. Elsewhere the lane is the
// scalar prepare()'s to handle (prepare_rare()).
template <class F>
struct PreparedLanes {
    Vec3T<F> r;
    F scale;
    MaskOf<F> common;
};

// 2^-⌊log2 m⌋ for a positive normal m, from the IEEE-754 bits: m's biased exponent e gives the
// bits of 2^(bias − e) as ((2·bias − e) << mantissa bits).
// One float lane or four (math/lanes.h's bit operations); double, with its own 64-bit layout, has
// the overload below.
template <class F>
inline F inverse_binary_power(F m) {
    using I = IntOf<F>;
    return float_from_bits(shift_left<23>(I(254) - shift_right<23>(bits_of(m))));
}
inline double inverse_binary_power(double m) {
    return std::bit_cast<double>((std::uint64_t{2046} - (std::bit_cast<std::uint64_t>(m) >> 52))
                                 << 52);
}

template <class F>
inline PreparedLanes<F> prepare_lanes(const Vec3T<F>& r) {
    using std::abs;
    const F m = max_like_std(max_like_std(abs(r.x), abs(r.y)), abs(r.z));
    // The sum is NaN only for a NaN component (the others are finite where m is in range).
    const MaskOf<F> common = (m >= F(0x1p-100)) & (m <= F(0x1p100)) & is_not_nan(r.x + r.y + r.z);
    const F scale = inverse_binary_power(m);  // exact multiplications: ldexp's result, no libm
    return {{r.x * scale, r.y * scale, r.z * scale}, scale, common};
}

// A direction made safe to evaluate (one lane): prepare_lanes()'s r and scale in its common case;
// otherwise the exact rescaling of the input by 2^-exponent with ldexp, or a flag.
template <class T>
struct Prepared {
    Vec3T<T> r;
    int exponent = 0;       // input = 2^exponent · r
    T scale = 1;            // 2^-exponent where |exponent| ≤ 100 (finish() scales J by it)
    bool usable = true;     // false: r = 0 or NaN → the fallback direction, J = 0
    bool infinite = false;  // an infinite component: r = its signs, J = 0
};

// ⌊log2 m⌋ for a positive normal m, and 2^e for |e| ≤ 126, both from the IEEE-754 bits.
inline int binary_exponent(float m) {
    return static_cast<int>(std::bit_cast<std::uint32_t>(m) >> 23) - 127;
}
inline int binary_exponent(double m) {
    return static_cast<int>(std::bit_cast<std::uint64_t>(m) >> 52) - 1023;
}
template <class T>
T power_of_two(int e) {
    if constexpr (std::is_same_v<T, float>)
        return std::bit_cast<float>(static_cast<std::uint32_t>(e + 127) << 23);
    else
        return std::bit_cast<double>(static_cast<std::uint64_t>(e + 1023) << 52);
}

// prepare() outside its common case: NaN, infinite, zero, or beyond 2^±100. Out of line.
template <class T>
[[gnu::noinline]] Prepared<T> prepare_rare(Vec3T<T> r) {
    Prepared<T> p;
    const T m = max_abs_component(r);
    if (std::isnan(r.x) || std::isnan(r.y) || std::isnan(r.z)) {
        p.r = kEnvFallbackDirection<T>;
        p.usable = false;
        return p;
    }
    if (std::isinf(r.x) || std::isinf(r.y) || std::isinf(r.z)) {
        auto sign_if_inf = [](T c) { return std::isinf(c) ? std::copysign(T(1), c) : T(0); };
        p.r = {sign_if_inf(r.x), sign_if_inf(r.y), sign_if_inf(r.z)};
        p.infinite = true;
        return p;
    }
    if (m == 0) {
        p.r = kEnvFallbackDirection<T>;
        p.usable = false;
        return p;
    }
    p.exponent = std::ilogb(m);
    if (p.exponent >= -100 && p.exponent <= 100) p.scale = power_of_two<T>(-p.exponent);
    p.r = {std::ldexp(r.x, -p.exponent), std::ldexp(r.y, -p.exponent),
           std::ldexp(r.z, -p.exponent)};
    return p;
}

template <class T>
inline Prepared<T> prepare(Vec3T<T> r) {
    const PreparedLanes<T> common = prepare_lanes(r);
    if (!common.common) return prepare_rare(r);
    Prepared<T> p;
    p.r = common.r;
    p.scale = common.scale;
    p.exponent = -binary_exponent(common.scale);
    return p;
}

// atan2: inline and libm-free in float (math/fast_atan2.h, float rounding, one lane or four),
// std::atan2 in double.
template <class F>
F any_atan2(F y, F x) {
    if constexpr (std::is_same_v<F, double>)
        return std::atan2(y, x);
    else
        return fast_atan2(y, x);
}

template <class T>
T clamp_finite(T x) {
    constexpr T kMax = std::numeric_limits<T>::max();
    return std::clamp(x, -kMax, kMax);  // x is never NaN here
}

// J(input) = J(r)·2^-exponent, entries clamped to the finite range; 0 where J is not defined.
template <class T>
[[gnu::noinline]] Jacobian23T<T> finish_rare(const Prepared<T>& p, Jacobian23T<T> j) {
    if (!p.usable || p.infinite) return {};
    auto scale = [&](Vec3T<T> v) {
        return Vec3T<T>{clamp_finite(std::ldexp(v.x, -p.exponent)),
                        clamp_finite(std::ldexp(v.y, -p.exponent)),
                        clamp_finite(std::ldexp(v.z, -p.exponent))};
    };
    return {scale(j.ds), scale(j.dt)};
}

// J scaled by a lane's exact power of two (prepare_lanes()' scale).
template <class F>
Jacobian23T<F> scaled(const Jacobian23T<F>& j, F scale) {
    return {j.ds * scale, j.dt * scale};
}

template <class T>
inline Jacobian23T<T> finish(const Prepared<T>& p, Jacobian23T<T> j) {
    if (p.usable && !p.infinite && p.exponent >= -100 && p.exponent <= 100)
        return scaled(j, p.scale);  // exact, and J ~ 1/|r| stays finite
    return finish_rare(p, j);
}

// 1/x for x > 0, clamped to the finite range (so that 0·(1/x) stays 0, never NaN).
template <class T>
T safe_inverse(T x) {
    return clamp_finite(T(1) / x);
}

// ---- Cube: the OpenGL face table (§3.1).
struct CubeFace {
    int axis;    // a
    int s_axis;  // g_s = s_sign · e_{s_axis}
    int s_sign;
    int t_axis;  // g_t = t_sign · e_{t_axis}
    int t_sign;
};
inline constexpr CubeFace kCubeFaces[6] = {
    {0, 2, -1, 1, -1},  // +X: sc = −r_z, tc = −r_y
    {0, 2, +1, 1, -1},  // −X: sc = +r_z, tc = −r_y
    {1, 0, +1, 2, +1},  // +Y: sc = +r_x, tc = +r_z
    {1, 0, +1, 2, -1},  // −Y: sc = +r_x, tc = −r_z
    {2, 0, +1, 1, -1},  // +Z: sc = +r_x, tc = −r_y
    {2, 0, -1, 1, -1},  // −Z: sc = −r_x, tc = −r_y
};

// A face as its major axis a (one of x, y, z set) and the sign of r_a, for any lane type.
template <class F>
struct CubeAxes {
    MaskOf<F> x, y, z, negative;
};

// r's face: the axis x, unless |r_y| > |r_x|; then z if |r_z| exceeds that (ties to the earlier
// axis, as the OpenGL selection rule).
template <class F>
CubeAxes<F> cube_axes(const Vec3T<F>& r) {
    using std::abs;
    const MaskOf<F> y_over_x = abs(r.y) > abs(r.x);
    const MaskOf<F> z = abs(r.z) > select(y_over_x, abs(r.y), abs(r.x));
    const F r_a = select(z, r.z, select(y_over_x, r.y, r.x));
    using M = MaskOf<F>;
    return {M(!(y_over_x | z)), M(y_over_x & !z), z, r_a < F(0)};
}

// Face `face` (0…5) as CubeAxes, for one lane.
template <class T>
CubeAxes<T> cube_axes_of_face(int face) {
    return {face / 2 == 0, face / 2 == 1, face / 2 == 2, face % 2 == 1};
}

// Where a prepared r meets the cube, for any lane type: the face, (s, t), and J before finish()'s
// (or scaled()'s) power of two.
template <class F>
struct CubeCoordsJacobianLanes {
    IntOf<F> face;
    F s, t;
    Jacobian23T<F> j;
};

// On the faces `a` (r's own, cube_axes(r), or a face known to be r's: the polar caps' ±Y), with
// kCubeFaces' entries chosen by selects: s' = s_sign·r_{s_axis}/|r_a|, t' =
// t_sign·r_{t_axis}/|r_a|, (s, t) = ((s' + 1)/2, (t' + 1)/2), and ∂s/∂r = k(g_s − s'σ e_a), ∂t/∂r =
// k(g_t − t'σ e_a) with k = 1/(2|r_a|): g_s, g_t and e_a are distinct axes, so each row has two
// non-zero entries.
template <class F>
inline CubeCoordsJacobianLanes<F> cube_coords_and_jacobian_lanes(const Vec3T<F>& r,
                                                                 const CubeAxes<F>& a) {
    using std::abs;
    using I = IntOf<F>;
    const F one(1), minus_one(-1), zero(0);
    const F ma = abs(select(a.z, r.z, select(a.y, r.y, r.x)));  // in [1, 2) after prepare()
    // a = x: s_axis z, t_axis y; a = y: s_axis x, t_axis z; a = z: s_axis x, t_axis y.
    const F r_s = select(a.x, r.z, r.x), r_t = select(a.y, r.z, r.y);
    const F s_sign =
        select(a.x, select(a.negative, one, minus_one), select(a.z & a.negative, minus_one, one));
    const F t_sign = select(a.y & !a.negative, one, minus_one);
    const F sp = s_sign * r_s / ma, tp = t_sign * r_t / ma;
    const F sigma = select(a.negative, minus_one, one);
    const F k = one / (F(2) * ma);
    const F ds_a = k * (zero - sp * sigma), dt_a = k * (zero - tp * sigma);
    const F ds_s = k * s_sign, dt_t = k * t_sign;
    const Jacobian23T<F> j{{select(a.x, ds_a, ds_s), select(a.y, ds_a, zero),
                            select(a.x, ds_s, select(a.z, ds_a, zero))},
                           {select(a.x, dt_a, zero), select(a.y, dt_a, dt_t),
                            select(a.y, dt_t, select(a.z, dt_a, zero))}};
    const I face = select(a.z, I(4), select(a.y, I(2), I(0))) + select(a.negative, I(1), I(0));
    return {face, F(0.5) * (sp + one), F(0.5) * (tp + one), j};
}

// (face, s, t) and J at a prepared direction, on the faces `a`.
template <class T>
inline EnvCoordsJacobianT<T> cube_coords_and_jacobian_at(const Prepared<T>& p,
                                                         const CubeAxes<T>& a) {
    const CubeCoordsJacobianLanes<T> c = cube_coords_and_jacobian_lanes(p.r, a);
    return {{c.face, c.s, c.t}, finish(p, c.j)};
}

template <class T>
EnvCoordsJacobianT<T> cube_coords_and_jacobian(Vec3T<T> r_in) {
    const Prepared<T> p = prepare(r_in);
    return cube_coords_and_jacobian_at(p, cube_axes(p.r));
}

// The same on face `Face`, which must be r_in's (cube_axes()): the polar caps' ±Y.
template <int Face, class T>
EnvCoordsJacobianT<T> cube_coords_and_jacobian_on(Vec3T<T> r_in) {
    return cube_coords_and_jacobian_at(prepare(r_in), cube_axes_of_face<T>(Face));
}

// ρ = √(r_x² + r_z²) of a prepared r: no overflow, |r_i| < 2.
template <class F>
F latlong_rho(const Vec3T<F>& r) {
    using std::sqrt;
    return sqrt(r.x * r.x + r.z * r.z);
}

// (s, t) of a prepared r with its ρ, for any lane type. t = arccos(r_y/|r|)/π, accurate at the
// poles too; at a pole (ρ = 0) s is undefined, ½ by convention.
template <class F>
inline Vec2T<F> latlong_coords_at(const Vec3T<F>& r, F rho) {
    using S = ScalarOf<F>;
    const F zero(0), one(1), half(0.5);
    const F t = any_atan2(rho, r.y) / F(kPi<S>);
    const F s = half + any_atan2(r.x, -r.z) / F(2 * kPi<S>);
    const MaskOf<F> pole = rho == zero;
    return {select(pole, half, clamp_like_std(s, zero, one)),
            select(pole, t, clamp_like_std(t, zero, one))};
}

// The Jacobian at a prepared r with ρ = √(r_x² + r_z²) > 0, for any lane type, before finish()'s
// (or scaled()'s) power of two: ∂s/∂r = (−r_z, 0, r_x)/(2πρ²); ∂t/∂r = −(e_y − r_y r/|r|²)/(πρ) =
// (r_y r_x/ρ, −ρ, r_y r_z/ρ)/(π|r|²). 1/ρ is clamped to the finite range (0·(1/ρ) stays 0).
template <class F>
inline Jacobian23T<F> latlong_jacobian_lanes(const Vec3T<F>& r, F rho) {
    using S = ScalarOf<F>;
    const F cx = r.x / rho, cz = r.z / rho;
    const F inv_rho = min_like_std(F(1) / rho, F(std::numeric_limits<S>::max()));
    const F p2 = dot(r, r);  // in [1, 12]
    const F a = inv_rho / F(2 * kPi<S>), b = F(1) / (F(kPi<S>) * p2);
    return {{a * -cz, a * F(0), a * cx}, {b * (r.y * cx), b * -rho, b * (r.y * cz)}};
}

// The same at the pole: J undefined, the caller takes the isotropic fallback (§3.4).
template <class T>
inline Jacobian23T<T> latlong_jacobian_at(const Prepared<T>& p, T rho) {
    if (rho == 0) return {};
    return finish(p, latlong_jacobian_lanes(p.r, rho));
}

template <class T>
EnvCoordsJacobianT<T> latlong_coords_and_jacobian(Vec3T<T> r_in) {
    const Prepared<T> p = prepare(r_in);
    const T rho = latlong_rho(p.r);
    const Vec2T<T> st = latlong_coords_at(p.r, rho);
    return {{0, st.x, st.y}, latlong_jacobian_at(p, rho)};
}

}  // namespace footprint::env_detail
