// scene/shapes.h — exact ray intersection and exact local differential geometry of the analytic
// shapes of scene/scene.h (plane, sphere, cylinder, paraboloid mirror, torus).
//
// Every shape is a parametric patch p(u, v); a hit returns the SurfaceHit of scene/surface.h: t, p,
// the unit normal n, ∂p/∂u, ∂p/∂v, the derivatives ∂n/∂u, ∂n/∂v of that UNIT normal, (u, v) and the
// geometric normal (= n: analytic shapes are smooth). `object` and `primitive` are left at −1.
// evaluate(shape, uv) gives the same fields (t = 0) for any (u, v), ignoring the shape's bounds
// (finite plane, cylinder height, mirror aperture): intersect() is evaluate() at the hit's (u, v),
// with p = origin + t·direction. Everything is double precision.
//
// ---- Axes. A shape with a direction (plane normal, cylinder/torus/paraboloid axis; the sphere
// uses +y) gets a right-handed orthonormal frame (a_u, a_v, a), a_u × a_v = a, from shape_axes():
//     w   = +y, or −z where the direction is within ~25.8° of ±y (|a_y| ≥ 0.9)
//     a_v = normalize(w − (w·a) a)      ("up" in the plane ⟂ a)
//     a_u = a_v × a
// so a = +y gives (a_u, a_v) = (+x, −z), a = +z gives (+x, +y), a = +x gives (−z, +y): a wall
// reads upright and unmirrored from its front, a floor from above with the viewer on +z.
//
// ---- Bodies of revolution (sphere, cylinder, torus): the azimuth φ about a is measured from the
// front direction −a_v towards a_u, u = ½ + φ/(2π) ∈ [0, 1], radial direction
//     e(φ) = sin φ a_u − cos φ a_v,      e'(φ) = de/dφ = cos φ a_u + sin φ a_v.
//   seen from +a (a = +y: x to the right, +z down the page):
//                       a_v (−z): u = 0 ≡ 1 (seam)
//                              |
//          −a_u: u = ¼  ———————+———————  a_u (+x): u = ¾
//                              |
//                       −a_v (+z): u = ½  (faces the default camera)
// (u, v) increase right and up on the outside seen from outside: ∂p/∂u × ∂p/∂v ∝ +n.
//
// ---- Plane: n = normalize(normal), local coordinates l = ((p − c)·a_u, (p − c)·a_v),
//     uv = uv_scale · l + (½, ½)          (the texture's centre sits on the plane's centre),
//     ∂p/∂u = a_u/uv_scale, ∂p/∂v = a_v/uv_scale, ∂n/∂u = ∂n/∂v = 0.
// A finite plane is |l_u| ≤ size.x/2, |l_v| ≤ size.y/2 (uv_scale·size = 1 shows the image once,
// exactly over uv ∈ [0, 1]²); an infinite one ignores size. Hit from both sides, n never flipped.
//
// ---- Sphere (centre c, radius r, polar axis +y): θ ∈ [0, π] the polar angle from +y,
//     p = c + r (sin θ e(φ) + cos θ y),   u = ½ + φ/(2π),   v = 1 − θ/π (1 at +y, 0 at −y),
//     n = (p − c)/r,   ∂n/∂u = (∂p/∂u)/r,   ∂n/∂v = (∂p/∂v)/r.
// At the poles ∂p/∂u = ∂n/∂u = 0 (degenerate, finite); there φ = 0.
//
// ---- Cylinder (open tube; centre c of the axis segment, unit axis a, radius R, height h):
//     p = c + R e(φ) + (v − ½) h a,   v ∈ [0, 1] from the bottom (−a) to the top rim,
//     n = e(φ) (outward),  ∂p/∂u = 2πR e'(φ), ∂p/∂v = h a,  ∂n/∂u = 2π e'(φ), ∂n/∂v = 0.
// Hit from both sides (inside and outside); rays parallel to the axis never hit.
//
// ---- Paraboloid mirror (focus F, unit axis a, focal length f > 0, aperture radius R): vertex
// V = F − f a; in the frame (a_u, a_v, a) at V the surface is z = (x² + y²)/(4f), x² + y² ≤ R²
// (so z = ρ²/(4f) − f relative to the focus), and it opens towards +a.
//            a ↑      \            /  ← rim, ρ = R
//              |        \   F    /       rays from F reflect parallel to a
//              |          `-V--´
//     (x, y) = 2R (u − ½, v − ½)       (planar: uv ∈ [0, 1]² covers the aperture's square)
//     p = V + x a_u + y a_v + (x² + y²)/(4f) a
//     n = (2f a − x a_u − y a_v)/L,  L = √(x² + y² + 4f²)   (towards the focus: concave side)
//     ∂p/∂u = 2R (a_u + x/(2f) a),    ∂n/∂u = 2R (−a_u/L − x n/L²)   (v likewise with y, a_v)
// Reflection r = d − 2(d·n)n of any ray from F is parallel to +a.
//
// ---- Torus (centre c, unit axis a, major radius R, minor radius r, 0 < r < R: ring tori only):
//     p = c + (R + r cos θ) e(φ) + r sin θ a,   θ = 2πv the minor angle,
//     v = 0 outer equator, ¼ top (+a side), ½ inner equator, ¾ bottom;  u = ½ + φ/(2π)
//     n = cos θ e(φ) + sin θ a,
//     ∂p/∂u = 2π (R + r cos θ) e'(φ),   ∂p/∂v = 2π r (−sin θ e(φ) + cos θ a),
//     ∂n/∂u = 2π cos θ e'(φ),           ∂n/∂v = 2π (−sin θ e(φ) + cos θ a).
// The ray is solved as a quartic in the torus frame, scaled by 1/(R + r) and started at the point
// of the ray nearest the centre (bounded, well-conditioned coefficients); its real roots are
// isolated between the roots of its derivatives (recursively: cubic, quadratic) and refined by
// safeguarded Newton–bisection, so the nearest root in (t_min, t_max) is found also for rays
// grazing the tube or threading the hole. A tangent (double-root) touch may be missed.
//
// ---- Hits: intersect(shape, ray, t_min, t_max) returns the nearest hit with t_min < t < t_max
// (t in units of |ray.direction|, which need not be 1), or nullopt: no hit, a non-finite or zero
// ray, a NaN range, or a degenerate shape (a non-positive or non-finite size, radius, focal length
// or uv_scale, a zero or non-finite normal/axis, a torus with r ≥ R). Results never contain NaN.
#pragma once

#include <optional>

#include <footprint/math/vec.h>
#include <footprint/math/vec3.h>
#include <footprint/scene/scene.h>
#include <footprint/scene/surface.h>

namespace footprint {

// The frame (a_u, a_v, a) of a direction (see "Axes" above): a = normalize(direction).
struct ShapeAxes {
    Vec3d u, v, axis;
};
// nullopt for a zero or non-finite direction.
std::optional<ShapeAxes> shape_axes(Vec3d direction);

// The nearest hit with t_min < t < t_max, or nullopt (see "Hits" above).
std::optional<SurfaceHit> intersect(const PlaneShape& shape, const Ray& ray, double t_min,
                                    double t_max);
std::optional<SurfaceHit> intersect(const SphereShape& shape, const Ray& ray, double t_min,
                                    double t_max);
std::optional<SurfaceHit> intersect(const CylinderShape& shape, const Ray& ray, double t_min,
                                    double t_max);
std::optional<SurfaceHit> intersect(const ParaboloidShape& shape, const Ray& ray, double t_min,
                                    double t_max);
std::optional<SurfaceHit> intersect(const TorusShape& shape, const Ray& ray, double t_min,
                                    double t_max);
// Dispatches on the variant; nullopt for the shapes rendered as meshes (is_mesh_shape), which are
// intersected elsewhere.
std::optional<SurfaceHit> intersect_analytic(const ShapeDesc& shape, const Ray& ray, double t_min,
                                             double t_max);

// The parameterisation p(u, v) and its derivatives at any finite (u, v), bounds ignored (t = 0);
// nullopt for a degenerate shape or non-finite uv.
std::optional<SurfaceHit> evaluate(const PlaneShape& shape, Vec2d uv);
std::optional<SurfaceHit> evaluate(const SphereShape& shape, Vec2d uv);
std::optional<SurfaceHit> evaluate(const CylinderShape& shape, Vec2d uv);
std::optional<SurfaceHit> evaluate(const ParaboloidShape& shape, Vec2d uv);
std::optional<SurfaceHit> evaluate(const TorusShape& shape, Vec2d uv);
// Dispatches on the variant; nullopt for the shapes rendered as meshes.
std::optional<SurfaceHit> evaluate_analytic(const ShapeDesc& shape, Vec2d uv);

}  // namespace footprint
