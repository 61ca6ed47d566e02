#include "envmap/env_footprint.h"

#include <algorithm>
#include <cmath>

namespace footprint {

namespace {

float norm(Vec3 a) {
    return std::sqrt(dot(a, a));
}

// G = S · J_P(A r) · A (spec §2.3): map motion in level-0 texels per unit change of r.
struct MapJacobian {
    Vec2 texel_scale;
    Jacobian23 j;
    const Mat3& rotation;

    Vec2 operator()(Vec3 x) const {
        const Vec3 ax = rotation * x;
        return {texel_scale.x * dot(j.ds, ax), texel_scale.y * dot(j.dt, ax)};
    }
};

}  // namespace

EnvFootprint compute_env_footprint(EnvLayout layout, Vec2 texel_scale, Vec3 r, Vec3 dr_dx,
                                   Vec3 dr_dy, const Mat3& rotation) {
    EnvFootprint f;
    const bool usable = is_finite(r) && norm(r) > 0;
    f.reflected = usable ? r : Vec3{0, 0, 1};
    f.map_direction = rotation * f.reflected;
    f.coords = env_coords(layout, f.map_direction);
    if (!usable || !is_finite(dr_dx) || !is_finite(dr_dy)) return f;
    const Jacobian23 j = env_jacobian(layout, f.map_direction);
    const MapJacobian G{texel_scale, j, rotation};
    f.d_dx = G(dr_dx);
    f.d_dy = G(dr_dy);
    f.curvature = footprint_matrix(f.d_dx, f.d_dy);
    f.matrix = f.curvature;
    if (!is_finite(f.d_dx) || !is_finite(f.d_dy) || !f.matrix.is_finite()) {
        f.d_dx = f.d_dy = {};
        f.curvature = f.matrix = {};
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
    f.reflected = 2 * nm_v * nm - nm_nm * v;
    auto a_v = [&](Vec3 x) { return 2 * dot(nm, x) * nm - nm_nm * x; };
    auto a_n = [&](Vec3 x) { return 2 * nm_v * x + 2 * dot(v, x) * nm - 2 * dot(nm, x) * v; };
    f.map_direction = options.rotation * f.reflected;
    f.coords = env_coords(layout, f.map_direction);
    const Jacobian23 j = env_jacobian(layout, f.map_direction);
    const MapJacobian G{texel_scale, j, options.rotation};

    // Eq. 5 / §2.4: D's columns, K12 = D Dᵀ.
    f.d_dx = G(a_v(g.dv_dx) + a_n(g.dn_dx));
    f.d_dy = G(a_v(g.dv_dy) + a_n(g.dn_dy));
    f.curvature = footprint_matrix(f.d_dx, f.d_dy);

    // Eqs. 10–12 / §2.5: B' = G A_n E B with E = |n| T, B = [[d1, d2], [0, d3]]: its columns are
    // G A_n (|n| d1 t1) and G A_n (|n| (d2 t1 + d3 t2)); K3 = B'B'ᵀ.
    const RoughnessFactor& b = g.roughness;
    const Vec2 b_col1 = G(a_n(n_len * b.d1 * g.t1));
    const Vec2 b_col2 = G(a_n(n_len * (b.d2 * g.t1 + b.d3 * g.t2)));
    f.roughness = footprint_matrix(b_col1, b_col2);

    const float kappa2 = options.kappa * options.kappa;
    f.matrix = f.curvature + kappa2 * f.roughness;  // eq. 13, K = D Dᵀ + κ² K3 (§2.6)
    if (!is_finite(f.d_dx) || !is_finite(f.d_dy) || !f.matrix.is_finite()) {
        // §4: isotropic fallback from roughness only, T_p = max(1, κ·‖G A_n E‖·l1).
        const FootprintEllipse gae =
            make_footprint_ellipse(G(a_n(n_len * g.t1)), G(a_n(n_len * g.t2)));
        float tp = options.kappa * gae.major_radius * isotropic_roughness(b.covariance());
        tp = std::isfinite(tp) ? std::max(1.0f, tp) : 1.0f;
        f.d_dx = {tp, 0};
        f.d_dy = {0, tp};
        f.curvature = footprint_matrix(f.d_dx, f.d_dy);
        f.roughness = {};
        f.matrix = f.curvature;
        f.isotropic_fallback = true;
    }
    return f;
}

}  // namespace footprint
