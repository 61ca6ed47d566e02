// envmap/env_layout_detail.h — (private to envmap) the inline pieces of the lat-long and cube
// mappings of env_layout.h: a direction prepared for evaluation (an exact power-of-two rescaling),
// the cube's face table, and (s, t) with the Jacobian for both layouts. env_layout.cpp builds its
// public functions from them; the common case of a form (a) footprint (env_footprint.h) inlines
// them, so that its results are the public functions' bit for bit.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "envmap/env_layout.h"
#include "math/fast_atan2.h"

namespace footprint::env_detail {

template <class T>
inline constexpr T kPi = T(3.14159265358979323846);

// A direction made safe to evaluate: `r` has its largest |component| in [1, 2) (an exact
// power-of-two rescaling of the input by 2^-exponent), so nothing below under- or overflows.
template <class T>
struct Prepared {
    Vec3T<T> r;
    int exponent = 0;       // input = 2^exponent · r
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
    p.r = {std::ldexp(r.x, -p.exponent), std::ldexp(r.y, -p.exponent),
           std::ldexp(r.z, -p.exponent)};
    return p;
}

template <class T>
[[gnu::always_inline]] inline Prepared<T> prepare(Vec3T<T> r) {
    Prepared<T> p;
    const T m = max_abs_component(r);
    if (m >= T(0x1p-100) && m <= T(0x1p100) && !std::isnan(r.x + r.y + r.z)) {
        // The common case (finite and in range: the sum is NaN only for a NaN component), without
        // libm: the exponent from the bits, and an exact multiplication by the power of two (the
        // same result as ldexp, a fraction of the cost).
        p.exponent = binary_exponent(m);
        const T scale = power_of_two<T>(-p.exponent);
        p.r = {r.x * scale, r.y * scale, r.z * scale};
        return p;
    }
    return prepare_rare(r);
}

// atan2: inline and libm-free in float (math/fast_atan2.h, float rounding), std::atan2 in double.
template <class T>
T any_atan2(T y, T x) {
    if constexpr (std::is_same_v<T, float>)
        return fast_atan2(y, x);
    else
        return std::atan2(y, x);
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

template <class T>
[[gnu::always_inline]] inline Jacobian23T<T> finish(const Prepared<T>& p, Jacobian23T<T> j) {
    if (p.usable && !p.infinite && p.exponent >= -100 && p.exponent <= 100) {
        // exact, and J ~ 1/|r| stays finite
        const T scale = power_of_two<T>(-p.exponent);
        return {j.ds * scale, j.dt * scale};
    }
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

template <class T>
inline int cube_face_of(Vec3T<T> r) {
    const T c[3] = {r.x, r.y, r.z};
    int a = 0;
    if (std::abs(r.y) > std::abs(r.x)) a = 1;
    if (std::abs(r.z) > std::abs(c[a])) a = 2;
    return 2 * a + (c[a] < 0 ? 1 : 0);
}

// Where a prepared r meets the cube: its face, |ma| and s' = sc/|ma|, t' = tc/|ma| (§3.1).
template <class T>
struct CubePoint {
    int face;
    T ma, sp, tp;

    explicit CubePoint(Vec3T<T> r) : CubePoint(r, cube_face_of(r)) {}
    // On a face known to be r's (cube_face_of(r)): a constant face folds the table away.
    [[gnu::always_inline]] CubePoint(Vec3T<T> r, int face_of_r) : face(face_of_r) {
        const CubeFace& f = kCubeFaces[face];
        const T c[3] = {r.x, r.y, r.z};  // indexed: cheaper than selecting component by component
        ma = std::abs(c[f.axis]);        // in [1, 2) after prepare()
        sp = T(f.s_sign) * c[f.s_axis] / ma;
        tp = T(f.t_sign) * c[f.t_axis] / ma;
    }
    CubeCoordsT<T> coords() const { return {face, T(0.5) * (sp + 1), T(0.5) * (tp + 1)}; }
};

// (face, s, t) and J at a prepared direction.
template <class T>
[[gnu::always_inline]] inline EnvCoordsJacobianT<T> cube_coords_and_jacobian_at(
    const Prepared<T>& p, const CubePoint<T>& q) {
    const CubeFace& f = kCubeFaces[q.face];
    const T sigma = q.face % 2 == 0 ? T(1) : T(-1);
    // ∂s/∂r = k(g_s − s'σ e_a), ∂t/∂r = k(g_t − t'σ e_a), k = 1/(2|ma|): g_s, g_t and e_a are
    // distinct axes, so each row has two non-zero entries.
    const T k = 1 / (2 * q.ma);
    T ds[3] = {}, dt[3] = {};
    ds[f.s_axis] = k * T(f.s_sign);
    ds[f.axis] = k * (T(0) - q.sp * sigma);
    dt[f.t_axis] = k * T(f.t_sign);
    dt[f.axis] = k * (T(0) - q.tp * sigma);
    return {q.coords(), finish(p, {{ds[0], ds[1], ds[2]}, {dt[0], dt[1], dt[2]}})};
}

template <class T>
[[gnu::always_inline]] inline EnvCoordsJacobianT<T> cube_coords_and_jacobian_at(
    const Prepared<T>& p) {
    return cube_coords_and_jacobian_at(p, CubePoint<T>(p.r));
}

template <class T>
EnvCoordsJacobianT<T> cube_coords_and_jacobian(Vec3T<T> r_in) {
    return cube_coords_and_jacobian_at(prepare(r_in));
}

// The same on face `Face`, which must be r_in's (cube_face_of()): the polar caps' ±Y.
template <int Face, class T>
EnvCoordsJacobianT<T> cube_coords_and_jacobian_on(Vec3T<T> r_in) {
    const Prepared<T> p = prepare(r_in);
    return cube_coords_and_jacobian_at(p, CubePoint<T>(p.r, Face));
}

// ρ = √(r_x² + r_z²) of a prepared r: no overflow, |r_i| < 2.
template <class T>
T latlong_rho(Vec3T<T> r) {
    return std::sqrt(r.x * r.x + r.z * r.z);
}

// (s, t) of a prepared r with its ρ.
template <class T>
[[gnu::always_inline]] inline Vec2T<T> latlong_coords_at(Vec3T<T> r, T rho) {
    const T t = any_atan2(rho, r.y) / kPi<T>;  // = arccos(r_y/|r|)/π, accurate at the poles too
    if (rho == 0) return {T(0.5), t};          // pole: s undefined, ½ by convention
    const T s = T(0.5) + any_atan2(r.x, -r.z) / (2 * kPi<T>);
    return {std::clamp(s, T(0), T(1)), std::clamp(t, T(0), T(1))};
}

// The Jacobian at a prepared r with ρ = √(r_x² + r_z²).
template <class T>
[[gnu::always_inline]] inline Jacobian23T<T> latlong_jacobian_at(const Prepared<T>& p, T rho) {
    const Vec3T<T> r = p.r;
    if (rho == 0) return {};  // pole: J undefined, the caller takes the isotropic fallback (§3.4)
    const T cx = r.x / rho, cz = r.z / rho, inv_rho = safe_inverse(rho);
    const T p2 = dot(r, r);  // in [1, 12]
    // ∂s/∂r = (−r_z, 0, r_x)/(2πρ²); ∂t/∂r = −(e_y − r_y r/|r|²)/(πρ) = (r_y r_x/ρ, −ρ, r_y
    // r_z/ρ)/(π|r|²).
    const Vec3T<T> ds = (inv_rho / (2 * kPi<T>)) * Vec3T<T>{-cz, 0, cx};
    const Vec3T<T> dt = (1 / (kPi<T> * p2)) * Vec3T<T>{r.y * cx, -rho, r.y * cz};
    return finish(p, {ds, dt});
}

template <class T>
EnvCoordsJacobianT<T> latlong_coords_and_jacobian(Vec3T<T> r_in) {
    const Prepared<T> p = prepare(r_in);
    const T rho = latlong_rho(p.r);
    const Vec2T<T> st = latlong_coords_at(p.r, rho);
    return {{0, st.x, st.y}, latlong_jacobian_at(p, rho)};
}

}  // namespace footprint::env_detail
