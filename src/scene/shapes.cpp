// scene/shapes.cpp — see shapes.h for the parameterisations and conventions.
#include "scene/shapes.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

namespace footprint {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2 * kPi;

bool positive(double x) {
    return std::isfinite(x) && x > 0;
}

// The ray with a unit direction: a point at τ along it is at t = τ/length along the input ray.
struct UnitRay {
    Vec3d origin, direction;
    double length = 1;
};

std::optional<UnitRay> unit_ray(const Ray& ray, double t_min, double t_max) {
    if (!is_finite(ray.origin) || !is_finite(ray.direction)) return std::nullopt;
    if (!(t_min < t_max)) return std::nullopt;  // also NaN
    const double len = length(ray.direction);
    if (!positive(len)) return std::nullopt;
    const Vec3d d = normalize(ray.direction);
    if (!is_finite(d) || dot(d, d) == 0) return std::nullopt;
    return UnitRay{ray.origin, d, len};
}

// t for τ along the unit ray, if t_min < t < t_max.
std::optional<double> ray_t(const UnitRay& ray, double tau, double t_min, double t_max) {
    const double t = tau / ray.length;
    if (!std::isfinite(t) || !(t > t_min && t < t_max)) return std::nullopt;
    return t;
}

Vec3d point_at(const Ray& ray, double t) {
    return ray.origin + t * ray.direction;
}

// (cos, sin) of the angle of the 2-vector (x along cos, y along sin); (1, 0) for the zero vector.
struct CosSin {
    double c = 1, s = 0;
};
CosSin cos_sin(double along_cos, double along_sin) {
    const double h = std::hypot(along_cos, along_sin);
    if (!(h > 0) || !std::isfinite(h)) return {};
    return {along_cos / h, along_sin / h};
}

// Radial direction e(φ) and its derivative e'(φ) about `axes` (shapes.h, bodies of revolution).
Vec3d radial(const ShapeAxes& a, CosSin phi) {
    return phi.s * a.u - phi.c * a.v;
}
Vec3d radial_derivative(const ShapeAxes& a, CosSin phi) {
    return phi.c * a.u + phi.s * a.v;
}

// φ of the point q (relative to the centre), measured from −a_v towards a_u; φ = 0 on the axis.
CosSin azimuth(const ShapeAxes& a, Vec3d q) {
    return cos_sin(-dot(q, a.v), dot(q, a.u));
}

// u = ½ + φ/(2π) ∈ [0, 1].
double azimuth_u(CosSin phi) {
    if (phi.s == 0 && phi.c > 0) return 0.5;  // includes the axis (avoids atan2(±0, ±0))
    return 0.5 + std::atan2(phi.s, phi.c) / kTwoPi;
}

SurfaceHit make_hit(Vec3d p, Vec3d n, Vec3d dpdu, Vec3d dpdv, Vec3d dndu, Vec3d dndv, Vec2d uv) {
    SurfaceHit h;
    h.p = p;
    h.n = n;
    h.dpdu = dpdu;
    h.dpdv = dpdv;
    h.dndu = dndu;
    h.dndv = dndv;
    h.uv = uv;
    h.geometric_normal = n;
    return h;
}

// ---- Plane.

struct PlaneFrame {
    ShapeAxes axes;
    double scale;
};

std::optional<PlaneFrame> plane_frame(const PlaneShape& s) {
    if (!is_finite(s.center) || !positive(s.uv_scale)) return std::nullopt;
    if (!s.infinite && !(positive(s.size.x) && positive(s.size.y))) return std::nullopt;
    const std::optional<ShapeAxes> axes = shape_axes(s.normal);
    if (!axes) return std::nullopt;
    return PlaneFrame{*axes, s.uv_scale};
}

SurfaceHit plane_geometry(const PlaneShape& s, const PlaneFrame& f, Vec2d uv) {
    const Vec3d dpdu = f.axes.u / f.scale, dpdv = f.axes.v / f.scale;
    const Vec3d p = s.center + (uv.x - 0.5) * dpdu + (uv.y - 0.5) * dpdv;
    return make_hit(p, f.axes.axis, dpdu, dpdv, {}, {}, uv);
}

// ---- Sphere: axes (+x, −z, +y).

constexpr ShapeAxes kSphereAxes{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};

bool valid(const SphereShape& s) {
    return is_finite(s.center) && positive(s.radius);
}

// θ from +y as (cos θ, sin θ), φ as (cos φ, sin φ).
SurfaceHit sphere_geometry(const SphereShape& s, CosSin theta, CosSin phi, Vec2d uv) {
    const ShapeAxes& a = kSphereAxes;
    const double r = s.radius;
    const Vec3d e = radial(a, phi), de = radial_derivative(a, phi);
    const Vec3d n = theta.s * e + theta.c * a.axis;
    // u = ½ + φ/(2π), v = 1 − θ/π:  ∂p/∂u = 2π ∂p/∂φ,  ∂p/∂v = −π ∂p/∂θ.
    const Vec3d dpdu = (kTwoPi * r * theta.s) * de;
    const Vec3d dpdv = (-kPi * r) * (theta.c * e - theta.s * a.axis);
    return make_hit(s.center + r * n, n, dpdu, dpdv, dpdu / r, dpdv / r, uv);
}

// ---- Cylinder.

struct CylinderFrame {
    ShapeAxes axes;
};

std::optional<CylinderFrame> cylinder_frame(const CylinderShape& s) {
    if (!is_finite(s.center) || !positive(s.radius) || !positive(s.height)) return std::nullopt;
    const std::optional<ShapeAxes> axes = shape_axes(s.axis);
    if (!axes) return std::nullopt;
    return CylinderFrame{*axes};
}

SurfaceHit cylinder_geometry(const CylinderShape& s, const ShapeAxes& a, CosSin phi, Vec2d uv) {
    const Vec3d e = radial(a, phi), de = radial_derivative(a, phi);
    const Vec3d p = s.center + s.radius * e + ((uv.y - 0.5) * s.height) * a.axis;
    return make_hit(p, e, (kTwoPi * s.radius) * de, s.height * a.axis, kTwoPi * de, {}, uv);
}

// ---- Paraboloid.

struct ParaboloidFrame {
    ShapeAxes axes;
    Vec3d vertex;
};

std::optional<ParaboloidFrame> paraboloid_frame(const ParaboloidShape& s) {
    if (!is_finite(s.focus) || !positive(s.focal_length) || !positive(s.radius))
        return std::nullopt;
    const std::optional<ShapeAxes> axes = shape_axes(s.axis);
    if (!axes) return std::nullopt;
    const Vec3d vertex = s.focus - s.focal_length * axes->axis;
    if (!is_finite(vertex)) return std::nullopt;
    return ParaboloidFrame{*axes, vertex};
}

// At local (x, y) = 2R (u − ½, v − ½) (shapes.h).
SurfaceHit paraboloid_geometry(const ParaboloidShape& s, const ParaboloidFrame& f, double x,
                               double y, Vec2d uv) {
    const ShapeAxes& a = f.axes;
    const double fl = s.focal_length, two_r = 2 * s.radius;
    const Vec3d p = f.vertex + x * a.u + y * a.v + ((x * x + y * y) / (4 * fl)) * a.axis;
    const double len = std::sqrt(x * x + y * y + 4 * fl * fl);
    const Vec3d n = ((2 * fl) * a.axis - x * a.u - y * a.v) / len;
    const Vec3d dpdu = two_r * (a.u + (x / (2 * fl)) * a.axis);
    const Vec3d dpdv = two_r * (a.v + (y / (2 * fl)) * a.axis);
    // n = N/L, ∂N/∂x = −a_u, ∂L/∂x = x/L:  ∂n/∂x = −a_u/L − x n/L².
    const Vec3d dndu = two_r * (-1 / len * a.u - (x / (len * len)) * n);
    const Vec3d dndv = two_r * (-1 / len * a.v - (y / (len * len)) * n);
    return make_hit(p, n, dpdu, dpdv, dndu, dndv, uv);
}

// ---- Torus.

struct TorusFrame {
    ShapeAxes axes;
};

std::optional<TorusFrame> torus_frame(const TorusShape& s) {
    if (!is_finite(s.center) || !positive(s.major_radius) || !positive(s.minor_radius))
        return std::nullopt;
    if (!(s.minor_radius < s.major_radius) || !std::isfinite(s.major_radius + s.minor_radius))
        return std::nullopt;
    const std::optional<ShapeAxes> axes = shape_axes(s.axis);
    if (!axes) return std::nullopt;
    return TorusFrame{*axes};
}

SurfaceHit torus_geometry(const TorusShape& s, const ShapeAxes& a, CosSin phi, CosSin theta,
                          Vec2d uv) {
    const double big = s.major_radius, small = s.minor_radius;
    const Vec3d e = radial(a, phi), de = radial_derivative(a, phi);
    const Vec3d n = theta.c * e + theta.s * a.axis;
    const Vec3d dn_dtheta = -theta.s * e + theta.c * a.axis;
    const Vec3d p = s.center + big * e + small * n;
    return make_hit(p, n, (kTwoPi * (big + small * theta.c)) * de, (kTwoPi * small) * dn_dtheta,
                    (kTwoPi * theta.c) * de, kTwoPi * dn_dtheta, uv);
}

// ---- Real roots of small polynomials: Σ c[i] s^i, degree n ≤ 4, c[n] ≠ 0.

double poly_eval(const double* c, int n, double x) {
    double r = c[n];
    for (int i = n - 1; i >= 0; --i) r = r * x + c[i];
    return r;
}

// The root in (a, b) of a polynomial with p(a) = fa and p(b) of opposite, nonzero signs:
// Newton steps, replaced by bisection whenever they leave the bracket.
double bracketed_root(const double* c, int n, double a, double b, double fa) {
    double dc[4] = {};
    for (int i = 0; i < n; ++i) dc[i] = (i + 1) * c[i + 1];
    double x = 0.5 * (a + b);
    for (int it = 0; it < 200; ++it) {
        const double f = poly_eval(c, n, x);
        if (f == 0) return x;
        if ((f < 0) == (fa < 0)) {
            a = x;
            fa = f;
        } else {
            b = x;
        }
        double next = x - f / poly_eval(dc, n - 1, x);
        if (!(next > a && next < b)) next = 0.5 * (a + b);  // also NaN
        if (next == x || b - a <= 4e-16 * std::max(std::abs(a), std::abs(b))) return next;
        x = next;
    }
    return x;
}

// The real roots in [lo, hi], ascending (a double root is found only where it is exactly 0 or
// isolated by sign changes); returns their number (≤ n). Between consecutive roots of p' the
// polynomial is monotonic, so each such interval holds at most one root, bracketed by signs.
int real_roots(const double* c, int n, double lo, double hi, double* roots) {
    if (n == 1) {
        const double r = -c[0] / c[1];
        if (!(r >= lo && r <= hi)) return 0;
        roots[0] = r;
        return 1;
    }
    double dc[4] = {};
    for (int i = 0; i < n; ++i) dc[i] = (i + 1) * c[i + 1];
    double points[6];
    const int critical = real_roots(dc, n - 1, lo, hi, points + 1);
    points[0] = lo;
    points[critical + 1] = hi;
    int count = 0;
    double fa = poly_eval(c, n, lo);
    if (fa == 0) roots[count++] = lo;
    for (int k = 0; k <= critical && count < n; ++k) {
        const double a = points[k], b = points[k + 1];
        const double fb = poly_eval(c, n, b);
        if (fb == 0) {
            if (count == 0 || roots[count - 1] != b) roots[count++] = b;
        } else if (fa != 0 && (fa < 0) != (fb < 0)) {
            roots[count++] = bracketed_root(c, n, a, b, fa);
        }
        fa = fb;
    }
    return count;
}

}  // namespace

std::optional<ShapeAxes> shape_axes(Vec3d direction) {
    const Vec3d a = normalize(direction);
    if (dot(a, a) == 0) return std::nullopt;
    const Vec3d w = std::abs(a.y) < 0.9 ? Vec3d{0, 1, 0} : Vec3d{0, 0, -1};
    const Vec3d v = normalize(w - dot(w, a) * a);
    return ShapeAxes{cross(v, a), v, a};
}

// ---- evaluate.

std::optional<SurfaceHit> evaluate(const PlaneShape& shape, Vec2d uv) {
    const std::optional<PlaneFrame> f = plane_frame(shape);
    if (!f || !is_finite(uv)) return std::nullopt;
    return plane_geometry(shape, *f, uv);
}

std::optional<SurfaceHit> evaluate(const SphereShape& shape, Vec2d uv) {
    if (!valid(shape) || !is_finite(uv)) return std::nullopt;
    const double theta = kPi * (1 - uv.y), phi = kTwoPi * (uv.x - 0.5);
    return sphere_geometry(shape, {std::cos(theta), std::sin(theta)},
                           {std::cos(phi), std::sin(phi)}, uv);
}

std::optional<SurfaceHit> evaluate(const CylinderShape& shape, Vec2d uv) {
    const std::optional<CylinderFrame> f = cylinder_frame(shape);
    if (!f || !is_finite(uv)) return std::nullopt;
    const double phi = kTwoPi * (uv.x - 0.5);
    return cylinder_geometry(shape, f->axes, {std::cos(phi), std::sin(phi)}, uv);
}

std::optional<SurfaceHit> evaluate(const ParaboloidShape& shape, Vec2d uv) {
    const std::optional<ParaboloidFrame> f = paraboloid_frame(shape);
    if (!f || !is_finite(uv)) return std::nullopt;
    const double two_r = 2 * shape.radius;
    return paraboloid_geometry(shape, *f, two_r * (uv.x - 0.5), two_r * (uv.y - 0.5), uv);
}

std::optional<SurfaceHit> evaluate(const TorusShape& shape, Vec2d uv) {
    const std::optional<TorusFrame> f = torus_frame(shape);
    if (!f || !is_finite(uv)) return std::nullopt;
    const double phi = kTwoPi * (uv.x - 0.5), theta = kTwoPi * uv.y;
    return torus_geometry(shape, f->axes, {std::cos(phi), std::sin(phi)},
                          {std::cos(theta), std::sin(theta)}, uv);
}

// ---- intersect.

std::optional<SurfaceHit> intersect(const PlaneShape& shape, const Ray& ray, double t_min,
                                    double t_max) {
    const std::optional<PlaneFrame> f = plane_frame(shape);
    const std::optional<UnitRay> r = unit_ray(ray, t_min, t_max);
    if (!f || !r) return std::nullopt;
    const Vec3d n = f->axes.axis;
    const double cosine = dot(r->direction, n);
    if (cosine == 0) return std::nullopt;
    const std::optional<double> t =
        ray_t(*r, dot(shape.center - r->origin, n) / cosine, t_min, t_max);
    if (!t) return std::nullopt;
    const Vec3d p = point_at(ray, *t);
    const Vec3d q = p - shape.center;
    const Vec2d local{dot(q, f->axes.u), dot(q, f->axes.v)};
    if (!is_finite(local)) return std::nullopt;
    if (!shape.infinite &&
        (std::abs(local.x) > 0.5 * shape.size.x || std::abs(local.y) > 0.5 * shape.size.y))
        return std::nullopt;
    SurfaceHit hit = plane_geometry(shape, *f, shape.uv_scale * local + Vec2d{0.5, 0.5});
    hit.t = *t;
    hit.p = p;
    return hit;
}

std::optional<SurfaceHit> intersect(const SphereShape& shape, const Ray& ray, double t_min,
                                    double t_max) {
    const std::optional<UnitRay> r = unit_ray(ray, t_min, t_max);
    if (!valid(shape) || !r) return std::nullopt;
    // |f + τ d|² = R², f = o − c, |d| = 1. The discriminant as R² − |f − (f·d) d|² and the near
    // root as c/q avoid cancellation (Haines et al., "Precision improvements for ray/sphere
    // intersection", Ray Tracing Gems ch. 7).
    const double radius = shape.radius;
    const Vec3d f = r->origin - shape.center, d = r->direction;
    const double b = dot(f, d);
    const Vec3d l = f - b * d;
    const double disc = (radius - length(l)) * (radius + length(l));
    if (!(disc >= 0)) return std::nullopt;
    const double c = (length(f) - radius) * (length(f) + radius);
    const double q = -b - std::copysign(std::sqrt(disc), b);
    double tau[2] = {q, q != 0 ? c / q : 0};
    if (tau[0] > tau[1]) std::swap(tau[0], tau[1]);
    for (const double tau_k : tau) {
        const std::optional<double> t = ray_t(*r, tau_k, t_min, t_max);
        if (!t) continue;
        const Vec3d p = point_at(ray, *t);
        const Vec3d qv = p - shape.center;
        const ShapeAxes& a = kSphereAxes;
        const double rho = std::hypot(dot(qv, a.u), dot(qv, a.v));
        const CosSin phi = azimuth(a, qv);
        const CosSin theta = cos_sin(dot(qv, a.axis), rho);
        const Vec2d uv{azimuth_u(phi), 1 - std::atan2(theta.s, theta.c) / kPi};
        SurfaceHit hit = sphere_geometry(shape, theta, phi, uv);
        hit.t = *t;
        hit.p = p;
        return hit;
    }
    return std::nullopt;
}

std::optional<SurfaceHit> intersect(const CylinderShape& shape, const Ray& ray, double t_min,
                                    double t_max) {
    const std::optional<CylinderFrame> fr = cylinder_frame(shape);
    const std::optional<UnitRay> r = unit_ray(ray, t_min, t_max);
    if (!fr || !r) return std::nullopt;
    const ShapeAxes& a = fr->axes;
    // In the plane ⟂ a: |f⊥ + τ d⊥|² = R², solved as the sphere's quadratic with σ = τ|d⊥|.
    const Vec3d f = r->origin - shape.center;
    const Vec2d f2{dot(f, a.u), dot(f, a.v)}, d2{dot(r->direction, a.u), dot(r->direction, a.v)};
    const double d_len = length(d2);
    if (!(d_len > 1e-300)) return std::nullopt;  // parallel to the axis
    const Vec2d dn = d2 / d_len;
    const double radius = shape.radius;
    const double b = dot(f2, dn);
    const double l = length(f2 - b * dn), fl = length(f2);
    const double disc = (radius - l) * (radius + l);
    if (!(disc >= 0)) return std::nullopt;
    const double c = (fl - radius) * (fl + radius);
    const double q = -b - std::copysign(std::sqrt(disc), b);
    double sigma[2] = {q, q != 0 ? c / q : 0};
    if (sigma[0] > sigma[1]) std::swap(sigma[0], sigma[1]);
    for (const double sigma_k : sigma) {
        const std::optional<double> t = ray_t(*r, sigma_k / d_len, t_min, t_max);
        if (!t) continue;
        const Vec3d p = point_at(ray, *t);
        const Vec3d qv = p - shape.center;
        const double along = dot(qv, a.axis);
        if (!(std::abs(along) <= 0.5 * shape.height)) continue;
        const CosSin phi = azimuth(a, qv);
        SurfaceHit hit =
            cylinder_geometry(shape, a, phi, {azimuth_u(phi), along / shape.height + 0.5});
        hit.t = *t;
        hit.p = p;
        return hit;
    }
    return std::nullopt;
}

std::optional<SurfaceHit> intersect(const ParaboloidShape& shape, const Ray& ray, double t_min,
                                    double t_max) {
    const std::optional<ParaboloidFrame> fr = paraboloid_frame(shape);
    const std::optional<UnitRay> r = unit_ray(ray, t_min, t_max);
    if (!fr || !r) return std::nullopt;
    const ShapeAxes& a = fr->axes;
    const double fl = shape.focal_length;
    // In the frame at the vertex: g(τ) = x(τ)² + y(τ)² − 4f z(τ) = A τ² + B τ + C = 0.
    const Vec3d q0 = r->origin - fr->vertex;
    const Vec3d o{dot(q0, a.u), dot(q0, a.v), dot(q0, a.axis)};
    const Vec3d d{dot(r->direction, a.u), dot(r->direction, a.v), dot(r->direction, a.axis)};
    const double qa = d.x * d.x + d.y * d.y;
    const double qb = 2 * (o.x * d.x + o.y * d.y) - 4 * fl * d.z;
    const double qc = o.x * o.x + o.y * o.y - 4 * fl * o.z;
    double tau[2];
    int count = 0;
    if (qa == 0) {  // parallel to the axis: one root
        if (qb == 0) return std::nullopt;
        tau[count++] = -qc / qb;
    } else {
        const double disc = qb * qb - 4 * qa * qc;
        if (!(disc >= 0)) return std::nullopt;
        const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
        if (q == 0) {
            tau[count++] = 0;
        } else {
            tau[count++] = q / qa;  // may be ±inf for a nearly axial ray: rejected below
            tau[count++] = qc / q;
        }
    }
    if (count == 2 && tau[0] > tau[1]) std::swap(tau[0], tau[1]);
    const auto g = [&](double s) {
        const Vec3d p = o + s * d;
        return p.x * p.x + p.y * p.y - 4 * fl * p.z;
    };
    for (int k = 0; k < count; ++k) {
        // One Newton step on the direct form of g (the expanded quadratic cancels for rays
        // from far away), kept only if it lowers the residual.
        double s = tau[k];
        const Vec3d ps = o + s * d;
        const double dg = 2 * (ps.x * d.x + ps.y * d.y) - 4 * fl * d.z;
        const double polished = s - g(s) / dg;
        if (std::isfinite(polished) && std::abs(g(polished)) < std::abs(g(s))) s = polished;
        const std::optional<double> t = ray_t(*r, s, t_min, t_max);
        if (!t) continue;
        const Vec3d p = point_at(ray, *t);
        const Vec3d qv = p - fr->vertex;
        const double x = dot(qv, a.u), y = dot(qv, a.v);
        if (!(x * x + y * y <= shape.radius * shape.radius)) continue;
        const double two_r = 2 * shape.radius;
        SurfaceHit hit = paraboloid_geometry(shape, *fr, x, y, {x / two_r + 0.5, y / two_r + 0.5});
        hit.t = *t;
        hit.p = p;
        return hit;
    }
    return std::nullopt;
}

std::optional<SurfaceHit> intersect(const TorusShape& shape, const Ray& ray, double t_min,
                                    double t_max) {
    const std::optional<TorusFrame> fr = torus_frame(shape);
    const std::optional<UnitRay> r = unit_ray(ray, t_min, t_max);
    if (!fr || !r) return std::nullopt;
    const ShapeAxes& a = fr->axes;
    // Torus frame (x, y along a_u, a_v; z along a), lengths in units of B = R + r, the origin
    // moved to the ray's point nearest the centre (τ0): |o| ≤ 1 wherever the ray can hit, and
    //   (|P|² + R² − r²)² − 4R² (P_x² + P_y²) = 0,   P = o + s d,  |d| = 1,  τ = τ0 + B s
    // expands with m = o·d, k = |o|² + R² − r² to
    //   s⁴ + 4m s³ + (4m² + 2k − 4R² d⊥²) s² + (4mk − 8R² o⊥·d⊥) s + k² − 4R² o⊥² = 0.
    const double bound = shape.major_radius + shape.minor_radius;
    const Vec3d q0 = r->origin - shape.center;
    const Vec3d o0{dot(q0, a.u), dot(q0, a.v), dot(q0, a.axis)};
    const Vec3d d{dot(r->direction, a.u), dot(r->direction, a.v), dot(r->direction, a.axis)};
    const double tau0 = -dot(o0, d);
    const Vec3d o = (o0 + tau0 * d) / bound;
    const double oo = dot(o, o);
    if (!(oo <= 1 + 1e-12)) return std::nullopt;  // misses the bounding sphere
    const double half_chord = std::sqrt(std::max(0.0, 1 - oo)) * (1 + 1e-9) + 1e-12;
    const double s_lo = std::max(-half_chord, (t_min * r->length - tau0) / bound);
    const double s_hi = std::min(half_chord, (t_max * r->length - tau0) / bound);
    if (!(s_lo <= s_hi)) return std::nullopt;
    const double big = shape.major_radius / bound, small = shape.minor_radius / bound;
    const double big2 = big * big;
    const double m = dot(o, d);
    const double k = oo + (big - small) * (big + small);
    const double d_perp2 = d.x * d.x + d.y * d.y, od_perp = o.x * d.x + o.y * d.y,
                 o_perp2 = o.x * o.x + o.y * o.y;
    const double c[5] = {k * k - 4 * big2 * o_perp2, 4 * m * k - 8 * big2 * od_perp,
                         4 * m * m + 2 * k - 4 * big2 * d_perp2, 4 * m, 1};
    double roots[8];
    const int count = real_roots(c, 4, s_lo, s_hi, roots);
    for (int i = 0; i < count; ++i) {
        const std::optional<double> t = ray_t(*r, tau0 + bound * roots[i], t_min, t_max);
        if (!t) continue;
        const Vec3d p = point_at(ray, *t);
        const Vec3d qv = p - shape.center;
        const CosSin phi = azimuth(a, qv);
        const double rho = std::hypot(dot(qv, a.u), dot(qv, a.v));
        const CosSin theta = cos_sin(rho - shape.major_radius, dot(qv, a.axis));
        double v = std::atan2(theta.s, theta.c) / kTwoPi;
        if (v < 0) v += 1;
        SurfaceHit hit = torus_geometry(shape, a, phi, theta, {azimuth_u(phi), v});
        hit.t = *t;
        hit.p = p;
        return hit;
    }
    return std::nullopt;
}

std::optional<SurfaceHit> intersect_analytic(const ShapeDesc& shape, const Ray& ray, double t_min,
                                             double t_max) {
    return std::visit(
        [&](const auto& s) -> std::optional<SurfaceHit> {
            if constexpr (is_mesh_shape<std::decay_t<decltype(s)>>) {
                return std::nullopt;
            } else {
                return intersect(s, ray, t_min, t_max);
            }
        },
        shape);
}

std::optional<SurfaceHit> evaluate_analytic(const ShapeDesc& shape, Vec2d uv) {
    return std::visit(
        [&](const auto& s) -> std::optional<SurfaceHit> {
            if constexpr (is_mesh_shape<std::decay_t<decltype(s)>>) {
                return std::nullopt;
            } else {
                return evaluate(s, uv);
            }
        },
        shape);
}

}  // namespace footprint
