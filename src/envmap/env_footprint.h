// envmap/env_footprint.h — the per-pixel environment-map footprint of [S97a], corrected (spec §2).
//
// For a reflecting surface point seen through a pixel, the lookup direction is the reflected view
// vector v_r and its footprint on the map is the ellipse of
//     K = D Dᵀ + κ² K3                                                     (eq. 13, spec §2.6)
// where D (2×2, level-0 texels per pixel) is how v_r's map position moves per pixel step —
// the aperture of the pixel and the curvature of the surface (eqs. 1–5) — and K3 = B'B'ᵀ is how
// far the sub-pixel bump slopes (roughness K_b = B Bᵀ) scatter it (eqs. 10–12).
//
// clang-format off
//   n_m = n + |n| T b                                    perturbed normal (§2.2)
//   v_r = 2 n_m (n_m·v) − v (n_m·n_m)                    eq. 4; |v_r| = |v||n_m|²
//   A_v = ∂v_r/∂v   = 2 n_m n_mᵀ − (n_m·n_m) I           eq. 8, with n_m (erratum 6)
//   A_n = ∂v_r/∂n_m = 2 (n_m·v) I + 2 n_m vᵀ − 2 v n_mᵀ  eq. 9
//   G   = S · J_P(A v_r) · A                             2×3, texels per unit of v_r; A the
//                                                        environment rotation
//   D   = G · [A_v ∂v/∂x + A_n ∂n/∂x,                    eq. 5
//              A_v ∂v/∂y + A_n ∂n/∂y]
//   K12 = D Dᵀ                                           NOT DᵀD (erratum 1)
//   M   = G A_n                                          2×3 (erratum 3)
//   E   = |n| T,  B' = M E B,  K3 = B' B'ᵀ               eqs. 10–12
// clang-format on
//
// Conventions (spec §1): v points from the surface TO the eye, any positive scale. With the paper's
// camera (eye at the origin looking along +z, pixel (x, y) → ray (x, y, z0)), v = −(x, y, z0) and
// ∂v/∂x = −e_x, ∂v/∂y = −e_y (erratum 2: the paper prints +e_x, which turns the compensation of a
// parabolic mirror seen from its focus into an addition). n may have any nonzero scale, varying
// over the screen, but ∂n/∂x must be the derivative of that same n. All factors are evaluated at
// one consistent (v, n_m, v_r) (erratum 6, [E11j]).
//
// κ (default 2) makes the roughness term measure-consistent with D Dᵀ: probes honouring K have a
// kernel covariance of K/4, so κ = 2 blurs with exactly K3 (spec §2.6, erratum 7); κ = 1 is the
// paper.
//
// Degenerate cases (spec §4): n_m·v ≤ 0 drops the bump (b = 0); if then n·v ≤ 0 (an interpolated
// normal at a silhouette) n is clamped towards v until n̂·v̂ = ε. A non-finite D or K falls back to
// an isotropic footprint from the roughness alone, T_p = max(1, κ·‖G A_n E‖·l1). Where J_P is
// undefined — exactly at a lat-long pole (§3.4) or the sphere map's rim direction −Z (§3.2) — and
// wherever a lat-long footprint reaches a pole (within θ_fp, 2σ), the footprint is isotropic with
// T_p = (texels per radian)·θ_fp, θ_fp the largest singular value of the tangential part of
// [∂v_r/∂x, ∂v_r/∂y]/|v_r|, enlarged by κ·(angular roughness) in form (b); texels per radian = H0/π
// (lat-long) or W0/4 (sphere, the centre's scale). Nothing here produces NaN from finite input;
// non-finite input gives a zero footprint in direction v_r = −v (or +z if v is unusable).
#pragma once

#include <footprint/bump/roughness.h>
#include <footprint/envmap/env_layout.h>
#include <footprint/math/footprint_ellipse.h>
#include <footprint/math/mat3.h>
#include <footprint/math/vec3.h>

namespace footprint {

struct ReflectionGeometry {
    Vec3 v;                // surface → eye
    Vec3 dv_dx{-1, 0, 0};  // ∂v/∂x (paper camera: −e_x)
    Vec3 dv_dy{0, -1, 0};  // ∂v/∂y (paper camera: −e_y; +e_y if window y points down)
    Vec3 n;                // surface normal (any nonzero scale)
    Vec3 dn_dx, dn_dy;     // derivatives of that same n per pixel step
    Vec2 bump_slope;       // b, in the frame T
    Vec3 t1{1, 0, 0};  // T = (t1 t2): ∂n̂_m/∂b, e.g. an orthonormal (e1, e2) (bump/local_frame.h)
    Vec3 t2{0, 1, 0};
    RoughnessFactor roughness;  // B with B Bᵀ = K_b (bump_lookup + roughness_factor)
};

struct EnvFootprintOptions {
    float kappa = 2.0f;  // κ of eq. 13 (spec §2.6)
    Mat3 rotation;       // A: world (eye) space → map space; identity by default
};

struct EnvFootprint {
    Vec3 reflected;      // v_r in world space (unnormalised)
    Vec3 map_direction;  // A v_r
    EnvCoords coords;    // where A v_r lands on the map
    Vec2 d_dx, d_dy;     // D's columns, level-0 texels per pixel
    Sym2 curvature;      // K12 = D Dᵀ
    Sym2 roughness;      // K3 = B'B'ᵀ
    Sym2 matrix;         // K = K12 + κ² K3
    // The same footprint as directions, in map space (A applied): ∂v_r/∂x, ∂v_r/∂y, and the
    // columns of A_n E B scaled by κ, so that for ANY map Jacobian G' = S' J_P'(A v_r),
    // K' = G'(dx dxᵀ + dy dyᵀ + r1 r1ᵀ + r2 r2ᵀ)G'ᵀ — how a lat-long lookup moves its footprint
    // onto a polar cap (environment_map.h). Zero where K is a fallback from non-finite input.
    Vec3 map_dr_dx, map_dr_dy, map_roughness1, map_roughness2;
    bool bump_dropped = false;        // n_m·v ≤ 0: b ignored
    bool normal_clamped = false;      // n·v ≤ 0: n clamped towards v
    bool isotropic_fallback = false;  // D or K was not finite, or J_P undefined (pole, rim)
};

// Form (a), like OpenImageIO's environment(): the footprint of a lookup direction r and its ray
// differentials ∂r/∂x, ∂r/∂y (any common scale of r): D = S J_P(A r) A [∂r/∂x, ∂r/∂y], K = D Dᵀ.
// For r = v_r and ∂r = ∂v_r this is exactly form (b)'s curvature term K12. Non-finite input gives a
// zero footprint (a point lookup) in the direction r (or +z).
EnvFootprint compute_env_footprint(EnvLayout layout, Vec2 texel_scale, Vec3 r, Vec3 dr_dx,
                                   Vec3 dr_dy, const Mat3& rotation = Mat3{});

// One form-(a) lookup of a batch: a direction r and its ray differentials ∂r/∂x, ∂r/∂y.
struct EnvRayDifferential {
    Vec3 direction, d_dx, d_dy;
};

// Form (a) with roughness: the footprint of a lookup direction r, its ray differentials and two
// roughness columns (A_n E B's of form (b), world space, before κ) — K = D Dᵀ + κ² K3 with
// D = S J_P(A r) A [∂r/∂x, ∂r/∂y] and K3 from the columns likewise. A form-(b) footprint whose
// spreads were moved onto another lookup direction (a local map's proxy, env_proxy.h) is this
// footprint there. Non-finite spreads give a point lookup in the direction r.
EnvFootprint compute_env_footprint(EnvLayout layout, Vec2 texel_scale, Vec3 r, Vec3 dr_dx,
                                   Vec3 dr_dy, Vec3 rough1, Vec3 rough2,
                                   const EnvFootprintOptions& options);

// Form (b), Schilling's. `texel_scale` = S = (W0, H0) of level 0 (a cube map's face size for both).
EnvFootprint compute_env_footprint(EnvLayout layout, Vec2 texel_scale,
                                   const ReflectionGeometry& geometry,
                                   const EnvFootprintOptions& options = {});

}  // namespace footprint
