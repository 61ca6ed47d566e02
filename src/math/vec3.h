// math/vec3.h — a small 3-vector for surface geometry: normals, tangents, local frames (bump/).
// Plain aggregate with component-wise operators, in the style of math/vec.h; float for per-pixel
// work, double (Vec3d) for references in tests.
//
// length() and normalize() are safe for any input: they never overflow or underflow for finite
// vectors (they rescale by the largest component), and normalize() returns the zero vector for a
// zero or non-finite input instead of NaN — callers test for it and take their documented fallback.
#pragma once

#include <algorithm>
#include <cmath>

namespace footprint {

template <class T>
struct Vec3T {
    T x = 0, y = 0, z = 0;
};
using Vec3 = Vec3T<float>;
using Vec3d = Vec3T<double>;

template <class T>
constexpr Vec3T<T> operator+(Vec3T<T> a, Vec3T<T> b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
constexpr Vec3T<T> operator-(Vec3T<T> a, Vec3T<T> b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
constexpr Vec3T<T> operator-(Vec3T<T> a) {
    return {-a.x, -a.y, -a.z};
}
template <class T>
constexpr Vec3T<T> operator*(T s, Vec3T<T> a) {
    return {s * a.x, s * a.y, s * a.z};
}
template <class T>
constexpr Vec3T<T> operator*(Vec3T<T> a, T s) {
    return {s * a.x, s * a.y, s * a.z};
}
template <class T>
constexpr Vec3T<T> operator/(Vec3T<T> a, T s) {
    return {a.x / s, a.y / s, a.z / s};
}
template <class T>
constexpr T dot(Vec3T<T> a, Vec3T<T> b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
// Right-handed: cross({1,0,0}, {0,1,0}) = {0,0,1}.
template <class T>
constexpr Vec3T<T> cross(Vec3T<T> a, Vec3T<T> b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
inline bool is_finite(Vec3T<T> a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
// max(|a.x|, |a.y|, |a.z|) for finite a (a NaN component may be skipped: test is_finite first).
template <class T>
inline T max_abs_component(Vec3T<T> a) {
    return std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)});
}
// |a|, without overflow or underflow for finite a. A NaN component gives NaN, otherwise an infinite
// one gives +Inf.
template <class T>
inline T length(Vec3T<T> a) {
    if (!is_finite(a)) return std::abs(a.x) + std::abs(a.y) + std::abs(a.z);  // NaN or +Inf
    const T scale = max_abs_component(a);
    if (scale == 0) return 0;
    const Vec3T<T> b = a / scale;
    return scale * std::sqrt(dot(b, b));
}
// a/|a|; the zero vector for a zero or non-finite a (never NaN).
template <class T>
inline Vec3T<T> normalize(Vec3T<T> a) {
    if (!is_finite(a)) return {};
    const T scale = max_abs_component(a);
    if (scale == 0) return {};
    const Vec3T<T> b = a / scale;
    return b / std::sqrt(dot(b, b));
}
// A right-handed unit tangent basis (u, v) at the unit vector n (u × v = n): u ⟂ n built from the
// x axis, or the y axis where n is within 53° of ±x (|n_x| ≥ 0.6), so u never degenerates.
template <class T>
inline void tangent_basis(Vec3T<T> n, Vec3T<T>& u, Vec3T<T>& v) {
    u = normalize(cross(n, std::abs(n.x) < T(0.6) ? Vec3T<T>{1, 0, 0} : Vec3T<T>{0, 1, 0}));
    v = cross(n, u);
}
template <class To, class From>
constexpr Vec3T<To> vec3_cast(Vec3T<From> a) {
    return {static_cast<To>(a.x), static_cast<To>(a.y), static_cast<To>(a.z)};
}

}  // namespace footprint
