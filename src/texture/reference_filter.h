// texture/reference_filter.h — the brute-force ground truth every filter is measured against.
//
// The ideal antialiased lookup, in footprint's measure convention (spec §2.6), is the texture's
// continuous reconstruction integrated against a Gaussian of covariance K/4 centred on the lookup:
//
//     C(c, K) = ∫ f(c + ξ) N(ξ; 0, K/4) dξ ,    f = bilinear interpolation of the level-0 texels
//
// (a σ = ½-pixel Gaussian pixel filter mapped through the Jacobian). It is computed by dense
// midpoint quadrature in the ellipse's principal frame, out to 4σ along each axis, with at least 8
// nodes per σ and at most ¼ texel between nodes, in double precision, straight from level 0: no
// pyramid, no approximation beyond the quadrature (the 4σ cut drops 0.03 % of the weight). It is
// slow — O(area) bilinear taps — and meant for tests, benchmarks' error figures and references.
#pragma once

#include <footprint/image/image.h>
#include <footprint/math/footprint_ellipse.h>
#include <footprint/texture/wrap.h>

namespace footprint {

struct ReferenceOptions {
    WrapMode wrap_s = WrapMode::repeat;
    WrapMode wrap_t = WrapMode::repeat;
    double truncation_sigmas = 4.0;
    double nodes_per_sigma = 8.0;
    double max_node_spacing = 0.25;  // level-0 texels
};

// C(c, K) for the lookup at normalised (s, t) with footprint `footprint` (level-0 texels):
// image.channels floats to `out`.
void reference_lookup(const Image& level0, double s, double t, const FootprintEllipse& footprint,
                      const ReferenceOptions& options, float* out);

}  // namespace footprint
