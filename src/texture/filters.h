// texture/filters.h — the anisotropic filters behind texture_lookup() (private to texture/).
// Inputs are already sanitised: (s, t) finite and reduced, the ellipse finite and bounded.
#pragma once

#include "math/footprint_ellipse.h"
#include "texture/footprint_assembly.h"
#include "texture/sampling.h"
#include "texture/texture_lookup.h"

namespace footprint::detail {

// Footprint assembly, spec §2.8 (footprint_assembly.h). Writes pyramid.channels() floats.
void filter_footprint_assembly(const MipPyramid& pyramid, float s, float t,
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

// EWA (ewa.h).
void filter_ewa(const MipPyramid& pyramid, float s, float t, const FootprintEllipse& footprint,
                const LookupOptions& options, float* out);

}  // namespace footprint::detail
