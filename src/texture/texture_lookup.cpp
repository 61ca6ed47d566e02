#include "texture/texture_lookup.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "math/fast_log2.h"

#include "texture/filters.h"
#include "texture/footprint_assembly.h"
#include "texture/sampling.h"
#include "texture/summed_area_table.h"
#include "texture/texture_lookup_route.h"
#include "texture/tiled_texels.h"

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

std::string oiio_wrap_modes(WrapMode s, WrapMode t) {
    auto name = [](WrapMode mode) {
        return mode == WrapMode::repeat ? "periodic" : to_string(mode);
    };
    return std::string(name(s)) + "," + name(t);
}

WrapModes parse_oiio_wrap_modes(std::string_view modes) {
    const auto parse = [](std::string_view mode) {
        return mode == "black" ? std::optional(WrapMode::clamp) : parse_wrap_mode(mode);
    };
    const std::size_t comma = modes.find(',');
    const std::string_view s = modes.substr(0, comma);
    return {parse(s), parse(comma == std::string_view::npos ? s : modes.substr(comma + 1))};
}

std::optional<TextureFilter> parse_texture_filter(std::string_view name) {
    for (TextureFilter f :
         {TextureFilter::nearest, TextureFilter::bilinear, TextureFilter::trilinear,
          TextureFilter::brilinear, TextureFilter::footprint_assembly, TextureFilter::ewa,
          TextureFilter::summed_area})
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
        case TextureFilter::brilinear:
            return "brilinear";
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

namespace texture_route {

template <class Texels>
void lookup_ellipse(const Texels& pyramid, float s, float t, const FootprintEllipse& footprint,
                    const LookupOptions& options, float* out) {
    if (!std::isfinite(s) || !std::isfinite(t)) {  // nowhere in particular: the texture mean
        std::copy_n(detail::level_texel(pyramid, pyramid.max_level(), 0, 0), pyramid.channels(),
                    out);
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
        case TextureFilter::trilinear:
        case TextureFilter::brilinear: {
            // Isotropic: ρ = λ1 for an ellipse (the coords overload uses GL's column lengths).
            const float lod = std::clamp(
                fast_log2(std::max(e.major_radius, 1e-30f)) + options.lod_bias, 0.0f, max_level);
            lookup_trilinear(pyramid, s, t,
                             options.filter == TextureFilter::brilinear
                                 ? detail::brilinear_lod(lod, options.brilinear_band)
                                 : lod,
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
            if constexpr (std::is_same_v<Texels, MipPyramid>) {
                lookup_summed_area(pyramid, s, t, e, out);
            } else {  // a tiled pyramid has no SAT: lookup_summed_area()'s fallback
                lookup_trilinear(pyramid, s, t, std::log2(std::max(e.major_radius, 1.0f)),
                                 LodBlend::linear, out);
            }
            return;
    }
}

template void lookup_ellipse(const MipPyramid&, float, float, const FootprintEllipse&,
                             const LookupOptions&, float*);
template void lookup_ellipse(const detail::TiledTexels&, float, float, const FootprintEllipse&,
                             const LookupOptions&, float*);

}  // namespace texture_route

void texture_lookup(const MipPyramid& pyramid, float s, float t, const FootprintEllipse& footprint,
                    const LookupOptions& options, float* out) {
    texture_route::lookup_ellipse(pyramid, s, t, footprint, options, out);
}

void texture_lookup(const MipPyramid& pyramid, const TextureCoords& c, const LookupOptions& options,
                    float* out) {
    texture_route::route_lookup(pyramid, c, options, out, nullptr);
}

namespace detail {

void texture_lookup(const TiledTexels& texels, const TextureCoords& c, const LookupOptions& options,
                    float* out) {
    texture_route::route_lookup(texels, c, options, out, nullptr);
}

}  // namespace detail

}  // namespace footprint
