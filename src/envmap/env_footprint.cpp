#include "envmap/env_footprint.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "envmap/env_footprint_plain.h"
#include "envmap/env_layout_detail.h"
#include "math/float4.h"
#include "math/lanes.h"

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

namespace {

// Form (a)'s plain footprint (env_footprint_plain.h) for any lane type (math/lanes.h): one ray or
// four. Where `plain`, the fields compute_env_footprint() sets, bit for bit: its common case in one
// pass, the layout's pieces (env_layout_detail.h) on the prepared direction and D = G [∂r/∂x,
// ∂r/∂y] (MapJacobian), with no branch for the rare cases, which are left to it.
template <class F>
struct PlainFootprintLanes {
    MaskOf<F> plain;
    Vec3T<F> map_direction, map_dr_dx, map_dr_dy;  // A r, A ∂r/∂x, A ∂r/∂y
    IntOf<F> face = IntOf<F>(0);
    F s, t;
    Vec2T<F> d_dx, d_dy;
    Sym2Lanes<F> matrix;  // K = D Dᵀ
};

template <class F>
inline PlainFootprintLanes<F> plain_footprint(EnvLayout layout, Vec2 texel_scale, const Vec3T<F>& r,
                                              const Vec3T<F>& dr_dx, const Vec3T<F>& dr_dy,
                                              const IdentitySkippingRotation& to_map) {
    using namespace env_detail;
    using std::sqrt;
    PlainFootprintLanes<F> f;
    f.map_direction = rotate(to_map, r);
    // prepare()'s common case (A r finite implies r finite), and |r| > 0 as
    // compute_env_footprint() requires.
    const PreparedLanes<F> p = prepare_lanes(f.map_direction);
    f.plain = p.common & (dot(r, r) > F(0));
    if (none(f.plain)) return f;
    Jacobian23T<F> j;
    if (layout == EnvLayout::cube) {
        const CubeCoordsJacobianLanes<F> c = cube_coords_and_jacobian_lanes(p.r, cube_axes(p.r));
        f.face = c.face;
        f.s = c.s;
        f.t = c.t;
        j = c.j;
    } else {
        const F rho = latlong_rho(p.r);
        const Vec2T<F> st = latlong_coords_at(p.r, rho);
        f.s = st.x;
        f.t = st.y;
        // Not the pole (ρ = 0: J undefined), and clear of it: isotropic_footprint_radius()'s first
        // test, ρ of A r at least the differentials' spread.
        const Vec3T<F>& m = f.map_direction;
        const F rho2 = m.x * m.x + m.z * m.z;
        f.plain = f.plain & !(rho == F(0)) & is_finite(rho2) & (rho2 > F(0x1p-100)) &
                  !(sqrt(rho2) < sqrt(dot(dr_dx, dr_dx) + dot(dr_dy, dr_dy)));
        if (none(f.plain)) return f;
        j = latlong_jacobian_lanes(p.r, rho);
    }
    j = scaled(j, p.scale);
    f.map_dr_dx = rotate(to_map, dr_dx);
    f.map_dr_dy = rotate(to_map, dr_dy);
    const F width(texel_scale.x), height(texel_scale.y);
    f.d_dx = {width * dot(j.ds, f.map_dr_dx), height * dot(j.dt, f.map_dr_dx)};
    f.d_dy = {width * dot(j.ds, f.map_dr_dy), height * dot(j.dt, f.map_dr_dy)};
    f.matrix = footprint_matrix_lanes(f.d_dx, f.d_dy);
    // A non-finite differential makes D, and so K, non-finite (0·∞ is NaN): one test for all.
    f.plain = f.plain & is_finite(f.matrix.xx + f.matrix.xy + f.matrix.yy);
    return f;
}

}  // namespace

bool plain_env_footprint(EnvLayout layout, Vec2 texel_scale, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                         const IdentitySkippingRotation& to_map, PlainEnvFootprint& out) {
    if (layout != EnvLayout::latlong && layout != EnvLayout::cube) return false;
    const PlainFootprintLanes<float> f =
        plain_footprint(layout, texel_scale, r, dr_dx, dr_dy, to_map);
    if (!f.plain) return false;
    out.reflected = r;
    out.map_direction = f.map_direction;
    out.coords = {f.face, f.s, f.t};
    out.map_dr_dx = f.map_dr_dx;
    out.map_dr_dy = f.map_dr_dy;
    out.d_dx = f.d_dx;
    out.d_dy = f.d_dy;
    out.matrix = {f.matrix.xx, f.matrix.xy, f.matrix.yy};
    return true;
}

void plain_env_footprints4(EnvLayout layout, Vec2 texel_scale, const EnvRayDifferential* rays,
                           const IdentitySkippingRotation& to_map, PlainEnvFootprints4& out) {
    out.plain = 0;
    if (layout != EnvLayout::latlong && layout != EnvLayout::cube) return;
    const PlainFootprintLanes<Float4> f = plain_footprint(
        layout, texel_scale, gather(rays, &EnvRayDifferential::direction),
        gather(rays, &EnvRayDifferential::d_dx), gather(rays, &EnvRayDifferential::d_dy), to_map);
    out.plain = f.plain.bits();
    if (out.plain == 0) return;
    f.face.store(out.face);
    f.s.store(out.s);
    f.t.store(out.t);
    f.matrix.xx.store(out.xx);
    f.matrix.xy.store(out.xy);
    f.matrix.yy.store(out.yy);
    f.map_direction.x.store(out.map_x);
    f.map_direction.y.store(out.map_y);
    f.map_direction.z.store(out.map_z);
}

namespace {

// K for a direction r (unnormalised) with spread ∂r/∂x, ∂r/∂y and the roughness columns rough1,
// rough2 (A_n E B's, before κ): D = G A [∂r/∂x, ∂r/∂y], K12 = D Dᵀ, K3 = (G A rough)(…)ᵀ, K = K12
// + κ² K3 (eq. 13, §2.6); towards a lat-long pole or at the sphere map's rim, the isotropic
// footprint of §3.4 from θ_fp. A non-finite K is left for the caller.
EnvFootprint footprint_of_spread(EnvLayout layout, Vec2 texel_scale, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                                 Vec3 rough1, Vec3 rough2, const EnvFootprintOptions& options) {
    EnvFootprint f;
    f.reflected = r;
    const IdentitySkippingRotation to_map(options.rotation);  // A
    f.map_direction = to_map(r);
    const EnvCoordsJacobian position = env_coords_and_jacobian(layout, f.map_direction);
    f.coords = position.coords;
    const Jacobian23& j = position.jacobian;
    const MapJacobian G{texel_scale, j};
    f.map_dr_dx = to_map(dr_dx);
    f.map_dr_dy = to_map(dr_dy);
    f.d_dx = G(f.map_dr_dx);
    f.d_dy = G(f.map_dr_dy);
    f.curvature = footprint_matrix(f.d_dx, f.d_dy);
    const Vec3 map_rough1 = to_map(rough1), map_rough2 = to_map(rough2);
    f.roughness = footprint_matrix(G(map_rough1), G(map_rough2));
    f.map_roughness1 = options.kappa * map_rough1;
    f.map_roughness2 = options.kappa * map_rough2;
    f.matrix = f.curvature + options.kappa * options.kappa * f.roughness;
    // §3.4: θ_fp from the spread of r per pixel, enlarged by κ·(angular roughness).
    const float theta = isotropic_footprint_radius(
        layout, j, f.map_direction,
        std::sqrt(dot(dr_dx, dr_dx) + dot(dr_dy, dr_dy)) +
            std::fabs(options.kappa) * std::sqrt(dot(rough1, rough1) + dot(rough2, rough2)),
        [&] {
            return (largest_tangent_singular_value(r, dr_dx, dr_dy) +
                    options.kappa * largest_tangent_singular_value(r, rough1, rough2)) /
                   norm(r);
        });
    if (theta >= 0) set_isotropic_pole_footprint(f, layout, texel_scale, theta);
    return f;
}

}  // namespace

EnvFootprint compute_env_footprint(EnvLayout layout, Vec2 texel_scale, Vec3 r, Vec3 dr_dx,
                                   Vec3 dr_dy, Vec3 rough1, Vec3 rough2,
                                   const EnvFootprintOptions& options) {
    if (!is_finite(r) || !(dot(r, r) > 0))
        return compute_env_footprint(layout, texel_scale, r, {}, {}, options.rotation);
    EnvFootprint f =
        footprint_of_spread(layout, texel_scale, r, dr_dx, dr_dy, rough1, rough2, options);
    if (!f.isotropic_fallback &&
        (!is_finite(f.d_dx) || !is_finite(f.d_dy) || !f.matrix.is_finite())) {
        // Non-finite spreads: a point lookup, as form (a) gives.
        f.d_dx = f.d_dy = {};
        f.curvature = f.roughness = f.matrix = {};
        f.map_dr_dx = f.map_dr_dy = f.map_roughness1 = f.map_roughness2 = {};
    }
    return f;
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
    auto a_v = [&](Vec3 x) { return 2 * dot(nm, x) * nm - nm_nm * x; };
    auto a_n = [&](Vec3 x) { return 2 * nm_v * x + 2 * dot(v, x) * nm - 2 * dot(nm, x) * v; };
    // Eq. 5 / §2.4: ∂v_r; eqs. 10–12 / §2.5: B' = G A_n E B with E = |n| T, B = [[d1, d2], [0,
    // d3]]: its columns are G A_n (|n| d1 t1) and G A_n (|n| (d2 t1 + d3 t2)).
    const RoughnessFactor& b = g.roughness;
    const bool bump_dropped = f.bump_dropped, normal_clamped = f.normal_clamped;
    f = footprint_of_spread(layout, texel_scale, 2 * nm_v * nm - nm_nm * v,
                            a_v(g.dv_dx) + a_n(g.dn_dx), a_v(g.dv_dy) + a_n(g.dn_dy),
                            a_n(n_len * b.d1 * g.t1), a_n(n_len * (b.d2 * g.t1 + b.d3 * g.t2)),
                            options);
    f.bump_dropped = bump_dropped, f.normal_clamped = normal_clamped;
    if (f.isotropic_fallback) return f;  // a pole's
    if (!is_finite(f.d_dx) || !is_finite(f.d_dy) || !f.matrix.is_finite()) {
        // §4: isotropic fallback from roughness only, T_p = max(1, κ·‖G A_n E‖·l1).
        const IdentitySkippingRotation to_map(options.rotation);  // A
        const MapJacobian G{texel_scale, env_coords_and_jacobian(layout, f.map_direction).jacobian};
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
