#include "math/footprint_ellipse.h"

#include <algorithm>
#include <cmath>

namespace footprint {

FootprintEllipse make_footprint_ellipse(const Sym2& k) {
    FootprintEllipse e;
    e.matrix = k;
    // Spec §2.7 (robust replacement of [S97a] eqs. 15–20).
    // hypot's overflow care is not needed: callers bound K (a non-finite K is rejected before).
    const float w = std::sqrt((k.xx - k.yy) * (k.xx - k.yy) + 4 * k.xy * k.xy);
    const float major_sq = std::max(0.0f, 0.5f * (k.xx + k.yy + w));
    const float minor_sq = major_sq > 0 ? std::max(0.0f, k.determinant()) / major_sq : 0.0f;
    e.major_radius = std::sqrt(major_sq);
    e.minor_radius = std::min(std::sqrt(minor_sq), e.major_radius);

    // Eigenvector of the larger eigenvalue; of the two algebraically equal forms take the one
    // without cancellation (erratum 4: the paper associates the axes the wrong way round).
    Vec2 r = k.xx >= k.yy ? Vec2{k.xx - k.yy + w, 2 * k.xy} : Vec2{2 * k.xy, k.yy - k.xx + w};
    const float len = std::sqrt(r.x * r.x + r.y * r.y);
    e.major_axis = len > 0 && std::isfinite(len) ? r / len : Vec2{1, 0};
    return e;
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
