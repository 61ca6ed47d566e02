#include "eval_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "cli_options.h"
#include "command_util.h"
#include "demo_scenes.h"
#include "eval_budget.h"
#include "eval_report.h"
#include "image/color.h"
#include "image/image_io.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"
#include "number_format.h"
#include "plane_view.h"
#include "progress.h"
#include "render/camera.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "render_progress.h"
#include "scene/scene_file.h"
#include "scene/scene_hash.h"
#include "texture/footprint_assembly.h"

namespace footprint {

namespace {

namespace fs = std::filesystem;

constexpr FilterMode kFilterModes[] = {FilterMode::bilinear, FilterMode::trilinear, FilterMode::fa,
                                       FilterMode::fa_rough, FilterMode::ewa_rough};
// Bumped whenever the reference's rendering changes, so that no cached reference of an older
// renderer is reused.
constexpr int kReferenceVersion = 4;
// Every render of an evaluation has its own seed, so that no two share a sample: the reference,
// the reference sequence, then each method (kFirstMethodSeed + its index; a sequence uses its
// method's seed for every frame). Supersampling with the reference's seed would take a prefix of
// the reference's own samples and measure an error that is too small.
constexpr std::uint32_t kReferenceSeed = 1, kSequenceReferenceSeed = 2, kFirstMethodSeed = 3;
constexpr int kMaxSpp = 1 << 16, kMaxReferenceSpp = 1 << 20, kMaxThreads = 1024;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Timed {
    Image image;
    double seconds = 0;
};

class Renderer {
  public:
    // `base`: the threads and the filters' tuning (κ, N_max) of every render.
    Renderer(const RenderScene& scene, const RenderOptions& base, bool progress)
        : scene_(scene), base_(base), progress_(progress) {}

    Result<Timed> render_one(FilterMode mode, int spp, std::uint32_t seed, const std::string& label,
                             int frame = 0, int frame_count = 0) const {
        RenderOptions options = base_;
        options.filter = mode;
        options.spp = spp;
        options.seed = seed;
        options.frame = frame;
        options.frame_count = frame_count;
        RenderStats stats;
        Result<Image> image = render_with_progress(scene_, options, label, progress_, &stats);
        if (!image) return image.error();
        return Timed{std::move(*image), stats.seconds};
    }

    Result<std::vector<Image>> sequence(FilterMode mode, int spp, std::uint32_t seed, int frames,
                                        const std::string& label) const {
        std::vector<Image> images;
        for (int f = 0; f < frames; ++f) {
            Result<Timed> t =
                render_one(mode, spp, seed,
                           label + " frame " + std::to_string(f + 1) + "/" + std::to_string(frames),
                           f, frames);
            if (!t) return t.error();
            images.push_back(std::move(t->image));
        }
        return images;
    }

  private:
    const RenderScene& scene_;
    RenderOptions base_;
    bool progress_;
};

// A cached render: read if present, else rendered and written (EXR, linear float).
Result<Image> cached(const fs::path& file, bool& was_cached,
                     const std::function<Result<Image>()>& make) {
    std::error_code ec;
    if (fs::is_regular_file(file, ec)) {
        Result<Image> image = load_image(file);
        if (image) {
            was_cached = true;
            return image;
        }
    }
    was_cached = false;
    Result<Image> image = make();
    if (!image) return image;
    if (Status s = save_image(*image, file); !s) return s.error();
    return image;
}

// Whether any value of an image is above 1: HDR, for FLIP.
bool has_hdr_values(const Image& image) {
    return std::any_of(image.pixels.begin(), image.pixels.end(), [](float v) { return v > 1; });
}

// What people look at: sRGB of the value clamped to [0, 1].
Image display_encoded(const Image& linear) {
    Image out = linear;
    for (float& v : out.pixels) v = linear_to_srgb(std::clamp(v, 0.0f, 1.0f));
    return out;
}

// Per-pixel mean |a − b| over the channels (1 channel), for choosing the crops.
Image absolute_error(const Image& a, const Image& b) {
    Image e(a.width, a.height, 1);
    for (std::size_t p = 0; p < a.pixel_count(); ++p) {
        double sum = 0;
        for (int c = 0; c < a.channels; ++c) {
            sum += std::abs(a.pixels[p * a.channels + c] - b.pixels[p * a.channels + c]);
        }
        e.pixels[p] = static_cast<float>(sum / a.channels);
    }
    return e;
}

// The first problem with the command line's numbers, if any.
std::optional<std::string> option_problem(const EvalCommandOptions& options) {
    if (auto problem = range_problem("--size", options.width, kDemoWidths)) return problem;
    if (auto problem = range_problem("--reference-spp", options.reference_spp, 1, kMaxReferenceSpp))
        return problem;
    if (options.supersampling_spp.empty()) return "--spp-list: needs at least one value";
    for (int spp : options.supersampling_spp) {
        if (auto problem = range_problem("--spp-list", spp, 1, kMaxSpp)) return problem;
        if (spp >= options.reference_spp) {
            return "--spp-list: " + std::to_string(spp) + " is not below --reference-spp " +
                   std::to_string(options.reference_spp) +
                   " (supersampling is measured against the reference: it must take fewer "
                   "samples)";
        }
    }
    if (options.filter_spp.empty() || options.filter_spp.front() != 1) {
        return "--filter-spp-list: must start with 1 (the filter modes' own rate)";
    }
    for (int spp : options.filter_spp) {
        if (auto problem = range_problem("--filter-spp-list", spp, 1, kMaxSpp)) return problem;
    }
    if (options.frames != 0) {
        if (auto problem = range_problem("--frames", options.frames, 2, 1000, "0: no flicker"))
            return problem;
    }
    if (auto problem = range_problem("--flicker-reference-spp", options.flicker_reference_spp, 1,
                                     kMaxReferenceSpp))
        return problem;
    if (auto problem = range_problem("--threads", options.threads, 0, kMaxThreads, "0: all cores"))
        return problem;
    if (auto problem = range_problem("--max-probes", options.max_probes, 1, kMaxProbeCount))
        return problem;
    return kappa_problem(options.kappa);
}

}  // namespace

Result<std::vector<NamedScene>> resolve_eval_scenes(const EvalCommandOptions& options) {
    std::vector<std::string> names = options.scenes;
    if (names.empty()) names = demo_scene_names();
    std::vector<NamedScene> scenes;
    for (const std::string& name : names) {
        Result<NamedScene> scene = resolve_scene(name, options.width);
        if (!scene) return scene.error();
        scenes.push_back(std::move(*scene));
    }
    return scenes;
}

std::optional<std::string> kappa_problem(float kappa) {
    if (kappa >= 0 && kappa <= 16) return std::nullopt;
    return "--kappa: " + std::to_string(kappa) + " is not in 0 … 16";
}

int run_eval_command(const EvalCommandOptions& options) {
    if (options.budget) return run_error_budget_command(options);
    if (const auto problem = option_problem(options)) return fail(*problem);
    Result<std::vector<NamedScene>> resolved = resolve_eval_scenes(options);
    if (!resolved) return fail(resolved.error().message);
    const std::vector<NamedScene>& scenes = *resolved;
    // Flicker is measured along a scene's camera path: asked for on a scene without one, refused
    // as `render --frames` refuses it (by default such a scene has no flicker column).
    for (const NamedScene& named : scenes)
        if (options.frames_given && options.frames != 0 && named.desc.camera_path.empty())
            return fail(named.name + ": --frames needs a camera_path in the scene");
    // A failed run leaves none of its files behind, except the cache: references of the scenes'
    // content, valid whatever failed, so that the run after the fix need not render them again.
    RunOutputs outputs;
    if (Status made = outputs.create_directories(options.out_dir / "cache"); !made)
        return fail(made.error().message);

    const bool show_progress = !options.quiet && Progress::stderr_is_terminal();
    EvalReport report;
    report.title = "footprint eval";
    report.generated_by = "footprint eval, " + std::to_string(options.reference_spp) +
                          "-spp references, flicker over " + std::to_string(options.frames) +
                          " frames";
    nlohmann::json results = {{"reference_spp", options.reference_spp},
                              {"frames", options.frames},
                              {"flicker_reference_spp", options.flicker_reference_spp},
                              {"scenes", nlohmann::json::array()}};
    std::string csv =
        "scene,method,family,spp,rmse,rmse_interior,ssim,flip_interior,flicker,seconds,"
        "equal_error_speedup\n";

    for (const NamedScene& named : scenes) {
        Result<RenderScene> prepared = prepare_render_scene(named.desc);
        if (!prepared) return fail("scene " + named.name + ": " + prepared.error().message);
        const RenderScene& scene = *prepared;
        const SceneDesc& desc = scene.desc();
        const fs::path dir = options.out_dir / named.name;
        if (Status made = outputs.create_directories(dir); !made) return fail(made.error().message);
        RenderOptions base;
        base.threads = options.threads;
        base.kappa = options.kappa;
        base.max_probes = options.max_probes;
        const Renderer renderer(scene, base, show_progress);
        const std::string key = hash_hex(scene_content_hash(desc)) + "-v" +
                                std::to_string(kReferenceVersion) + "-" +
                                std::to_string(desc.width) + "x" + std::to_string(desc.height);

        // The reference, cached by content.
        bool reference_cached = false;
        double reference_seconds = 0;
        Result<Image> reference = cached(
            options.out_dir / "cache" /
                (key + "-ref" + std::to_string(options.reference_spp) + ".exr"),
            reference_cached, [&]() -> Result<Image> {
                Result<Timed> t = renderer.render_one(FilterMode::reference, options.reference_spp,
                                                      kReferenceSeed, named.name + " reference");
                if (!t) return t.error();
                reference_seconds = t->seconds;
                return std::move(t->image);
            });
        if (!reference) return fail(reference.error().message);
        const Image reference_display = display_encoded(*reference);
        if (Status s = outputs.save(*reference, dir / "reference.png"); !s) {
            return fail(s.error().message);
        }

        // The reference sequence for flicker, cached likewise.
        const bool animated = options.frames >= 2 && !desc.camera_path.empty();
        std::vector<Image> reference_sequence;
        bool sequence_cached = animated;
        for (int f = 0; animated && f < options.frames; ++f) {
            bool was_cached = false;
            Result<Image> frame =
                cached(options.out_dir / "cache" /
                           (key + "-seq" + std::to_string(options.frames) + "-ref" +
                            std::to_string(options.flicker_reference_spp) + "-" +
                            std::to_string(f) + ".exr"),
                       was_cached, [&]() -> Result<Image> {
                           Result<Timed> t = renderer.render_one(
                               FilterMode::reference, options.flicker_reference_spp,
                               kSequenceReferenceSeed,
                               named.name + " reference frame " + std::to_string(f + 1) + "/" +
                                   std::to_string(options.frames),
                               f, options.frames);
                           if (!t) return t.error();
                           return std::move(t->image);
                       });
            if (!frame) return fail(frame.error().message);
            sequence_cached = sequence_cached && was_cached;
            reference_sequence.push_back(std::move(*frame));
        }

        const Image mask = interior_mask(scene);
        // FLIP over the interior, LDR or HDR as the reference is, for every method alike.
        FlipOptions flip_options;
        flip_options.mask = &mask;
        flip_options.range = has_hdr_values(*reference) ? FlipRange::hdr : FlipRange::ldr;
        double interior_fraction = 0;
        for (float m : mask.pixels) interior_fraction += m;
        interior_fraction /= static_cast<double>(std::max<std::size_t>(1, mask.pixels.size()));

        struct Method {
            FilterMode mode;
            int spp;
            std::string name, family, file;
            std::uint32_t seed = 0;
        };
        std::vector<Method> methods;
        auto add_modes = [&](std::span<const FilterMode> modes, const std::string& family) {
            for (FilterMode mode : modes) {
                for (int spp : options.filter_spp) {
                    const std::string name = filter_mode_name(mode);
                    const std::string rate = std::to_string(spp) + " spp";
                    methods.push_back({mode, spp, spp == 1 ? name : name + " " + rate, family,
                                       spp == 1 ? name : name + "_" + std::to_string(spp) + "spp"});
                }
            }
        };
        add_modes(kFilterModes, "filter");
        if (options.peers) add_modes(peer_filter_modes(), "peer");
        for (int spp : options.supersampling_spp) {
            methods.push_back({FilterMode::reference, spp,
                               "supersampling " + std::to_string(spp) + " spp", "supersampling",
                               "supersampling_" + std::to_string(spp)});
        }
        for (std::size_t i = 0; i < methods.size(); ++i) {
            methods[i].seed = kFirstMethodSeed + static_cast<std::uint32_t>(i);
        }

        EvalScene eval_scene;
        eval_scene.name = named.name;
        eval_scene.title = named.title;
        eval_scene.width = desc.width;
        eval_scene.height = desc.height;
        eval_scene.reference_file = named.name + "/reference.png";
        eval_scene.reference_spp = options.reference_spp;
        eval_scene.reference_seconds = reference_seconds;
        // The filter modes at more than 1 spp are measured (the convergence plot) but neither
        // shown nor measured for flicker: the report shows what each method is at its own rate.
        std::vector<Image> images;       // of the methods shown
        std::vector<std::size_t> shown;  // their indices in `methods`
        for (std::size_t i = 0; i < methods.size(); ++i) {
            const Method& m = methods[i];
            const bool show = m.family == "supersampling" || m.spp == 1;
            Result<Timed> rendered =
                renderer.render_one(m.mode, m.spp, m.seed, named.name + " " + m.name);
            if (!rendered) return fail(named.name + " " + m.name + ": " + rendered.error().message);
            Timed& t = *rendered;
            EvalMethod em;
            em.name = m.name;
            em.family = m.family;
            em.series = m.family == "supersampling" ? m.family : filter_mode_name(m.mode);
            em.spp = m.spp;
            em.seconds = t.seconds;
            if (show) {
                em.image_file = named.name + "/" + m.file + ".png";
                if (Status s = outputs.save(t.image, options.out_dir / em.image_file); !s) {
                    return fail(s.error().message);
                }
            }
            Result<ImageComparison> all = compare_images(t.image, *reference);
            if (!all) return fail(named.name + " " + m.name + ": " + all.error().message);
            em.rmse = all->rmse;
            MetricsOptions interior;
            interior.mask = &mask;
            if (interior_fraction > 0) {
                Result<ImageComparison> inside = compare_images(t.image, *reference, interior);
                if (inside) em.rmse_interior = inside->rmse;
            }
            Result<ImageComparison> display =
                compare_images(display_encoded(t.image), reference_display);
            if (display) em.ssim = display->ssim;
            if (interior_fraction > 0) {
                Result<FlipResult> f = flip(t.image, *reference, flip_options);
                if (f) em.flip_interior = f->mean;
            }
            if (animated && show) {
                const Result<std::vector<Image>> sequence = renderer.sequence(
                    m.mode, m.spp, m.seed, options.frames, named.name + " " + m.name);
                if (!sequence)
                    return fail(named.name + " " + m.name + ": " + sequence.error().message);
                Result<double> f = flicker(*sequence, reference_sequence);
                em.flicker = f ? *f : kNaN;
            }
            eval_scene.methods.push_back(em);
            if (show) {
                images.push_back(std::move(t.image));
                shown.push_back(i);
            }
        }

        // Heat maps on one scale per scene that no pixel saturates (eval_report.h), crops where
        // bilinear errs most.
        std::vector<Image> errors;
        for (const Image& image : images) errors.push_back(absolute_error(image, *reference));
        eval_scene.heat_map_scale = scene_heat_map_scale(errors);
        for (std::size_t k = 0; k < shown.size(); ++k) {
            EvalMethod& em = eval_scene.methods[shown[k]];
            em.heat_map_file = named.name + "/" + methods[shown[k]].file + "_error.png";
            const Image heat = error_heat_map(images[k], *reference, eval_scene.heat_map_scale);
            if (Status s = outputs.save(heat, options.out_dir / em.heat_map_file); !s) {
                return fail(s.error().message);
            }
        }
        eval_scene.crops = hardest_regions(errors.front(), 3, std::max(12, desc.width / 10));
        // Rows of the CSV and JSON.
        const std::vector<EvalMethod> supersampling = supersampling_methods(eval_scene);
        nlohmann::json scene_json = {{"name", named.name},
                                     {"title", named.title},
                                     {"width", desc.width},
                                     {"height", desc.height},
                                     {"content_hash", key},
                                     {"reference_cached", reference_cached},
                                     {"reference_sequence_cached", sequence_cached},
                                     {"reference_seconds", json_number(reference_seconds)},
                                     {"interior_fraction", interior_fraction},
                                     {"methods", nlohmann::json::array()}};
        for (const EvalMethod& em : eval_scene.methods) {
            double speedup = kNaN;
            if (em.family != "supersampling") {
                const EqualErrorSpeedup s = equal_error_speedup(em, supersampling);
                if (s.defined) speedup = s.speedup;
            }
            scene_json["methods"].push_back({{"method", em.name},
                                             {"family", em.family},
                                             {"spp", em.spp},
                                             {"rmse", em.rmse},
                                             {"rmse_interior", json_number(em.rmse_interior)},
                                             {"ssim", em.ssim},
                                             {"flip_interior", json_number(em.flip_interior)},
                                             {"flicker", json_number(em.flicker)},
                                             {"seconds", em.seconds},
                                             {"equal_error_speedup", json_number(speedup)}});
            csv += named.name + "," + em.name + "," + em.family + "," + std::to_string(em.spp) +
                   "," + format_number(em.rmse) + "," + format_number(em.rmse_interior) + "," +
                   format_number(em.ssim) + "," + format_number(em.flip_interior) + "," +
                   format_number(em.flicker) + "," + format_number(em.seconds) + "," +
                   format_number(speedup) + "\n";
        }
        results["scenes"].push_back(scene_json);
        report.scenes.push_back(std::move(eval_scene));
        if (!options.quiet) {
            std::printf("%-17s done (reference %s)\n", named.name.c_str(),
                        reference_cached ? "cached" : "rendered");
        }
    }

    if (Status s = outputs.write(options.out_dir / "results.csv", csv); !s) {
        return fail(s.error().message);
    }
    if (Status s = outputs.write(options.out_dir / "results.json", results.dump(2) + "\n"); !s) {
        return fail(s.error().message);
    }
    const fs::path html = options.out_dir / "index.html";
    if (Status s = write_eval_report(report, html); !s) return fail(s.error().message);
    // The report is complete: one the browser check faults stays, for the user to look at.
    outputs.keep();
    if (options.browser_check) {
        const BrowserCheck check = check_report_in_browser(html, report_image_count(report));
        if (check.chromium_found && !check.passed()) {
            return fail("the report " + quoted(html) +
                        " does not show every image: " + check.problem);
        }
        if (!options.quiet && !check.chromium_found) {
            std::fprintf(stderr, "footprint: not checked in a browser: %s\n",
                         check.problem.c_str());
        }
    }
    if (!options.quiet) {
        std::printf("wrote %s, results.csv and results.json to %s\n", "index.html",
                    options.out_dir.string().c_str());
    }
    return 0;
}

}  // namespace footprint
