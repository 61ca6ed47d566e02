// envmap/env_lookup_general.h — internal to the environment lookups, not a public header: the
// definitions of env_lookup_route.h's steps, written once over the map type `Map` (an
// EnvironmentMap in memory, or a TiledEnvironment read through tiles, tiled_environment.h) and
// compiled for each in its own file (environment_map.cpp, tiled_environment.cpp). The lines of a
// map in memory that lie on one face's row-major levels take shortcuts (environment_map.cpp's
// cube_line_on_face(), latlong_path_inside(), request_cube_line_on_face()), which read the texels
// that the general path reads, in the same order.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "envmap/env_lookup_route.h"
#include "envmap/env_sampling.h"
#include "envmap/latlong_path.h"
#include "envmap/polar_caps.h"
#include "texture/footprint_assembly.h"
#include "texture/sampling.h"
#include "texture/texture_lookup_route.h"

namespace footprint::env_route {

// The anisotropy EWA allows a lat-long footprint beyond footprint assembly's probe budget
// (LookupOptions::ewa_beyond_probes). Such footprints are longer than ~15 times their probes' size
// by definition, so the texture filters' 16:1 would give back most of the blur the fallback
// removes; 64:1 keeps the mirror cylinder's 36:1 reflections sharp (docs/performance.md) and bounds
// a lookup to about 3 600 texels.
constexpr float kEwaBeyondProbesAnisotropy = 64;

// Probe placement on the sphere for the curved layouts (lat-long, sphere, paraboloid): a probe
// offset o (level-0 texels, along r1) is taken back to the tangent plane at r̂ through the inverse
// of the tangent Jacobian J_t = S·J_P·[e1 e2] and placed at the direction r̂ + J_t⁻¹o (the gnomonic
// point, so the probes lie on the great circle through r̂ — exactly what the cube's face-plane
// offsets are). In (s, t) the probes then follow the map's own curvature: latitude circles near
// the poles, the sphere map's bent iso-lines near its rim, the paraboloid's other hemisphere.
struct TangentProbes {
    bool valid = false;
    Vec3 centre, e1, e2;   // r̂ and a tangent basis
    float inv[2][2] = {};  // J_t⁻¹ (radians per texel)

    template <class Map>
    static TangentProbes at(const Map& map, Vec3 direction) {
        TangentProbes p;
        if (map.layout() == EnvLayout::cube) return p;  // face-plane offsets are already gnomonic
        const float len = std::sqrt(dot(direction, direction));
        if (!(len > 0) || !std::isfinite(len)) return p;
        p.centre = direction / len;
        tangent_basis(p.centre, p.e1, p.e2);
        const Jacobian23 j = env_jacobian(map.layout(), p.centre);
        const Vec2 scale = map.texel_scale();
        const float j11 = scale.x * dot(j.ds, p.e1), j12 = scale.x * dot(j.ds, p.e2);
        const float j21 = scale.y * dot(j.dt, p.e1), j22 = scale.y * dot(j.dt, p.e2);
        const float det = j11 * j22 - j12 * j21;
        if (!(std::fabs(det) > 1e-12f * (j11 * j11 + j12 * j12 + j21 * j21 + j22 * j22)) ||
            !std::isfinite(det))
            return p;
        p.inv[0][0] = j22 / det, p.inv[0][1] = -j12 / det;
        p.inv[1][0] = -j21 / det, p.inv[1][1] = j11 / det;
        p.valid = true;
        return p;
    }

    // The ratio of J_t's singular values (≥ 1): how much the layout stretches a round footprint,
    // the anisotropy of the ellipse of J_t⁻¹'s columns.
    float distortion() const {
        const FootprintEllipse e =
            make_footprint_ellipse(Vec2{inv[0][0], inv[1][0]}, Vec2{inv[0][1], inv[1][1]});
        const float ratio = e.major_radius / e.minor_radius;
        return std::isfinite(ratio) ? std::max(ratio, 1.0f) : 1.0f;
    }

    EnvCoords place(EnvLayout layout, Vec2 offset) const {
        const float a = inv[0][0] * offset.x + inv[0][1] * offset.y;
        const float b = inv[1][0] * offset.x + inv[1][1] * offset.y;
        return env_coords(layout, centre + a * e1 + b * e2);
    }
};

// N_max for a sphere-map line centred at `direction`: scaled by the map's distortion there
// (TangentProbes::distortion()), within kMaxProbeCount. Out of line: the rare layout.
template <class Map>
[[gnu::noinline]] int sphere_probe_limit(const Map& map, Vec3 direction, int max_probes) {
    const TangentProbes tangent = TangentProbes::at(map, direction);
    if (!tangent.valid) return max_probes;
    const float scaled =
        std::ceil(static_cast<float>(std::max(max_probes, 1)) * tangent.distortion());
    return scaled < static_cast<float>(kMaxProbeCount) ? static_cast<int>(scaled) : kMaxProbeCount;
}

// Where a probe centre (s, t) of `face` lands: itself while it lies on the face's valid region,
// otherwise the face and (s, t) that own its direction (spec §3.1 [E6s], §3.3, §3.4): cube
// probes move to the neighbour face, lat-long probes beyond a pole continue over it along the
// great circle (the seam s = 0 ≡ 1 wraps in the pyramid itself), sphere-map probes beyond the rim
// fold back into the disk, and paraboloid probes beyond the equator move to the other hemisphere.
inline EnvCoords place_probe(EnvLayout layout, int face, float s, float t) {
    switch (layout) {
        case EnvLayout::cube:
            if (s < 0 || s > 1 || t < 0 || t > 1) return cube_reproject(face, s, t);
            break;
        case EnvLayout::latlong:
            if (t < 0 || t > 1) {
                const Vec2 st = latlong_coords(latlong_direction(s, t));
                return {0, st.x, st.y};
            }
            break;
        case EnvLayout::sphere:
        case EnvLayout::paraboloid: {
            const float a = 2 * s - 1, b = 2 * t - 1;
            if (a * a + b * b > 1) return env_coords(layout, env_direction(layout, face, s, t));
            break;
        }
    }
    return {face, s, t};
}

// The shortcuts of a map in memory (environment_map.cpp; lookup_plan() says when it takes them).
// A cube line whose ends' taps lie on its centre face's levels, blended into out (false, with
// nothing written, for any other line); the same requested into `line` for a later read (false
// also for a line of more than kDeferredProbes probes); and a lat-long line on its quadratic path
// clear of the seam and the poles.
bool cube_line_on_face(const MipPyramid& face, EnvCoords c, ProbePlan plan, const float* weights,
                       detail::TrilinearLevels levels, float* out);
bool request_cube_line_on_face(const MipPyramid& face, EnvCoords c, ProbePlan plan,
                               const float* weights, detail::TrilinearLevels levels,
                               DeferredCubeLine& line);
bool latlong_path_inside(const MipPyramid& map, QuadraticPath path, int count, const float* weights,
                         detail::TrilinearLevels levels, float* out);

template <class Map>
float centre_probe_lod(const Map& map, const EnvFootprint& footprint,
                       const LookupOptions& options) {
    if (!footprint.matrix.is_finite()) return -1;
    if (map.layout() == EnvLayout::latlong && map.polar_cap(0) &&
        in_polar_cap_region(footprint.map_direction))
        return -1;
    const float width = map.texel_scale().x;
    if (map.layout() == EnvLayout::sphere && footprint.matrix.trace() > 0.25f * width * width)
        return -1;
    return single_probe_lod(footprint.matrix, options, map.face(footprint.coords.face).max_level());
}

template <class Map>
void filter_probe_taps(const Map& map, const detail::ProbeTaps& taps,
                       detail::TrilinearLevels levels, float* out) {
    detail::dispatch_stride(map.face(0).stride(), [&]<int S>() {
        detail::store(detail::blend_probe<S>(taps, levels), map.channels(), out);
    });
}

template <class Map>
void filter_centre_probe(const Map& map, const CentreProbe& probe, float* out) {
    const EnvCoords& c = probe.coords;
    filter_probe_taps(map, detail::probe_taps_on_face(map, c.face, c.s, c.t, probe.levels),
                      probe.levels, out);
}

// Flattened: everything it calls that can be inlined is, so that its probe loop compiles the same
// however much else this file inlines (otherwise GCC's unit-growth limit can push the probe taps
// out of line as the file grows).
template <class Map>
[[gnu::flatten]] bool general_lookup(const Map& map, const FootprintCentre& footprint,
                                     const PolarCapFootprintOn<CapOf<Map>>& cap,
                                     const LookupOptions& options, float* out,
                                     DeferredCubeLine* defer) {
    if (cap.valid) {
        polar_cap_filter(cap, options, out);
        return false;
    }
    const EnvCoords& c = footprint.coords;
    const auto& centre = map.face(c.face);
    const Vec2 size = map.texel_scale();
    FootprintEllipse e = footprint.matrix.is_finite() ? make_footprint_ellipse(footprint.matrix)
                                                      : FootprintEllipse{};
    if (map.layout() == EnvLayout::sphere && e.major_radius > 0.5f * size.x) {
        // §3.2: towards the singular rim the anisotropy grows without bound; clamp λ1 ≤ W/2.
        e.major_radius = 0.5f * size.x;
        e.minor_radius = std::min(e.minor_radius, e.major_radius);
        e.matrix = e.from_axes();
    }
    if (options.filter != TextureFilter::footprint_assembly) {
        texture_route::lookup_ellipse(centre, c.s, c.t, e, options, out);  // the centre face only
        return false;
    }
    // Footprint assembly (spec §2.8–2.9): probes along r1 on the centre face's (s, t) plane, each
    // placed on the face that owns its direction (place_probe), all at the centre face's lod.
    // N_max bounds the anisotropy on the sphere (environment_map.h): towards the sphere map's rim
    // the map adds up to 67:1 of its own, so a line there may take N_max × its distortion.
    const int max_probes =
        map.layout() == EnvLayout::sphere
            ? sphere_probe_limit(map, footprint.map_direction, options.max_probes)
            : options.max_probes;
    const ProbePlan plan = plan_probes(e, options.probe_rule, max_probes, centre.max_level(),
                                       options.lod_bias, options.isotropic_ratio);
    if (options.ewa_beyond_probes && map.layout() == EnvLayout::latlong &&
        exceeds_probe_budget(plan, e)) {
        LookupOptions ewa = options;
        ewa.filter = TextureFilter::ewa;
        ewa.max_anisotropy = kEwaBeyondProbesAnisotropy;
        // Larger than four maps is the map's mean whatever its size: bounded, as the GPU bounds it.
        const float limit = 4.0f * std::max(size.x, size.y);
        e.major_radius = std::min(e.major_radius, limit);
        e.minor_radius = std::min(e.minor_radius, limit);
        e.matrix = e.from_axes();
        texture_route::lookup_ellipse(centre, c.s, c.t, e, ewa, out);  // the centre face only
        return false;
    }
    return lookup_plan(map, footprint, plan, options, out, defer);
}

// Footprint assembly of a planned line (general_lookup()'s, or the batch's short_plans4()):
// done into out, or, given `defer`, a cube line on its face requested into it (then true).
template <class Map>
[[gnu::flatten]] bool lookup_plan(const Map& map, const FootprintCentre& footprint,
                                  const ProbePlan& plan, const LookupOptions& options, float* out,
                                  DeferredCubeLine* defer) {
    const EnvCoords& c = footprint.coords;
    const auto& centre = map.face(c.face);
    const Vec2 size = map.texel_scale();
    const LodBlend blend = effective_lod_blend(plan, options.lod_blend);
    float weights[kMaxProbeCount];
    probe_weights(plan, weights);
    const TangentProbes tangent =
        plan.count > 1 ? TangentProbes::at(map, footprint.map_direction) : TangentProbes{};
    const QuadraticPath path =
        map.layout() == EnvLayout::latlong && tangent.valid && plan.count > 2
            ? QuadraticPath::through(
                  c, tangent.place(EnvLayout::latlong, plan.offset(plan.count - 1)),
                  tangent.place(EnvLayout::latlong, -plan.offset(plan.count - 1)))
            : QuadraticPath{};
    // All probes read plan.lod's levels (the centre face's).
    const detail::TrilinearLevels levels =
        detail::trilinear_levels(plan.lod, centre.max_level(), blend);
    if constexpr (std::is_same_v<Map, EnvironmentMap>) {
        if (map.layout() == EnvLayout::cube) {
            // (The count is tested here too, so that longer lines skip the call.)
            if (defer && plan.count <= kDeferredProbes &&
                request_cube_line_on_face(centre, c, plan, weights, levels, *defer))
                return true;
            if (cube_line_on_face(centre, c, plan, weights, levels, out)) return false;
        }
        if (path.valid && latlong_path_inside(centre, path, plan.count, weights, levels, out))
            return false;
    }
    // Each probe is placed on the face or at the direction that owns it (place_probe,
    // TangentProbes, QuadraticPath), its taps read seamlessly.
    auto place = [&](int i) {
        const Vec2 o = plan.offset(i);
        EnvCoords p;
        if (!(path.valid && path.place(i, plan.count, p)))
            p = tangent.valid
                    ? tangent.place(map.layout(), o)
                    : place_probe(map.layout(), c.face, c.s + o.x / size.x, c.t + o.y / size.y);
        return p;
    };
    detail::dispatch_stride(centre.stride(), [&]<int S>() {
        const detail::Texel<S> result =
            detail::blend_probe_line<S>(plan.count, weights, levels, centre.stride(), [&](int i) {
                const EnvCoords p = place(i);
                return detail::probe_taps(map, p.face, p.s, p.t, levels);
            });
        detail::store(result, centre.channels(), out);
    });
    return false;
}

template <class Map>
bool polar_cap_lookup(const Map& map, Vec3 r, Vec3 map_direction, Vec3 dr_dx, Vec3 dr_dy,
                      const IdentitySkippingRotation& to_map, const LookupOptions& options,
                      float* out) {
    if (!is_finite(r)) return false;
    const bool spread = is_finite(dr_dx) && is_finite(dr_dy);  // else a point lookup
    const PolarCapFootprintOn<CapOf<Map>> cap = polar_cap_footprint(
        map, map_direction, spread ? to_map(dr_dx) : Vec3{}, spread ? to_map(dr_dy) : Vec3{});
    if (!cap.valid) return false;
    polar_cap_filter(cap, options, out);
    return true;
}

// The single-call entry points' own steps, internal to the file that includes this one (so that
// GCC may specialise them for their few callers there, as it does a file's own functions).
namespace {

// A form (a) lookup (the single-call entry points).
template <class Map>
inline void single_lookup(const Map& map, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                          const LookupOptions& options, const IdentitySkippingRotation& to_map,
                          float* out) {
    CentreProbe probe;
    if (route_lookup(map, r, dr_dx, dr_dy, options, to_map, out, probe, nullptr) ==
        Routed::centre_probe)
        filter_centre_probe(map, probe, out);
}

// environment_lookup(), both forms, and environment_bilinear() (environment_map.h).
template <class Map>
void lookup(const Map& map, const EnvFootprint& footprint, const LookupOptions& options,
            float* out) {
    CentreProbe probe;
    if (route_lookup(map, footprint, options, out, probe, nullptr) == Routed::centre_probe)
        filter_centre_probe(map, probe, out);
}

// (The vectors by reference: passed on by value, GCC copies them through the stack twice.)
template <class Map>
void lookup(const Map& map, const Vec3& r, const Vec3& dr_dx, const Vec3& dr_dy,
            const EnvLookupOptions& options, float* out) {
    if (options.rotation)
        single_lookup(map, r, dr_dx, dr_dy, options, IdentitySkippingRotation(*options.rotation),
                      out);
    else
        single_lookup(map, r, dr_dx, dr_dy, options, IdentitySkippingRotation::none(), out);
}

template <class Map>
void bilinear(const Map& map, Vec3 r, int level, float* out) {
    const EnvCoords c = env_coords(map.layout(), r);
    const auto& face = map.face(c.face);
    level = std::clamp(level, 0, face.max_level());
    detail::dispatch_stride(face.stride(), [&]<int S>() {
        detail::store(detail::env_bilinear<S>(map, c.face, level, c.s, c.t), face.channels(), out);
    });
}

}  // namespace
}  // namespace footprint::env_route
