#include "texture/texture_lookup.h"

#include <algorithm>
#include <cmath>

#include "math/fast_log2.h"

#include "texture/filters.h"
#include "texture/footprint_assembly.h"
#include "texture/sampling.h"
#include "texture/summed_area_table.h"

namespace footprint {

std::optional<WrapMode> parse_wrap_mode(std::string_view name) {
    if (name == "repeat" || name == "periodic") return WrapMode::repeat;
    if (name == "clamp") return WrapMode::clamp;
    if (name == "mirror") return WrapMode::mirror;
    return std::nullopt;
}

const char* to_string(WrapMode mode) {
    switch (mode) {
        case WrapMode::repeat:
            return "repeat";
        case WrapMode::clamp:
            return "clamp";
        case WrapMode::mirror:
            return "mirror";
    }
    return "?";
}

std::optional<TextureFilter> parse_texture_filter(std::string_view name) {
    for (TextureFilter f :
         {TextureFilter::nearest, TextureFilter::bilinear, TextureFilter::trilinear,
          TextureFilter::footprint_assembly, TextureFilter::ewa, TextureFilter::summed_area})
        if (name == to_string(f)) return f;
    return std::nullopt;
}

const char* to_string(TextureFilter filter) {
    switch (filter) {
        case TextureFilter::nearest:
            return "nearest";
        case TextureFilter::bilinear:
            return "bilinear";
        case TextureFilter::trilinear:
            return "trilinear";
        case TextureFilter::footprint_assembly:
            return "fa";
        case TextureFilter::ewa:
            return "ewa";
        case TextureFilter::summed_area:
            return "sat";
    }
    return "?";
}

FootprintEllipse footprint_of(const MipPyramid& pyramid, const TextureCoords& c) {
    const float w0 = static_cast<float>(pyramid.width(0)),
                h0 = static_cast<float>(pyramid.height(0));
    return make_footprint_ellipse(Vec2{c.dsdx * w0, c.dtdx * h0}, Vec2{c.dsdy * w0, c.dtdy * h0});
}

namespace {

// Footprints beyond a few texture sizes all read the coarsest level; bounding them keeps every
// loop finite and every float in range.
FootprintEllipse bounded(const MipPyramid& pyramid, FootprintEllipse e) {
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

void lookup_nearest(const MipPyramid& pyramid, float s, float t, float* out) {
    const MipPyramid::LevelView& level = pyramid.level(0);
    const int x = wrap_index(static_cast<int>(std::floor(s * static_cast<float>(level.width))),
                             level.width, pyramid.wrap_s());
    const int y = wrap_index(static_cast<int>(std::floor(t * static_cast<float>(level.height))),
                             level.height, pyramid.wrap_t());
    const float* texel = level.texel(x, y);
    for (int c = 0; c < pyramid.channels(); ++c) out[c] = texel[c];
}

void lookup_trilinear(const MipPyramid& pyramid, float s, float t, float lod, LodBlend blend,
                      float* out) {
    detail::dispatch_stride(pyramid.stride(), [&]<int S>() {
        detail::store(detail::sample_trilinear<S>(pyramid, s, t, lod, blend), pyramid.channels(),
                      out);
    });
}

void lookup_summed_area(const MipPyramid& pyramid, float s, float t, const FootprintEllipse& e,
                        float* out) {
    const SummedAreaTable* sat = pyramid.summed_area_table();
    if (sat == nullptr) {  // built without a SAT: documented fallback to trilinear
        lookup_trilinear(pyramid, s, t, std::log2(std::max(e.major_radius, 1.0f)), LodBlend::linear,
                         out);
        return;
    }
    // Bounding rectangle of ξᵀK⁻¹ξ = 1: half-widths √k11, √k22; at least one texel wide.
    const double hx = std::max(0.5, std::sqrt(double(std::max(0.0f, e.matrix.xx))));
    const double hy = std::max(0.5, std::sqrt(double(std::max(0.0f, e.matrix.yy))));
    const double ex = double(s) * sat->width(),
                 ey = double(t) * sat->height();  // texel-edge coordinates
    sat->box_mean(ex - hx, ey - hy, ex + hx, ey + hy, out);
}

}  // namespace

void texture_lookup(const MipPyramid& pyramid, float s, float t, const FootprintEllipse& footprint,
                    const LookupOptions& options, float* out) {
    if (!std::isfinite(s) || !std::isfinite(t)) {  // nowhere in particular: the texture mean
        std::copy_n(pyramid.texel(pyramid.max_level(), 0, 0), pyramid.channels(), out);
        return;
    }
    s = reduce_coordinate(s, pyramid.wrap_s());
    t = reduce_coordinate(t, pyramid.wrap_t());
    const FootprintEllipse e = bounded(pyramid, footprint);
    const float max_level = static_cast<float>(pyramid.max_level());

    switch (options.filter) {
        case TextureFilter::nearest:
            lookup_nearest(pyramid, s, t, out);
            return;
        case TextureFilter::bilinear:
            lookup_trilinear(pyramid, s, t, 0.0f, LodBlend::linear, out);
            return;
        case TextureFilter::trilinear: {
            // Isotropic: ρ = λ1 for an ellipse (the coords overload uses GL's column lengths).
            const float lod = fast_log2(std::max(e.major_radius, 1e-30f)) + options.lod_bias;
            lookup_trilinear(pyramid, s, t, std::clamp(lod, 0.0f, max_level), LodBlend::linear,
                             out);
            return;
        }
        case TextureFilter::footprint_assembly:
            detail::filter_footprint_assembly(pyramid, s, t, e, options, out);
            return;
        case TextureFilter::ewa:
            detail::filter_ewa(pyramid, s, t, e, options, out);
            return;
        case TextureFilter::summed_area:
            lookup_summed_area(pyramid, s, t, e, out);
            return;
    }
}

namespace {

// The lookups a batch requests now and reads later (texture_lookup_batch()).
struct Requests {
    detail::RequestedProbe& probe;
    detail::RequestedLine<detail::kRequestedLineProbes>& line;
};

// texture_lookup(coords): the lookup done into out (Requested::done), or, given `requests` (the
// batch), a lookup that is one bilinear or trilinear probe — magnification, the GL rule, a
// near-isotropic footprint — requested into requests.probe, and a short footprint-assembly line
// into requests.line, for the caller to read (bit for bit what is done into out without them).
[[gnu::always_inline]] inline detail::Requested route_lookup(const MipPyramid& pyramid,
                                                             const TextureCoords& c,
                                                             const LookupOptions& options,
                                                             float* out, const Requests* requests) {
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
        texture_lookup(pyramid, c.s, c.t, FootprintEllipse{}, options, out);
        return Requested::done;
    }
    const float w0 = static_cast<float>(pyramid.width(0)),
                h0 = static_cast<float>(pyramid.height(0));
    const Vec2 d_dx{c.dsdx * w0, c.dtdx * h0}, d_dy{c.dsdy * w0, c.dtdy * h0};  // columns of D
    const float len_x2 = dot(d_dx, d_dx), len_y2 = dot(d_dy, d_dy);
    // No footprint needed: the level-0 baselines, and magnification — a footprint inside one texel
    // (trace K = |D|²_F ≤ 1 ⇒ λ1 ≤ 1) is one bilinear probe at level 0 for every mipmapping filter.
    const bool mipmapped = options.filter == TextureFilter::trilinear ||
                           options.filter == TextureFilter::footprint_assembly ||
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
        texture_lookup(pyramid, c.s, c.t, make_footprint_ellipse(kHuge, kHuge, 0.0f), options, out);
        return Requested::done;
    }
    if (options.filter == TextureFilter::trilinear && std::isfinite(len_x2 + len_y2)) {
        // GL rule (OpenGL 4.6 §8.14.1): ρ = max(|∂(X,Y)/∂x|, |∂(X,Y)/∂y|), lod = log2 ρ.
        const float rho_sq = std::max(len_x2, len_y2);
        const float lod = 0.5f * fast_log2(std::max(rho_sq, 1e-30f)) + options.lod_bias;
        return trilinear(
            reduce_coordinate(c.s, pyramid.wrap_s()), reduce_coordinate(c.t, pyramid.wrap_t()),
            std::clamp(lod, 0.0f, static_cast<float>(pyramid.max_level())), LodBlend::linear);
    }
    // Near-isotropic footprints are one trilinear probe: skip the ellipse's axes.
    const float lod = single_probe_lod(footprint_matrix(d_dx, d_dy), options, pyramid.max_level());
    if (lod >= 0.0f)
        return trilinear(reduce_coordinate(c.s, pyramid.wrap_s()),
                         reduce_coordinate(c.t, pyramid.wrap_t()), lod,
                         single_probe_blend(options.lod_blend));
    if (requests && options.filter == TextureFilter::footprint_assembly) {
        // The ellipse overload's footprint assembly ((s, t) reduced, the footprint bounded),
        // requested.
        return detail::request_footprint_assembly(
            pyramid, reduce_coordinate(c.s, pyramid.wrap_s()),
            reduce_coordinate(c.t, pyramid.wrap_t()),
            bounded(pyramid, make_footprint_ellipse(d_dx, d_dy)), options, out, requests->probe,
            requests->line);
    }
    texture_lookup(pyramid, c.s, c.t, make_footprint_ellipse(d_dx, d_dy), options, out);
    return Requested::done;
}

}  // namespace

void texture_lookup(const MipPyramid& pyramid, const TextureCoords& c, const LookupOptions& options,
                    float* out) {
    route_lookup(pyramid, c, options, out, nullptr);
}

void texture_lookup_batch(const MipPyramid& pyramid, std::span<const TextureCoords> coords,
                          const LookupOptions& options, float* out) {
    // Lookups are taken kGroup at a time: those that are one probe or a short line have their
    // texels requested, and are read once the whole group is routed, when the texels have arrived
    // (enough lookups in flight to cover a miss to memory, few enough that their texels are still
    // cached when read; footprint-bench texture chose 16 over 8 and 32, docs/performance.md).
    // Every other lookup is done at once.
    constexpr std::size_t kGroup = 16;
    const int channels = pyramid.channels();
    detail::RequestedReads<kGroup> reads;
    for (std::size_t first = 0; first < coords.size(); first += kGroup) {
        const std::size_t count = std::min(kGroup, coords.size() - first);
        for (std::size_t i = 0; i < count; ++i) {
            float* result = out + (first + i) * channels;
            const Requests requests{reads.next_probe(), reads.next_line()};
            reads.add(route_lookup(pyramid, coords[first + i], options, result, &requests), result);
        }
        reads.read(pyramid.stride(), channels);
    }
}

}  // namespace footprint
