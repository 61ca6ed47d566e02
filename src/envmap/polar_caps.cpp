#include "envmap/polar_caps.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/parallel.h"
#include "envmap/env_layout_detail.h"
#include "envmap/env_sampling.h"
#include "envmap/tiled_environment.h"
#include "math/fast_atan2.h"
#include "math/lanes.h"
#include "texture/filters.h"
#include "texture/footprint_assembly_lanes.h"
#include "texture/texture_lookup.h"
#include "texture/texture_lookup_route.h"

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
        parallel_for_each(0, size, [&](int y) {
            for (int x = 0; x < size; ++x) {
                const Vec3 d = cube_direction<float>(face, (x + 0.5f) / n, (y + 0.5f) / n);
                const float len = std::sqrt(dot(d, d));
                const float sin_colatitude = std::sqrt(d.x * d.x + d.z * d.z) / len;
                const float texel_angle = 2 / n * std::fabs(d.y) / len;  // the tangential side
                const float latlong_angle =
                    std::min(2 * std::numbers::pi_v<float> * sin_colatitude / latlong_size.x,
                             std::numbers::pi_v<float> / latlong_size.y);
                // Clamped as a float: at the pole itself (the centre texel of a cap of odd size)
                // latlong_angle is 0 and the ratio infinite, which no int holds.
                const int k = static_cast<int>(
                    std::clamp(std::ceil(texel_angle / latlong_angle), 2.0f, 64.0f));
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

// K on a cap face of n texels from map-space direction spreads, for any lane type (math/lanes.h):
// pairs of columns (dx, dy), and the roughness pair where given, each adding (G a)(G a)ᵀ +
// (G b)(G b)ᵀ with G = n·J, J at (s, t) on the face (finished). `valid` where K is finite and the
// probes stay on the face: they and their kernels reach about 2λ1 ≤ 2√tr K from the centre.
template <class F>
struct CapMatrixLanes {
    Sym2Lanes<F> matrix;
    MaskOf<F> valid;
};

template <class F>
inline CapMatrixLanes<F> cap_matrix(F s, F t, const Jacobian23T<F>& j, const Vec3T<F>& dx,
                                    const Vec3T<F>& dy, const Vec3T<F>* roughness, F n) {
    using std::sqrt;
    auto on_cap = [&](const Vec3T<F>& w) { return Vec2T<F>{n * dot(j.ds, w), n * dot(j.dt, w)}; };
    Sym2Lanes<F> k = footprint_matrix_lanes(on_cap(dx), on_cap(dy));
    if (roughness) {
        const Sym2Lanes<F> kr = footprint_matrix_lanes(on_cap(roughness[0]), on_cap(roughness[1]));
        k = {k.xx + kr.xx, k.xy + kr.xy, k.yy + kr.yy};
    }
    const F zero(0), one(1);
    const F reach = (F(2) * sqrt(k.xx + k.yy) + one) / n;
    const MaskOf<F> on_face =
        (s - reach >= zero) & (s + reach <= one) & (t - reach >= zero) & (t + reach <= one);
    return {k, MaskOf<F>(is_finite(k.xx) & is_finite(k.xy) & is_finite(k.yy) & on_face)};
}

// K on the cap and whether the caps can filter it, for r in the caps' region
// (in_polar_cap_region()). `latlong_trace`: tr K of the lat-long footprint, if one was computed (0
// otherwise).
template <class Map>
PolarCapFootprintOn<CapOf<Map>> cap_footprint(const Map& map, Vec3 r, Vec3 dx, Vec3 dy,
                                              const Vec3* roughness, float latlong_trace) {
    PolarCapFootprintOn<CapOf<Map>> f;
    f.cap = map.polar_cap(r.y > 0 ? 0 : 1);
    // Face 2 or 3: |r_y| is the major axis within 30°.
    const EnvCoordsJacobian cj = r.y > 0 ? env_detail::cube_coords_and_jacobian_on<2>(r)
                                         : env_detail::cube_coords_and_jacobian_on<3>(r);
    f.coords = cj.coords;
    // K from the footprint's map-space direction differentials (env_footprint.h): this keeps the
    // anisotropy even where the lat-long footprint fell back to an isotropic one.
    const CapMatrixLanes<float> k = cap_matrix(cj.coords.s, cj.coords.t, cj.jacobian, dx, dy,
                                               roughness, static_cast<float>(f.cap->width(0)));
    f.matrix = {k.matrix.xx, k.matrix.xy, k.matrix.yy};
    // Non-finite input left no differentials (env_footprint.h) but a roughness-only fallback K:
    // that K lives in lat-long texels, so the lat-long path filters it.
    f.valid = k.valid && !(f.matrix.trace() == 0 && latlong_trace > 0);
    return f;
}

}  // namespace

template <class Map>
PolarCapFootprintOn<CapOf<Map>> polar_cap_footprint(const Map& map, const EnvFootprint& footprint) {
    if (!in_polar_cap_region(footprint.map_direction)) return {};
    const Vec3 roughness[2] = {footprint.map_roughness1, footprint.map_roughness2};
    return cap_footprint(map, footprint.map_direction, footprint.map_dr_dx, footprint.map_dr_dy,
                         roughness, footprint.matrix.trace());
}

template <class Map>
PolarCapFootprintOn<CapOf<Map>> polar_cap_footprint(const Map& map, Vec3 map_direction,
                                                    Vec3 map_dr_dx, Vec3 map_dr_dy) {
    return cap_footprint(map, map_direction, map_dr_dx, map_dr_dy, nullptr, 0.0f);
}

template PolarCapFootprint polar_cap_footprint(const EnvironmentMap&, const EnvFootprint&);
template PolarCapFootprint polar_cap_footprint(const EnvironmentMap&, Vec3, Vec3, Vec3);
template PolarCapFootprintOn<detail::TiledTexels> polar_cap_footprint(
    const detail::TiledEnvironment&, const EnvFootprint&);
template PolarCapFootprintOn<detail::TiledTexels> polar_cap_footprint(
    const detail::TiledEnvironment&, Vec3, Vec3, Vec3);

namespace {

// polar_cap_filter() at the footprint's single_probe_lod(), or given `probe` and `line` (caps in
// memory only), polar_cap_request().
template <class Cap>
inline detail::Requested filter_cap(const PolarCapFootprintOn<Cap>& f, float lod,
                                    const LookupOptions& options, float* out,
                                    detail::RequestedProbe* probe,
                                    detail::RequestedLine<detail::kRequestedLineProbes>* line) {
    constexpr bool in_memory = std::is_same_v<Cap, MipPyramid>;
    const Cap& cap = *f.cap;
    const EnvCoords& c = f.coords;
    // One probe (the common case): no ellipse axes.
    if (lod >= 0.0f) {
        if (in_memory && probe) {
            const detail::TrilinearLevels levels = detail::trilinear_levels(
                lod, cap.max_level(), single_probe_blend(options.lod_blend));
            *probe = {detail::probe_taps(cap, c.s, c.t, levels), levels};
            probe->request(cap.stride());
            return detail::Requested::probe;
        }
        detail::dispatch_stride(cap.stride(), [&]<int S>() {
            detail::store(detail::sample_trilinear<S>(cap, c.s, c.t, lod,
                                                      single_probe_blend(options.lod_blend)),
                          cap.channels(), out);
        });
        return detail::Requested::done;
    }
    const FootprintEllipse ellipse = make_footprint_ellipse(f.matrix);
    if (options.filter == TextureFilter::footprint_assembly) {
        // A valid cap footprint is finite and on the face, so texture_lookup()'s sanitising
        // (reducing (s, t), bounding the ellipse) has nothing to do.
        if constexpr (in_memory) {
            if (probe)
                return detail::request_footprint_assembly(cap, c.s, c.t, ellipse, options, out,
                                                          *probe, *line);
        }
        detail::filter_footprint_assembly(cap, c.s, c.t, ellipse, options, out);
        return detail::Requested::done;
    }
    texture_route::lookup_ellipse(cap, c.s, c.t, ellipse, options, out);
    return detail::Requested::done;
}

}  // namespace

template <class Cap>
void polar_cap_filter(const PolarCapFootprintOn<Cap>& f, const LookupOptions& options, float* out) {
    filter_cap(f, single_probe_lod(f.matrix, options, f.cap->max_level()), options, out, nullptr,
               nullptr);
}

template void polar_cap_filter(const PolarCapFootprint&, const LookupOptions&, float*);
template void polar_cap_filter(const PolarCapFootprintOn<detail::TiledTexels>&,
                               const LookupOptions&, float*);

detail::Requested polar_cap_request(const PolarCapFootprint& f, float lod,
                                    const LookupOptions& options, float* out,
                                    detail::RequestedProbe& probe,
                                    detail::RequestedLine<detail::kRequestedLineProbes>& line) {
    return filter_cap(f, lod, options, out, &probe, &line);
}

// in_polar_cap_region(), the environment's polar_cap_lookup() and cap_footprint() (form (a)),
// four lanes at once: the same steps over Float4 (math/lanes.h), with prepare()'s rare cases left
// to the scalar functions.
void polar_cap_footprints4(const EnvironmentMap& map, const EnvRayDifferential* rays,
                           const IdentitySkippingRotation& to_map, const LookupOptions& options,
                           PolarCapFootprints4& out) {
    using namespace env_detail;
    const Vec3T<Float4> m = rotate(to_map, gather(rays, &EnvRayDifferential::direction));
    const Float4 len = sqrt(dot(m, m)), zero(0.0f);
    const Mask4 region = (len > zero) & (abs(m.y) >= Float4(kPolarCapCosine) * len);
    out.region = region.bits();
    out.valid = 0;
    if (out.region == 0) return;
    // prepare()'s common case (A r finite, so r is finite as polar_cap_lookup() requires), on the
    // faces 2 (+Y) and 3 (−Y).
    const PreparedLanes<Float4> p = prepare_lanes(m);
    const Mask4 north = m.y > zero, all = region | !region, none = !all;
    const CubeCoordsJacobianLanes<Float4> c =
        cube_coords_and_jacobian_lanes(p.r, CubeAxes<Float4>{none, all, none, !north});
    // The map-space differentials, zero where either is not finite (a point lookup).
    const Vec3T<Float4> dx = gather(rays, &EnvRayDifferential::d_dx);
    const Vec3T<Float4> dy = gather(rays, &EnvRayDifferential::d_dy);
    const Mask4 spread = is_finite_lanes(dx) & is_finite_lanes(dy);
    const Vec3T<Float4> wx = select(spread, rotate(to_map, dx), Vec3T<Float4>{});
    const Vec3T<Float4> wy = select(spread, rotate(to_map, dy), Vec3T<Float4>{});
    const MipPyramid& cap = *map.polar_cap(0);  // both caps are the same size
    const CapMatrixLanes<Float4> k = cap_matrix(c.s, c.t, scaled(c.j, p.scale), wx, wy,
                                                static_cast<const Vec3T<Float4>*>(nullptr),
                                                Float4(static_cast<float>(cap.width(0))));
    out.valid = (region & p.common & k.valid).bits();
    if (out.valid == 0) return;
    select(north, Int4(0), Int4(1)).store(out.cap);
    c.s.store(out.s);
    c.t.store(out.t);
    k.matrix.xx.store(out.xx);
    k.matrix.xy.store(out.xy);
    k.matrix.yy.store(out.yy);
    (has_single_probe_rule(options)
         ? single_probe_lod(k.matrix.xx, k.matrix.xy, k.matrix.yy, options.lod_bias,
                            cap.max_level(), options.isotropic_ratio)
         : Float4(-1.0f))
        .store(out.lod);
}

}  // namespace footprint
