// texture/texture_lookup_route.h — internal to texture_lookup(), not a public header: the routing
// of a lookup by its coordinates (route_lookup()) that the single call (texture_lookup.cpp) and
// the batch (texture_lookup_batch.cpp) share, and the simple filters it ends in.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "math/fast_log2.h"
#include "math/footprint_ellipse.h"
#include "texture/filters.h"
#include "texture/footprint_assembly.h"
#include "texture/sampling.h"
#include "texture/texture_lookup.h"
#include "texture/tiled_texels.h"

namespace footprint::texture_route {

// Each function here reads a MipPyramid or TiledTexels (tiled_texels.h), `Texels`, alike.

// Footprints beyond a few texture sizes all read the coarsest level; bounding them keeps every
// loop finite and every float in range.
template <class Texels>
FootprintEllipse bounded(const Texels& pyramid, FootprintEllipse e) {
    const float limit = 4.0f * static_cast<float>(std::max(pyramid.width(0), pyramid.height(0)));
    if (!e.matrix.is_finite() || !std::isfinite(e.major_radius) || !std::isfinite(e.minor_radius) ||
        !is_finite(e.major_axis))
        return FootprintEllipse{};  // non-finite derivatives: a point sample
    if (e.major_radius > limit || e.minor_radius > limit) {
        e.major_radius = std::min(e.major_radius, limit);
        e.minor_radius = std::min(e.minor_radius, limit);
        e.matrix = e.from_axes();
    }
    return e;
}

// The nearest level-0 texel of reduced (s, t).
template <class Texels>
void lookup_nearest(const Texels& pyramid, float s, float t, float* out) {
    const int w = pyramid.width(0), h = pyramid.height(0);
    const int x =
        wrap_index(static_cast<int>(std::floor(s * static_cast<float>(w))), w, pyramid.wrap_s());
    const int y =
        wrap_index(static_cast<int>(std::floor(t * static_cast<float>(h))), h, pyramid.wrap_t());
    const float* texel = detail::level_texel(pyramid, 0, x, y);
    for (int c = 0; c < pyramid.channels(); ++c) out[c] = texel[c];
}

// One trilinear probe at reduced (s, t).
template <class Texels>
void lookup_trilinear(const Texels& pyramid, float s, float t, float lod, LodBlend blend,
                      float* out) {
    detail::dispatch_stride(pyramid.stride(), [&]<int S>() {
        detail::store(detail::sample_trilinear<S>(pyramid, s, t, lod, blend), pyramid.channels(),
                      out);
    });
}

// texture_lookup(pyramid, s, t, footprint, options, out) of either source (texture_lookup.cpp).
template <class Texels>
void lookup_ellipse(const Texels& pyramid, float s, float t, const FootprintEllipse& footprint,
                    const LookupOptions& options, float* out);

// The lookups a batch requests now and reads later (texture_lookup_batch()).
struct Requests {
    detail::RequestedProbe& probe;
    detail::RequestedLine<detail::kRequestedLineProbes>& line;
};

// texture_lookup(coords): the lookup done into out (Requested::done), or, given `requests` (the
// batch), a lookup that is one bilinear or trilinear probe — magnification, the GL rule, a
// near-isotropic footprint — requested into requests.probe, and a short footprint-assembly line
// into requests.line, for the caller to read (bit for bit what is done into out without them).
template <class Texels>
detail::Requested route_lookup(const Texels& pyramid, const TextureCoords& c,
                               const LookupOptions& options, float* out, const Requests* requests) {
    using detail::Requested;
    // One trilinear probe at reduced (s, t): lookup_trilinear(), or requested.
    auto trilinear = [&](float s, float t, float lod, LodBlend blend) {
        if (!requests) {
            lookup_trilinear(pyramid, s, t, lod, blend, out);
            return Requested::done;
        }
        const detail::TrilinearLevels levels =
            detail::trilinear_levels(lod, pyramid.max_level(), blend);
        requests->probe = {detail::probe_taps(pyramid, s, t, levels), levels};
        requests->probe.request(pyramid.stride());
        return Requested::probe;
    };
    if (!std::isfinite(c.s) || !std::isfinite(c.t)) {  // the ellipse overload returns the mean
        lookup_ellipse(pyramid, c.s, c.t, FootprintEllipse{}, options, out);
        return Requested::done;
    }
    const float w0 = static_cast<float>(pyramid.width(0)),
                h0 = static_cast<float>(pyramid.height(0));
    const Vec2 d_dx{c.dsdx * w0, c.dtdx * h0}, d_dy{c.dsdy * w0, c.dtdy * h0};  // columns of D
    const float len_x2 = dot(d_dx, d_dx), len_y2 = dot(d_dy, d_dy);
    // No footprint needed: the level-0 baselines, and magnification — a footprint inside one texel
    // (trace K = |D|²_F ≤ 1 ⇒ λ1 ≤ 1) is one bilinear probe at level 0 for every mipmapping filter.
    const bool isotropic =
        options.filter == TextureFilter::trilinear || options.filter == TextureFilter::brilinear;
    const bool mipmapped = isotropic || options.filter == TextureFilter::footprint_assembly ||
                           options.filter == TextureFilter::ewa;
    const bool magnified = mipmapped && len_x2 + len_y2 <= 1.0f && options.lod_bias <= 0.0f;
    if (options.filter == TextureFilter::nearest || options.filter == TextureFilter::bilinear ||
        magnified) {
        const float s = reduce_coordinate(c.s, pyramid.wrap_s()),
                    t = reduce_coordinate(c.t, pyramid.wrap_t());
        if (options.filter == TextureFilter::nearest) {
            lookup_nearest(pyramid, s, t, out);
            return Requested::done;
        }
        if (requests)  // level 0's bilinear sample is the trilinear probe at lod 0 (w = 0)
            return trilinear(s, t, 0.0f, LodBlend::linear);
        detail::lookup_level0_bilinear(pyramid, s, t, out);
        return Requested::done;
    }
    if (!std::isfinite(len_x2 + len_y2) && std::isfinite(c.dsdx) && std::isfinite(c.dtdx) &&
        std::isfinite(c.dsdy) && std::isfinite(c.dtdy)) {
        // Finite derivatives whose footprint overflows float: larger than any texture.
        constexpr float kHuge = 1e30f;
        lookup_ellipse(pyramid, c.s, c.t, make_footprint_ellipse(kHuge, kHuge, 0.0f), options, out);
        return Requested::done;
    }
    if (isotropic && std::isfinite(len_x2 + len_y2)) {
        // GL rule (OpenGL 4.6 §8.14.1): ρ = max(|∂(X,Y)/∂x|, |∂(X,Y)/∂y|), lod = log2 ρ.
        const float rho_sq = std::max(len_x2, len_y2);
        const float lod = std::clamp(0.5f * fast_log2(std::max(rho_sq, 1e-30f)) + options.lod_bias,
                                     0.0f, static_cast<float>(pyramid.max_level()));
        return trilinear(reduce_coordinate(c.s, pyramid.wrap_s()),
                         reduce_coordinate(c.t, pyramid.wrap_t()),
                         options.filter == TextureFilter::brilinear
                             ? detail::brilinear_lod(lod, options.brilinear_band)
                             : lod,
                         LodBlend::linear);
    }
    // Near-isotropic footprints are one trilinear probe: skip the ellipse's axes.
    const float lod = single_probe_lod(footprint_matrix(d_dx, d_dy), options, pyramid.max_level());
    if (lod >= 0.0f)
        return trilinear(reduce_coordinate(c.s, pyramid.wrap_s()),
                         reduce_coordinate(c.t, pyramid.wrap_t()), lod,
                         single_probe_blend(options.lod_blend));
    if constexpr (std::is_same_v<Texels, MipPyramid>) {
        if (requests && options.filter == TextureFilter::footprint_assembly) {
            // The ellipse overload's footprint assembly ((s, t) reduced, the footprint bounded),
            // requested.
            return detail::request_footprint_assembly(
                pyramid, reduce_coordinate(c.s, pyramid.wrap_s()),
                reduce_coordinate(c.t, pyramid.wrap_t()),
                bounded(pyramid, make_footprint_ellipse(d_dx, d_dy)), options, out, requests->probe,
                requests->line);
        }
    }
    lookup_ellipse(pyramid, c.s, c.t, make_footprint_ellipse(d_dx, d_dy), options, out);
    return Requested::done;
}

}  // namespace footprint::texture_route
