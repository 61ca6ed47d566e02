// scene/ray_differentials.h — how a surface hit moves when the pixel moves: ∂p, ∂n and ∂(u, v)
// per pixel step, from the ray's own derivatives (Igehy, "Tracing Ray Differentials", SIGGRAPH
// 1999, §3; pbrt's SurfaceInteraction::ComputeDifferentials), exact to first order.
//
// A camera ray o(x, y) + t d(x, y) comes with ∂o/∂x, ∂d/∂x, ∂o/∂y, ∂d/∂y (per pixel; a pinhole
// camera has ∂o = 0, an orthographic one ∂d = 0). The hit p = o + t d lies on the surface; moving
// the pixel by one step in x moves it, to first order, within the tangent plane at p (normal n_g):
//     ∂t/∂x = −((∂o/∂x + t ∂d/∂x)·n_g) / (d·n_g)          (Igehy eq. 10, transfer to the plane)
//     ∂p/∂x = ∂o/∂x + t ∂d/∂x + (∂t/∂x) d                  (Igehy eq. 9)
// This is the exact derivative of the hit point for any surface, not only a plane: p(x) stays on
// the surface, so ∂p/∂x is tangent, and the first-order motion along d is fixed by that.
// The texture-coordinate derivatives solve ∂p/∂x = p_u ∂u/∂x + p_v ∂v/∂x in the least-squares
// sense (p_u = ∂p/∂u, p_v = ∂p/∂v; exact where ∂p/∂x lies in their span), by the 2×2 normal
// equations
//     [p_u·p_u  p_u·p_v] [∂u/∂x]   [p_u·∂p/∂x]
//     [p_u·p_v  p_v·p_v] [∂v/∂x] = [p_v·∂p/∂x],
// and the normal follows the chain rule: ∂n/∂x = n_u ∂u/∂x + n_v ∂v/∂x. Likewise for y.
//
// Degenerate cases (never NaN):
//   * grazing (|d̂·n̂_g| < kGrazingCosine), a zero or non-finite normal/direction, non-finite input
//     or results: valid = false and every field zero;
//   * a rank-deficient tangent frame (a sphere's pole: p_u = 0; det of the normal equations below
//     1e-12·|p_u|²|p_v|²): (u, v) are solved from the longer of p_u, p_v alone, the other
//     derivative 0; both zero: ∂(u, v) = 0 (∂p is still exact and valid = true).
#pragma once

#include <footprint/math/vec.h>
#include <footprint/math/vec3.h>
#include <footprint/scene/surface.h>

namespace footprint {

// A ray and its derivatives per pixel step in x and y (any units: t stays in units of |d|).
struct RayDifferential {
    Ray ray;
    Vec3d dodx, dddx;  // ∂o/∂x, ∂d/∂x
    Vec3d dody, dddy;  // ∂o/∂y, ∂d/∂y
};

struct SurfaceDifferentials {
    Vec3d dpdx, dpdy;    // ∂p/∂x, ∂p/∂y (world units per pixel)
    Vec3d dndx, dndy;    // ∂n/∂x, ∂n/∂y of the unit shading normal
    Vec2d duvdx, duvdy;  // ∂(u, v)/∂x, ∂(u, v)/∂y
    bool valid = false;
};

// Below this |cos| between the ray and the geometric normal a hit counts as grazing: the
// derivatives grow like 1/cos and are meaningless there (the footprint spans the horizon).
constexpr double kGrazingCosine = 1e-8;

// The differentials at `hit` of the ray `rd.ray` (hit.t, hit.p, hit.geometric_normal, hit.dpdu,
// dpdv, dndu, dndv are used). See above for the formulas and the degenerate cases.
SurfaceDifferentials surface_differentials(const RayDifferential& rd, const SurfaceHit& hit);

}  // namespace footprint
