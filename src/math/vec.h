// math/vec.h — the small fixed-size vectors the filters and the geometry use.
// Plain aggregates with component-wise operators; float for texel-space work, double where a
// caller needs it (reference integrals) through the template.
#pragma once

#include <cmath>

namespace footprint {

template <class T>
struct Vec2T {
    T x = 0, y = 0;
};
using Vec2 = Vec2T<float>;
using Vec2d = Vec2T<double>;

template <class T>
constexpr Vec2T<T> operator+(Vec2T<T> a, Vec2T<T> b) {
    return {a.x + b.x, a.y + b.y};
}
template <class T>
constexpr Vec2T<T> operator-(Vec2T<T> a, Vec2T<T> b) {
    return {a.x - b.x, a.y - b.y};
}
template <class T>
constexpr Vec2T<T> operator-(Vec2T<T> a) {
    return {-a.x, -a.y};
}
template <class T>
constexpr Vec2T<T> operator*(T s, Vec2T<T> a) {
    return {s * a.x, s * a.y};
}
template <class T>
constexpr Vec2T<T> operator*(Vec2T<T> a, T s) {
    return {s * a.x, s * a.y};
}
template <class T>
constexpr Vec2T<T> operator/(Vec2T<T> a, T s) {
    return {a.x / s, a.y / s};
}
template <class T>
constexpr T dot(Vec2T<T> a, Vec2T<T> b) {
    return a.x * b.x + a.y * b.y;
}
template <class T>
inline T length(Vec2T<T> a) {
    return std::hypot(a.x, a.y);
}
template <class T>
inline bool is_finite(Vec2T<T> a) {
    return std::isfinite(a.x) && std::isfinite(a.y);
}

}  // namespace footprint
