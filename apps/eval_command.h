// apps/eval_command.h — `footprint eval`: every claim about quality, measured against a ground
// truth, with a visual report.
//
//   footprint eval [SCENE...] --out DIR [--size W] [--reference-spp N] [--spp-list 1,4,16,64]
//                  [--filter-spp-list 1,4,16] [--peers] [--kappa K] [--max-probes N] [--frames N]
//                  [--flicker-reference-spp N] [--threads N] [--no-browser-check]
//                  [--quiet]
//   footprint eval --budget [SCENE...] --out DIR [--budget-filter MODE] ... (apps/eval_budget.h)
//
// SCENE is a built-in demo name (apps/demo_scenes.h; default: all of them) or a scene file
// (.json). For each scene it renders
//   * every filter mode at 1 spp (bilinear, trilinear, fa, fa-rough, ewa-rough:
//     apps/cli_options.h) and at the other rates of --filter-spp-list, and with --peers the
//     peers' modes (lean, toksvig, specular-aa, stochastic) likewise,
//   * supersampling at each spp of --spp-list: the `reference` mode (finest-level bilinear
//     lookups, micro-roughness sampled) with N samples per pixel, N below --reference-spp,
// and compares each with a high-spp reference (`reference` at --reference-spp, 1024 by default).
// Every render has its own seed (render/renderer.h's RenderOptions::seed), so that supersampling
// never reuses the reference's samples and its error is measured, not underestimated. Measured:
// RMSE in linear light over all pixels and over the *interior* mask (pixels whose whole pixel
// filter, ±1.5 pixels, sees one object: no silhouettes, no horizon), SSIM on the display
// encoding (sRGB of the clamped value, the images people look at), and the render time. Scenes
// with a camera_path (every built-in one) are also rendered as --frames-frame sequences
// (default 8) for every method and a reference sequence (--flicker-reference-spp, 256 by
// default), giving each method's flicker: its mean absolute frame-to-frame difference divided by
// the reference sequence's (1 = as stable as the ground truth).
//
// Writes DIR/index.html (the report: images side by side, error heat maps, zoomed crops of the
// hardest regions, the table and an error-versus-time plot with each method's equal-error
// speedup over supersampling; apps/eval_report.h), DIR/results.csv and DIR/results.json (one row
// per scene and method), the images under DIR/<scene>/, and caches the references under
// DIR/cache/ keyed by a hash of the scene's content (every field of the scene, the bytes of every
// file it reads or the pixels of every generated image) and the reference settings: a changed
// scene never reuses a stale reference. Unless --no-browser-check, the report is then opened in
// headless Chromium (when installed) and must show every image.
//
// Returns 0, or 1 after one line "footprint: …" naming the scene, file or value at fault. A run
// that fails removes the files and folders it had written, except the cache (valid references,
// kept for the run after the fix) and a complete report that the browser check finds faulty
// (kept to be looked at).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "command_util.h"
#include "core/result.h"

namespace footprint {

struct EvalCommandOptions {
    std::vector<std::string> scenes;  // demo names or .json files; empty: every built-in demo
    std::filesystem::path out_dir = "eval";
    int width = 320;  // built-in demos: height = width · 9/16; scene files keep their own size
    int reference_spp = 1024;
    std::vector<int> supersampling_spp = {1, 4, 16, 64};
    // The filter modes' rates: 1 first, then the rates of the convergence plot (supersampling on
    // top of filtering, RenderOptions::spp).
    std::vector<int> filter_spp = {1, 4, 16};
    int frames = 8;                   // 0: no flicker measurement
    bool frames_given = false;        // --frames named: every scene needs a camera_path
    int flicker_reference_spp = 256;  // the reference sequence's samples per pixel
    int threads = 0;
    float kappa = 2;      // κ of the filter modes' environment footprint (RenderOptions::kappa)
    int max_probes = 30;  // footprint assembly's N_max (RenderOptions::max_probes)
    // --peers: also the peers' modes (render/renderer.h: lean, toksvig, specular-aa, stochastic)
    // at every rate of filter_spp, family "peer".
    bool peers = false;
    bool browser_check = true;
    bool quiet = false;
    // --budget: the error budget of one filtered mode instead (apps/eval_budget.h), with
    // reference_spp samples.
    bool budget = false;
    std::string budget_filter = "fa-rough";  // a filtered mode's name (renderer.h)
};
int run_eval_command(const EvalCommandOptions& options);

// Shared by the evaluation and the budget (apps/eval_budget.cpp): the scenes named by
// options.scenes (every demo if none), or an Error naming the first that cannot be resolved;
// and the problem with --kappa, if any.

Result<std::vector<NamedScene>> resolve_eval_scenes(const EvalCommandOptions& options);
std::optional<std::string> kappa_problem(float kappa);

}  // namespace footprint
