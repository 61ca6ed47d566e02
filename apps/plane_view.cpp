#include "plane_view.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>

#include "core/parallel.h"
#include "math/sample_patterns.h"
#include "progress.h"

namespace footprint {

namespace {

double radians(double degrees) {
    return degrees * std::numbers::pi / 180.0;
}

// Wraps an unbounded coordinate in double precision, as the pyramid's wrap mode would, so that
// the float handed to texture_lookup keeps its sub-texel precision far from the origin.
float wrap_coordinate(double s, WrapMode mode) {
    switch (mode) {
        case WrapMode::repeat:
            return static_cast<float>(s - std::floor(s));
        case WrapMode::mirror:
            return static_cast<float>(s - 2.0 * std::floor(0.5 * s));
        case WrapMode::clamp:
            return static_cast<float>(std::clamp(s, -1.0, 2.0));
    }
    return static_cast<float>(s);
}

// The sky in the image's channel layout: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA (alpha 1).
std::array<float, MipPyramid::kMaxChannels> sky_texel(const std::array<float, 3>& rgb,
                                                      int channels) {
    std::array<float, MipPyramid::kMaxChannels> v{};
    const float grey = 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
    if (channels <= 2) {
        v[0] = grey;
        if (channels == 2) v[1] = 1.0f;
    } else {
        v[0] = rgb[0], v[1] = rgb[1], v[2] = rgb[2];
        for (int c = 3; c < channels; ++c) v[c] = 1.0f;
    }
    return v;
}

template <class RowFunction>
PlaneRenderStats render_rows(int height, Progress* progress, const RowFunction& row) {
    const auto start = std::chrono::steady_clock::now();
    std::atomic<std::uint64_t> lookups{0};
    parallel_for(0, height, 1, [&](int first, int end) {
        std::uint64_t local = 0;
        for (int y = first; y != end; ++y) {
            local += row(y);
            if (progress) progress->advance();
        }
        lookups.fetch_add(local, std::memory_order_relaxed);
    });
    PlaneRenderStats stats;
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats.lookups = lookups.load();
    return stats;
}

}  // namespace

int plane_view_height(int width) {
    return std::max(1, static_cast<int>(std::lround(width * 9.0 / 16.0)));
}

PlaneView::PlaneView(const PlaneViewOptions& options) : options_(options) {
    a_ = std::tan(0.5 * radians(options.horizontal_fov_degrees)) / (0.5 * options.width);
    cx_ = 0.5 * options.width;
    cy_ = 0.5 * options.height;
    sin_p_ = std::sin(radians(options.pitch_degrees));
    cos_p_ = std::cos(radians(options.pitch_degrees));
    cos_yaw_ = std::cos(radians(options.yaw_degrees));
    sin_yaw_ = std::sin(radians(options.yaw_degrees));
}

double PlaneView::horizon_row() const {
    return cy_ - sin_p_ / (a_ * cos_p_);
}

bool PlaneView::hit(double x, double y, double& s, double& t) const {
    const double dy = direction_y(y);
    if (!(dy < -kMinDirectionY)) return false;
    // d = f + a(x − cx) r − a(y − cy) u with f = (0, −sin p, cos p), u = (0, cos p, sin p).
    const double dx = a_ * (x - cx_);
    const double dz = cos_p_ - a_ * (y - cy_) * sin_p_;
    const double tau = options_.eye_height / -dy;
    const double px = tau * dx, pz = tau * dz;  // E = (0, h, 0)
    const double k = options_.uv_scale;
    s = options_.s_offset + k * (cos_yaw_ * px + sin_yaw_ * pz);
    t = options_.t_offset + k * (sin_yaw_ * px - cos_yaw_ * pz);
    return true;
}

PlaneSample PlaneView::sample(double x, double y) const {
    PlaneSample out;
    const double dy = direction_y(y);
    if (!(dy < -kMinDirectionY)) return out;
    out.hit = hit(x, y, out.s, out.t);
    const double dx = a_ * (x - cx_);
    const double dz = cos_p_ - a_ * (y - cy_) * sin_p_;
    const double tau = options_.eye_height / -dy;
    // ∂P = τ (d' − (d'_y / d_y) d), x and z components.
    // Along x: d' = a r = (a, 0, 0), d'_y = 0.
    const double dPx_dx = tau * a_, dPz_dx = 0.0;
    // Along y: d' = −a u = (0, −a cos p, −a sin p).
    const double ddy_y = -a_ * cos_p_, ddz_y = -a_ * sin_p_;
    const double dPx_dy = tau * (0.0 - (ddy_y / dy) * dx);
    const double dPz_dy = tau * (ddz_y - (ddy_y / dy) * dz);
    const double k = options_.uv_scale;
    out.dsdx = k * (cos_yaw_ * dPx_dx + sin_yaw_ * dPz_dx);
    out.dtdx = k * (sin_yaw_ * dPx_dx - cos_yaw_ * dPz_dx);
    out.dsdy = k * (cos_yaw_ * dPx_dy + sin_yaw_ * dPz_dy);
    out.dtdy = k * (sin_yaw_ * dPx_dy - cos_yaw_ * dPz_dy);
    return out;
}

Image render_plane_view(const MipPyramid& pyramid, const PlaneViewOptions& view,
                        const LookupOptions& lookup, PlaneRenderStats* stats, Progress* progress) {
    const PlaneView camera(view);
    const int channels = pyramid.channels();
    Image image(view.width, view.height, channels);
    const auto sky = sky_texel(view.sky, channels);
    const PlaneRenderStats result = render_rows(view.height, progress, [&](int y) {
        std::uint64_t lookups = 0;
        for (int x = 0; x < view.width; ++x) {
            float* out = image.at(x, y);
            const PlaneSample p = camera.sample(x + 0.5, y + 0.5);
            if (!p.hit) {
                std::copy_n(sky.data(), channels, out);
                continue;
            }
            TextureCoords c;
            c.s = wrap_coordinate(p.s, pyramid.wrap_s());
            c.t = wrap_coordinate(p.t, pyramid.wrap_t());
            c.dsdx = static_cast<float>(p.dsdx);
            c.dtdx = static_cast<float>(p.dtdx);
            c.dsdy = static_cast<float>(p.dsdy);
            c.dtdy = static_cast<float>(p.dtdy);
            float texel[MipPyramid::kMaxChannels];
            texture_lookup(pyramid, c, lookup, texel);
            std::copy_n(texel, channels, out);
            ++lookups;
        }
        return lookups;
    });
    if (stats) *stats = result;
    return image;
}

Image render_plane_reference(const MipPyramid& pyramid, const PlaneViewOptions& view,
                             const PlaneReferenceOptions& options, PlaneRenderStats* stats,
                             Progress* progress) {
    const PlaneView camera(view);
    const int channels = pyramid.channels();
    const int n = std::max(1, options.samples_per_axis);
    Image image(view.width, view.height, channels);
    const auto sky = sky_texel(view.sky, channels);
    // Gaussian pixel filter, σ = ½ pixel, truncated at ±3σ (gaussian_pixel_offset).
    LookupOptions bilinear;
    bilinear.filter = TextureFilter::bilinear;
    const FootprintEllipse point{};  // bilinear ignores the footprint
    const double inv_count = 1.0 / (static_cast<double>(n) * n);

    const PlaneRenderStats result = render_rows(view.height, progress, [&](int y) {
        std::uint64_t lookups = 0;
        for (int x = 0; x < view.width; ++x) {
            double acc[MipPyramid::kMaxChannels] = {};
            const std::uint32_t pixel_seed =
                hash32(options.seed ^ hash32(static_cast<std::uint32_t>(y) ^
                                             hash32(static_cast<std::uint32_t>(x))));
            for (int j = 0; j < n; ++j) {
                for (int i = 0; i < n; ++i) {
                    const std::uint32_t h =
                        hash32(pixel_seed + static_cast<std::uint32_t>(j * n + i));
                    const double ux = (i + unit_float(h)) / n;
                    const double uy = (j + unit_float(hash32(h))) / n;
                    const double ox = gaussian_pixel_offset(ux);
                    const double oy = gaussian_pixel_offset(uy);
                    double s, t;
                    if (camera.hit(x + 0.5 + ox, y + 0.5 + oy, s, t)) {
                        float texel[MipPyramid::kMaxChannels];
                        texture_lookup(pyramid, wrap_coordinate(s, pyramid.wrap_s()),
                                       wrap_coordinate(t, pyramid.wrap_t()), point, bilinear,
                                       texel);
                        for (int c = 0; c < channels; ++c) acc[c] += texel[c];
                        ++lookups;
                    } else {
                        for (int c = 0; c < channels; ++c) acc[c] += sky[c];
                    }
                }
            }
            float* out = image.at(x, y);
            for (int c = 0; c < channels; ++c) out[c] = static_cast<float>(acc[c] * inv_count);
        }
        return lookups;
    });
    if (stats) *stats = result;
    return image;
}

double plane_rmse(const Image& image, const Image& reference, const PlaneViewOptions& view,
                  std::size_t* pixels) {
    const PlaneView camera(view);
    double sum = 0;
    std::size_t count = 0;
    const int channels = std::min(image.channels, reference.channels);
    const int width = std::min({image.width, reference.width, view.width});
    const int height = std::min({image.height, reference.height, view.height});
    for (int y = 0; y < height; ++y) {
        if (!camera.covers_row(y)) continue;
        for (int x = 0; x < width; ++x) {
            for (int c = 0; c < channels; ++c) {
                const double e = double(image.at(x, y, c)) - double(reference.at(x, y, c));
                sum += e * e;
            }
            ++count;
        }
    }
    if (pixels) *pixels = count;
    return count == 0 || channels == 0 ? 0.0 : std::sqrt(sum / (double(count) * channels));
}

}  // namespace footprint
