#include "render_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_options.h"
#include "command_util.h"
#include "image/image_io.h"
#include "progress.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "scene/scene_file.h"

namespace footprint {

namespace {

constexpr int kDefaultReferenceSpp = 64;
constexpr int kMaxSpp = 1 << 16;
constexpr int kMaxFrames = 100000;
constexpr int kMaxThreads = 1024;

bool is_float_format(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".exr" || ext == ".hdr";
}

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
        if (auto problem = range_problem("--spp", *options.spp, 1, kMaxSpp)) return problem;
    }
    if (options.width) {
        if (auto problem = range_problem("--size", *options.width, kImageWidths)) return problem;
    }
    if (options.frames) {
        if (auto problem = range_problem("--frames", *options.frames, 1, kMaxFrames))
            return problem;
    }
    if (auto problem = range_problem("--threads", options.threads, 0, kMaxThreads, "0: all cores"))
        return problem;
    if (!std::isfinite(options.exposure)) return "--exposure: must be finite";
    return std::nullopt;
}

// The scene's image resized to `width` pixels wide, the height keeping the aspect ratio.
void resize_image(SceneDesc& desc, int width) {
    const double aspect = static_cast<double>(desc.height) / desc.width;
    desc.height = std::max(1, static_cast<int>(std::lround(width * aspect)));
    desc.width = width;
}

void report(const RenderCommandOptions& options, const SceneDesc& desc, const RenderOptions& ro,
            const RenderStats& stats, int frame_count) {
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
                                        {"frames", frame_count}};
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
    const std::string what =
        options.frames ? std::to_string(frame_count) + " frames " +
                             frame_file(options.output, 0, frame_count).string() + " … " +
                             frame_file(options.output, frame_count - 1, frame_count).string()
                       : options.output.string();
    report_written(what, desc.width, desc.height, mode, ro.spp, stats.seconds);
}

}  // namespace

int run_render_command(const RenderCommandOptions& options) {
    const Result<FilterMode> mode = parse_render_filter(options.filter);
    if (!mode) return fail(mode.error().message);
    if (const auto problem = option_problem(options)) return fail(*problem);
    if (const auto problem = output_file_problem(options.output)) return fail(*problem);

    Result<SceneDesc> desc = load_scene_file(options.scene);
    if (!desc) return fail(with_shared_data_hint(desc.error().message));
    const bool show_progress = !options.quiet && Progress::stderr_is_terminal();
    if (show_progress) std::fprintf(stderr, "  loading %s\n", options.scene.string().c_str());
    if (options.frames && desc->camera_path.empty()) {
        return fail(options.scene.string() + ": --frames needs a camera_path in the scene");
    }
    if (options.width) resize_image(*desc, *options.width);
    Result<RenderScene> scene = prepare_render_scene(*desc);
    if (!scene) return fail(scene.error().message);

    RenderOptions render_options;
    render_options.filter = *mode;
    render_options.spp =
        options.spp.value_or(*mode == FilterMode::reference ? kDefaultReferenceSpp : 1);
    render_options.seed = options.seed;
    render_options.threads = options.threads;
    const int frame_count = options.frames.value_or(1);
    render_options.frame_count = options.frames.value_or(0);
    Progress progress(
        std::string("render ") + filter_mode_name(*mode),
        static_cast<std::uint64_t>(render_tile_count(desc->width, desc->height)) * frame_count,
        show_progress);
    RenderStats stats;
    RunOutputs outputs;  // a sequence that fails part way leaves none of its frames behind
    for (int frame = 0; frame < frame_count; ++frame) {
        render_options.frame = frame;
        RenderStats frame_stats;
        Image image = render(*scene, render_options, &frame_stats, [&] { progress.advance(); });
        stats.seconds += frame_stats.seconds;
        stats.pixels += frame_stats.pixels;
        stats.samples += frame_stats.samples;
        stats.lookups += frame_stats.lookups;
        stats.non_finite_samples += frame_stats.non_finite_samples;
        stats.non_finite_pixels += frame_stats.non_finite_pixels;
        if (!is_float_format(options.output) && options.exposure != 0) {
            const float scale = std::exp2(options.exposure);
            for (float& v : image.pixels) v *= scale;
        }
        const std::filesystem::path file =
            options.frames ? frame_file(options.output, frame, frame_count) : options.output;
        if (Status saved = outputs.save(image, file); !saved) return fail(saved.error().message);
    }
    outputs.keep();
    progress.finish();
    report(options, *desc, render_options, stats, frame_count);
    return 0;
}

}  // namespace footprint
