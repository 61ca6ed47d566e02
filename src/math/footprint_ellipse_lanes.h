// math/footprint_ellipse_lanes.h — (private) make_footprint_ellipse()'s arithmetic written once
// over a lane type (math/lanes.h): one footprint, or four at once for the batches' plans
// (texture/footprint_assembly.cpp). make_footprint_ellipse() is its float instance.
#pragma once

#include "math/lanes.h"

namespace footprint {

// λ1² and λ2² of K = [[xx, xy], [xy, yy]] (spec §2.7) without square roots of λ, and
// w = √((xx − yy)² + 4xy²), from which the eigenvector comes. major_sq is ½(tr K + w) itself, which
// may round below 0 for a K at 0; minor_sq is 0 unless major_sq > 0. hypot's overflow care is not
// needed: callers bound K (a non-finite K is rejected before).
template <class F>
struct AxesSquared {
    F w, major_sq, minor_sq;
};
template <class F>
inline AxesSquared<F> axes_squared(F xx, F xy, F yy) {
    using std::sqrt;
    const F zero(0);
    const F w = sqrt((xx - yy) * (xx - yy) + F(4) * xy * xy);
    const F major_sq = F(0.5) * (xx + yy + w);
    const F determinant = xx * yy - xy * xy;
    return {w, major_sq, select(major_sq > zero, max_like_std(zero, determinant) / major_sq, zero)};
}

// The ellipse's semi-axes λ1 ≥ λ2 and the unit major axis r1: the eigenvector of the larger
// eigenvalue, of its two algebraically equal forms the one without cancellation (erratum 4: the
// paper associates the axes the wrong way round); (1, 0) where it has no direction.
template <class F>
struct EllipseLanes {
    F major_radius, minor_radius;
    Vec2T<F> major_axis;
};
template <class F>
inline EllipseLanes<F> footprint_ellipse_lanes(F xx, F xy, F yy) {
    using std::sqrt;
    const F zero(0), one(1), two(2);
    const AxesSquared<F> a = axes_squared(xx, xy, yy);
    const F l1 = sqrt(max_like_std(zero, a.major_sq));
    const F l2 = min_like_std(sqrt(a.minor_sq), l1);
    const MaskOf<F> xx_major = xx >= yy;
    const Vec2T<F> r{select(xx_major, xx - yy + a.w, two * xy),
                     select(xx_major, two * xy, yy - xx + a.w)};
    const F len = sqrt(r.x * r.x + r.y * r.y);
    const MaskOf<F> unit = (len > zero) & is_finite(len);
    return {l1, l2, {select(unit, r.x / len, one), select(unit, r.y / len, zero)}};
}

}  // namespace footprint
