#include "render_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

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

int run_render_command(const RenderCommandOptions& options) {
    const std::optional<FilterMode> mode = parse_filter_mode(options.filter);
    if (!mode) {
        return fail("--filter: unknown mode '" + options.filter +
                    "' (valid: " + filter_mode_names() + ")");
    }
    if (options.spp < 0 || options.spp > kMaxSpp) {
        return fail("--spp: " + std::to_string(options.spp) + " is not in 1 … " +
                    std::to_string(kMaxSpp));
    }
    if (options.threads < 0) return fail("--threads: must be ≥ 0 (0: all cores)");
    if (!std::isfinite(options.exposure)) return fail("--exposure: must be finite");
    if (options.frames < 0 || options.frames > 100000) {
        return fail("--frames: " + std::to_string(options.frames) + " is not in 1 … 100000");
    }
    if (const auto problem = output_file_problem(options.output)) return fail(*problem);

    Result<SceneDesc> desc = load_scene_file(options.scene);
    if (!desc) return fail(desc.error().message);
    const bool show_progress = !options.quiet && Progress::stderr_is_terminal();
    if (show_progress) std::fprintf(stderr, "  loading %s\n", options.scene.string().c_str());
    if (options.frames > 0 && desc->camera_path.empty()) {
        return fail(options.scene.string() + ": --frames needs a camera_path in the scene");
    }
    Result<RenderScene> scene = prepare_render_scene(*desc);
    if (!scene) return fail(scene.error().message);

    RenderOptions render_options;
    render_options.filter = *mode;
    render_options.spp =
        options.spp > 0 ? options.spp : (*mode == FilterMode::reference ? kDefaultReferenceSpp : 1);
    render_options.threads = options.threads;
    const int frame_count = std::max(1, options.frames);
    render_options.frame_count = options.frames;
    Progress progress(
        std::string("render ") + filter_mode_name(*mode),
        static_cast<std::uint64_t>(render_tile_count(desc->width, desc->height)) * frame_count,
        show_progress);
    RenderStats stats;
    for (int frame = 0; frame < frame_count; ++frame) {
        render_options.frame = frame;
        RenderStats frame_stats;
        Image image = render(*scene, render_options, &frame_stats, [&] { progress.advance(); });
        stats.seconds += frame_stats.seconds;
        stats.pixels += frame_stats.pixels;
        stats.lookups += frame_stats.lookups;
        if (!is_float_format(options.output) && options.exposure != 0) {
            const float scale = std::exp2(options.exposure);
            for (float& v : image.pixels) v *= scale;
        }
        const std::filesystem::path file =
            options.frames > 0 ? frame_file(options.output, frame, frame_count) : options.output;
        if (Status saved = save_image(image, file); !saved) return fail(saved.error().message);
    }
    progress.finish();

    if (options.json) {
        const nlohmann::json summary = {{"scene", options.scene.string()},
                                        {"output", options.output.string()},
                                        {"filter", filter_mode_name(*mode)},
                                        {"spp", render_options.spp},
                                        {"threads", options.threads},
                                        {"width", desc->width},
                                        {"height", desc->height},
                                        {"pixels", stats.pixels},
                                        {"seconds", stats.seconds},
                                        {"lookups", stats.lookups},
                                        {"frames", frame_count}};
        std::printf("%s\n", summary.dump().c_str());
    } else if (!options.quiet) {
        std::fprintf(stderr, "footprint: wrote %s (%dx%d, %s, %d spp, %.2f s)\n",
                     options.output.string().c_str(), desc->width, desc->height,
                     filter_mode_name(*mode), render_options.spp, stats.seconds);
    }
    return 0;
}

}  // namespace footprint
