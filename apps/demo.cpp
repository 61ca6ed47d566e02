#include "demo.h"

#include <cmath>
#include <cstdio>
#include <system_error>

#include <nlohmann/json.hpp>

#include "cli_options.h"
#include "command_util.h"
#include "demo_scenes.h"
#include "image/image_io.h"
#include "metrics/image_metrics.h"
#include "plane_view.h"
#include "progress.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "render_progress.h"

namespace footprint {

namespace {

namespace fs = std::filesystem;

constexpr FilterMode kDemoModes[] = {FilterMode::bilinear, FilterMode::trilinear, FilterMode::fa,
                                     FilterMode::fa_rough, FilterMode::ewa_rough};

struct Rendered {
    Image image;
    RenderStats stats;
};

Result<Rendered> render_timed(const RenderScene& scene, const RenderOptions& options,
                              const std::string& label, bool show_progress) {
    Rendered r;
    Result<Image> image = render_with_progress(scene, options, label, show_progress, &r.stats);
    if (!image) return image.error();
    r.image = std::move(*image);
    return r;
}

}  // namespace

int run_demo_command(const DemoCommandOptions& options) {
    if (auto problem = range_problem("--size", options.width, kDemoWidths)) return fail(*problem);
    if (options.reference_spp < 1 || options.reference_spp > 65536) {
        return fail("--spp " + std::to_string(options.reference_spp) +
                    " is out of range (1 to 65536)");
    }
    if (auto problem = range_problem("--threads", options.threads, 0, 1024, "0: all cores"))
        return fail(*problem);
    const std::vector<std::string>& names =
        options.scenes.empty() ? demo_scene_names() : options.scenes;
    DemoSceneOptions scene_options;
    scene_options.width = options.width;
    scene_options.height = plane_view_height(options.width);
    std::vector<DemoScene> scenes;
    for (const std::string& name : names) {
        Result<DemoScene> scene = make_demo_scene(name, scene_options);
        if (!scene) return fail(scene.error().message);
        scenes.push_back(std::move(*scene));
    }
    RunOutputs outputs;  // a failed run leaves none of its files behind
    if (Status made = outputs.create_directories(options.out_dir); !made)
        return fail(made.error().message);

    const bool show_progress = !options.quiet && Progress::stderr_is_terminal();
    nlohmann::json report = {{"width", scene_options.width},
                             {"height", scene_options.height},
                             {"reference_spp", options.reference_spp},
                             {"scenes", nlohmann::json::array()}};
    std::printf("%-17s %-10s %10s %9s\n", "scene", "filter", "rmse", "seconds");
    bool warned = false;  // the contact sheets' warning (no labels), once
    for (const DemoScene& demo : scenes) {
        Result<RenderScene> scene = prepare_render_scene(demo.scene);
        if (!scene) return fail("demo scene " + demo.name + ": " + scene.error().message);
        const fs::path dir = options.out_dir / demo.name;
        if (Status made = outputs.create_directories(dir); !made) return fail(made.error().message);

        RenderOptions render_options;
        render_options.threads = options.threads;
        render_options.filter = FilterMode::reference;
        render_options.spp = options.reference_spp;
        const Result<Rendered> rendered_reference =
            render_timed(*scene, render_options, demo.name + " reference", show_progress);
        if (!rendered_reference) return fail(rendered_reference.error().message);
        const Rendered& reference = *rendered_reference;
        if (Status s = outputs.save(reference.image, dir / "reference.png"); !s) {
            return fail(s.error().message);
        }
        nlohmann::json entry = {
            {"name", demo.name},
            {"title", demo.title},
            {"assets", demo.assets},
            {"reference",
             {{"file", demo.name + "/reference.png"}, {"seconds", reference.stats.seconds}}},
            {"modes", nlohmann::json::array()}};
        std::printf("%-17s %-10s %10s %9.2f\n", demo.name.c_str(), "reference", "-",
                    reference.stats.seconds);
        std::vector<Rendered> rendered;
        for (FilterMode mode : kDemoModes) {
            render_options.filter = mode;
            render_options.spp = 1;
            Result<Rendered> r = render_timed(
                *scene, render_options, demo.name + " " + filter_mode_name(mode), show_progress);
            if (!r) return fail(r.error().message);
            const std::string file = std::string(filter_mode_name(mode)) + ".png";
            if (Status s = outputs.save(r->image, dir / file); !s) return fail(s.error().message);
            const Result<ImageComparison> comparison = compare_images(r->image, reference.image);
            if (!comparison)
                return fail(demo.name + " " + filter_mode_name(mode) + ": " +
                            comparison.error().message);
            const double error = comparison->rmse;
            entry["modes"].push_back({{"filter", filter_mode_name(mode)},
                                      {"file", demo.name + "/" + file},
                                      {"rmse", error},
                                      {"seconds", r->stats.seconds},
                                      {"lookups", r->stats.lookups}});
            std::printf("%-17s %-10s %10.5f %9.3f\n", demo.name.c_str(), filter_mode_name(mode),
                        error, r->stats.seconds);
            rendered.push_back(std::move(*r));
        }
        std::vector<const Image*> sheet_images = {&reference.image};
        std::vector<std::string> labels = {
            panel_label("reference", options.reference_spp, NAN, reference.stats.seconds)};
        for (std::size_t i = 0; i < rendered.size(); ++i) {
            sheet_images.push_back(&rendered[i].image);
            labels.push_back(panel_label(filter_mode_name(kDemoModes[i]), 1,
                                         entry["modes"][i]["rmse"].get<double>(),
                                         rendered[i].stats.seconds));
        }
        const ContactSheet sheet = contact_sheet(sheet_images, labels);
        if (!sheet.warning.empty() && !warned) warn(sheet.warning);
        warned = warned || !sheet.warning.empty();
        if (Status s = outputs.save(sheet.image, dir / "contact_sheet.png"); !s) {
            return fail(s.error().message);
        }
        report["scenes"].push_back(entry);
    }
    if (Status s = outputs.write(options.out_dir / "demo.json", report.dump(2) + "\n"); !s) {
        return fail(s.error().message);
    }
    outputs.keep();
    std::printf(
        "wrote %zu scene%s (reference, %zu modes, contact sheet each) and demo.json to %s\n",
        scenes.size(), scenes.size() == 1 ? "" : "s", std::size(kDemoModes),
        options.out_dir.string().c_str());
    return 0;
}

}  // namespace footprint
