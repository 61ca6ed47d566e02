#include "texture/texture_lookup.h"

#include <algorithm>
#include <cmath>

#include "math/fast_log2.h"

#include "texture/filters.h"
#include "texture/footprint_assembly.h"
#include "texture/sampling.h"
#include "texture/summed_area_table.h"
#include "texture/texture_lookup_route.h"

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

namespace texture_route {

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

}  // namespace texture_route

namespace {

void lookup_summed_area(const MipPyramid& pyramid, float s, float t, const FootprintEllipse& e,
                        float* out) {
    const SummedAreaTable* sat = pyramid.summed_area_table();
    if (sat == nullptr) {  // built without a SAT: documented fallback to trilinear
        texture_route::lookup_trilinear(pyramid, s, t, std::log2(std::max(e.major_radius, 1.0f)),
                                        LodBlend::linear, out);
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
    const FootprintEllipse e = texture_route::bounded(pyramid, footprint);
    const float max_level = static_cast<float>(pyramid.max_level());

    switch (options.filter) {
        case TextureFilter::nearest:
            texture_route::lookup_nearest(pyramid, s, t, out);
            return;
        case TextureFilter::bilinear:
            texture_route::lookup_trilinear(pyramid, s, t, 0.0f, LodBlend::linear, out);
            return;
        case TextureFilter::trilinear: {
            // Isotropic: ρ = λ1 for an ellipse (the coords overload uses GL's column lengths).
            const float lod = fast_log2(std::max(e.major_radius, 1e-30f)) + options.lod_bias;
            texture_route::lookup_trilinear(pyramid, s, t, std::clamp(lod, 0.0f, max_level),
                                            LodBlend::linear, out);
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

void texture_lookup(const MipPyramid& pyramid, const TextureCoords& c, const LookupOptions& options,
                    float* out) {
    texture_route::route_lookup(pyramid, c, options, out, nullptr);
}

}  // namespace footprint
