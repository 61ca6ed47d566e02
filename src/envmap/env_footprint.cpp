#include "envmap/env_footprint.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "envmap/env_layout_detail.h"
#include "math/float4.h"

namespace footprint {

namespace {

float norm(Vec3 a) {
    return std::sqrt(dot(a, a));
}

// G = S · J_P(A r) · A (spec §2.3): map motion in level-0 texels per unit change of r. Takes the
// change already in map space (A x), which the footprint keeps anyway (EnvFootprint::map_dr_dx …).
struct MapJacobian {
    Vec2 texel_scale;
    Jacobian23 j;

    Vec2 operator()(Vec3 ax) const {
        return {texel_scale.x * dot(j.ds, ax), texel_scale.y * dot(j.dt, ax)};
    }
};

// The largest singular value of the 3×2 matrix [a b] with both columns projected onto the plane
// ⟂ r̂ (the angular size of a spread of directions around r, times |r|).
float largest_tangent_singular_value(Vec3 r, Vec3 a, Vec3 b) {
    const Vec3 r_hat = r / norm(r);
    a = a - dot(a, r_hat) * r_hat;
    b = b - dot(b, r_hat) * r_hat;
    return make_footprint_ellipse(Sym2{dot(a, a), dot(a, b), dot(b, b)}).major_radius;
}

// Where the footprint is one isotropic probe of T_p = (texels per radian)·θ_fp instead of the
// ellipse of J_P: where J_P is undefined — the lat-long poles (§3.4) and the sphere map's rim
// direction −Z (§3.2), for which env_jacobian() returns 0 — and, for the lat-long map, wherever
// the footprint (to θ_fp, i.e. 2σ of the K/4 kernel) reaches a pole: there the linearisation in (s,
// t) fails (the s-row grows as 1/ρ, and Rule B's probe budget would blur t by the anisotropy
// instead), while the probe's bilinear taps continue over the pole.
// Returns θ_fp there, and a negative value elsewhere. θ_fp (`theta()`, singular values) is only
// evaluated where it can matter: `spread_bound` ≥ θ_fp·|r| (a Frobenius norm of the spread), and a
// footprint reaches the pole only if ρ < sin(θ_fp)·|r| ≤ spread_bound.
template <class Theta>
float isotropic_footprint_radius(EnvLayout layout, const Jacobian23& j, Vec3 map_direction,
                                 float spread_bound, Theta&& theta) {
    if (layout != EnvLayout::latlong && layout != EnvLayout::sphere) return -1;
    if (dot(j.ds, j.ds) == 0 && dot(j.dt, j.dt) == 0) return theta();
    if (layout != EnvLayout::latlong) return -1;
    const float rho2 = map_direction.x * map_direction.x + map_direction.z * map_direction.z;
    const float rho = std::isfinite(rho2) && rho2 > 0x1p-100f  // else hypot's scaling is needed
                          ? std::sqrt(rho2)
                          : std::hypot(map_direction.x, map_direction.z);
    if (!(rho < spread_bound)) return -1;
    const float theta_fp = theta();
    const float reach = std::min(theta_fp, std::numbers::pi_v<float> / 2);
    return rho < std::sin(reach) * norm(map_direction) ? theta_fp : -1;
}

void set_isotropic_pole_footprint(EnvFootprint& f, EnvLayout layout, Vec2 texel_scale,
                                  float angular_radius) {
    const float texels_per_radian = layout == EnvLayout::latlong
                                        ? texel_scale.y / std::numbers::pi_v<float>
                                        : 0.25f * texel_scale.x;
    float tp = texels_per_radian * angular_radius;
    if (!std::isfinite(tp)) tp = 0;
    f.d_dx = {tp, 0};
    f.d_dy = {0, tp};
    f.curvature = footprint_matrix(f.d_dx, f.d_dy);
    f.roughness = {};
    f.matrix = f.curvature;
    f.isotropic_fallback = true;
}

}  // namespace

EnvFootprint compute_env_footprint(EnvLayout layout, Vec2 texel_scale, Vec3 r, Vec3 dr_dx,
                                   Vec3 dr_dy, const Mat3& rotation) {
    EnvFootprint f;
    const IdentitySkippingRotation to_map(rotation);  // A
    const bool usable = is_finite(r) && norm(r) > 0;
    f.reflected = usable ? r : Vec3{0, 0, 1};
    f.map_direction = to_map(f.reflected);
    const EnvCoordsJacobian position = env_coords_and_jacobian(layout, f.map_direction);
    f.coords = position.coords;
    if (!usable || !is_finite(dr_dx) || !is_finite(dr_dy)) return f;
    const Jacobian23& j = position.jacobian;
    f.map_dr_dx = to_map(dr_dx);
    f.map_dr_dy = to_map(dr_dy);
    const float theta = isotropic_footprint_radius(
        layout, j, f.map_direction, std::sqrt(dot(dr_dx, dr_dx) + dot(dr_dy, dr_dy)),
        [&] { return largest_tangent_singular_value(r, dr_dx, dr_dy) / norm(r); });
    if (theta >= 0) {
        set_isotropic_pole_footprint(f, layout, texel_scale, theta);
        return f;
    }
    const MapJacobian G{texel_scale, j};  // D = G [∂r/∂x, ∂r/∂y]
    f.d_dx = G(f.map_dr_dx);
    f.d_dy = G(f.map_dr_dy);
    f.curvature = footprint_matrix(f.d_dx, f.d_dy);
    f.matrix = f.curvature;
    if (!is_finite(f.d_dx) || !is_finite(f.d_dy) || !f.matrix.is_finite()) {
        f.d_dx = f.d_dy = {};
        f.curvature = f.matrix = {};
        f.map_dr_dx = f.map_dr_dy = {};
    }
    return f;
}

EnvFootprint PlainEnvFootprint::full() const {
    EnvFootprint f;
    f.reflected = reflected;
    f.map_direction = map_direction;
    f.coords = coords;
    f.map_dr_dx = map_dr_dx;
    f.map_dr_dy = map_dr_dy;
    f.d_dx = d_dx;
    f.d_dy = d_dy;
    f.curvature = f.matrix = matrix;
    return f;
}

bool plain_env_footprint(EnvLayout layout, Vec2 texel_scale, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                         const IdentitySkippingRotation& to_map, PlainEnvFootprint& out) {
    using namespace env_detail;
    if (layout != EnvLayout::latlong && layout != EnvLayout::cube) return false;
    out.reflected = r;
    out.map_direction = to_map(r);
    // prepare()'s common case (finite, max |component| within 2^±100), and |r| > 0 as
    // compute_env_footprint() requires (A r finite implies r finite).
    const Prepared<float> p = prepare(out.map_direction);
    if (!p.usable || p.infinite || p.exponent < -100 || p.exponent > 100 || !(dot(r, r) > 0))
        return false;
    EnvCoordsJacobian position;
    if (layout == EnvLayout::latlong) {
        const float rho = latlong_rho(p.r);
        if (rho == 0) return false;  // J undefined: the pole
        const Vec2 st = latlong_coords_at(p.r, rho);
        position = {{0, st.x, st.y}, latlong_jacobian_at(p, rho)};
        // Clear of the poles: isotropic_footprint_radius()'s first test, the same way.
        const Vec3 m = out.map_direction;
        const float rho2 = m.x * m.x + m.z * m.z;
        if (!(std::isfinite(rho2) && rho2 > 0x1p-100f) ||
            std::sqrt(rho2) < std::sqrt(dot(dr_dx, dr_dx) + dot(dr_dy, dr_dy)))
            return false;
    } else {
        position = cube_coords_and_jacobian_at(p);
    }
    out.coords = position.coords;
    out.map_dr_dx = to_map(dr_dx);
    out.map_dr_dy = to_map(dr_dy);
    const MapJacobian G{texel_scale, position.jacobian};
    out.d_dx = G(out.map_dr_dx);
    out.d_dy = G(out.map_dr_dy);
    out.matrix = footprint_matrix(out.d_dx, out.d_dy);
    // A non-finite differential makes D, and so K, non-finite (0·∞ is NaN): one test for all.
    return std::isfinite(out.matrix.xx + out.matrix.xy + out.matrix.yy);
}

namespace {

// Three Float4: a Vec3 of each of four lanes.
struct Vec3x4 {
    Float4 x, y, z;
};

Vec3x4 gather(const EnvRayDifferential* rays, Vec3 EnvRayDifferential::*member) {
    const Vec3 &a = rays[0].*member, &b = rays[1].*member, &c = rays[2].*member,
               &d = rays[3].*member;
    return {{a.x, b.x, c.x, d.x}, {a.y, b.y, c.y, d.y}, {a.z, b.z, c.z, d.z}};
}

// A v (Mat3::operator*'s order of operations), or v where A is the identity.
Vec3x4 rotate(const IdentitySkippingRotation& to_map, const Vec3x4& v) {
    if (to_map.is_identity()) return v;
    const auto& m = to_map.matrix().m;
    auto row = [&](int i) {
        return Float4(m[i][0]) * v.x + Float4(m[i][1]) * v.y + Float4(m[i][2]) * v.z;
    };
    return {row(0), row(1), row(2)};
}

Float4 dot(const Vec3x4& a, const Vec3x4& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

}  // namespace

// The operations of plain_env_footprint() for EnvLayout::cube (prepare(), CubePoint,
// cube_coords_and_jacobian_at(), finish(), MapJacobian, footprint_matrix()), lane by lane in the
// same order, with the face table's entries chosen by selects.
void plain_cube_footprints4(Vec2 texel_scale, const EnvRayDifferential* rays,
                            const IdentitySkippingRotation& to_map, PlainCubeFootprints4& out) {
    const Vec3x4 r = gather(rays, &EnvRayDifferential::direction);
    const Vec3x4 m = rotate(to_map, r);
    // prepare()'s common case, max |component| within 2^±100 and no NaN, and |r| > 0.
    const Float4 big = max_like_std(max_like_std(abs(m.x), abs(m.y)), abs(m.z));
    Mask4 plain = (big >= Float4(0x1p-100f)) & (big <= Float4(0x1p100f)) &
                  is_not_nan(m.x + m.y + m.z) & (dot(r, r) > Float4(0.0f));
    // 2^-exponent, exponent = (bits >> 23) − 127, from the bits: (254 − (bits >> 23)) << 23.
    const Float4 scale = float_from_bits(shift_left<23>(Int4(254) - shift_right<23>(bits_of(big))));
    const Vec3x4 p{m.x * scale, m.y * scale, m.z * scale};

    // cube_face_of(): the axis a (x, unless |y| > |x|; then z if |z| exceeds that) and its sign.
    const Mask4 y_over_x = abs(p.y) > abs(p.x);
    const Mask4 z_axis = abs(p.z) > select(y_over_x, abs(p.y), abs(p.x));
    const Mask4 y_axis = y_over_x & !z_axis;
    const Mask4 x_axis = !(y_over_x | z_axis);
    const Float4 c_axis = select(z_axis, p.z, select(y_over_x, p.y, p.x));
    const Mask4 negative = c_axis < Float4(0.0f);
    const Int4 face = shift_left<1>(select(z_axis, Int4(2), select(y_axis, Int4(1), Int4(0)))) +
                      select(negative, Int4(1), Int4(0));
    // CubePoint: ma = |c[a]|, s' = s_sign·c[s_axis]/ma, t' = t_sign·c[t_axis]/ma (kCubeFaces).
    const Float4 one(1.0f), minus_one(-1.0f);
    const Float4 ma = abs(c_axis);
    const Float4 c_s = select(x_axis, p.z, p.x), c_t = select(y_axis, p.z, p.y);
    const Float4 s_sign =
        select(x_axis, select(negative, one, minus_one), select(z_axis & negative, minus_one, one));
    const Float4 t_sign = select(y_axis & !negative, one, minus_one);
    const Float4 sp = s_sign * c_s / ma, tp = t_sign * c_t / ma;

    // cube_coords_and_jacobian_at(): ∂s/∂r = k(g_s − s'σ e_a), ∂t/∂r = k(g_t − t'σ e_a), then
    // finish()'s exact 2^-exponent.
    const Float4 sigma = select(negative, minus_one, one);
    const Float4 k = one / (Float4(2.0f) * ma);
    const Float4 ds_a = k * (Float4(0.0f) - sp * sigma), dt_a = k * (Float4(0.0f) - tp * sigma);
    const Float4 ds_s = k * s_sign, dt_t = k * t_sign, zero(0.0f);
    // a = x: s_axis z, t_axis y; a = y: s_axis x, t_axis z; a = z: s_axis x, t_axis y.
    const Vec3x4 ds{select(x_axis, ds_a, ds_s) * scale, select(y_axis, ds_a, zero) * scale,
                    select(x_axis, ds_s, select(z_axis, ds_a, zero)) * scale};
    const Vec3x4 dt{select(x_axis, dt_a, zero) * scale, select(y_axis, dt_a, dt_t) * scale,
                    select(y_axis, dt_t, select(z_axis, dt_a, zero)) * scale};

    // MapJacobian: D's columns; K = D Dᵀ (footprint_matrix()).
    const Vec3x4 mdx = rotate(to_map, gather(rays, &EnvRayDifferential::d_dx));
    const Vec3x4 mdy = rotate(to_map, gather(rays, &EnvRayDifferential::d_dy));
    const Float4 width(texel_scale.x), height(texel_scale.y);
    const Float4 dxs = width * dot(ds, mdx), dxt = height * dot(dt, mdx);
    const Float4 dys = width * dot(ds, mdy), dyt = height * dot(dt, mdy);
    const Float4 xx = dxs * dxs + dys * dys, xy = dxs * dxt + dys * dyt, yy = dxt * dxt + dyt * dyt;
    plain = plain & (abs(xx + xy + yy) < Float4(std::numeric_limits<float>::infinity()));

    out.plain = plain.bits();
    face.store(out.face);
    (Float4(0.5f) * (sp + one)).store(out.s);
    (Float4(0.5f) * (tp + one)).store(out.t);
    xx.store(out.xx);
    xy.store(out.xy);
    yy.store(out.yy);
    m.x.store(out.map_x);
    m.y.store(out.map_y);
    m.z.store(out.map_z);
}

EnvFootprint compute_env_footprint(EnvLayout layout, Vec2 texel_scale, const ReflectionGeometry& g,
                                   const EnvFootprintOptions& options) {
    EnvFootprint f;
    Vec3 v = g.v, n = g.n;
    const float v_len = norm(v), n_len = norm(n);
    if (!is_finite(v) || !is_finite(n) || !(v_len > 0) || !(n_len > 0) ||
        !std::isfinite(v_len * n_len)) {
        // Nothing to reflect: look straight back along the view ray, with no footprint.
        f.reflected = is_finite(v) && v_len > 0 ? -v : Vec3{0, 0, 1};
        f.map_direction = options.rotation * f.reflected;
        f.coords = env_coords(layout, f.map_direction);
        return f;
    }

    // §2.2: the perturbed normal, the bump dropped where it faces away, silhouettes clamped.
    Vec3 nm = n + n_len * (g.bump_slope.x * g.t1 + g.bump_slope.y * g.t2);
    if (!is_finite(nm) || !(dot(nm, v) > 0)) {
        nm = n;
        f.bump_dropped = true;
    }
    if (!(dot(n, v) > 0)) {
        constexpr float kSilhouetteCosine = 1e-3f;  // ε: n̂·v̂ after the clamp
        const Vec3 v_hat = v / v_len;
        n = n - (dot(n, v_hat) - kSilhouetteCosine * n_len) * v_hat;
        nm = n;
        f.normal_clamped = true;
    }

    // Eq. 4 and the Jacobians of eqs. 8, 9 (applied to vectors, never formed).
    const float nm_v = dot(nm, v), nm_nm = dot(nm, nm);
    f.reflected = 2 * nm_v * nm - nm_nm * v;
    auto a_v = [&](Vec3 x) { return 2 * dot(nm, x) * nm - nm_nm * x; };
    auto a_n = [&](Vec3 x) { return 2 * nm_v * x + 2 * dot(v, x) * nm - 2 * dot(nm, x) * v; };
    const IdentitySkippingRotation to_map(options.rotation);  // A
    f.map_direction = to_map(f.reflected);
    const EnvCoordsJacobian position = env_coords_and_jacobian(layout, f.map_direction);
    f.coords = position.coords;
    const Jacobian23& j = position.jacobian;
    const MapJacobian G{texel_scale, j};

    // Eq. 5 / §2.4: D's columns, K12 = D Dᵀ.
    const Vec3 dvr_dx = a_v(g.dv_dx) + a_n(g.dn_dx), dvr_dy = a_v(g.dv_dy) + a_n(g.dn_dy);
    f.map_dr_dx = to_map(dvr_dx);
    f.map_dr_dy = to_map(dvr_dy);
    f.d_dx = G(f.map_dr_dx);
    f.d_dy = G(f.map_dr_dy);
    f.curvature = footprint_matrix(f.d_dx, f.d_dy);

    // Eqs. 10–12 / §2.5: B' = G A_n E B with E = |n| T, B = [[d1, d2], [0, d3]]: its columns are
    // G A_n (|n| d1 t1) and G A_n (|n| (d2 t1 + d3 t2)); K3 = B'B'ᵀ.
    const RoughnessFactor& b = g.roughness;
    const Vec3 rough1 = a_n(n_len * b.d1 * g.t1);
    const Vec3 rough2 = a_n(n_len * (b.d2 * g.t1 + b.d3 * g.t2));
    const Vec3 map_rough1 = to_map(rough1), map_rough2 = to_map(rough2);
    f.roughness = footprint_matrix(G(map_rough1), G(map_rough2));
    f.map_roughness1 = options.kappa * map_rough1;
    f.map_roughness2 = options.kappa * map_rough2;

    const float kappa2 = options.kappa * options.kappa;
    f.matrix = f.curvature + kappa2 * f.roughness;  // eq. 13, K = D Dᵀ + κ² K3 (§2.6)
    // §3.4: θ_fp from the spread of v_r per pixel, enlarged by κ·(angular roughness).
    const float theta = isotropic_footprint_radius(
        layout, j, f.map_direction,
        std::sqrt(dot(dvr_dx, dvr_dx) + dot(dvr_dy, dvr_dy)) +
            std::fabs(options.kappa) * std::sqrt(dot(rough1, rough1) + dot(rough2, rough2)),
        [&] {
            return (largest_tangent_singular_value(f.reflected, dvr_dx, dvr_dy) +
                    options.kappa * largest_tangent_singular_value(f.reflected, rough1, rough2)) /
                   norm(f.reflected);
        });
    if (theta >= 0) {
        set_isotropic_pole_footprint(f, layout, texel_scale, theta);
        return f;
    }
    if (!is_finite(f.d_dx) || !is_finite(f.d_dy) || !f.matrix.is_finite()) {
        // §4: isotropic fallback from roughness only, T_p = max(1, κ·‖G A_n E‖·l1).
        const FootprintEllipse gae =
            make_footprint_ellipse(G(to_map(a_n(n_len * g.t1))), G(to_map(a_n(n_len * g.t2))));
        float tp = options.kappa * gae.major_radius * isotropic_roughness(b.covariance());
        tp = std::isfinite(tp) ? std::max(1.0f, tp) : 1.0f;
        f.d_dx = {tp, 0};
        f.d_dy = {0, tp};
        f.curvature = footprint_matrix(f.d_dx, f.d_dy);
        f.roughness = {};
        f.matrix = f.curvature;
        f.map_dr_dx = f.map_dr_dy = f.map_roughness1 = f.map_roughness2 = {};
        f.isotropic_fallback = true;
    }
    return f;
}

}  // namespace footprint
