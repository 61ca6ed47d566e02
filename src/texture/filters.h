// texture/filters.h — the anisotropic filters behind texture_lookup() (private to texture/).
// Inputs are already sanitised: (s, t) finite and reduced, the ellipse finite and bounded.
#pragma once

#include "math/footprint_ellipse.h"
#include "texture/texture_lookup.h"

namespace footprint::detail {

// Footprint assembly, spec §2.8 (footprint_assembly.h). Writes pyramid.channels() floats.
void filter_footprint_assembly(const MipPyramid& pyramid, float s, float t,
                               const FootprintEllipse& footprint, const LookupOptions& options,
                               float* out);

// EWA (ewa.h).
void filter_ewa(const MipPyramid& pyramid, float s, float t, const FootprintEllipse& footprint,
                const LookupOptions& options, float* out);

}  // namespace footprint::detail
