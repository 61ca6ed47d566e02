// math/footprint_ellipse.h — the pixel footprint as an ellipse in texel space.
//
// A pixel's footprint on a texture is described by the 2×2 screen→texel Jacobian
//     D = ∂(X,Y)/∂(x,y) = [ ∂X/∂x  ∂X/∂y ]      (level-0 texels per pixel, spec §1)
//                         [ ∂Y/∂x  ∂Y/∂y ]
// whose columns are the texel-space images of one pixel step in x and in y. The footprint
// matrix is K = D Dᵀ (spec §2.4; the paper prints DᵀD, which has the right eigenvalues but the
// eigenvectors of *screen* space: erratum 1). The footprint ellipse is ξᵀ K⁻¹ ξ = 1, ξ the
// texel offset from the centre; it is exactly the image of the unit pixel circle under D.
//
// Its principal axes (semi-axes λ1 ≥ λ2, unit major direction r1) come from the robust closed
// form of spec §2.7, never from eq. (17) of [S97a], which cancels catastrophically in float:
//     W   = hypot(k11 − k22, 2 k12)
//     λ1² = (k11 + k22 + W)/2
//     λ2² = max(0, k11 k22 − k12²) / λ1²
//     r1  = normalize(k11 − k22 + W, 2 k12)   if k11 ≥ k22
//           normalize(2 k12, k22 − k11 + W)   otherwise;   (1, 0) if that vector is 0
// The form covers k12 = 0, k11 = k22, rank-1 K and K = 0.
//
// Measures (spec §2.6): K is the "one pixel step" ellipse. A filter that honours it has a
// kernel covariance of K/4 (a σ = ½-pixel Gaussian pixel filter), which is what footprint
// assembly (Rule B) and EWA implement and what the tests check.
#pragma once

#include <footprint/math/vec.h>

namespace footprint {

// Symmetric 2×2 matrix [[xx, xy], [xy, yy]]: a footprint matrix K or a covariance.
struct Sym2 {
    float xx = 0, xy = 0, yy = 0;

    float trace() const { return xx + yy; }
    float determinant() const { return xx * yy - xy * xy; }
    bool is_finite() const { return std::isfinite(xx) && std::isfinite(xy) && std::isfinite(yy); }
    // vᵀ M v
    float quadratic_form(Vec2 v) const {
        return xx * v.x * v.x + 2 * xy * v.x * v.y + yy * v.y * v.y;
    }
};

inline Sym2 operator+(const Sym2& a, const Sym2& b) {
    return {a.xx + b.xx, a.xy + b.xy, a.yy + b.yy};
}
inline Sym2 operator*(float s, const Sym2& a) {
    return {s * a.xx, s * a.xy, s * a.yy};
}

// The footprint matrix K = D Dᵀ for a Jacobian with columns d_dx = ∂(X,Y)/∂x, d_dy = ∂(X,Y)/∂y.
inline Sym2 footprint_matrix(Vec2 d_dx, Vec2 d_dy) {
    return {d_dx.x * d_dx.x + d_dy.x * d_dy.x,  //
            d_dx.x * d_dx.y + d_dy.x * d_dy.y,  //
            d_dx.y * d_dx.y + d_dy.y * d_dy.y};
}

// The outer product s · v vᵀ.
inline Sym2 outer(Vec2 v, float s = 1) {
    return {s * v.x * v.x, s * v.x * v.y, s * v.y * v.y};
}

struct FootprintEllipse {
    Sym2 matrix;             // K, level-0 texels²
    float major_radius = 0;  // λ1, level-0 texels
    float minor_radius = 0;  // λ2 ≤ λ1
    Vec2 major_axis{1, 0};   // r1, unit length

    Vec2 minor_axis() const { return {-major_axis.y, major_axis.x}; }  // r2 = (−r1.y, r1.x)
    float anisotropy() const { return minor_radius > 0 ? major_radius / minor_radius : INFINITY; }
    // The matrix rebuilt from the axes: λ1² r1 r1ᵀ + λ2² r2 r2ᵀ.
    Sym2 from_axes() const {
        return outer(major_axis, major_radius * major_radius) +
               outer(minor_axis(), minor_radius * minor_radius);
    }
};

// Principal axes of K by the robust form of spec §2.7 (eqs. 15–20 of [S97a], corrected).
// K must be finite and positive semi-definite; a slightly indefinite K (rounding) gives λ2 = 0.
FootprintEllipse make_footprint_ellipse(const Sym2& k);

// Convenience: the ellipse of K = D Dᵀ.
inline FootprintEllipse make_footprint_ellipse(Vec2 d_dx, Vec2 d_dy) {
    return make_footprint_ellipse(footprint_matrix(d_dx, d_dy));
}

// An ellipse with given semi-axes and major direction angle θ (radians) — for tests and benchmarks.
FootprintEllipse make_footprint_ellipse(float major_radius, float minor_radius, float angle);

}  // namespace footprint
