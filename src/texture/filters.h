// texture/filters.h — the anisotropic filters behind texture_lookup() (private to texture/).
// Inputs are already sanitised: (s, t) finite and reduced, the ellipse finite and bounded.
#pragma once

#include <cstddef>

#include "math/footprint_ellipse.h"
#include "texture/footprint_assembly.h"
#include "texture/sampling.h"
#include "texture/texture_lookup.h"

namespace footprint::detail {

// Footprint assembly, spec §2.8 (footprint_assembly.h), on a MipPyramid or TiledTexels
// (tiled_texels.h). Writes pyramid.channels() floats.
template <class Texels>
void filter_footprint_assembly(const Texels& pyramid, float s, float t,
                               const FootprintEllipse& footprint, const LookupOptions& options,
                               float* out);

// filter_footprint_assembly() for callers that request many lookups before reading any, so that
// their misses to memory overlap (the environment batch). A lookup of one probe is requested into
// `probe`, a line of at most kRequestedLineProbes probes inside row-major levels into `line` (their
// blend<S>() read them later, bit for bit what filter_footprint_assembly() writes); any other
// lookup is filtered into out at once.
enum class Requested { done, probe, line };
constexpr int kRequestedLineProbes = 8;
Requested request_footprint_assembly(const MipPyramid& pyramid, float s, float t,
                                     const FootprintEllipse& footprint,
                                     const LookupOptions& options, float* out,
                                     RequestedProbe& probe,
                                     RequestedLine<kRequestedLineProbes>& line);
// The same for a footprint already planned (as plan_probes() plans it for `pyramid` and `options`).
Requested request_footprint_assembly(const MipPyramid& pyramid, float s, float t,
                                     const ProbePlan& plan, const LookupOptions& options,
                                     float* out, RequestedProbe& probe,
                                     RequestedLine<kRequestedLineProbes>& line);

// The lookups of a batch's group, requested now and read later, each with where its result goes:
// at most Capacity lookups between two read()s. A caller routes each lookup with next_probe() and
// next_line() as the places to request into, add()s what the routing did, and read()s the group
// once all are routed (then the requests are spent).
template <std::size_t Capacity>
class RequestedReads {
  public:
    RequestedProbe& next_probe() { return probes_[probe_count_].probe; }
    RequestedLine<kRequestedLineProbes>& next_line() { return lines_[line_count_].line; }

    // What the lookup whose result goes to `out` did: requested into next_probe() or
    // next_line(), or done.
    void add(Requested requested, float* out) {
        if (requested == Requested::probe) probes_[probe_count_++].out = out;
        if (requested == Requested::line) lines_[line_count_++].out = out;
    }

    // Reads every request into its result: `channels` floats of texels `stride` floats wide.
    void read(int stride, int channels) {
        dispatch_stride(stride, [&]<int S>() {
            for (std::size_t i = 0; i < probe_count_; ++i)
                store(probes_[i].probe.template blend<S>(), channels, probes_[i].out);
            for (std::size_t i = 0; i < line_count_; ++i)
                store(lines_[i].line.template blend<S>(), channels, lines_[i].out);
        });
        probe_count_ = line_count_ = 0;
    }

  private:
    struct Probe {
        RequestedProbe probe;
        float* out;
    };
    struct Line {
        RequestedLine<kRequestedLineProbes> line;
        float* out;
    };
    Probe probes_[Capacity];
    Line lines_[Capacity];
    std::size_t probe_count_ = 0, line_count_ = 0;
};

// EWA (ewa.h), on a MipPyramid or TiledTexels.
template <class Texels>
void filter_ewa(const Texels& pyramid, float s, float t, const FootprintEllipse& footprint,
                const LookupOptions& options, float* out);

}  // namespace footprint::detail
