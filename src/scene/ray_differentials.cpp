// scene/ray_differentials.cpp — see ray_differentials.h.
#include "scene/ray_differentials.h"

#include <cmath>

namespace footprint {
namespace {

bool is_finite(double x) {
    return std::isfinite(x);
}

// Least-squares (a, b) with a·pu + b·pv ≈ w (ray_differentials.h, normal equations).
Vec2d solve_tangent(Vec3d pu, Vec3d pv, Vec3d w) {
    const double uu = dot(pu, pu), uv = dot(pu, pv), vv = dot(pv, pv);
    const double ru = dot(pu, w), rv = dot(pv, w);
    const double det = uu * vv - uv * uv;
    if (det > 1e-12 * uu * vv && det > 0)
        return {(vv * ru - uv * rv) / det, (uu * rv - uv * ru) / det};
    // Rank-deficient: the longer column alone.
    if (uu >= vv && uu > 0) return {ru / uu, 0};
    if (vv > 0) return {0, rv / vv};
    return {};
}

// ∂p, ∂(u, v), ∂n for one pixel direction; false if not finite.
bool transfer(const Ray& ray, const SurfaceHit& hit, Vec3d ng, double cosine, Vec3d dodx,
              Vec3d dddx, Vec3d& dpdx, Vec2d& duvdx, Vec3d& dndx) {
    const Vec3d moved = dodx + hit.t * dddx;
    const double dtdx = -dot(moved, ng) / cosine;
    dpdx = moved + dtdx * ray.direction;
    duvdx = solve_tangent(hit.dpdu, hit.dpdv, dpdx);
    dndx = duvdx.x * hit.dndu + duvdx.y * hit.dndv;
    return footprint::is_finite(dpdx) && footprint::is_finite(duvdx) && footprint::is_finite(dndx);
}

}  // namespace

SurfaceDifferentials surface_differentials(const RayDifferential& rd, const SurfaceHit& hit) {
    const Ray& ray = rd.ray;
    if (!footprint::is_finite(ray.origin) || !footprint::is_finite(ray.direction) ||
        !is_finite(hit.t) || !footprint::is_finite(hit.dpdu) || !footprint::is_finite(hit.dpdv) ||
        !footprint::is_finite(hit.dndu) || !footprint::is_finite(hit.dndv))
        return {};
    const Vec3d ng = normalize(hit.geometric_normal), d_unit = normalize(ray.direction);
    if (dot(ng, ng) == 0 || dot(d_unit, d_unit) == 0) return {};
    if (!(std::abs(dot(d_unit, ng)) >= kGrazingCosine)) return {};
    const double cosine = dot(ray.direction, ng);  // d·n_g, in the units of d
    SurfaceDifferentials out;
    if (!transfer(ray, hit, ng, cosine, rd.dodx, rd.dddx, out.dpdx, out.duvdx, out.dndx) ||
        !transfer(ray, hit, ng, cosine, rd.dody, rd.dddy, out.dpdy, out.duvdy, out.dndy))
        return {};
    out.valid = true;
    return out;
}

}  // namespace footprint
