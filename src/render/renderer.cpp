#include "render/renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>

#include "render/camera.h"
#include "render/sample_shader.h"

namespace footprint {

namespace {

constexpr FilterMode kAllModes[] = {
    FilterMode::bilinear,    FilterMode::trilinear, FilterMode::fa,   FilterMode::fa_rough,
    FilterMode::ewa_rough,   FilterMode::reference, FilterMode::lean, FilterMode::toksvig,
    FilterMode::specular_aa, FilterMode::stochastic};
constexpr FilterMode kPeerModes[] = {FilterMode::lean, FilterMode::toksvig, FilterMode::specular_aa,
                                     FilterMode::stochastic};

using detail::Rgb;

CameraDesc view_camera(const SceneDesc& scene, const RenderOptions& options) {
    if (options.frame_count < 1) return scene.camera;
    return camera_for_frame(scene, options.frame, options.frame_count);
}

// What a tile counts of its pixels' samples.
struct SampleCounts {
    std::uint64_t non_finite_samples = 0, non_finite_pixels = 0;
};

// The mean of the pixel's finite samples (0 if none is finite).
Rgb render_pixel_with(detail::SampleShader& shader, const PinholeCamera& camera,
                      const RenderOptions& options, int x, int y, SampleCounts& counts) {
    const int n = std::max(1, options.spp);
    double sum[3] = {0, 0, 0};
    int kept = 0;
    for (int k = 0; k < n; ++k) {
        Vec2d random;
        const RayDifferential ray = detail::sample_ray(camera, options, x, y, k, random);
        const Rgb c = shader.shade(ray, random);
        if (!(std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]))) {
            ++counts.non_finite_samples;
            continue;
        }
        for (int i = 0; i < 3; ++i) sum[i] += c[i];
        ++kept;
    }
    if (kept == 0) {
        ++counts.non_finite_pixels;
        return {0, 0, 0};
    }
    return {static_cast<float>(sum[0] / kept), static_cast<float>(sum[1] / kept),
            static_cast<float>(sum[2] / kept)};
}

}  // namespace

std::optional<FilterMode> parse_filter_mode(std::string_view name) {
    for (FilterMode mode : kAllModes) {
        if (name == filter_mode_name(mode)) return mode;
    }
    return std::nullopt;
}

const char* filter_mode_name(FilterMode mode) {
    switch (mode) {
        case FilterMode::bilinear:
            return "bilinear";
        case FilterMode::trilinear:
            return "trilinear";
        case FilterMode::fa:
            return "fa";
        case FilterMode::fa_rough:
            return "fa-rough";
        case FilterMode::ewa_rough:
            return "ewa-rough";
        case FilterMode::reference:
            return "reference";
        case FilterMode::lean:
            return "lean";
        case FilterMode::toksvig:
            return "toksvig";
        case FilterMode::specular_aa:
            return "specular-aa";
        case FilterMode::stochastic:
            return "stochastic";
    }
    return "?";
}

std::span<const FilterMode> all_filter_modes() {
    return kAllModes;
}

std::span<const FilterMode> peer_filter_modes() {
    return kPeerModes;
}

Image interior_mask(const RenderScene& scene) {
    const SceneDesc& desc = scene.desc();
    const PinholeCamera camera(desc.camera, desc.width, desc.height);
    Image mask(desc.width, desc.height, 1, 0.0f);
    constexpr double kReach = 1.5;
    const double offsets[3] = {-kReach, 0, kReach};
    for (int y = 0; y < desc.height; ++y) {
        for (int x = 0; x < desc.width; ++x) {
            int object = -2;
            bool same = true;
            for (double dy : offsets) {
                for (double dx : offsets) {
                    const RayDifferential ray = camera.ray(x + 0.5 + dx, y + 0.5 + dy);
                    const std::optional<SceneHit> hit = scene.intersect(ray.ray, 1e-9, INFINITY);
                    const int id = hit ? hit->surface.object : -1;
                    if (object == -2) object = id;
                    same = same && id == object && id >= 0;
                }
            }
            mask.at(x, y, 0) = same ? 1.0f : 0.0f;
        }
    }
    return mask;
}

int render_tile_count(int width, int height) {
    return detail::tile_count(width, height);
}

Image render(const RenderScene& scene, const RenderOptions& options, RenderStats* stats,
             const std::function<void()>& tile_done) {
    const auto start = std::chrono::steady_clock::now();
    const int width = scene.desc().width, height = scene.desc().height;
    const PinholeCamera camera(view_camera(scene.desc(), options), width, height);
    const int first = options.rows ? std::clamp(options.rows->begin, 0, height) : 0;
    const int rows = options.rows ? std::clamp(options.rows->end, first, height) - first : height;
    Image image(width, rows, 3);
    std::atomic<std::uint64_t> lookups{0}, non_finite_samples{0}, non_finite_pixels{0};
    detail::for_each_tile(width, rows, options.threads, [&](const detail::Tile& tile) {
        detail::SampleShader shader(scene, options);
        SampleCounts counts;
        for (int y = tile.y0; y < tile.y1; ++y) {
            for (int x = tile.x0; x < tile.x1; ++x) {
                const Rgb c = render_pixel_with(shader, camera, options, x, first + y, counts);
                std::copy(c.begin(), c.end(), image.at(x, y));
            }
        }
        lookups += shader.lookups;
        non_finite_samples += counts.non_finite_samples;
        non_finite_pixels += counts.non_finite_pixels;
        if (tile_done) tile_done();
    });
    if (stats) {
        stats->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->pixels = static_cast<std::uint64_t>(width) * rows;
        stats->samples = stats->pixels * static_cast<std::uint64_t>(std::max(1, options.spp));
        stats->lookups = lookups;
        stats->non_finite_samples = non_finite_samples;
        stats->non_finite_pixels = non_finite_pixels;
    }
    return image;
}

}  // namespace footprint
