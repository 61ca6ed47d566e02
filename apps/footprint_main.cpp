// footprint — the command-line program: argument parsing only; the commands live in demo.cpp,
// bake_command.cpp, env_command.cpp, eval_command.cpp, maketx_command.cpp, merge_command.cpp,
// metrics_command.cpp, render_command.cpp, texture_demo.cpp and view_command.cpp.
//   footprint --version
//   footprint demo [--out DIR] [--scene NAME...] [--size N] [--spp N] [--threads N] [--quiet]
//   footprint eval [SCENE...] [--out DIR] [--size W] [--reference-spp N] [--spp-list 1,4,16,64]
//                  [--filter-spp-list 1,4,16] [--peers] [--kappa K]
//                  [--budget [--budget-filter MODE]]
//                  [--frames N] [--flicker-reference-spp N] [--threads N] [--no-browser-check]
//   footprint metrics A B [--mask M] [--peak P] [--ignore-non-finite] [--ppd N]
//                     [--flip-range ldr|hdr|auto] [--flip-map FILE] [--json]
//   footprint texture-demo [--out DIR] [--size N] [--samples N] [--quiet]
//   footprint plane TEXTURE -o OUT [--filter F] [--size N] [--uv-scale X] [--repair-non-finite]
//                   [--quiet]
//   footprint env convert IN [IN...] --to LAYOUT -o OUT [-o OUT...] [--size N] [--from LAYOUT]
//                         [--from-cube-layout A] [--cube-layout A] [--repair-non-finite] [--quiet]
//   footprint render SCENE -o OUT [--filter MODE] [--spp N] [--seed N] [--size WIDTH]
//                    [--frames N|A-B/N] [--tile I/N] [--threads N] [--exposure E]
//                    [--device cpu|gpu] [--json] [--quiet]
//   footprint merge TILE.exr... -o OUT [--exposure E] [--quiet]
//   footprint view SCENE [--filter MODE] [--size WxH] [--exposure E] [--frames N]
//                  [--screenshot FILE]
//   footprint maketx IN -o OUT.exr [--wrap MODE[,MODE]] [--downsample box|tent] [--tile-size N]
//                    [--bump [--height] [--invalid-normals clamp]] [--env LAYOUT]
//   footprint bake color|bump|env IN -o OUT.ktx|OUT.exr [--srgb|--linear] [--float32] [--wrap W]
//                  [--downsample box|tent] [--height] [--invalid-normals clamp] [--size N]
// Filter names: one vocabulary across the commands (apps/cli_options.h, kFilterHelp below).
// Exit status: 0 success, 1 bad input or failure (one line on stderr), 2 command-line usage error.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "bake_command.h"
#include "cli_options.h"
#include "command_util.h"
#include "demo.h"
#include "env_command.h"
#include "eval_command.h"
#include "maketx_command.h"
#include "merge_command.h"
#include "metrics_command.h"
#include "render_command.h"
#include "texture_demo.h"
#include "view_command.h"

namespace {

// The filter vocabulary (apps/cli_options.h), at the end of `footprint --help`.
constexpr const char* kFilterHelp = R"(
Filters (--filter; a name means the same filter in every command):
  nearest    the nearest texel of the finest level               plane, texture-demo
  bilinear   one bilinear lookup of the finest level, no         render, plane, texture-demo,
             footprint (the aliased baseline)                    demo, eval
  trilinear  isotropic MIP: two levels, bilinear in each         render, plane, texture-demo,
                                                                 demo, eval
  brilinear  trilinear, but two levels only within a quarter    plane, texture-demo
             level of a transition, one elsewhere
  fa         footprint assembly                                  render, plane, texture-demo,
                                                                 demo, eval
  fa-rough   fa plus the roughness pyramid: a bump map's         render, demo, eval
             slopes widen the reflection and the highlights
  ewa        elliptical weighted average                         plane, texture-demo
  ewa-rough  ewa plus the roughness pyramid                      render, demo, eval
  sat        summed-area table                                   plane, texture-demo
  reference  the ground truth: --spp samples per pixel, each     render (demo, eval and
             a finest-level bilinear lookup                      texture-demo render one)
  lean       peer: LEAN mapping (the slope moments) at a GPU's    render, eval --peers
             anisotropic filter
  toksvig    peer: Toksvig's normal-length roughness             render, eval --peers
  specular-aa  peer: roughness from the normal's change across   render, eval --peers
             the pixel (Kaplanyan 2016, Tokuyoshi 2019)
  stochastic peer: stochastic texture filtering (Pharr 2024),    render, eval --peers
             one random position per lookup
  point      the GPU path's bilinear                             render --device gpu, view
  hw-aniso   the GPU's own anisotropic filtering (no roughness)  render --device gpu, view
  (render --device gpu and view also take trilinear, fa, fa-rough)
)";

// An option that takes one of `names`, refused as footprint words an unknown value
// (cli_options.h), not as CLI11 does.
CLI::Validator one_of(std::vector<std::string_view> names) {
    return CLI::Validator(
        [names](std::string& value) {
            return footprint::unknown_value_problem(value, names).value_or(std::string());
        },
        "");
}

int run(int argc, char** argv) {
    CLI::App app{"footprint — anisotropic texture filtering by footprint assembly"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "footprint " FOOTPRINT_VERSION);

    footprint::TextureDemoOptions demo;
    std::string demo_out = "out/texture";
    CLI::App* demo_cmd = app.add_subcommand(
        "texture-demo",
        "Render the built-in texture on a grazing plane with every texture filter and a reference");
    demo_cmd->add_option("--out", demo_out, "Output directory (created if missing)")
        ->capture_default_str();
    demo_cmd
        ->add_option("--size", demo.width,
                     footprint::width_help("Image width in pixels", footprint::kDemoWidths))
        ->capture_default_str();
    demo_cmd->add_option("--samples", demo.samples_per_axis, "Reference: N×N samples per pixel")
        ->capture_default_str();
    demo_cmd->add_flag("--quiet,-q", demo.quiet, "No progress output");

    footprint::PlaneCommandOptions plane;
    std::string plane_texture, plane_output;
    CLI::App* plane_cmd =
        app.add_subcommand("plane", "Render a texture file on a grazing plane with one filter");
    plane_cmd->add_option("texture", plane_texture, "Texture file (PNG, JPEG, EXR, HDR, TIFF, …)")
        ->required();
    plane_cmd
        ->add_option("-o,--out", plane_output,
                     "Output image (.png/.jpg/.tif sRGB, .exr/.hdr linear)")
        ->required();
    plane_cmd->add_option("--filter", plane.filter, footprint::plane_filter_names("|"))
        ->capture_default_str();
    plane_cmd
        ->add_option("--size", plane.width,
                     footprint::width_help("Image width in pixels", footprint::kImageWidths))
        ->capture_default_str();
    plane_cmd->add_option("--uv-scale", plane.uv_scale, "Texture repeats per world unit")
        ->capture_default_str();
    plane_cmd->add_flag("--repair-non-finite", plane.repair_non_finite,
                        "Replace NaN/Inf texels by the mean of their finite neighbours (with a "
                        "warning) instead of refusing the texture");
    plane_cmd->add_flag("--quiet,-q", plane.quiet, "No progress output");

    footprint::MaketxCommandOptions maketx;
    std::string maketx_input, maketx_output, maketx_downsample = "box";
    CLI::App* maketx_cmd = app.add_subcommand(
        "maketx",
        "Write a texture's MIP pyramid as a tiled MIP-mapped EXR, prepared once for the "
        "texture system (as OpenImageIO's maketx)");
    maketx_cmd->add_option("input", maketx_input, "Texture file (PNG, JPEG, EXR, HDR, TIFF, …)")
        ->required();
    maketx_cmd->add_option("-o,--out", maketx_output, "Output file (.exr)")->required();
    maketx_cmd->add_option("--wrap", maketx.wrap, "repeat, clamp or mirror; or S,T")
        ->capture_default_str();
    maketx_cmd->add_option("--downsample", maketx_downsample, "The pyramid's filter: box or tent")
        ->check(one_of({"box", "tent"}))
        ->capture_default_str();
    maketx_cmd->add_option("--tile-size", maketx.tile_size, "Tiles of N×N texels, 16 to 1024")
        ->capture_default_str();
    maketx_cmd->add_flag("--bump", maketx.bump,
                         "IN is a normal map: write its bump + roughness pyramid (5 moment "
                         "channels, strength 1), read tile by tile by the texture system");
    maketx_cmd->add_flag("--height", maketx.height, "With --bump: IN is a height map");
    maketx_cmd->add_flag("--quiet,-q", maketx.quiet, "No output but errors");
    maketx_cmd->add_option("--env", maketx.env,
                           "IN is an environment map of this layout (auto, latlong, cube, sphere, "
                           "paraboloid): write its pyramids and polar caps, prepared once");
    std::string maketx_invalid = "error";
    maketx_cmd
        ->add_option("--invalid-normals", maketx_invalid,
                     "With --bump: a normal map's invalid texels are an error, or clamped")
        ->check(one_of({"error", "clamp"}))
        ->capture_default_str();

    footprint::BakeCommandOptions bake;
    std::string bake_input, bake_output, bake_invalid = "error", bake_wrap, bake_downsample;
    bool bake_srgb = false, bake_linear = false;
    int bake_size = 0;
    CLI::App* bake_cmd = app.add_subcommand(
        "bake",
        "Write the maps an engine loads (KTX 1 or EXR), level by level as footprint "
        "builds them: a colour MIP chain, bump moment maps, an environment cube map");
    bake_cmd->add_option("kind", bake.kind, "color, bump or env")
        ->required()
        ->check(one_of({"color", "bump", "env"}));
    bake_cmd->add_option("input", bake_input, "Texture, normal / height map or environment file")
        ->required();
    bake_cmd->add_option("-o,--out", bake_output, "Output file (.ktx or .exr)")->required();
    bake_cmd->add_flag("--srgb", bake_srgb, "color, env: decode IN from sRGB (default: by file)");
    bake_cmd->add_flag("--linear", bake_linear, "color, env: read IN as linear (default: by file)");
    bake_cmd->add_flag("--float32", bake.float32, "KTX: RGBA32F instead of RGBA16F");
    bake_cmd->add_option("--wrap", bake_wrap, "color, bump: repeat, clamp or mirror; or S,T");
    bake_cmd->add_option("--downsample", bake_downsample, "color, bump: box (default) or tent")
        ->check(one_of({"box", "tent"}));
    bake_cmd->add_flag("--height", bake.height, "bump: IN is a height map");
    bake_cmd
        ->add_option("--invalid-normals", bake_invalid,
                     "bump: a normal map's invalid texels are an error, or clamped")
        ->check(one_of({"error", "clamp"}))
        ->capture_default_str();
    bake_cmd->add_option("--size", bake_size,
                         "env: the cube's face edge, 1 to 16384 (default: the source's angular "
                         "resolution)");
    bake_cmd->add_flag("--quiet,-q", bake.quiet, "No output but errors");

    footprint::EnvConvertCommandOptions convert;
    std::vector<std::string> convert_inputs, convert_outputs;
    CLI::App* env_cmd = app.add_subcommand("env", "Environment maps");
    env_cmd->require_subcommand(1);
    CLI::App* convert_cmd = env_cmd->add_subcommand(
        "convert", "Convert an environment map to another layout, filtered (not point-sampled)");
    convert_cmd
        ->add_option("inputs", convert_inputs,
                     "1 file (lat-long, sphere, cube cross/strip, OpenEXR envmap), 2 (paraboloid "
                     "front, back) or 6 (cube faces +X -X +Y -Y +Z -Z)")
        ->required();
    convert_cmd->add_option("--to", convert.to, "cube|latlong|sphere|paraboloid")->required();
    convert_cmd
        ->add_option("-o,--out", convert_outputs,
                     "Output file; cube: 1 or 6 (-o per face), paraboloid: 1 (side by side) or 2")
        ->required()
        ->allow_extra_args(false);
    convert_cmd
        ->add_option("--size", convert.size,
                     "Cube face / lat-long width / sphere / paraboloid face size; 0: keep the "
                     "source's angular resolution")
        ->capture_default_str();
    convert_cmd->add_option("--from", convert.from,
                            "Input layout cube|latlong|sphere|paraboloid (default: detect)");
    convert_cmd
        ->add_option("--from-cube-layout", convert.from_cube_layout,
                     "Input cube image: auto|hcross|vcross|3x2|2x3|column|row|openexr")
        ->capture_default_str();
    convert_cmd
        ->add_option("--cube-layout", convert.cube_layout,
                     "Output cube image: hcross|vcross|3x2|2x3|column|row")
        ->capture_default_str();
    convert_cmd->add_flag("--repair-non-finite", convert.repair_non_finite,
                          "Replace NaN/Inf input texels by the mean of their finite neighbours "
                          "(with a warning) instead of refusing the input");
    convert_cmd->add_flag("--quiet,-q", convert.quiet, "No progress or summary output");

    footprint::DemoCommandOptions scene_demo;
    std::string scene_demo_out = scene_demo.out_dir.string();
    CLI::App* scene_demo_cmd = app.add_subcommand(
        "demo",
        "Render the papers' figures (built-in scenes) with every filter mode and a reference");
    scene_demo_cmd->add_option("--out", scene_demo_out, "Output directory (created if missing)")
        ->capture_default_str();
    scene_demo_cmd->add_option(
        "--scene", scene_demo.scenes,
        "Scenes to render (default: all): cylinder parabolic_mirror water "
        "bump_plate secret_writing brushed_sphere terrain procedural procedural_bump "
        "irradiance local_environment parallax shadows environment_probe");
    scene_demo_cmd
        ->add_option("--size", scene_demo.width,
                     footprint::width_help("Image width in pixels", footprint::kDemoWidths))
        ->capture_default_str();
    scene_demo_cmd
        ->add_option("--spp", scene_demo.reference_spp, "Reference samples per pixel, 1 to 65536")
        ->capture_default_str();
    scene_demo_cmd
        ->add_option("--threads", scene_demo.threads, "Worker threads, 0 to 1024 (0: all cores)")
        ->capture_default_str();
    scene_demo_cmd->add_flag("--quiet,-q", scene_demo.quiet, "No progress output");

    footprint::MetricsCommandOptions metrics;
    std::string metrics_a, metrics_b, metrics_mask, metrics_flip_map, metrics_flip_range = "auto";
    CLI::App* metrics_cmd = app.add_subcommand(
        "metrics",
        "Compare two images (linear light): RMSE, PSNR, SSIM and mean FLIP, optionally masked");
    metrics_cmd->add_option("a", metrics_a, "First image (the test)")->required();
    metrics_cmd->add_option("b", metrics_b, "Second image (the reference)")->required();
    metrics_cmd->add_option("--mask", metrics_mask, "Mask image: pixels where channel 0 > 0.5");
    metrics_cmd->add_option("--peak", metrics.peak, "PSNR peak and SSIM dynamic range")
        ->capture_default_str();
    metrics_cmd
        ->add_option("--ppd", metrics.ppd,
                     "FLIP's pixels per degree of visual angle, > 0 to 1000 (default: 0.7 m from "
                     "a 0.7 m wide 3840-pixel monitor)")
        ->capture_default_str();
    metrics_cmd
        ->add_option("--flip-range", metrics_flip_range,
                     "ldr: LDR-FLIP on values clamped to [0, 1]; hdr: HDR-FLIP (exposures from B); "
                     "auto: HDR-FLIP when a colour value of A or B is > 1")
        ->check(one_of({"ldr", "hdr", "auto"}))
        ->capture_default_str();
    metrics_cmd->add_option("--flip-map", metrics_flip_map,
                            "Write the per-pixel FLIP error (1 channel, in [0, 1]) to this image");
    metrics_cmd->add_flag("--json", metrics.json, "Print one JSON line");
    metrics_cmd->add_flag("--ignore-non-finite", metrics.ignore_non_finite,
                          "Leave pixels with NaN or infinity in A or B out of every metric "
                          "(default: an error; FLIP is then not computed)");

    footprint::EvalCommandOptions eval;
    std::string eval_out = eval.out_dir.string();
    bool eval_no_browser = false;
    CLI::App* eval_cmd = app.add_subcommand(
        "eval", "Measure every filter mode and supersampling against a reference; HTML report");
    eval_cmd->add_option("scenes", eval.scenes,
                         "Built-in demo names or .json scene files (default: every demo)");
    eval_cmd->add_option("--out", eval_out, "Output directory")->capture_default_str();
    eval_cmd
        ->add_option(
            "--size", eval.width,
            footprint::width_help("Image width of the built-in demos", footprint::kDemoWidths) +
                "; scene files keep their own size")
        ->capture_default_str();
    eval_cmd->add_option("--reference-spp", eval.reference_spp, "Reference samples per pixel")
        ->capture_default_str();
    eval_cmd
        ->add_option("--spp-list", eval.supersampling_spp,
                     "Supersampling rates, each below --reference-spp")
        ->delimiter(',')
        ->capture_default_str();
    eval_cmd
        ->add_option("--filter-spp-list", eval.filter_spp,
                     "The filter modes' rates: 1, then those of the convergence plot")
        ->delimiter(',')
        ->capture_default_str();
    eval_cmd->add_option("--frames", eval.frames, "Frames for flicker, 2 to 1000 (0: none)")
        ->capture_default_str();
    eval_cmd
        ->add_option("--flicker-reference-spp", eval.flicker_reference_spp,
                     "Samples per pixel of the reference sequence")
        ->capture_default_str();
    eval_cmd->add_option("--threads", eval.threads, "Worker threads, 0 to 1024 (0: all cores)")
        ->capture_default_str();
    eval_cmd
        ->add_option("--kappa", eval.kappa,
                     "κ of the filter modes' environment footprint, 0 to 16 (spec §2.6)")
        ->capture_default_str();
    eval_cmd
        ->add_option("--max-probes", eval.max_probes,
                     "N_max of fa's and fa-rough's probe lines, 1 to 1024 (more anisotropy raises "
                     "their level)")
        ->capture_default_str();
    eval_cmd->add_flag("--peers", eval.peers,
                       "Also the peers' modes: lean, toksvig, specular-aa, stochastic "
                       "(docs/rendering.md#peers)");
    eval_cmd->add_flag("--no-browser-check", eval_no_browser,
                       "Do not open the report in headless Chromium");
    eval_cmd->add_flag("--quiet,-q", eval.quiet, "No progress output");
    eval_cmd->add_flag("--budget", eval.budget,
                       "The error budget instead: each term of --budget-filter's pixel taken from "
                       "the reference in turn (docs/evaluation.md)");
    eval_cmd
        ->add_option("--budget-filter", eval.budget_filter,
                     "The filtered mode the budget examines (bilinear, trilinear, fa, fa-rough, "
                     "ewa-rough, or a peer's)")
        ->capture_default_str();

    footprint::RenderCommandOptions render;
    std::string render_scene, render_output;
    CLI::App* render_cmd = app.add_subcommand(
        "render", "Render a scene file (JSON) with one filter mode, or its ground truth");
    render_cmd
        ->add_option("scene", render_scene, "Scene file (.json) or a built-in demo scene's name")
        ->required();
    render_cmd
        ->add_option("-o,--out", render_output,
                     "Output image (.png/.jpg/.tif sRGB, .exr/.hdr linear)")
        ->required();
    render_cmd->add_option("--filter", render.filter, footprint::render_filter_names("|"))
        ->capture_default_str();
    render_cmd->add_option("--spp", render.spp,
                           "Samples per pixel, 1 to 65536 (default 1; reference: 64)");
    render_cmd
        ->add_option("--seed", render.seed,
                     "Seed of the sample sequences (different seeds: independent samples)")
        ->capture_default_str();
    render_cmd->add_option(
        "--size", render.width,
        "Image width in pixels, " + footprint::range_text(footprint::kImageWidths) +
            " (height from the scene's aspect ratio; default: the scene's size)");
    render_cmd->add_option("--threads", render.threads, "Worker threads, 0 to 1024 (0: all cores)")
        ->capture_default_str();
    render_cmd
        ->add_option("--exposure", render.exposure, "Exposure in stops (PNG/JPEG/TIFF output)")
        ->capture_default_str();
    std::string render_frames, render_tile;
    render_cmd->add_option("--frames", render_frames,
                           "N: render N ≥ 1 frames along the scene's camera_path (OUT_0000.png, "
                           "…); A-B/N: only frames A to B of those N");
    render_cmd->add_option("--tile", render_tile,
                           "I/N: render the I-th of N horizontal bands into OUT.exr (footprint "
                           "merge assembles them)");
    render_cmd
        ->add_option("--device", render.device,
                     "cpu, or gpu: the GPU path, one sample per pixel (--filter " +
                         footprint::gpu_filter_names("|") + ")")
        ->capture_default_str();
    render_cmd
        ->add_option("--texture-memory-mb", render.texture_memory_mb,
                     "The texture cache's bound: MiB of texels of tiled files (maketx output)")
        ->capture_default_str();
    render_cmd->add_option("--texture-cache-dir", render.texture_cache_dir,
                           "Keep pyramids built for plain image files in this folder (tiled "
                           "EXR), read tile by tile like maketx output");
    render_cmd->add_flag("--json", render.json, "Print a one-line JSON summary to stdout");
    render_cmd->add_flag("--quiet,-q", render.quiet, "No progress output");

    footprint::MergeCommandOptions merge;
    std::vector<std::string> merge_tiles;
    std::string merge_output;
    CLI::App* merge_cmd = app.add_subcommand(
        "merge", "Assemble the bands of footprint render --tile into the whole image");
    merge_cmd->add_option("tiles", merge_tiles, "The bands (.exr), in any order")->required();
    merge_cmd->add_option("-o,--out", merge_output, "Output image (as footprint render -o)")
        ->required();
    merge_cmd->add_option("--exposure", merge.exposure, "Exposure in stops (PNG/JPEG/TIFF output)")
        ->capture_default_str();
    merge_cmd->add_flag("--quiet,-q", merge.quiet, "No report line");

    footprint::ViewCommandOptions view;
    CLI::App* view_cmd = app.add_subcommand(
        "view", "Show a scene in a window, rendered on the GPU (orbit, zoom, switch modes)");
    view_cmd->add_option("scene", view.scene, "Scene file (.json) or a built-in demo scene's name")
        ->required();
    view_cmd->add_option("--filter", view.filter, footprint::gpu_filter_names("|"))
        ->capture_default_str();
    view_cmd->add_option("--size", view.size, "Window size WIDTHxHEIGHT (default 1280x720)");
    view_cmd->add_option("--exposure", view.exposure, "Exposure in stops")->capture_default_str();
    view_cmd->add_option("--frames", view.frames, "Close after N frames (scripted runs)");
    view_cmd->add_option("--screenshot", view.screenshot,
                         "With --frames: write the last frame to this image file");

    // After the subcommands (which would inherit it): the commands with --filter get it too.
    app.footer(kFilterHelp);
    render_cmd->footer(kFilterHelp);
    view_cmd->footer(kFilterHelp);
    plane_cmd->footer(kFilterHelp);

    // An unknown command, named with the nearest one (CLI11 would say only that a subcommand is
    // required).
    std::vector<std::string> command_names;
    for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; }))
        command_names.push_back(command->get_name());
    const std::vector<std::string_view> commands(command_names.begin(), command_names.end());
    if (argc >= 2) {
        if (const auto problem = footprint::unknown_command_problem(argv[1], commands)) {
            std::fprintf(stderr, "footprint: %s (see footprint --help)\n", problem->c_str());
            return 2;
        }
    }

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ValidationError& e) {
        // A value the option refuses is bad input, as footprint's own checks' are: exit 1.
        std::fprintf(stderr, "footprint: %s\n", e.what());
        return 1;
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "footprint: %s (see footprint --help)\n", e.what());
        return 2;
    }

    if (*demo_cmd) {
        demo.out_dir = demo_out;
        return footprint::run_texture_demo_command(demo);
    }
    if (*scene_demo_cmd) {
        scene_demo.out_dir = scene_demo_out;
        return footprint::run_demo_command(scene_demo);
    }
    if (*eval_cmd) {
        eval.out_dir = eval_out;
        eval.frames_given = eval_cmd->count("--frames") > 0;
        eval.browser_check = !eval_no_browser;
        return footprint::run_eval_command(eval);
    }
    if (*metrics_cmd) {
        metrics.a = metrics_a;
        metrics.b = metrics_b;
        metrics.mask = metrics_mask;
        metrics.flip_map = metrics_flip_map;
        metrics.flip_range = metrics_flip_range == "ldr"   ? footprint::FlipRange::ldr
                             : metrics_flip_range == "hdr" ? footprint::FlipRange::hdr
                                                           : footprint::FlipRange::automatic;
        return footprint::run_metrics_command(metrics);
    }
    if (*render_cmd) {
        render.scene = render_scene;
        render.output = render_output;
        if (!render_frames.empty())
            if (auto s = footprint::parse_frames_option(render_frames, render); !s)
                return footprint::fail(s.error().message);
        if (!render_tile.empty())
            if (auto s = footprint::parse_tile_option(render_tile, render); !s)
                return footprint::fail(s.error().message);
        return footprint::run_render_command(render);
    }
    if (*merge_cmd) {
        merge.tiles.assign(merge_tiles.begin(), merge_tiles.end());
        merge.output = merge_output;
        return footprint::run_merge_command(merge);
    }
    if (*view_cmd) return footprint::run_view_command(view);
    if (*maketx_cmd) {
        maketx.input = maketx_input;
        maketx.output = maketx_output;
        maketx.clamp_invalid_normals = maketx_invalid == "clamp";
        maketx.downsample = maketx_downsample == "tent" ? footprint::DownsampleFilter::tent
                                                        : footprint::DownsampleFilter::box;
        return footprint::run_maketx_command(maketx);
    }
    if (*bake_cmd) {
        if (bake_srgb && bake_linear) return footprint::fail("--srgb and --linear: give one");
        bake.input = bake_input;
        bake.output = bake_output;
        bake.encoding = bake_srgb     ? footprint::ColorEncoding::srgb
                        : bake_linear ? footprint::ColorEncoding::linear
                                      : footprint::ColorEncoding::automatic;
        if (bake_cmd->count("--wrap") > 0) bake.wrap = bake_wrap;
        if (bake_cmd->count("--downsample") > 0)
            bake.downsample = bake_downsample == "tent" ? footprint::DownsampleFilter::tent
                                                        : footprint::DownsampleFilter::box;
        if (bake_cmd->count("--size") > 0) bake.size = bake_size;
        bake.clamp_invalid_normals = bake_invalid == "clamp";
        return footprint::run_bake_command(bake);
    }
    if (*env_cmd) {
        convert.inputs.assign(convert_inputs.begin(), convert_inputs.end());
        convert.outputs.assign(convert_outputs.begin(), convert_outputs.end());
        return footprint::run_env_convert_command(convert);
    }
    plane.texture = plane_texture;
    plane.output = plane_output;
    return footprint::run_plane_command(plane);
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "footprint: internal error: %s\n", e.what());
        return 1;
    }
}
