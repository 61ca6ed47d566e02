#include "render_command.h"

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
    if (const auto problem = output_file_problem(options.output)) return fail(*problem);

    Result<SceneDesc> desc = load_scene_file(options.scene);
    if (!desc) return fail(desc.error().message);
    const bool show_progress = !options.quiet && Progress::stderr_is_terminal();
    if (show_progress) std::fprintf(stderr, "  loading %s\n", options.scene.string().c_str());
    Result<RenderScene> scene = prepare_render_scene(*desc);
    if (!scene) return fail(scene.error().message);

    RenderOptions render_options;
    render_options.filter = *mode;
    render_options.spp =
        options.spp > 0 ? options.spp : (*mode == FilterMode::reference ? kDefaultReferenceSpp : 1);
    render_options.threads = options.threads;
    Progress progress(std::string("render ") + filter_mode_name(*mode),
                      static_cast<std::uint64_t>(render_tile_count(desc->width, desc->height)),
                      show_progress);
    RenderStats stats;
    Image image = render(*scene, render_options, &stats, [&] { progress.advance(); });
    progress.finish();

    if (!is_float_format(options.output) && options.exposure != 0) {
        const float scale = std::exp2(options.exposure);
        for (float& v : image.pixels) v *= scale;
    }
    if (Status saved = save_image(image, options.output); !saved)
        return fail(saved.error().message);

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
                                        {"lookups", stats.lookups}};
        std::printf("%s\n", summary.dump().c_str());
    } else if (!options.quiet) {
        std::fprintf(stderr, "footprint: wrote %s (%dx%d, %s, %d spp, %.2f s)\n",
                     options.output.string().c_str(), desc->width, desc->height,
                     filter_mode_name(*mode), render_options.spp, stats.seconds);
    }
    return 0;
}

}  // namespace footprint
