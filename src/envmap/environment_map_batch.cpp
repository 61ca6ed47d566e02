// The batched environment lookups (environment_lookup_batch()): the steps of env_lookup_route.h,
// their texels requested for a group of lookups and read once the group is routed.
#include <algorithm>
#include <cstddef>
#include <span>

#include "envmap/env_lookup_route.h"
#include "envmap/env_sampling.h"
#include "envmap/environment_map.h"
#include "envmap/polar_caps.h"
#include "math/float4.h"
#include "texture/footprint_assembly_lanes.h"
#include "texture/sampling.h"

namespace footprint {
namespace env_route {
namespace {

// What a batch does with a routed lookup whose result goes to `result`: a deferred line is added
// to `reads`, a centre probe's taps are requested into it, a lookup done needs nothing.
template <std::size_t Capacity>
inline void add_routed(const EnvironmentMap& map, Routed routed, const CentreProbe& probe,
                       int stride, float* result, detail::RequestedReads<Capacity>& reads) {
    switch (routed) {
        case Routed::done:
            break;
        case Routed::deferred_line:
            reads.add(detail::Requested::line, result);
            break;
        case Routed::centre_probe: {
            const EnvCoords& c = probe.coords;
            detail::RequestedProbe& requested = reads.next_probe();
            requested = {detail::probe_taps(map, c.face, c.s, c.t, probe.levels), probe.levels};
            requested.request(stride);
            reads.add(detail::Requested::probe, result);
            break;
        }
    }
}

// The footprints of four rays of a batch, computed at once (math/float4.h), each lane exactly what
// route_lookup() computes for its ray: the polar-cap footprint where a lat-long map's caps take it,
// the plain footprint (plain_env_footprint()) of a cube or lat-long map elsewhere, the
// single-probe lods, and the plans of the short lines among them. A lane that none of them takes
// goes the scalar way (route_lookup()).
struct FourFootprints {
    // What every group computes the same way: the map's and the options' constants.
    struct Setting {
        bool four_at_once;  // a cube or lat-long map
        bool caps;          // a lat-long map with polar caps
        bool rule_b;        // has_single_probe_rule(): else every lod is −1 and no plan is made
        int max_level, cap_max_level;  // every face's, both caps'

        Setting(const EnvironmentMap& map, const LookupOptions& options)
            : four_at_once(map.layout() == EnvLayout::cube || map.layout() == EnvLayout::latlong),
              caps(map.layout() == EnvLayout::latlong && map.polar_cap(0)),
              rule_b(has_single_probe_rule(options)),
              max_level(map.face(0).max_level()),
              cap_max_level(caps ? map.polar_cap(0)->max_level() : 0) {}
    };

    PolarCapFootprints4 capped;  // region: the caps' lanes; valid: the lanes they take
    PlainEnvFootprints4 plain;   // outside the caps' region
    float lod[4];                // the plain footprints' single-probe lods (< 0: a line)
    ShortPlans4 plans, cap_plans;

    void compute(const EnvironmentMap& map, const EnvRayDifferential* rays,
                 const IdentitySkippingRotation& to_map, const LookupOptions& options,
                 const Setting& setting) {
        plain.plain = plans.planned = 0;
        if (setting.caps) {
            polar_cap_footprints4(map, rays, to_map, options, capped);
            cap_plans.planned = 0;
            if (setting.rule_b &&
                (capped.valid & (Float4::load(capped.lod) < Float4(0.0f)).bits()) != 0)
                short_plans4(Float4::load(capped.xx), Float4::load(capped.xy),
                             Float4::load(capped.yy), options.probe_rule, options.max_probes,
                             setting.cap_max_level, options.lod_bias, options.isotropic_ratio,
                             cap_plans);
            if (capped.region == 0xf) return;  // no lane for plain_env_footprint()
        }
        plain_env_footprints4(map.layout(), map.texel_scale(), rays, to_map, plain);
        if (!setting.rule_b) {
            Float4(-1.0f).store(lod);
            return;
        }
        const Float4 xx = Float4::load(plain.xx), xy = Float4::load(plain.xy),
                     yy = Float4::load(plain.yy);
        const Float4 lods = single_probe_lod(xx, xy, yy, options.lod_bias, setting.max_level,
                                             options.isotropic_ratio);
        lods.store(lod);
        if (((lods < Float4(0.0f)).bits() & plain.plain) != 0)
            short_plans4(xx, xy, yy, options.probe_rule, options.max_probes, setting.max_level,
                         options.lod_bias, options.isotropic_ratio, plans);
    }

    bool cap_takes(int lane) const { return capped.valid >> lane & 1; }
    bool plain_takes(int lane) const {
        return (plain.plain >> lane & 1) && !(capped.region >> lane & 1);
    }
};

// Form (a) lookups of many rays (the batch entry points).
inline void batch_lookup(const EnvironmentMap& map, std::span<const EnvRayDifferential> rays,
                         const LookupOptions& options, const IdentitySkippingRotation& to_map,
                         float* out) {
    // The footprints are computed four at a time (FourFootprints). The lookups that are one probe
    // (most of them: at the footprint's centre, or on a polar cap), the cube lines on their face
    // (DeferredCubeLine) and the short lines on a polar cap are deferred: their texels are
    // requested, and they are filtered once the group's footprints are all computed, when the
    // texels have arrived. Enough lookups in flight to cover a miss to memory, few enough that
    // their texels are still cached when read. Every other lookup is done at once.
    constexpr std::size_t kGroup = 16;
    const int channels = map.channels();
    detail::RequestedReads<kGroup> reads;
    const int stride = map.face(0).stride();  // the caps' too (the same channels)
    const FourFootprints::Setting setting(map, options);
    FourFootprints footprints[kGroup / 4];
    for (std::size_t first = 0; first < rays.size(); first += kGroup) {
        const std::size_t count = std::min(kGroup, rays.size() - first);
        if (setting.four_at_once)
            for (std::size_t lane = 0; lane < count; lane += 4) {
                EnvRayDifferential tail[4];  // the last lanes, padded with the last ray
                const EnvRayDifferential* four = &rays[first + lane];
                if (count - lane < 4) {
                    for (std::size_t i = 0; i < 4; ++i)
                        tail[i] = rays[first + std::min(lane + i, count - 1)];
                    four = tail;
                }
                footprints[lane / 4].compute(map, four, to_map, options, setting);
            }
        for (std::size_t i = 0; i < count; ++i) {
            const EnvRayDifferential& ray = rays[first + i];
            float* result = out + (first + i) * channels;
            const FourFootprints& f = footprints[i / 4];
            const int lane = static_cast<int>(i % 4);
            if (setting.caps && f.cap_takes(lane)) {
                // route_lookup()'s polar cap branch, from the lane.
                const PolarCapFootprint cap = f.capped.footprint(map, lane);
                reads.add(f.cap_plans.planned >> lane & 1
                              ? detail::request_footprint_assembly(
                                    *cap.cap, cap.coords.s, cap.coords.t, f.cap_plans.plan(lane),
                                    options, result, reads.next_probe(), reads.next_line())
                              : polar_cap_request(cap, f.capped.lod[lane], options, result,
                                                  reads.next_probe(), reads.next_line()),
                          result);
                continue;
            }
            CentreProbe probe;
            Routed routed;
            if (setting.four_at_once && f.plain_takes(lane)) {
                // route_lookup()'s plain branch, from the lane.
                DeferredCubeLine* defer = &reads.next_line();
                if (f.lod[lane] >= 0.0f) {
                    probe = centre_probe(map, f.plain.coords(lane), f.lod[lane], options);
                    routed = Routed::centre_probe;
                } else if (f.plans.planned >> lane & 1) {
                    routed = lookup_plan(map, FootprintCentre(f.plain, lane), f.plans.plan(lane),
                                         options, result, defer)
                                 ? Routed::deferred_line
                                 : Routed::done;
                } else {
                    routed = general_lookup(map, FootprintCentre(f.plain, lane),
                                            PolarCapFootprint{}, options, result, defer)
                                 ? Routed::deferred_line
                                 : Routed::done;
                }
            } else {
                routed = route_lookup(map, ray.direction, ray.d_dx, ray.d_dy, options, to_map,
                                      result, probe, &reads.next_line());
            }
            add_routed(map, routed, probe, stride, result, reads);
        }
        reads.read(stride, channels);
    }
}

// environment_lookup_batch() of computed footprints.
inline void footprint_batch_lookup(const EnvironmentMap& map,
                                   std::span<const EnvFootprint> footprints,
                                   const LookupOptions& options, float* out) {
    // Each footprint routed as the single call routes it, its centre probe, cube line or polar
    // cap's probe or line read with its group's (as batch_lookup() reads them). On a cube or
    // lat-long map the lines off the polar caps are set aside and planned four at a time
    // (short_plans4(), each lane plan_probes()' plan bit for bit), as batch_lookup() plans them.
    constexpr std::size_t kGroup = 16;
    const int channels = map.channels();
    const int stride = map.face(0).stride();
    const FourFootprints::Setting setting(map, options);
    const bool plan_four_at_once = setting.four_at_once && setting.rule_b;
    detail::RequestedReads<kGroup> reads;
    std::size_t lines[kGroup];  // the group's footprints set aside to be planned four at a time
    for (std::size_t first = 0; first < footprints.size(); first += kGroup) {
        const std::size_t count = std::min(kGroup, footprints.size() - first);
        std::size_t line_count = 0;
        for (std::size_t i = first; i < first + count; ++i) {
            // route_lookup()'s steps, with a polar cap's probe or line requested as well.
            const EnvFootprint& footprint = footprints[i];
            float* result = out + i * channels;
            if (const float lod = centre_probe_lod(map, footprint, options); lod >= 0.0f) {
                add_routed(map, Routed::centre_probe,
                           centre_probe(map, footprint.coords, lod, options), stride, result,
                           reads);
                continue;
            }
            if (plan_four_at_once && footprint.matrix.is_finite() &&
                !in_caps_region(map, footprint.map_direction)) {
                lines[line_count++] = i;  // general_lookup() without a cap, below
                continue;
            }
            const PolarCapFootprint cap = cap_footprint(map, footprint);
            if (cap.valid) {  // polar_cap_filter(), requested
                reads.add(polar_cap_request(
                              cap, single_probe_lod(cap.matrix, options, cap.cap->max_level()),
                              options, result, reads.next_probe(), reads.next_line()),
                          result);
                continue;
            }
            if (general_lookup(map, footprint, cap, options, result, &reads.next_line()))
                reads.add(detail::Requested::line, result);
        }
        // The lines set aside (cap_footprint() invalid off the caps): general_lookup()'s plan,
        // four at a time where short_plans4() takes it.
        for (std::size_t k = 0; k < line_count; k += 4) {
            float xx[4], xy[4], yy[4];  // the last lanes padded with the last line
            for (std::size_t j = 0; j < 4; ++j) {
                const Sym2& m = footprints[lines[std::min(k + j, line_count - 1)]].matrix;
                xx[j] = m.xx, xy[j] = m.xy, yy[j] = m.yy;
            }
            ShortPlans4 plans;
            short_plans4(Float4::load(xx), Float4::load(xy), Float4::load(yy), options.probe_rule,
                         options.max_probes, setting.max_level, options.lod_bias,
                         options.isotropic_ratio, plans);
            for (std::size_t j = 0; j < 4 && k + j < line_count; ++j) {
                const std::size_t i = lines[k + j];
                float* result = out + i * channels;
                const bool deferred =
                    plans.planned >> j & 1
                        ? lookup_plan(map, footprints[i], plans.plan(static_cast<int>(j)), options,
                                      result, &reads.next_line())
                        : general_lookup(map, footprints[i], PolarCapFootprint{}, options, result,
                                         &reads.next_line());
                if (deferred) reads.add(detail::Requested::line, result);
            }
        }
        reads.read(stride, channels);
    }
}

}  // namespace
}  // namespace env_route

void environment_lookup_batch(const EnvironmentMap& map, std::span<const EnvRayDifferential> rays,
                              const EnvLookupOptions& options, float* out) {
    if (options.rotation)
        env_route::batch_lookup(map, rays, options, IdentitySkippingRotation(*options.rotation),
                                out);
    else
        env_route::batch_lookup(map, rays, options, IdentitySkippingRotation::none(), out);
}

void environment_lookup_batch(const EnvironmentMap& map, std::span<const EnvFootprint> footprints,
                              const LookupOptions& options, float* out) {
    env_route::footprint_batch_lookup(map, footprints, options, out);
}

}  // namespace footprint
