// footprint-bench — benchmarks measured as ratios against a peer or a baseline in the same run.
//   footprint-bench texture [--json FILE]   our filters vs OpenImageIO's TextureSystem
//   footprint-bench pyramid [--json FILE]   MIP pyramid build time and memory layouts
//   footprint-bench bump [--json FILE]      bump/roughness pyramid build and filtered bump lookups
//   footprint-bench env [--json FILE]       environment-map lookups vs OpenImageIO's environment()
//   footprint-bench gpu [--json FILE] [--size WxH]   GPU frame times per mode vs hw-aniso
//   footprint-bench texsys [--json FILE]    TextureSystem vs OpenImageIO's, textures > the cache
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <stdexcept>

#include "cli_options.h"

#include "bump_bench.h"
#include "env_bench.h"
#include "gpu_bench.h"
#include "pyramid_bench.h"
#include "texsys_bench.h"
#include "texture_bench.h"

int main(int argc, char** argv) {
    using namespace footprint::bench;
    CLI::App app{"footprint-bench: texture filtering benchmarks"};
    app.require_subcommand(1);

    TextureBenchOptions texture;
    CLI::App* tex =
        app.add_subcommand("texture", "our filters against OpenImageIO's TextureSystem::texture()");
    tex->add_option("--json", texture.json_path, "write the cases as JSON to this file");
    tex->add_option("--size", texture.texture_size, "texture size (square)")
        ->check(CLI::Range(64, 8192));
    tex->add_option("--lookups", texture.lookups_per_regime, "pre-generated lookups per regime")
        ->check(CLI::Range(1000, 100000000));
    tex->add_option("--error-subset", texture.error_subset,
                    "lookups per regime compared against the reference");
    tex->add_option("--threads", texture.thread_counts, "thread counts to measure")
        ->check(CLI::Range(1, 256));
    tex->add_option("--filters", texture.filters,
                    "filters: nearest bilinear trilinear brilinear fa ewa sat");
    tex->add_option("--regimes", texture.regimes, "regimes: tiny moderate aniso32");
    tex->add_option("--tile-log2", texture.tile_log2,
                    "pyramid tile size 2^k (default: the library's)")
        ->check(CLI::Range(0, 6));
    tex->add_option("--max-probes", texture.max_probes, "footprint assembly probe budget")
        ->check(CLI::Range(1, 1024));
    tex->add_option("--probe-rule", texture.probe_rule, "footprint assembly probe rule")
        ->check(CLI::IsMember({"b", "gaussian", "ext", "texram"}));
    tex->add_option("--lod-blend", texture.lod_blend, "footprint assembly level blend")
        ->check(CLI::IsMember({"linear", "variance", "automatic"}));
    tex->add_option("--brilinear-band", texture.brilinear_band,
                    "brilinear's blend band around each level transition, in levels")
        ->check(CLI::Range(0.0f, 1.0f));
    tex->add_option("--rounds", texture.rounds, "timed passes per rate (the best counts)")
        ->check(CLI::Range(1, 100));
    tex->add_flag("!--no-oiio", texture.with_oiio, "skip the OpenImageIO peer");
    tex->add_flag("--quiet", texture.quiet, "no progress output");

    TexsysBenchOptions texsys;
    CLI::App* tsys = app.add_subcommand(
        "texsys", "the TextureSystem against OpenImageIO's on textures that do not fit its cache");
    tsys->add_option("--json", texsys.json_path, "write the results as JSON to this file");
    tsys->add_option("--textures", texsys.textures, "texture files")->check(CLI::Range(1, 64));
    tsys->add_option("--size", texsys.size, "texture size (square, RGB float)")
        ->check(CLI::Range(64, 16384));
    tsys->add_option("--cache-mb", texsys.cache_mb, "max_memory_mb of both texture systems")
        ->check(CLI::Range(1, 1 << 20));
    std::string texsys_frame;
    tsys->add_option("--frame", texsys_frame, "frame size WxH (default 1280x720)");
    tsys->add_option("--frames", texsys.frames, "frames per run, the first cold")
        ->check(CLI::Range(2, 100));
    tsys->add_option("--rounds", texsys.rounds, "runs per system, in turn (the best counts)")
        ->check(CLI::Range(1, 100));
    tsys->add_option("--threads", texsys.thread_counts, "thread counts to measure")
        ->check(CLI::Range(1, 256));
    tsys->add_option("--dir", texsys.dir, "where the texture files are written, kept and reused");
    tsys->add_option("--api", texsys.api,
                     "oiio: also footprint behind OpenImageIO's TextureSystem interface")
        ->check(CLI::IsMember({"native", "oiio"}));
    tsys->add_flag("!--no-oiio", texsys.with_oiio, "skip the OpenImageIO peer");
    tsys->add_flag("--quiet", texsys.quiet, "no progress output");

    PyramidBenchOptions pyramid;
    CLI::App* pyr =
        app.add_subcommand("pyramid", "MIP pyramid build time, and lookup speed per memory layout");
    pyr->add_option("--json", pyramid.json_path, "write the results as JSON to this file");
    pyr->add_option("--size", pyramid.build_size, "build benchmark image size (square, RGBA float)")
        ->check(CLI::Range(64, 16384));
    pyr->add_flag("--quiet", pyramid.quiet, "no progress output");

    BumpBenchOptions bump;
    CLI::App* bmp =
        app.add_subcommand("bump", "bump/roughness pyramid build time and filtered bump lookups");
    bmp->add_option("--json", bump.json_path, "write the results as JSON to this file");
    bmp->add_option("--size", bump.build_size, "height map size for the build benchmark")
        ->check(CLI::Range(16, 16384));
    bmp->add_option("--lookup-size", bump.lookup_size, "bump map size for the lookups")
        ->check(CLI::Range(16, 8192));
    bmp->add_flag("--quiet", bump.quiet, "no progress output");

    EnvBenchOptions env;
    CLI::App* envc = app.add_subcommand(
        "env", "environment-map lookups against OpenImageIO's TextureSystem::environment()");
    envc->add_option("--json", env.json_path, "write the cases as JSON to this file");
    envc->add_option("--lookups", env.lookups_per_regime, "pre-generated lookups per regime")
        ->check(CLI::Range(1000, 100000000));
    envc->add_option("--latlong-width", env.latlong_width,
                     "lat-long map width (the height is half of it)")
        ->check(CLI::Range(64, 16384));
    envc->add_option("--cube-size", env.cube_size, "cube map face size")
        ->check(CLI::Range(16, 8192));
    envc->add_option("--isotropic-ratio", env.isotropic_ratio,
                     "our lookups' LookupOptions::isotropic_ratio (1 = Rule B exactly)")
        ->check(CLI::Range(1.0f, 4.0f));
    envc->add_option("--probe-rule", env.probe_rule, "our lookups' footprint assembly probe rule")
        ->check(CLI::IsMember({"b", "gaussian"}));
    envc->add_option("--lod-blend", env.lod_blend, "our lookups' footprint assembly level blend")
        ->check(CLI::IsMember({"automatic", "linear", "variance"}));
    envc->add_option("--rounds", env.rounds, "timed passes per rate (the best counts)")
        ->check(CLI::Range(1, 100));
    envc->add_option("--error-subset", env.error_subset,
                     "lookups per regime compared against the reference");
    envc->add_option("--threads", env.thread_counts, "thread counts to measure")
        ->check(CLI::Range(1, 256));
    envc->add_option("--regimes", env.regimes, "regimes: tiny moderate aniso32 pole_band")
        ->check(CLI::IsMember({"tiny", "moderate", "aniso32", "pole_band"}));
    envc->add_flag("--footprints", env.footprints,
                   "also time lookups of precomputed footprints (form (b)'s entry points), "
                   "single and batched");
    envc->add_flag("!--no-oiio", env.with_oiio, "skip the OpenImageIO peer");
    envc->add_flag("--quiet", env.quiet, "no progress output");

    GpuBenchOptions gpu;
    CLI::App* gpuc = app.add_subcommand(
        "gpu",
        "GPU frame times of every mode on the demo scenes, against hw-aniso (the GPU's own)");
    gpuc->add_option("--json", gpu.json_path, "write the results as JSON to this file");
    gpuc->add_option("--size", gpu.size, "frame size WIDTHxHEIGHT")->capture_default_str();
    gpuc->add_option("--frames", gpu.frames, "timed frames per mode and scene")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    gpuc->add_option("--warmup", gpu.warmup, "untimed frames first")
        ->check(CLI::Range(0, 1000))
        ->capture_default_str();
    gpuc->add_option("--scenes", gpu.scenes,
                     "demo scene names or scene files (default: every demo scene)");
    gpuc->add_flag("--quality", gpu.quality,
                   "measure the images instead: interior RMSE against the CPU reference");
    gpuc->add_option("--reference-spp", gpu.reference_spp, "the reference's samples per pixel")
        ->check(CLI::Range(1, 65536))
        ->capture_default_str();

    CLI11_PARSE(app, argc, argv);
    try {
        if (*tex) return run_texture_bench(texture);
        if (*tsys) {
            if (!texsys_frame.empty()) {
                const auto size = footprint::parse_image_size("--frame", texsys_frame);
                if (!size) throw std::runtime_error(size.error().message);
                texsys.width = size->width, texsys.height = size->height;
            }
            return run_texsys_bench(texsys);
        }
        if (*pyr) return run_pyramid_bench(pyramid);
        if (*bmp) return run_bump_bench(bump);
        if (*envc) return run_env_bench(env);
        if (*gpuc) return run_gpu_bench(gpu);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "footprint-bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
