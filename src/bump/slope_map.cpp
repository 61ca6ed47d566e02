// bump/slope_map.cpp — slope maps from height maps and normal maps (conventions in slope_map.h).
#include "bump/slope_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/parallel.h"
#include "image/image_io.h"

namespace footprint {
namespace {

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

std::string texel_name(int x, int y) {
    // Built with += : GCC 12 gives a false -Wrestrict for "(" + std::string at -O3.
    std::string s = "(";
    s += std::to_string(x);
    s += ", ";
    s += std::to_string(y);
    s += ')';
    return s;
}

// Checks the shape of a user image: non-empty, channel count in [min_channels, max_channels],
// pixel vector of the declared size. `what` names the image in the message.
Status check_image(const Image& image, const char* what, int min_channels, int max_channels,
                   const char* channel_help) {
    if (image.width <= 0 || image.height <= 0) {
        return Error{std::string(what) + " has zero size (" + std::to_string(image.width) + "×" +
                     std::to_string(image.height) + ")"};
    }
    if (image.channels < min_channels || image.channels > max_channels) {
        return Error{std::string(what) + " has " + std::to_string(image.channels) + " channels; " +
                     channel_help};
    }
    const std::uint64_t expected = static_cast<std::uint64_t>(image.width) *
                                   static_cast<std::uint64_t>(image.height) *
                                   static_cast<std::uint64_t>(image.channels);
    if (image.pixels.size() != expected) {
        return Error{std::string(what) + " is malformed: it holds " +
                     std::to_string(image.pixels.size()) + " values, not " +
                     std::to_string(image.width) + "×" + std::to_string(image.height) + "×" +
                     std::to_string(image.channels) + " = " + std::to_string(expected)};
    }
    return {};
}

// Neighbour indices and their distance for a central difference along one axis of size n.
struct Stencil {
    int lo, hi;
    double span;  // hi − lo in texels; 0 where there is no neighbour (size 1, or repeat with n = 2)
};

Stencil stencil(int i, int n, HeightMapWrap wrap) {
    if (n == 1) return {i, i, 0.0};
    if (wrap == HeightMapWrap::repeat) {
        const int lo = (i - 1 + n) % n, hi = (i + 1) % n;
        return {lo, hi, lo == hi ? 0.0 : 2.0};
    }
    const int lo = std::max(i - 1, 0), hi = std::min(i + 1, n - 1);
    return {lo, hi, static_cast<double>(hi - lo)};
}

double difference(const Image& h, int x0, int y0, int x1, int y1, double span) {
    if (span == 0.0) return 0.0;
    return (static_cast<double>(h.at(x1, y1, 0)) - static_cast<double>(h.at(x0, y0, 0))) / span;
}

bool positive_finite(float value) {
    return std::isfinite(value) && value > 0.0f;
}

}  // namespace

Result<Image> slopes_from_height_map(const Image& height, const HeightMapOptions& options) {
    if (Status s = check_image(height, "height map", 1, 1 << 30,
                               "a height map needs at least 1 (channel 0 is the height)");
        !s) {
        return s.error();
    }
    if (!std::isfinite(options.height_scale)) {
        return Error{std::string("height map option height_scale = ") +
                     number(options.height_scale) + " is not finite"};
    }
    if (!positive_finite(options.texel_size_u)) {
        return Error{std::string("height map option texel_size_u = ") +
                     number(options.texel_size_u) + " must be finite and > 0"};
    }
    if (!positive_finite(options.texel_size_v)) {
        return Error{std::string("height map option texel_size_v = ") +
                     number(options.texel_size_v) + " must be finite and > 0"};
    }
    const int w = height.width, h = height.height;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (!std::isfinite(height.at(x, y, 0))) {
                return Error{std::string("height map texel ") + texel_name(x, y) +
                             " has the non-finite height " + number(height.at(x, y, 0))};
            }
        }
    }
    // b1 = −∂h/∂u, b2 = −∂h/∂v = +∂h/∂row (v = 1 − t points up, rows down): slope_map.h.
    const double scale_u = static_cast<double>(options.height_scale) / options.texel_size_u;
    const double scale_v = static_cast<double>(options.height_scale) / options.texel_size_v;
    Image slopes(w, h, 2);
    // Rows in parallel (oneTBB); a float overflow is reported for the first texel in row order.
    parallel_for(0, h, 16, [&](int first, int end) {
        for (int y = first; y < end; ++y) {
            const Stencil sv = stencil(y, h, options.wrap_v);
            for (int x = 0; x < w; ++x) {
                const Stencil su = stencil(x, w, options.wrap_u);
                const double dh_dx = difference(height, su.lo, y, su.hi, y, su.span);
                const double dh_drow = difference(height, x, sv.lo, x, sv.hi, sv.span);
                slopes.at(x, y, 0) = static_cast<float>(-dh_dx * scale_u);
                slopes.at(x, y, 1) = static_cast<float>(dh_drow * scale_v);
            }
        }
    });
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (!std::isfinite(slopes.at(x, y, 0)) || !std::isfinite(slopes.at(x, y, 1))) {
                const Stencil su = stencil(x, w, options.wrap_u),
                              sv = stencil(y, h, options.wrap_v);
                return Error{std::string("height map texel ") + texel_name(x, y) + ": the slope (" +
                             number(-difference(height, su.lo, y, su.hi, y, su.span) * scale_u) +
                             ", " +
                             number(difference(height, x, sv.lo, x, sv.hi, sv.span) * scale_v) +
                             ") overflows a float; height_scale / texel_size is too large"};
            }
    return slopes;
}

Result<Image> slopes_from_normal_map(const Image& normals, const NormalMapOptions& options) {
    if (Status s = check_image(normals, "normal map", 2, 4,
                               "a normal map needs 2 (x, y), 3 (x, y, z) or 4 (x, y, z, alpha)");
        !s) {
        return s.error();
    }
    if (!std::isfinite(options.strength)) {
        return Error{std::string("normal map option strength = ") + number(options.strength) +
                     " is not finite"};
    }
    if (!positive_finite(options.max_slope)) {
        return Error{std::string("normal map option max_slope = ") + number(options.max_slope) +
                     " must be finite and > 0"};
    }
    const bool reconstruct_z = normals.channels == 2;
    const double flip_y = options.green_convention == NormalMapGreen::directx ? -1.0 : 1.0;
    const double max_slope = options.max_slope;
    Image slopes(normals.width, normals.height, 2);
    for (int y = 0; y < normals.height; ++y) {
        for (int x = 0; x < normals.width; ++x) {
            const float* c = normals.at(x, y);
            const double nx = 2.0 * c[0] - 1.0;
            const double ny = flip_y * (2.0 * c[1] - 1.0);
            double nz;
            if (reconstruct_z) {
                const double r = 1.0 - nx * nx - ny * ny;
                nz = r > 0.0 ? std::sqrt(r) : (std::isnan(r) ? r : 0.0);
            } else {
                nz = 2.0 * c[2] - 1.0;
            }
            const bool finite = std::isfinite(nx) && std::isfinite(ny) && std::isfinite(nz);
            const double nxy = std::hypot(nx, ny);
            double b1 = 0.0, b2 = 0.0;
            if (finite && nz > 0.0 && nxy <= max_slope * nz) {
                b1 = nx / nz;  // n ∝ (−h_u, −h_v, 1) ⇒ b = (n_x, n_y)/n_z
                b2 = ny / nz;
            } else if (options.invalid_normal_policy == InvalidNormalPolicy::clamp) {
                if (finite && nxy > 0.0) {
                    b1 = max_slope * nx / nxy;
                    b2 = max_slope * ny / nxy;
                }
            } else {
                std::string cause;
                if (!finite) {
                    cause = "a component is NaN or infinite";
                } else if (nz <= 0.0) {
                    cause = reconstruct_z ? "n_x² + n_y² ≥ 1, so the reconstructed n_z is 0 (the "
                                            "normal lies in the tangent plane)"
                                          : "n_z ≤ 0 (the normal lies on or below the tangent "
                                            "plane)";
                } else {
                    cause = std::string("its slope |(n_x, n_y)|/n_z = ") + number(nxy / nz) +
                            " exceeds max_slope = " + number(max_slope);
                }
                std::string encoded = "(";
                encoded += number(c[0]);
                encoded += ", ";
                encoded += number(c[1]);
                if (!reconstruct_z) encoded += ", " + number(c[2]);
                encoded += ")";
                return Error{std::string("normal map texel ") + texel_name(x, y) + " = " + encoded +
                             " is invalid: n = (" + number(nx) + ", " + number(ny) + ", " +
                             number(nz) + "): " + cause};
            }
            const float s1 = static_cast<float>(options.strength * b1);
            const float s2 = static_cast<float>(options.strength * b2);
            if (!std::isfinite(s1) || !std::isfinite(s2)) {
                return Error{std::string("normal map texel ") + texel_name(x, y) +
                             ": the slope times strength = " + number(options.strength) +
                             " overflows a float"};
            }
            slopes.at(x, y, 0) = s1;
            slopes.at(x, y, 1) = s2;
        }
    }
    return slopes;
}

Image normals_from_slopes(const Image& slopes) {
    if (slopes.width <= 0 || slopes.height <= 0) return Image{};
    Image normals(slopes.width, slopes.height, 3);
    if (slopes.channels < 1 || slopes.pixels.size() < slopes.pixel_count() * slopes.channels) {
        // Malformed input: the flat normal everywhere.
        for (std::size_t i = 0; i < normals.pixel_count(); ++i) {
            normals.pixels[3 * i + 0] = 0.5f;
            normals.pixels[3 * i + 1] = 0.5f;
            normals.pixels[3 * i + 2] = 1.0f;
        }
        return normals;
    }
    for (int y = 0; y < slopes.height; ++y) {
        for (int x = 0; x < slopes.width; ++x) {
            double b1 = slopes.at(x, y, 0);
            double b2 = slopes.channels > 1 ? slopes.at(x, y, 1) : 0.0;
            if (!std::isfinite(b1) || !std::isfinite(b2)) b1 = b2 = 0.0;
            // n = (b1, b2, 1)/|(b1, b2, 1)|; hypot avoids overflow for huge slopes.
            const double inv = 1.0 / std::hypot(b1, b2, 1.0);
            float* c = normals.at(x, y);
            c[0] = std::clamp(static_cast<float>(0.5 * (b1 * inv + 1.0)), 0.0f, 1.0f);
            c[1] = std::clamp(static_cast<float>(0.5 * (b2 * inv + 1.0)), 0.0f, 1.0f);
            c[2] = std::clamp(static_cast<float>(0.5 * (inv + 1.0)), 0.0f, 1.0f);
        }
    }
    return normals;
}

Result<Image> load_slope_map(const std::filesystem::path& file,
                             const SlopeMapLoadOptions& options) {
    ImageLoadOptions load_options;
    load_options.encoding = ColorEncoding::linear;  // data, not colour
    // A normal map's NaN texels reach slopes_from_normal_map, whose policy decides.
    if (options.source == SlopeMapSource::normal_map)
        load_options.non_finite = NonFinitePolicy::keep;
    Result<Image> image = load_image(file, load_options);
    if (!image) return image.error();
    Result<Image> slopes = options.source == SlopeMapSource::height_map
                               ? slopes_from_height_map(*image, options.height_map)
                               : slopes_from_normal_map(*image, options.normal_map);
    if (!slopes) {
        std::string message = "cannot make a slope map from '";
        message += file.string();
        message += "': ";
        message += slopes.error().message;
        return Error{message};
    }
    return slopes;
}

Vec2 slopes_from_natural_derivatives(Vec2 f, float pu_length, float pv_length) {
    // b1 = −f_u/|p_u|, b2 = −f_v/|p_v| (slope_map.h, from spec §6.1 with s_u = −|p_v| e_u …).
    Vec2 b;
    if (positive_finite(pu_length)) b.x = -f.x / pu_length;
    if (positive_finite(pv_length)) b.y = -f.y / pv_length;
    if (!std::isfinite(b.x)) b.x = 0.0f;
    if (!std::isfinite(b.y)) b.y = 0.0f;
    return b;
}

Vec2 natural_derivatives_from_slopes(Vec2 b, float pu_length, float pv_length) {
    Vec2 f;
    if (std::isfinite(pu_length) && pu_length >= 0.0f) f.x = -b.x * pu_length;
    if (std::isfinite(pv_length) && pv_length >= 0.0f) f.y = -b.y * pv_length;
    if (!std::isfinite(f.x)) f.x = 0.0f;
    if (!std::isfinite(f.y)) f.y = 0.0f;
    return f;
}

}  // namespace footprint
