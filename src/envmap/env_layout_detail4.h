// envmap/env_layout_detail4.h — (private to envmap) env_layout_detail.h's cube mapping for four
// directions at once (math/float4.h): the batch's footprints (env_footprint.h, polar_caps.h) are
// computed four lookups at a time, structure of arrays. Each piece does, lane by lane, exactly the
// operations of its scalar namesake in the same order, so that every lane's result is the scalar
// one bit for bit; the face table's entries are chosen by selects.
#pragma once

#include "envmap/env_layout_detail.h"
#include "math/float4.h"
#include "math/mat3.h"

namespace footprint::env_detail {

// A Vec3 of each of four lanes.
struct Vec3x4 {
    Float4 x, y, z;
};

// The Vec3 `member` of items[0..3].
template <class T>
Vec3x4 gather(const T* items, Vec3 T::*member) {
    const Vec3 &a = items[0].*member, &b = items[1].*member, &c = items[2].*member,
               &d = items[3].*member;
    return {{a.x, b.x, c.x, d.x}, {a.y, b.y, c.y, d.y}, {a.z, b.z, c.z, d.z}};
}

// is_finite(Vec3) of each lane.
inline Mask4 is_finite(const Vec3x4& v) {
    return is_finite(v.x) & is_finite(v.y) & is_finite(v.z);
}

inline Float4 dot(const Vec3x4& a, const Vec3x4& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

// A v (Mat3::operator*'s order of operations), or v where A is the identity.
inline Vec3x4 rotate(const IdentitySkippingRotation& to_map, const Vec3x4& v) {
    if (to_map.is_identity()) return v;
    const auto& m = to_map.matrix().m;
    auto row = [&](int i) {
        return Float4(m[i][0]) * v.x + Float4(m[i][1]) * v.y + Float4(m[i][2]) * v.z;
    };
    return {row(0), row(1), row(2)};
}

// prepare()'s common case: `common` where max |component| lies within 2^±100 and no component is
// NaN (elsewhere the lane is the scalar code's to handle); there r = 2^exponent·p, scale =
// 2^-exponent.
struct Prepared4 {
    Vec3x4 p;
    Float4 scale;
    Mask4 common;
};
inline Prepared4 prepare4(const Vec3x4& r) {
    const Float4 big = max_like_std(max_like_std(abs(r.x), abs(r.y)), abs(r.z));
    const Mask4 common =
        (big >= Float4(0x1p-100f)) & (big <= Float4(0x1p100f)) & is_not_nan(r.x + r.y + r.z);
    // exponent = (bits >> 23) − 127, so 2^-exponent has the bits (254 − (bits >> 23)) << 23.
    const Float4 scale = float_from_bits(shift_left<23>(Int4(254) - shift_right<23>(bits_of(big))));
    return {{r.x * scale, r.y * scale, r.z * scale}, scale, common};
}

// A cube face as its major axis a (one of the three masks set per lane) and the sign of r_a.
struct CubeAxes4 {
    Mask4 x, y, z, negative;
};
// cube_face_of(): x, unless |y| > |x|; then z if |z| exceeds that.
inline CubeAxes4 cube_axes4(const Vec3x4& p) {
    const Mask4 y_over_x = abs(p.y) > abs(p.x);
    const Mask4 z = abs(p.z) > select(y_over_x, abs(p.y), abs(p.x));
    const Float4 c_axis = select(z, p.z, select(y_over_x, p.y, p.x));
    return {!(y_over_x | z), y_over_x & !z, z, c_axis < Float4(0.0f)};
}

struct CubeCoordsJacobian4 {
    Int4 face;
    Float4 s, t;
    Vec3x4 ds, dt;  // J, finished (the input's scale)
};
// cube_coords_and_jacobian_at(prepare(r), CubePoint(p, face)) on the faces `axes` (r's own, or
// the polar caps' ±Y), for the lanes where prepared.common.
inline CubeCoordsJacobian4 cube_coords_and_jacobian4(const Prepared4& prepared,
                                                     const CubeAxes4& axes) {
    const Vec3x4& p = prepared.p;
    const Float4 one(1.0f), minus_one(-1.0f), zero(0.0f);
    const Mask4 x_axis = axes.x, y_axis = axes.y, z_axis = axes.z, negative = axes.negative;
    // CubePoint: ma = |c[a]|, s' = s_sign·c[s_axis]/ma, t' = t_sign·c[t_axis]/ma (kCubeFaces).
    const Float4 ma = abs(select(z_axis, p.z, select(y_axis, p.y, p.x)));
    const Float4 c_s = select(x_axis, p.z, p.x), c_t = select(y_axis, p.z, p.y);
    const Float4 s_sign =
        select(x_axis, select(negative, one, minus_one), select(z_axis & negative, minus_one, one));
    const Float4 t_sign = select(y_axis & !negative, one, minus_one);
    const Float4 sp = s_sign * c_s / ma, tp = t_sign * c_t / ma;
    // ∂s/∂r = k(g_s − s'σ e_a), ∂t/∂r = k(g_t − t'σ e_a), k = 1/(2|ma|); then finish()'s exact
    // 2^-exponent.
    const Float4 sigma = select(negative, minus_one, one);
    const Float4 k = one / (Float4(2.0f) * ma);
    const Float4 ds_a = k * (zero - sp * sigma), dt_a = k * (zero - tp * sigma);
    const Float4 ds_s = k * s_sign, dt_t = k * t_sign;
    const Float4 scale = prepared.scale;
    // a = x: s_axis z, t_axis y; a = y: s_axis x, t_axis z; a = z: s_axis x, t_axis y.
    const Vec3x4 ds{select(x_axis, ds_a, ds_s) * scale, select(y_axis, ds_a, zero) * scale,
                    select(x_axis, ds_s, select(z_axis, ds_a, zero)) * scale};
    const Vec3x4 dt{select(x_axis, dt_a, zero) * scale, select(y_axis, dt_a, dt_t) * scale,
                    select(y_axis, dt_t, select(z_axis, dt_a, zero)) * scale};
    const Int4 face = shift_left<1>(select(z_axis, Int4(2), select(y_axis, Int4(1), Int4(0)))) +
                      select(negative, Int4(1), Int4(0));
    return {face, Float4(0.5f) * (sp + one), Float4(0.5f) * (tp + one), ds, dt};
}

// K = D Dᵀ (footprint_matrix()) of D's columns, and whether it is finite (plain_env_footprint()'s
// test: the sum of its entries).
struct Sym2x4 {
    Float4 xx, xy, yy;
    Mask4 finite() const { return is_finite(xx + xy + yy); }
};
inline Sym2x4 footprint_matrix4(Float4 dxs, Float4 dxt, Float4 dys, Float4 dyt) {
    return {dxs * dxs + dys * dys, dxs * dxt + dys * dyt, dxt * dxt + dyt * dyt};
}

}  // namespace footprint::env_detail
