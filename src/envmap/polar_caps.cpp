#include "envmap/polar_caps.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <tbb/parallel_for.h>

#include "envmap/env_layout_detail.h"
#include "envmap/env_sampling.h"
#include "math/fast_atan2.h"
#include "texture/filters.h"
#include "texture/footprint_assembly.h"
#include "texture/texture_lookup.h"

namespace footprint {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr float kPolarCapCosine = 0.8660254f;  // cos 30°: caps serve footprints centred above 60°

}  // namespace

int polar_cap_size(int latlong_height, float resolution) {
    // A cap face of n texels has n/2 texels per radian at its centre, the lat-long map H/π.
    return std::max(2, static_cast<int>(std::ceil(resolution * 2 * latlong_height / kPi)));
}

// The cap face (2: +Y, 3: −Y) of `map` (lat-long, level 0 built): each texel the average of the
// map's bilinear reconstruction over a k × k grid in the texel, k chosen so that the samples lie
// no more than one lat-long texel apart (near the pole a cap texel spans many lat-long columns).
// The face is gnomonic, so a sample's direction is (2s − 1, ±1, ±(2t − 1)) without trigonometry,
// and its lat-long position needs two inline atan2.
Image polar_cap_image(const EnvironmentMap& map, int face, int size) {
    const int channels = map.channels();
    const Vec2 latlong_size = map.texel_scale();
    const MipPyramid& level0 = map.face(0);
    Image cap(size, size, channels);
    const float n = static_cast<float>(size);
    const float inv_pi = 1.0f / std::numbers::pi_v<float>;
    detail::dispatch_stride(level0.stride(), [&]<int S>() {
        tbb::parallel_for(0, size, [&](int y) {
            for (int x = 0; x < size; ++x) {
                const Vec3 d = cube_direction<float>(face, (x + 0.5f) / n, (y + 0.5f) / n);
                const float len = std::sqrt(dot(d, d));
                const float sin_colatitude = std::sqrt(d.x * d.x + d.z * d.z) / len;
                const float texel_angle = 2 / n * std::fabs(d.y) / len;  // the tangential side
                const float latlong_angle =
                    std::min(2 * std::numbers::pi_v<float> * sin_colatitude / latlong_size.x,
                             std::numbers::pi_v<float> / latlong_size.y);
                const int k =
                    std::clamp(static_cast<int>(std::ceil(texel_angle / latlong_angle)), 2, 64);
                detail::Texel<S> sum{};
                for (int j = 0; j < k; ++j)
                    for (int i = 0; i < k; ++i) {
                        const Vec3 p = cube_direction<float>(face, (x + (i + 0.5f) / k) / n,
                                                             (y + (j + 0.5f) / k) / n);
                        const float rho = std::sqrt(p.x * p.x + p.z * p.z);
                        const float t = fast_atan2(rho, p.y) * inv_pi;
                        const float s = 0.5f + 0.5f * fast_atan2(p.x, -p.z) * inv_pi;
                        detail::add_scaled(sum, 1.0f, detail::env_bilinear<S>(map, 0, 0, s, t));
                    }
                sum.v *= 1.0f / static_cast<float>(k * k);
                detail::store(sum, channels, cap.at(x, y));
            }
        });
    });
    return cap;
}

bool in_polar_cap_region(Vec3 r) {
    const float len = std::sqrt(dot(r, r));
    return len > 0 && std::fabs(r.y) >= kPolarCapCosine * len;
}

namespace {

// K on the cap from map-space direction spreads (pairs of columns, each pair adding (G a)(G a)ᵀ +
// (G b)(G b)ᵀ), and whether the caps can filter it, for r in the caps' region
// (in_polar_cap_region()). `latlong_trace`: tr K of the lat-long footprint, if one was computed (0
// otherwise).
PolarCapFootprint cap_footprint(const EnvironmentMap& map, Vec3 r, Vec3 dx, Vec3 dy,
                                const Vec3* roughness, float latlong_trace) {
    PolarCapFootprint f;
    f.cap = map.polar_cap(r.y > 0 ? 0 : 1);
    const float n = static_cast<float>(f.cap->width(0));
    // Face 2 or 3: |r_y| is the major axis within 30°.
    const EnvCoordsJacobian cj = r.y > 0 ? env_detail::cube_coords_and_jacobian_on<2>(r)
                                         : env_detail::cube_coords_and_jacobian_on<3>(r);
    f.coords = cj.coords;
    // K on the cap from the footprint's map-space direction differentials (env_footprint.h): this
    // keeps the anisotropy even where the lat-long footprint fell back to an isotropic one.
    const Jacobian23& jc = cj.jacobian;
    auto on_cap = [&](Vec3 w) { return Vec2{n * dot(jc.ds, w), n * dot(jc.dt, w)}; };
    f.matrix = footprint_matrix(on_cap(dx), on_cap(dy));
    if (roughness)
        f.matrix = f.matrix + footprint_matrix(on_cap(roughness[0]), on_cap(roughness[1]));
    // Non-finite input left no differentials (env_footprint.h) but a roughness-only fallback K:
    // that K lives in lat-long texels, so the lat-long path filters it.
    if (!f.matrix.is_finite() || (f.matrix.trace() == 0 && latlong_trace > 0)) return f;
    // Stay on the face: the probes and their kernels reach about 2λ1 ≤ 2√tr K from the centre.
    const float reach = (2 * std::sqrt(f.matrix.trace()) + 1) / n;
    const EnvCoords& c = f.coords;
    f.valid = c.s - reach >= 0 && c.s + reach <= 1 && c.t - reach >= 0 && c.t + reach <= 1;
    return f;
}

}  // namespace

PolarCapFootprint polar_cap_footprint(const EnvironmentMap& map, const EnvFootprint& footprint) {
    if (!in_polar_cap_region(footprint.map_direction)) return {};
    const Vec3 roughness[2] = {footprint.map_roughness1, footprint.map_roughness2};
    return cap_footprint(map, footprint.map_direction, footprint.map_dr_dx, footprint.map_dr_dy,
                         roughness, footprint.matrix.trace());
}

PolarCapFootprint polar_cap_footprint(const EnvironmentMap& map, Vec3 map_direction, Vec3 map_dr_dx,
                                      Vec3 map_dr_dy) {
    return cap_footprint(map, map_direction, map_dr_dx, map_dr_dy, nullptr, 0.0f);
}

void polar_cap_filter(const PolarCapFootprint& f, const LookupOptions& options, float* out) {
    const MipPyramid& cap = *f.cap;
    const EnvCoords& c = f.coords;
    // One probe (the common case): no ellipse axes.
    const float lod = single_probe_lod(f.matrix, options, cap.max_level());
    if (lod >= 0.0f) {
        detail::dispatch_stride(cap.stride(), [&]<int S>() {
            detail::store(detail::sample_trilinear<S>(cap, c.s, c.t, lod,
                                                      single_probe_blend(options.lod_blend)),
                          cap.channels(), out);
        });
        return;
    }
    const FootprintEllipse ellipse = make_footprint_ellipse(f.matrix);
    if (options.filter == TextureFilter::footprint_assembly) {
        // A valid cap footprint is finite and on the face, so texture_lookup()'s sanitising
        // (reducing (s, t), bounding the ellipse) has nothing to do.
        detail::filter_footprint_assembly(cap, c.s, c.t, ellipse, options, out);
        return;
    }
    texture_lookup(cap, c.s, c.t, ellipse, options, out);
}

}  // namespace footprint
