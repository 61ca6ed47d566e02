#include "math/footprint_ellipse.h"

#include <algorithm>
#include <cmath>

#include "math/footprint_ellipse_lanes.h"

namespace footprint {

FootprintEllipse make_footprint_ellipse(const Sym2& k) {
    // Spec §2.7 (robust replacement of [S97a] eqs. 15–20).
    const EllipseLanes<float> e = footprint_ellipse_lanes(k.xx, k.xy, k.yy);
    FootprintEllipse f;
    f.matrix = k;
    f.major_radius = e.major_radius;
    f.minor_radius = e.minor_radius;
    f.major_axis = e.major_axis;
    return f;
}

FootprintEllipse make_footprint_ellipse(float major_radius, float minor_radius, float angle) {
    FootprintEllipse e;
    e.major_radius = major_radius;
    e.minor_radius = minor_radius;
    e.major_axis = {std::cos(angle), std::sin(angle)};
    e.matrix = e.from_axes();
    return e;
}

}  // namespace footprint
