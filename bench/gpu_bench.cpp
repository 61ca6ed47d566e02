#include "gpu_bench.h"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "bench_util.h"
#include "cli_options.h"
#include "command_util.h"
#include "demo_scenes.h"
#include "gpu/gpu_renderer.h"
#include "metrics/image_metrics.h"
#include "render/renderer.h"

namespace footprint::bench {

namespace {

constexpr double kTargetFramesPerSecond = 60;
constexpr double kTargetRatioToHardware = 2;

struct ModeTime {
    std::string scene, mode;
    double median_ms = 0, min_ms = 0;  // GPU time (timestamps)
    double wall_ms = 0;                // median draw + glFinish
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

double interior_rmse(const Image& image, const Image& reference, const Image& mask) {
    MetricsOptions options;
    options.mask = &mask;
    const Result<ImageComparison> d = compare_images(image, reference, options);
    return d ? d->rmse : std::numeric_limits<double>::quiet_NaN();
}

// --quality: the interior RMSE of CPU fa-rough and of every GPU mode against the reference.
nlohmann::json measure_quality(const std::string& name, const RenderScene& scene,
                               GpuRenderer& renderer, int reference_spp) {
    RenderOptions reference_options;
    reference_options.filter = FilterMode::reference;
    reference_options.spp = reference_spp;
    const Image reference = render(scene, reference_options);
    const Image mask = interior_mask(scene);
    RenderOptions cpu_options;
    cpu_options.filter = FilterMode::fa_rough;
    nlohmann::json row = {
        {"scene", name},
        {"cpu_fa_rough", interior_rmse(render(scene, cpu_options), reference, mask)}};
    std::printf("%-17s %12.5f", name.c_str(), row["cpu_fa_rough"].get<double>());
    for (GpuFilter filter : all_gpu_filters()) {
        GpuRenderOptions options;
        options.filter = filter;
        Result<Image> image = renderer.render(options);
        const double e = image ? interior_rmse(*image, reference, mask)
                               : std::numeric_limits<double>::quiet_NaN();
        row[std::string("gpu_") + gpu_filter_name(filter)] = number_or_null(e);
        std::printf(" %12.5f", e);
    }
    std::printf("\n");
    return row;
}

}  // namespace

int run_gpu_bench(const GpuBenchOptions& options) {
    const Result<ImageSize> size = parse_image_size("--size", options.size);
    if (!size) {
        std::fprintf(stderr, "footprint-bench: %s\n", size.error().message.c_str());
        return 1;
    }
    const int width = size->width, height = size->height;
    Result<GpuDevice> device = GpuDevice::headless();
    if (!device) {
        std::fprintf(stderr, "footprint-bench: gpu: %s\n", device.error().message.c_str());
        return 1;
    }
    std::printf("device: %s\n", device->description().c_str());
    if (options.quality) {
        std::printf("%dx%d, interior RMSE against the CPU reference at %d spp\n%-17s %12s", width,
                    height, options.reference_spp, "scene", "CPU fa-rough");
        for (GpuFilter filter : all_gpu_filters())
            std::printf(" %12s", (std::string("GPU ") + gpu_filter_name(filter)).c_str());
        std::printf("\n");
    } else {
        std::printf("%dx%d, %d timed frames after %d warm-up frames, median GPU time\n", width,
                    height, options.frames, options.warmup);
        std::printf("%-17s %-10s %10s %10s %10s %10s\n", "scene", "mode", "ms/frame", "min ms",
                    "frames/s", "wall ms");
    }
    const std::vector<std::string> scenes =
        options.scenes.empty() ? demo_scene_names() : options.scenes;
    std::vector<ModeTime> times;
    nlohmann::json targets = nlohmann::json::array(), quality = nlohmann::json::array();
    bool all_met = true;
    for (const std::string& name : scenes) {
        Result<NamedScene> named = resolve_scene(name);
        if (!named) {
            std::fprintf(stderr, "footprint-bench: %s\n", named.error().message.c_str());
            return 1;
        }
        named->desc.width = width;
        named->desc.height = height;
        Result<RenderScene> scene = prepare_render_scene(named->desc);
        if (!scene) {
            std::fprintf(stderr, "footprint-bench: %s\n", scene.error().message.c_str());
            return 1;
        }
        Result<GpuRenderer> renderer = GpuRenderer::create(*scene);
        if (!renderer) {
            std::fprintf(stderr, "footprint-bench: %s: %s\n", name.c_str(),
                         renderer.error().message.c_str());
            return 1;
        }
        if (options.quality) {
            quality.push_back(measure_quality(name, *scene, *renderer, options.reference_spp));
            continue;
        }
        double fa_rough_ms = 0, hw_ms = 0;
        for (GpuFilter filter : all_gpu_filters()) {
            GpuRenderOptions render_options;
            render_options.filter = filter;
            std::vector<double> ms, wall;
            for (int f = 0; f < options.warmup + options.frames; ++f) {
                GpuFrameStats stats;
                Result<Image> image = renderer->render(render_options, &stats);
                if (!image) {
                    std::fprintf(stderr, "footprint-bench: %s\n", image.error().message.c_str());
                    return 1;
                }
                if (f >= options.warmup) {
                    ms.push_back(stats.gpu_ms);
                    wall.push_back(stats.wall_ms);
                }
            }
            const ModeTime t{name, gpu_filter_name(filter), median(ms),
                             *std::min_element(ms.begin(), ms.end()), median(wall)};
            times.push_back(t);
            if (filter == GpuFilter::fa_rough) fa_rough_ms = t.median_ms;
            if (filter == GpuFilter::hw_aniso) hw_ms = t.median_ms;
            std::printf("%-17s %-10s %10.3f %10.3f %10.1f %10.3f\n", name.c_str(), t.mode.c_str(),
                        t.median_ms, t.min_ms, 1000.0 / t.median_ms, t.wall_ms);
        }
        const double fps = 1000.0 / fa_rough_ms, ratio = fa_rough_ms / hw_ms;
        const bool met = fps >= kTargetFramesPerSecond && ratio <= kTargetRatioToHardware;
        all_met = all_met && met;
        std::printf(
            "%-17s fa-rough %.1f frames/s (target >= %.0f), %.2fx hw-aniso's time "
            "(target <= %.0fx): %s\n",
            name.c_str(), fps, kTargetFramesPerSecond, ratio, kTargetRatioToHardware,
            met ? "met" : "NOT met");
        targets.push_back({{"scene", name},
                           {"fa_rough_frames_per_second", fps},
                           {"fa_rough_over_hw_aniso", ratio},
                           {"met", met}});
    }
    if (options.quality) {
        if (!options.json_path.empty())
            write_json(options.json_path, {{"device", device->description()},
                                           {"width", width},
                                           {"height", height},
                                           {"reference_spp", options.reference_spp},
                                           {"quality", quality}});
        return 0;
    }
    if (!options.json_path.empty()) {
        nlohmann::json cases = nlohmann::json::array();
        for (const ModeTime& t : times)
            cases.push_back({{"scene", t.scene},
                             {"mode", t.mode},
                             {"median_ms", t.median_ms},
                             {"min_ms", t.min_ms},
                             {"wall_ms", t.wall_ms},
                             {"frames_per_second", 1000.0 / t.median_ms}});
        write_json(options.json_path, {{"device", device->description()},
                                       {"width", width},
                                       {"height", height},
                                       {"frames", options.frames},
                                       {"cases", cases},
                                       {"targets", targets},
                                       {"all_targets_met", all_met}});
    }
    return 0;
}

}  // namespace footprint::bench
