#include "render_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>

#include "cli_options.h"
#include "command_util.h"
#include "gpu/gpu_renderer.h"
#include "image/image_io.h"
#include "progress.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "scene/scene_file.h"

namespace footprint {

namespace {

constexpr int kDefaultReferenceSpp = 64;
constexpr int kMaxFrames = 100000;
constexpr int kMaxTextureMemoryMb = 1 << 20;
constexpr int kMaxTiles = 16384;  // the tallest image's rows

}  // namespace

std::filesystem::path frame_file(const std::filesystem::path& output, int frame, int frame_count) {
    const int digits =
        std::max(4, static_cast<int>(std::to_string(std::max(0, frame_count - 1)).size()));
    std::string number = std::to_string(frame);
    if (static_cast<int>(number.size()) < digits) number.insert(0, digits - number.size(), '0');
    std::filesystem::path file = output;
    file.replace_filename(output.stem().string() + "_" + number + output.extension().string());
    return file;
}

namespace {

// The first problem with the command line's numbers, if any.
std::optional<std::string> option_problem(const RenderCommandOptions& options) {
    if (options.spp) {
        if (auto problem = range_problem("--spp", *options.spp, kRenderSpp)) return problem;
    }
    if (options.width) {
        if (auto problem = range_problem("--size", *options.width, kImageWidths)) return problem;
    }
    if (options.frames) {
        if (auto problem = range_problem("--frames", *options.frames, 1, kMaxFrames))
            return problem;
    }
    if (const auto& range = options.frame_range) {
        if (!options.frames) return "--frames A-B/N: N is missing";
        const int n = *options.frames;
        if (range->first < 0 || range->first > range->second || range->second >= n)
            return "--frames " + std::to_string(range->first) + "-" +
                   std::to_string(range->second) + "/" + std::to_string(n) +
                   ": A-B must lie within 0-" + std::to_string(n - 1) + " with A <= B";
    }
    if (const auto& tile = options.tile) {
        if (auto problem = range_problem("--tile N", tile->second, 1, kMaxTiles)) return problem;
        if (tile->first < 1 || tile->first > tile->second)
            return "--tile " + std::to_string(tile->first) + "/" + std::to_string(tile->second) +
                   ": I must be 1 to " + std::to_string(tile->second);
        if (options.output.extension() != ".exr")
            return "--tile: a band is written as an OpenEXR data window, so -o must be .exr (got "
                   "'" +
                   options.output.string() + "'); footprint merge writes any format";
    }
    if (auto problem = range_problem("--threads", options.threads, kRenderThreads, "0: all cores"))
        return problem;
    if (!std::isfinite(options.exposure)) return "--exposure: must be finite";
    if (auto problem =
            range_problem("--texture-memory-mb", options.texture_memory_mb, 1, kMaxTextureMemoryMb))
        return problem;
    return std::nullopt;
}

// The scene's image resized to `width` pixels wide, the height keeping the aspect ratio.
void resize_image(SceneDesc& desc, int width) {
    const double aspect = static_cast<double>(desc.height) / desc.width;
    desc.height = std::max(1, static_cast<int>(std::lround(width * aspect)));
    desc.width = width;
}

// What one run renders: frames first … last of a sequence of `count` (0: the still image, the
// scene's camera), each whole or the rows of its tile, and where each goes.
struct RunPlan {
    int first = 0, last = 0, count = 0;
    std::optional<RowBand> rows;
    ImageSaveOptions save;  // a tile: its band

    int frames() const { return last - first + 1; }
    std::filesystem::path file(const std::filesystem::path& output, int frame) const {
        return count > 0 ? frame_file(output, frame, count) : output;
    }
};

// The plan of `options` for the scene's image size; an error where --tile asks for more bands
// than the image has rows.
Result<RunPlan> plan_run(const RenderCommandOptions& options, const SceneDesc& desc) {
    RunPlan plan;
    if (options.frames) {
        plan.count = *options.frames;
        plan.last = plan.count - 1;
        if (options.frame_range) std::tie(plan.first, plan.last) = *options.frame_range;
    }
    if (const auto& tile = options.tile) {
        if (tile->second > desc.height)
            return Error{"--tile " + std::to_string(tile->first) + "/" +
                         std::to_string(tile->second) + ": the image has only " +
                         std::to_string(desc.height) + " rows"};
        plan.rows = tile_rows(tile->first, tile->second, desc.height);
        plan.save.band = ImageBand{plan.rows->begin, desc.width, desc.height};
    }
    return plan;
}

// What a run wrote, for its report line: the output, or a sequence's first and last frames.
std::string written_files(const RenderCommandOptions& options, const RunPlan& plan) {
    if (plan.count == 0) return options.output.string();
    return std::to_string(plan.frames()) + " frames " +
           plan.file(options.output, plan.first).string() + " … " +
           plan.file(options.output, plan.last).string();
}

void report(const RenderCommandOptions& options, const SceneDesc& desc, const RenderOptions& ro,
            const RenderStats& stats, const TextureSystemStats& textures, const RunPlan& plan) {
    const int frame_count = plan.frames();
    const char* mode = filter_mode_name(ro.filter);
    if (options.json) {
        const nlohmann::json summary = {{"scene", options.scene.string()},
                                        {"output", options.output.string()},
                                        {"filter", mode},
                                        {"spp", ro.spp},
                                        {"seed", ro.seed},
                                        {"threads", options.threads},
                                        {"width", desc.width},
                                        {"height", desc.height},
                                        {"pixels", stats.pixels},
                                        {"seconds", stats.seconds},
                                        {"lookups", stats.lookups},
                                        {"non_finite_samples", stats.non_finite_samples},
                                        {"non_finite_pixels", stats.non_finite_pixels},
                                        {"frames", frame_count},
                                        {"texture_tiles_loaded", textures.tiles_loaded},
                                        {"texture_peak_bytes", textures.peak_bytes}};
        std::printf("%s\n", summary.dump().c_str());
    }
    if (options.quiet) return;
    if (stats.non_finite_samples > 0) {
        std::fprintf(stderr,
                     "footprint: warning: %llu of %llu samples were not finite and were dropped "
                     "(%llu pixels had no finite sample: written as 0)\n",
                     static_cast<unsigned long long>(stats.non_finite_samples),
                     static_cast<unsigned long long>(stats.samples),
                     static_cast<unsigned long long>(stats.non_finite_pixels));
    }
    if (options.json) return;
    report_written(written_files(options, plan), desc.width, desc.height, mode, ro.spp,
                   stats.seconds);
}

void apply_exposure(const RenderCommandOptions& options, Image& image) {
    if (is_float_image_file(options.output) || options.exposure == 0) return;
    const float scale = std::exp2(options.exposure);
    for (float& v : image.pixels) v *= scale;
}

// The scene file's name before a message that does not start with it.
std::string with_scene(const std::filesystem::path& scene, const std::string& message) {
    const std::string name = scene.string();
    return message.rfind(name, 0) == 0 ? message : name + ": " + message;
}

// --device gpu: the same scene, outputs and report, rendered by the GPU path.
int run_gpu_render(const RenderCommandOptions& options, GpuFilter filter, const SceneDesc& desc,
                   const RenderScene& scene, const RunPlan& plan) {
    Result<GpuDevice> device = GpuDevice::headless();
    if (!device) return fail("--device gpu: " + device.error().message);
    Result<GpuRenderer> renderer = GpuRenderer::create(scene);
    if (!renderer) return fail(with_scene(options.scene, renderer.error().message));
    const int frame_count = plan.frames();
    GpuRenderOptions render_options;
    render_options.filter = filter;
    render_options.frame_count = plan.count;
    render_options.rows = plan.rows;
    double seconds = 0, gpu_ms = 0;
    RunOutputs outputs;  // a sequence that fails part way leaves none of its frames behind
    for (int frame = plan.first; frame <= plan.last; ++frame) {
        render_options.frame = frame;
        const auto start = std::chrono::steady_clock::now();
        GpuFrameStats stats;
        Result<Image> image = renderer->render(render_options, &stats);
        if (!image) return fail("--device gpu: " + image.error().message);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        gpu_ms += stats.gpu_ms;
        apply_exposure(options, *image);
        const std::filesystem::path file = plan.file(options.output, frame);
        if (Status saved = outputs.save(*image, file, plan.save); !saved)
            return fail(saved.error().message);
    }
    outputs.keep();
    const std::uint64_t pixels = static_cast<std::uint64_t>(desc.width) *
                                 (plan.rows ? plan.rows->end - plan.rows->begin : desc.height) *
                                 frame_count;
    if (options.json) {
        const nlohmann::json summary = {{"scene", options.scene.string()},
                                        {"output", options.output.string()},
                                        {"device", "gpu"},
                                        {"gpu", device->description()},
                                        {"filter", gpu_filter_name(filter)},
                                        {"spp", 1},
                                        {"width", desc.width},
                                        {"height", desc.height},
                                        {"pixels", pixels},
                                        {"seconds", seconds},
                                        {"gpu_ms", gpu_ms},
                                        {"warmup_ms", renderer->warmup_ms()},
                                        {"frames", frame_count}};
        std::printf("%s\n", summary.dump().c_str());
        return 0;
    }
    if (options.quiet) return 0;
    report_written(written_files(options, plan), desc.width, desc.height,
                   std::string(gpu_filter_name(filter)) + ", GPU " + device->description(), 1,
                   seconds);
    return 0;
}

}  // namespace

int run_render_command(const RenderCommandOptions& options) {
    if (options.device != "cpu" && options.device != "gpu")
        return fail("--device: unknown device '" + options.device + "'; it is cpu or gpu");
    const bool gpu = options.device == "gpu";
    std::optional<GpuFilter> gpu_filter;
    if (gpu) {
        const Result<GpuFilter> filter = parse_gpu_render_filter(options.filter);
        if (!filter) return fail(filter.error().message);
        gpu_filter = *filter;
        if (options.spp && *options.spp != 1)
            return fail("--spp " + std::to_string(*options.spp) +
                        ": --device gpu renders one sample per pixel (--spp 1)");
    }
    const Result<FilterMode> mode =
        gpu ? Result<FilterMode>(FilterMode::fa_rough) : parse_render_filter(options.filter);
    if (!mode) return fail(mode.error().message);
    if (const auto problem = option_problem(options)) return fail(*problem);
    if (const auto problem = output_file_problem(options.output)) return fail(*problem);

    Result<NamedScene> named = resolve_scene(options.scene.string());
    if (!named) return fail(named.error().message);
    SceneDesc* desc = &named->desc;
    const bool show_progress = !options.quiet && Progress::stderr_is_terminal();
    if (show_progress) std::fprintf(stderr, "  loading %s\n", options.scene.string().c_str());
    if (options.frames && desc->camera_path.empty()) {
        return fail(options.scene.string() + ": --frames needs a camera_path in the scene");
    }
    if (options.width) resize_image(*desc, *options.width);
    TextureSystemOptions texture_options;
    texture_options.max_memory_mb = static_cast<std::size_t>(options.texture_memory_mb);
    texture_options.cache_dir = options.texture_cache_dir;
    Result<std::unique_ptr<TextureSystem>> textures = TextureSystem::create(texture_options);
    if (!textures) return fail(textures.error().message);
    Result<RunPlan> plan = plan_run(options, *desc);
    if (!plan) return fail(plan.error().message);
    Result<RenderScene> scene = prepare_render_scene(*desc, std::move(*textures));
    if (!scene) return fail(scene.error().message);
    if (gpu) return run_gpu_render(options, *gpu_filter, *desc, *scene, *plan);

    RenderOptions render_options;
    render_options.filter = *mode;
    render_options.spp =
        options.spp.value_or(*mode == FilterMode::reference ? kDefaultReferenceSpp : 1);
    render_options.seed = options.seed;
    render_options.threads = options.threads;
    render_options.frame_count = plan->count;
    render_options.rows = plan->rows;
    const int rows = plan->rows ? plan->rows->end - plan->rows->begin : desc->height;
    Progress progress(
        std::string("render ") + filter_mode_name(*mode),
        static_cast<std::uint64_t>(render_tile_count(desc->width, rows)) * plan->frames(),
        show_progress);
    RenderStats stats;
    RunOutputs outputs;  // a sequence that fails part way leaves none of its frames behind
    for (int frame = plan->first; frame <= plan->last; ++frame) {
        render_options.frame = frame;
        RenderStats frame_stats;
        Image image = render(*scene, render_options, &frame_stats, [&] { progress.advance(); });
        if (Status s = scene->take_texture_errors(); !s) return fail(s.error().message);
        for (const Error& warning : scene->textures().take_warnings())
            std::fprintf(stderr, "footprint: warning: %s\n", warning.message.c_str());
        stats.seconds += frame_stats.seconds;
        stats.pixels += frame_stats.pixels;
        stats.samples += frame_stats.samples;
        stats.lookups += frame_stats.lookups;
        stats.non_finite_samples += frame_stats.non_finite_samples;
        stats.non_finite_pixels += frame_stats.non_finite_pixels;
        apply_exposure(options, image);
        const std::filesystem::path file = plan->file(options.output, frame);
        if (Status saved = outputs.save(image, file, plan->save); !saved)
            return fail(saved.error().message);
    }
    outputs.keep();
    progress.finish();
    report(options, *desc, render_options, stats, scene->textures().stats(), *plan);
    return 0;
}

namespace {

// A non-negative decimal integer of at most 9 digits, the whole of `text`.
std::optional<int> whole_number(std::string_view text) {
    if (text.empty() || text.size() > 9) return std::nullopt;
    int value = 0;
    for (char c : text) {
        if (c < '0' || c > '9') return std::nullopt;
        value = value * 10 + (c - '0');
    }
    return value;
}

}  // namespace

Status parse_frames_option(std::string_view text, RenderCommandOptions& options) {
    const std::size_t slash = text.find('/');
    if (slash == std::string_view::npos) {
        const std::optional<int> n = whole_number(text);
        if (!n) return Error{"--frames '" + std::string(text) + "': expected N or A-B/N"};
        options.frames = *n;
        return {};
    }
    const std::string_view range = text.substr(0, slash);
    const std::size_t dash = range.find('-');
    const std::optional<int> n = whole_number(text.substr(slash + 1));
    const std::optional<int> a =
        dash == std::string_view::npos ? std::nullopt : whole_number(range.substr(0, dash));
    const std::optional<int> b =
        dash == std::string_view::npos ? std::nullopt : whole_number(range.substr(dash + 1));
    if (!n || !a || !b)
        return Error{"--frames '" + std::string(text) +
                     "': expected N or A-B/N (frames A to B of N, from 0)"};
    options.frames = *n;
    options.frame_range = std::pair{*a, *b};
    return {};
}

Status parse_tile_option(std::string_view text, RenderCommandOptions& options) {
    const std::size_t slash = text.find('/');
    const std::optional<int> i =
        slash == std::string_view::npos ? std::nullopt : whole_number(text.substr(0, slash));
    const std::optional<int> n =
        slash == std::string_view::npos ? std::nullopt : whole_number(text.substr(slash + 1));
    if (!i || !n)
        return Error{"--tile '" + std::string(text) + "': expected I/N (band I of N, from 1)"};
    options.tile = std::pair{*i, *n};
    return {};
}

RowBand tile_rows(int i, int n, int height) {
    auto edge = [&](int k) { return static_cast<int>(static_cast<std::int64_t>(k) * height / n); };
    return {edge(i - 1), edge(i)};
}

}  // namespace footprint
