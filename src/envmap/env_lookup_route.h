// envmap/env_lookup_route.h — internal to the environment lookups, not a public header: the steps
// footprint → plan → probes → blend that the single lookups (environment_map.cpp) and the batches
// (environment_map_batch.cpp) share. route_lookup() takes a lookup from its footprint to one of
// three ends: done into out, one probe at the footprint's centre left to the caller (CentreProbe),
// or, given a DeferredCubeLine (the batch), a cube line on its face requested for a later read.
//
// Each step reads an EnvironmentMap or a TiledEnvironment (tiled_environment.h), `Map`, alike;
// the batch and the deferred lines are the EnvironmentMap's alone. The templates declared here
// are defined in env_lookup_general.h and instantiated by environment_map.cpp (EnvironmentMap)
// and tiled_environment.cpp (TiledEnvironment).
#pragma once

#include "envmap/env_footprint.h"
#include "envmap/env_footprint_plain.h"
#include "envmap/environment_map.h"
#include "envmap/polar_caps.h"
#include "math/mat3.h"
#include "texture/footprint_assembly.h"
#include "texture/sampling.h"

namespace footprint::env_route {

// The level of the one trilinear probe at the footprint's centre that a near-isotropic footprint
// takes (without the ellipse's axes), or −1 where the lookup takes another path: a polar cap, a
// line of probes, another filter, or the sphere map's rim.
template <class Map>
float centre_probe_lod(const Map& map, const EnvFootprint& footprint, const LookupOptions& options);

// The one trilinear probe at the footprint's centre, c at lod (centre_probe_lod()): where it is and
// which levels it reads. A single lookup reads it at once (filter_centre_probe); the batch
// requests its taps first and reads them later (batch_lookup()).
struct CentreProbe {
    EnvCoords coords;
    detail::TrilinearLevels levels;
};
template <class Map>
inline CentreProbe centre_probe(const Map& map, const EnvCoords& c, float lod,
                                const LookupOptions& options) {
    return {c, detail::trilinear_levels(lod, map.face(c.face).max_level(),
                                        single_probe_blend(options.lod_blend))};
}

// A lat-long footprint near a pole, carried onto its polar cap; invalid elsewhere.
template <class Map>
inline PolarCapFootprintOn<CapOf<Map>> cap_footprint(const Map& map,
                                                     const EnvFootprint& footprint) {
    return map.layout() == EnvLayout::latlong && map.polar_cap(0)
               ? polar_cap_footprint(map, footprint)
               : PolarCapFootprintOn<CapOf<Map>>{};
}

// What general_lookup() reads of a footprint: taken from an EnvFootprint or, without building one,
// from a PlainEnvFootprint (implicitly: either is passed as is).
struct FootprintCentre {
    EnvCoords coords;
    Sym2 matrix;
    Vec3 map_direction;

    FootprintCentre(const EnvFootprint& f)
        : coords(f.coords), matrix(f.matrix), map_direction(f.map_direction) {}
    FootprintCentre(const PlainEnvFootprint& f)
        : coords(f.coords), matrix(f.matrix), map_direction(f.map_direction) {}
    FootprintCentre(const PlainEnvFootprints4& f, int lane)
        : coords(f.coords(lane)), matrix(f.matrix(lane)), map_direction(f.map_direction(lane)) {}
};

// The cube lines on their face (environment_map.cpp's cube_line_on_face()) of at most
// kDeferredProbes probes: the batch requests them and reads them once its group's footprints are
// computed.
constexpr int kDeferredProbes = detail::kRequestedLineProbes;
using DeferredCubeLine = detail::RequestedLine<kDeferredProbes>;

// Every other lookup (a line of probes, another filter), given the footprint's cap_footprint(),
// done into out; or, given `defer` (the batch), a cube line on its face requested into it for a
// later read: then true.
template <class Map>
bool general_lookup(const Map& map, const FootprintCentre& footprint,
                    const PolarCapFootprintOn<CapOf<Map>>& cap, const LookupOptions& options,
                    float* out, DeferredCubeLine* defer);

// Footprint assembly of a planned line (general_lookup()'s, or the batch's short_plans4()):
// done into out, or, given `defer`, a cube line on its face requested into it (then true).
template <class Map>
bool lookup_plan(const Map& map, const FootprintCentre& footprint, const ProbePlan& plan,
                 const LookupOptions& options, float* out, DeferredCubeLine* defer);

// Whether the polar caps of a lat-long map take a direction (map space) rather than the map.
template <class Map>
inline bool in_caps_region(const Map& map, Vec3 map_direction) {
    return map.layout() == EnvLayout::latlong && map.polar_cap(0) &&
           in_polar_cap_region(map_direction);
}

// Form (a) on a lat-long map, for a direction within a polar cap's region (in_caps_region()): the
// cap's footprint needs only the map-space direction and its differentials (as
// compute_env_footprint() sets them), so the lat-long footprint (two atan2 and its Jacobian) is
// skipped. False, with nothing written, where the cap cannot take it (then the lat-long footprint
// decides).
template <class Map>
bool polar_cap_lookup(const Map& map, Vec3 r, Vec3 map_direction, Vec3 dr_dx, Vec3 dr_dy,
                      const IdentitySkippingRotation& to_map, const LookupOptions& options,
                      float* out);

// What route_lookup() did with a lookup: done it into out, left its centre probe to the
// caller, or (given a DeferredCubeLine) requested its cube line there for the caller to read.
enum class Routed { done, centre_probe, deferred_line };

// A lookup of a computed footprint: one probe at its centre, returned in `probe` for the caller to
// filter, a cube line on its face requested into `defer` where given, or any other lookup, done
// here into out.
template <class Map>
inline Routed route_lookup(const Map& map, const EnvFootprint& footprint,
                           const LookupOptions& options, float* out, CentreProbe& probe,
                           DeferredCubeLine* defer) {
    const float lod = centre_probe_lod(map, footprint, options);
    if (lod >= 0.0f) {
        probe = centre_probe(map, footprint.coords, lod, options);
        return Routed::centre_probe;
    }
    return general_lookup(map, footprint, cap_footprint(map, footprint), options, out, defer)
               ? Routed::deferred_line
               : Routed::done;
}

// A form (a) lookup, routed: a polar cap's (in its region), the common case in one pass
// (plain_env_footprint()), or the careful path (compute_env_footprint()). A lookup that is one
// probe at the footprint's centre (most are) is returned in `probe`, for the caller to filter (the
// batch defers it until its texels have arrived); given `defer` (the batch), a cube line on its
// face is requested there; every other lookup is done here, into out.
template <class Map>
[[gnu::always_inline]] inline Routed route_lookup(const Map& map, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                                                  const LookupOptions& options,
                                                  const IdentitySkippingRotation& to_map,
                                                  float* out, CentreProbe& probe,
                                                  DeferredCubeLine* defer) {
    const Vec3 map_direction = to_map(r);
    if (in_caps_region(map, map_direction)) {
        if (polar_cap_lookup(map, r, map_direction, dr_dx, dr_dy, to_map, options, out))
            return Routed::done;
    } else if (PlainEnvFootprint plain; plain_env_footprint(map.layout(), map.texel_scale(), r,
                                                            dr_dx, dr_dy, to_map, plain)) {
        const float lod =
            single_probe_lod(plain.matrix, options, map.face(plain.coords.face).max_level());
        if (lod >= 0.0f) {
            probe = centre_probe(map, plain.coords, lod, options);
            return Routed::centre_probe;
        }
        return general_lookup(map, plain, PolarCapFootprintOn<CapOf<Map>>{}, options, out,
                              defer)  // no caps
                   ? Routed::deferred_line
                   : Routed::done;
    }
    return route_lookup(
        map,
        compute_env_footprint(map.layout(), map.texel_scale(), r, dr_dx, dr_dy, to_map.matrix()),
        options, out, probe, defer);
}

}  // namespace footprint::env_route
