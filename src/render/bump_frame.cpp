#include "render/bump_frame.h"

namespace footprint {

namespace {

Vec3 to_float(Vec3d v) {
    return vec3_cast<float>(v);
}

}  // namespace

BumpFrameAtHit bump_frame(const BumpDesc& bump, const SceneHit& hit) {
    const SurfaceHit& s = hit.surface;
    const Vec3 n = to_float(s.n);
    if (hit.tangent) {
        // glTF: e1 = the tangent made orthogonal to n, e2 = sign·(n × e1) (up the image).
        const Vec3 t = to_float(*hit.tangent);
        const Vec3 e1 = normalize(t - dot(t, n) * n);
        if (dot(e1, e1) > 0) {
            return {{e1, static_cast<float>(hit.tangent_sign) * cross(n, e1)}, 1};
        }
    }
    switch (bump.frame) {
        case BumpFrame::natural: {
            const NaturalFrame natural = make_natural_frame(to_float(s.dpdu), to_float(s.dpdv), n);
            return {tangent_frame(natural), -1};
        }
        case BumpFrame::normalized: {
            const NaturalFrame natural = make_natural_frame(to_float(s.dpdu), to_float(s.dpdv), n);
            return {{normalize(natural.s_u), normalize(natural.s_v)}, -1};
        }
        case BumpFrame::main_direction: {
            const bool own = bump.main_direction.x == 0 && bump.main_direction.y == 0 &&
                             bump.main_direction.z == 0;
            const Vec3 m = to_float(own ? s.dpdv : bump.main_direction);
            return {tangent_frame(make_orthonormal_frame(n, m)), 1};
        }
    }
    return {};
}

Sym2 covariance_in_frame(const Sym2& k, const TangentFrame& t, Vec3 e1, Vec3 e2) {
    const float a1 = dot(e1, t.t1), a2 = dot(e1, t.t2), b1 = dot(e2, t.t1), b2 = dot(e2, t.t2);
    auto form = [&](float x1, float x2, float y1, float y2) {
        return x1 * (k.xx * y1 + k.xy * y2) + x2 * (k.xy * y1 + k.yy * y2);
    };
    return {form(a1, a2, a1, a2), form(a1, a2, b1, b2), form(b1, b2, b1, b2)};
}

}  // namespace footprint
