#include "envmap/env_layout.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <type_traits>

#include "envmap/env_layout_detail.h"

namespace footprint {

using namespace env_detail;  // the inline lat-long and cube pieces (env_layout_detail.h)

namespace {

template <class T>
Vec3T<T> axis(int i, T sign) {
    return {i == 0 ? sign : T(0), i == 1 ? sign : T(0), i == 2 ? sign : T(0)};
}

bool valid_face(int face, int count) {
    return face >= 0 && face < count;
}

template <class T>
bool finite2(T s, T t) {
    return std::isfinite(s) && std::isfinite(t);
}

}  // namespace

int face_count(EnvLayout layout) {
    switch (layout) {
        case EnvLayout::cube:
            return 6;
        case EnvLayout::paraboloid:
            return 2;
        case EnvLayout::latlong:
        case EnvLayout::sphere:
            return 1;
    }
    return 1;
}

const char* env_layout_name(EnvLayout layout) {
    switch (layout) {
        case EnvLayout::cube:
            return "cube";
        case EnvLayout::latlong:
            return "latlong";
        case EnvLayout::sphere:
            return "sphere";
        case EnvLayout::paraboloid:
            return "paraboloid";
    }
    return "?";
}

std::optional<EnvLayout> parse_env_layout(std::string_view name) {
    for (EnvLayout l :
         {EnvLayout::cube, EnvLayout::latlong, EnvLayout::sphere, EnvLayout::paraboloid})
        if (name == env_layout_name(l)) return l;
    return std::nullopt;
}

// ---------------------------------------------------------------------------------------- cube

template <class T>
CubeCoordsT<T> cube_coords(Vec3T<T> r_in) {
    const Vec3T<T> r = prepare(r_in).r;
    const CubeCoordsJacobianLanes<T> c = cube_coords_and_jacobian_lanes(r, cube_axes(r));
    return {c.face, c.s, c.t};
}

template <class T>
Jacobian23T<T> cube_jacobian(Vec3T<T> r_in) {
    return cube_coords_and_jacobian(r_in).jacobian;
}

template <class T>
Vec3T<T> cube_direction(int face, T s, T t) {
    if (!valid_face(face, 6) || !finite2(s, t)) return kEnvFallbackDirection<T>;
    const CubeFace& f = kCubeFaces[face];
    const T sigma = face % 2 == 0 ? T(1) : T(-1);
    const Vec3T<T> gs = axis(f.s_axis, T(f.s_sign)), gt = axis(f.t_axis, T(f.t_sign));
    const Vec3T<T> r = axis(f.axis, sigma) + (2 * s - 1) * gs + (2 * t - 1) * gt;
    if (is_finite(r)) return r;
    // 2s − 1 overflowed: the same direction at half the scale (s − ½ is finite for finite s).
    return axis(f.axis, sigma / 2) + (s - T(0.5)) * gs + (t - T(0.5)) * gt;
}

template <class T>
CubeCoordsT<T> cube_reproject(int face, T s, T t) {
    return cube_coords(cube_direction(face, s, t));
}

// ------------------------------------------------------------------------------------ lat-long

template <class T>
Vec2T<T> latlong_coords(Vec3T<T> r_in) {
    const Vec3T<T> r = prepare(r_in).r;
    return latlong_coords_at(r, latlong_rho(r));
}

template <class T>
Jacobian23T<T> latlong_jacobian(Vec3T<T> r_in) {
    const Prepared<T> p = prepare(r_in);
    return latlong_jacobian_at(p, latlong_rho(p.r));
}

template <class T>
Vec3T<T> latlong_direction(T s, T t) {
    if (!finite2(s, t)) return kEnvFallbackDirection<T>;
    // Reduce before multiplying by π so that huge s, t stay accurate and finite.
    const T phi = 2 * kPi<T> * std::remainder(s - T(0.5), T(1));
    const T theta = kPi<T> * std::remainder(t, T(2));
    const T st = std::sin(theta);
    return {st * std::sin(phi), std::cos(theta), -st * std::cos(phi)};
}

// -------------------------------------------------------------------------------------- sphere

namespace {

// The stable pieces of the sphere map at a prepared r: m, (a, b) = (r_x, r_y)/m, c = w/m.
template <class T>
struct SphereParts {
    T p, m, a, b, c;
};

template <class T>
SphereParts<T> sphere_parts(Vec3T<T> r) {
    SphereParts<T> q;
    q.p = length(r);
    const T h = std::hypot(r.x, r.y);
    if (r.z >= 0) {
        const T w = r.z + q.p;
        q.m = std::sqrt(2 * q.p * w);
        q.c = std::sqrt(w / (2 * q.p));
    } else {
        // w = r_z + p = h²/(p − r_z) without cancellation; m = √(2pw) = h·√(2p/(p − r_z)).
        q.m = h * std::sqrt(2 * q.p / (q.p - r.z));
        q.c = h / std::sqrt(2 * q.p * (q.p - r.z));
    }
    if (q.m == 0) {  // rim: r̂ = −e_z
        q.a = 1, q.b = 0;
        return q;
    }
    q.a = std::clamp(r.x / q.m, T(-1), T(1));
    q.b = std::clamp(r.y / q.m, T(-1), T(1));
    return q;
}

}  // namespace

template <class T>
Vec2T<T> sphere_coords(Vec3T<T> r_in) {
    const SphereParts<T> q = sphere_parts(prepare(r_in).r);
    return {T(0.5) * (q.a + 1), T(0.5) * (1 - q.b)};  // t = 0 the top row: +Y up in the image
}

template <class T>
Jacobian23T<T> sphere_jacobian(Vec3T<T> r_in) {
    const Prepared<T> p = prepare(r_in);
    const Vec3T<T> r = p.r;
    const SphereParts<T> q = sphere_parts(r);
    if (q.m == 0) return {};  // rim: singular (§3.2)
    // ∇m = (r_x e_x + r_y e_y + w(e_z + r/p))/m = (a, b, c) + c r/p;
    // ∂s/∂r = ½(e_x − a ∇m)/m, ∂t/∂r = −½(e_y − b ∇m)/m (t = ½(1 − b): the image's rows).
    const Vec3T<T> grad_m = Vec3T<T>{q.a, q.b, q.c} + (q.c / q.p) * r;
    const T k = T(0.5) * safe_inverse(q.m);
    return finish(
        p, {k * (Vec3T<T>{1, 0, 0} - q.a * grad_m), -k * (Vec3T<T>{0, 1, 0} - q.b * grad_m)});
}

template <class T>
Vec3T<T> sphere_direction(T s, T t) {
    if (!finite2(s, t)) return kEnvFallbackDirection<T>;
    T a = 2 * s - 1, b = 1 - 2 * t;
    T rho = std::hypot(a, b);
    if (!(rho < 2)) return {0, 0, -1};  // also catches an overflowed 2s − 1
    if (rho > 1) {                      // fold back through the rim: ρ → 2 − ρ, azimuth + π
        const T k = -(2 - rho) / rho;
        a *= k, b *= k;
        rho = 2 - rho;
    }
    const T nz = std::sqrt(std::max(T(0), (1 - rho) * (1 + rho)));
    return {2 * a * nz, 2 * b * nz, 1 - 2 * rho * rho};
}

// ---------------------------------------------------------------------------------- paraboloid

template <class T>
EnvCoordsT<T> paraboloid_coords(Vec3T<T> r_in) {
    const Vec3T<T> r = prepare(r_in).r;
    const int face = r.z >= 0 ? 0 : 1;
    const T delta = length(r) + std::abs(r.z);  // |r| ± r_z, no cancellation; ≥ 1
    return {face, T(0.5) * (r.x / delta + 1), T(0.5) * (1 - r.y / delta)};  // +Y up in the image
}

template <class T>
Jacobian23T<T> paraboloid_jacobian(Vec3T<T> r_in) {
    const Prepared<T> p = prepare(r_in);
    const Vec3T<T> r = p.r;
    const T pr = length(r), sign = r.z >= 0 ? T(1) : T(-1);
    const T delta = pr + std::abs(r.z);
    const T x = r.x / delta, y = r.y / delta;
    // ∂x/∂r = (e_x − x (r/|r| ± e_z))/δ; ∂s = ½ ∂x, ∂t = −½ ∂y (t = ½(1 − y): the image's rows).
    const Vec3T<T> g = (1 / pr) * r + Vec3T<T>{0, 0, sign};
    const T k = 1 / (2 * delta);
    return finish(p, {k * (Vec3T<T>{1, 0, 0} - x * g), -k * (Vec3T<T>{0, 1, 0} - y * g)});
}

template <class T>
Vec3T<T> paraboloid_direction(int face, T s, T t) {
    if (!valid_face(face, 2) || !finite2(s, t)) return kEnvFallbackDirection<T>;
    const T x = 2 * s - 1, y = 1 - 2 * t, sign = face == 0 ? T(1) : T(-1);
    const T k = x * x + y * y;
    if (!std::isfinite(k)) return {0, 0, -sign};  // infinitely far out: the other pole
    const T inv = 1 / (1 + k);
    return {2 * x * inv, 2 * y * inv, sign * (1 - k) * inv};
}

// ---------------------------------------------------------------------------------- any layout

template <class T>
EnvCoordsT<T> env_coords(EnvLayout layout, Vec3T<T> r) {
    switch (layout) {
        case EnvLayout::cube:
            return cube_coords(r);
        case EnvLayout::paraboloid:
            return paraboloid_coords(r);
        case EnvLayout::latlong: {
            const Vec2T<T> st = latlong_coords(r);
            return {0, st.x, st.y};
        }
        case EnvLayout::sphere: {
            const Vec2T<T> st = sphere_coords(r);
            return {0, st.x, st.y};
        }
    }
    return {};
}

template <class T>
Jacobian23T<T> env_jacobian(EnvLayout layout, Vec3T<T> r) {
    switch (layout) {
        case EnvLayout::cube:
            return cube_jacobian(r);
        case EnvLayout::paraboloid:
            return paraboloid_jacobian(r);
        case EnvLayout::latlong:
            return latlong_jacobian(r);
        case EnvLayout::sphere:
            return sphere_jacobian(r);
    }
    return {};
}

template <class T>
EnvCoordsJacobianT<T> env_coords_and_jacobian(EnvLayout layout, Vec3T<T> r) {
    switch (layout) {
        case EnvLayout::cube:
            return cube_coords_and_jacobian(r);
        case EnvLayout::latlong:
            return latlong_coords_and_jacobian(r);
        case EnvLayout::paraboloid:
        case EnvLayout::sphere:
            break;
    }
    return {env_coords(layout, r), env_jacobian(layout, r)};
}

template <class T>
Vec3T<T> env_direction(EnvLayout layout, int face, T s, T t) {
    switch (layout) {
        case EnvLayout::cube:
            return cube_direction(face, s, t);
        case EnvLayout::paraboloid:
            return paraboloid_direction(face, s, t);
        case EnvLayout::latlong:
            return latlong_direction(s, t);
        case EnvLayout::sphere:
            return sphere_direction(s, t);
    }
    return kEnvFallbackDirection<T>;
}

#define FOOTPRINT_ENV_LAYOUT_INSTANTIATE(T)                                      \
    template CubeCoordsT<T> cube_coords(Vec3T<T>);                               \
    template Jacobian23T<T> cube_jacobian(Vec3T<T>);                             \
    template Vec3T<T> cube_direction(int, T, T);                                 \
    template CubeCoordsT<T> cube_reproject(int, T, T);                           \
    template Vec2T<T> latlong_coords(Vec3T<T>);                                  \
    template Jacobian23T<T> latlong_jacobian(Vec3T<T>);                          \
    template Vec3T<T> latlong_direction(T, T);                                   \
    template Vec2T<T> sphere_coords(Vec3T<T>);                                   \
    template Jacobian23T<T> sphere_jacobian(Vec3T<T>);                           \
    template Vec3T<T> sphere_direction(T, T);                                    \
    template EnvCoordsT<T> paraboloid_coords(Vec3T<T>);                          \
    template Jacobian23T<T> paraboloid_jacobian(Vec3T<T>);                       \
    template Vec3T<T> paraboloid_direction(int, T, T);                           \
    template EnvCoordsT<T> env_coords(EnvLayout, Vec3T<T>);                      \
    template Jacobian23T<T> env_jacobian(EnvLayout, Vec3T<T>);                   \
    template EnvCoordsJacobianT<T> env_coords_and_jacobian(EnvLayout, Vec3T<T>); \
    template Vec3T<T> env_direction(EnvLayout, int, T, T);

FOOTPRINT_ENV_LAYOUT_INSTANTIATE(float)
FOOTPRINT_ENV_LAYOUT_INSTANTIATE(double)

#undef FOOTPRINT_ENV_LAYOUT_INSTANTIATE

EnvTexel env_texel_of_direction(EnvLayout layout, int face, int x, int y, int w, int h) {
    const float width = static_cast<float>(w), height = static_cast<float>(h);
    const EnvCoords c =
        env_coords(layout, env_direction(layout, face, (static_cast<float>(x) + 0.5f) / width,
                                         (static_cast<float>(y) + 0.5f) / height));
    return {c.face, std::clamp(static_cast<int>(c.s * width), 0, w - 1),
            std::clamp(static_cast<int>(c.t * height), 0, h - 1)};
}

}  // namespace footprint
