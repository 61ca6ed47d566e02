#include "envmap/env_layout.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <type_traits>

#include "math/fast_atan2.h"

namespace footprint {

namespace {

template <class T>
constexpr T kPi = T(3.14159265358979323846);

template <class T>
Vec3T<T> axis(int i, T sign) {
    return {i == 0 ? sign : T(0), i == 1 ? sign : T(0), i == 2 ? sign : T(0)};
}

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

template <class T>
Prepared<T> prepare(Vec3T<T> r) {
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
Jacobian23T<T> finish(const Prepared<T>& p, Jacobian23T<T> j) {
    if (!p.usable || p.infinite) return {};
    if (p.exponent >= -100 && p.exponent <= 100) {  // exact, and J ~ 1/|r| stays finite
        const T scale = power_of_two<T>(-p.exponent);
        return {j.ds * scale, j.dt * scale};
    }
    auto scale = [&](Vec3T<T> v) {
        return Vec3T<T>{clamp_finite(std::ldexp(v.x, -p.exponent)),
                        clamp_finite(std::ldexp(v.y, -p.exponent)),
                        clamp_finite(std::ldexp(v.z, -p.exponent))};
    };
    return {scale(j.ds), scale(j.dt)};
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
constexpr CubeFace kCubeFaces[6] = {
    {0, 2, -1, 1, -1},  // +X: sc = −r_z, tc = −r_y
    {0, 2, +1, 1, -1},  // −X: sc = +r_z, tc = −r_y
    {1, 0, +1, 2, +1},  // +Y: sc = +r_x, tc = +r_z
    {1, 0, +1, 2, -1},  // −Y: sc = +r_x, tc = −r_z
    {2, 0, +1, 1, -1},  // +Z: sc = +r_x, tc = −r_y
    {2, 0, -1, 1, -1},  // −Z: sc = −r_x, tc = −r_y
};

template <class T>
int cube_face_of(Vec3T<T> r) {
    const T c[3] = {r.x, r.y, r.z};
    int a = 0;
    if (std::abs(r.y) > std::abs(r.x)) a = 1;
    if (std::abs(r.z) > std::abs(c[a])) a = 2;
    return 2 * a + (c[a] < 0 ? 1 : 0);
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

// Where a prepared r meets the cube: its face, |ma| and s' = sc/|ma|, t' = tc/|ma| (§3.1).
template <class T>
struct CubePoint {
    int face;
    T ma, sp, tp;

    explicit CubePoint(Vec3T<T> r) : face(cube_face_of(r)) {
        const CubeFace& f = kCubeFaces[face];
        const T c[3] = {r.x, r.y, r.z};  // indexed: cheaper than selecting component by component
        ma = std::abs(c[f.axis]);        // in [1, 2) after prepare()
        sp = T(f.s_sign) * c[f.s_axis] / ma;
        tp = T(f.t_sign) * c[f.t_axis] / ma;
    }
    CubeCoordsT<T> coords() const { return {face, T(0.5) * (sp + 1), T(0.5) * (tp + 1)}; }
};

template <class T>
CubeCoordsT<T> cube_coords(Vec3T<T> r_in) {
    return CubePoint<T>(prepare(r_in).r).coords();
}

template <class T>
EnvCoordsJacobianT<T> cube_coords_and_jacobian(Vec3T<T> r_in) {
    const Prepared<T> p = prepare(r_in);
    const CubePoint<T> q(p.r);
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

// ρ = √(r_x² + r_z²) of a prepared r: no overflow, |r_i| < 2.
template <class T>
T latlong_rho(Vec3T<T> r) {
    return std::sqrt(r.x * r.x + r.z * r.z);
}

// (s, t) of a prepared r with its ρ.
template <class T>
Vec2T<T> latlong_coords_at(Vec3T<T> r, T rho) {
    const T t = any_atan2(rho, r.y) / kPi<T>;  // = arccos(r_y/|r|)/π, accurate at the poles too
    if (rho == 0) return {T(0.5), t};          // pole: s undefined, ½ by convention
    const T s = T(0.5) + any_atan2(r.x, -r.z) / (2 * kPi<T>);
    return {std::clamp(s, T(0), T(1)), std::clamp(t, T(0), T(1))};
}

template <class T>
Vec2T<T> latlong_coords(Vec3T<T> r_in) {
    const Vec3T<T> r = prepare(r_in).r;
    return latlong_coords_at(r, latlong_rho(r));
}

// The Jacobian at a prepared r with ρ = √(r_x² + r_z²).
template <class T>
Jacobian23T<T> latlong_jacobian_at(const Prepared<T>& p, T rho) {
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
Jacobian23T<T> latlong_jacobian(Vec3T<T> r_in) {
    const Prepared<T> p = prepare(r_in);
    return latlong_jacobian_at(p, latlong_rho(p.r));
}

template <class T>
EnvCoordsJacobianT<T> latlong_coords_and_jacobian(Vec3T<T> r_in) {
    const Prepared<T> p = prepare(r_in);
    const T rho = latlong_rho(p.r);
    const Vec2T<T> st = latlong_coords_at(p.r, rho);
    return {{0, st.x, st.y}, latlong_jacobian_at(p, rho)};
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

}  // namespace footprint
