#include "eval_budget.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

#include "cli_options.h"
#include "command_util.h"
#include "demo_scenes.h"
#include "metrics/image_metrics.h"
#include "number_format.h"
#include "progress.h"
#include "render/error_budget.h"
#include "render/render_scene.h"
#include "render/renderer.h"

namespace footprint {

namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Row {
    std::string term, description;
    double rmse = kNaN, rmse_interior = kNaN;
};

// RMSE over every pixel and over the interior mask (NaN without interior pixels).
Result<Row> measure(const Image& image, const Image& reference, const Image& mask,
                    bool has_interior) {
    Row row;
    Result<ImageComparison> all = compare_images(image, reference);
    if (!all) return all.error();
    row.rmse = all->rmse;
    if (has_interior) {
        MetricsOptions interior;
        interior.mask = &mask;
        Result<ImageComparison> inside = compare_images(image, reference, interior);
        if (!inside) return inside.error();
        row.rmse_interior = inside->rmse;
    }
    return row;
}

// 1 − rmse/base on the interior: the share of the mode's error the term removes.
double removed(const Row& row, const Row& mode) {
    return 1 - row.rmse_interior / mode.rmse_interior;
}

}  // namespace

int run_error_budget_command(const EvalCommandOptions& options) {
    if (auto problem = range_problem("--reference-spp", options.reference_spp, 1, 1 << 20))
        return fail(*problem);
    if (const auto problem = kappa_problem(options.kappa)) return fail(*problem);
    const std::optional<FilterMode> mode = parse_filter_mode(options.budget_filter);
    if (!mode || *mode == FilterMode::reference) {
        return fail("--budget-filter: '" + options.budget_filter +
                    "' is not a filtered mode; it accepts bilinear, trilinear, fa, fa-rough, "
                    "ewa-rough, lean, toksvig, specular-aa, stochastic");
    }
    Result<std::vector<NamedScene>> resolved = resolve_eval_scenes(options);
    if (!resolved) return fail(resolved.error().message);
    const std::vector<NamedScene>& scenes = *resolved;
    RunOutputs outputs;
    if (Status made = outputs.create_directories(options.out_dir); !made)
        return fail(made.error().message);
    const bool show_progress = !options.quiet && Progress::stderr_is_terminal();
    const std::string mode_name = filter_mode_name(*mode);

    std::string csv = "scene,term,description,rmse,rmse_interior,removed_interior\n";
    nlohmann::json results = {{"filter", mode_name},
                              {"reference_spp", options.reference_spp},
                              {"scenes", nlohmann::json::array()}};
    std::string table;
    for (const NamedScene& named : scenes) {
        Result<RenderScene> prepared = prepare_render_scene(named.desc);
        if (!prepared) return fail("scene " + named.name + ": " + prepared.error().message);
        const RenderScene& scene = *prepared;
        const fs::path dir = options.out_dir / named.name;
        if (Status made = outputs.create_directories(dir); !made) return fail(made.error().message);

        ErrorBudgetOptions budget_options;
        budget_options.filter = *mode;
        budget_options.spp = options.reference_spp;
        budget_options.threads = options.threads;
        budget_options.kappa = options.kappa;
        budget_options.max_probes = options.max_probes;
        Progress bar(
            named.name + " budget",
            static_cast<std::uint64_t>(render_tile_count(scene.desc().width, scene.desc().height)),
            show_progress);
        const ErrorBudgetImages images =
            render_error_budget(scene, budget_options, [&] { bar.advance(); });
        bar.finish();
        if (Status s = scene.take_texture_errors(); !s) {
            return fail("scene " + named.name + ": " + s.error().message);
        }

        const Image mask = interior_mask(scene);
        bool has_interior = false;
        for (float m : mask.pixels) has_interior = has_interior || m > 0.5f;

        std::vector<Row> rows;
        std::vector<std::pair<std::string, const Image*>> named_images = {
            {mode_name, &images.filtered}};
        for (std::size_t t = 0; t < all_budget_terms().size(); ++t) {
            named_images.emplace_back(budget_term_name(all_budget_terms()[t]), &images.terms[t]);
        }
        for (std::size_t i = 0; i < named_images.size(); ++i) {
            Result<Row> row =
                measure(*named_images[i].second, images.reference, mask, has_interior);
            if (!row)
                return fail(named.name + " " + named_images[i].first + ": " + row.error().message);
            row->term = named_images[i].first;
            row->description = i == 0 ? "the mode as it renders, 1 spp"
                                      : budget_term_description(all_budget_terms()[i - 1]);
            rows.push_back(*row);
            if (Status s = outputs.save(*named_images[i].second,
                                        dir / ("budget_" + named_images[i].first + ".png"));
                !s) {
                return fail(s.error().message);
            }
        }
        if (Status s = outputs.save(images.reference, dir / "budget_reference.png"); !s) {
            return fail(s.error().message);
        }

        nlohmann::json scene_json = {
            {"name", named.name}, {"seconds", images.seconds}, {"terms", nlohmann::json::array()}};
        char line[256];
        std::snprintf(line, sizeof line, "%s (%s, %d-spp reference, %.1f s)\n", named.name.c_str(),
                      mode_name.c_str(), options.reference_spp, images.seconds);
        table += line;
        std::snprintf(line, sizeof line, "  %-16s %12s %12s %9s\n", "term", "RMSE", "interior",
                      "removed");
        table += line;
        for (const Row& row : rows) {
            const double share = removed(row, rows.front());
            std::snprintf(
                line, sizeof line, "  %-16s %12s %12s %9s\n", row.term.c_str(),
                format_number(row.rmse, "%.4g").c_str(),
                format_number(row.rmse_interior, "%.4g").c_str(),
                &row == &rows.front() ? "" : (format_number(100 * share, "%.1f") + " %").c_str());
            table += line;
            csv += named.name + "," + row.term + ",\"" + row.description + "\"," +
                   format_number(row.rmse) + "," + format_number(row.rmse_interior) + "," +
                   (&row == &rows.front() ? "" : format_number(share)) + "\n";
            scene_json["terms"].push_back(
                {{"term", row.term},
                 {"description", row.description},
                 {"rmse", json_number(row.rmse)},
                 {"rmse_interior", json_number(row.rmse_interior)},
                 {"removed_interior", &row == &rows.front() ? nullptr : json_number(share)}});
        }
        results["scenes"].push_back(scene_json);
    }
    if (Status s = outputs.write(options.out_dir / "budget.csv", csv); !s) {
        return fail(s.error().message);
    }
    if (Status s = outputs.write(options.out_dir / "budget.json", results.dump(2) + "\n"); !s) {
        return fail(s.error().message);
    }
    outputs.keep();
    std::fputs(table.c_str(), stdout);
    return 0;
}

}  // namespace footprint
