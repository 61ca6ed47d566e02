#include "pyramid_bench.h"

#include <tbb/global_control.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "bench_lookups.h"
#include "bench_texture_content.h"
#include "bench_util.h"
#include "texture/texture_lookup.h"

namespace footprint::bench {

int run_pyramid_bench(const PyramidBenchOptions& opt) {
    const ProgressNote note(opt.quiet);
    nlohmann::json j;
    j["benchmark"] = "pyramid";

    // Build time.
    Image rgba(opt.build_size, opt.build_size, 4);
    {
        std::mt19937 rng(1);
        std::uniform_real_distribution<float> u(0, 1);
        for (float& v : rgba.pixels) v = u(rng);
    }
    std::printf("pyramid build, %d² RGBA float (best of 3)\n%-6s %7s %10s\n", opt.build_size,
                "filter", "threads", "seconds");
    for (DownsampleFilter filter : {DownsampleFilter::box, DownsampleFilter::tent})
        for (int threads : {1, 2}) {
            note("building");
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            MipPyramidOptions po;
            po.downsample = filter;
            double best = 1e300;
            for (int r = 0; r < 3; ++r) {
                const auto start = Clock::now();
                const MipPyramid p = MipPyramid::build(rgba, po);
                best = std::min(best, seconds_since(start));
            }
            const char* name = filter == DownsampleFilter::box ? "box" : "tent";
            std::printf("%-6s %7d %10.3f\n", name, threads, best);
            j["build"].push_back({{"filter", name},
                                  {"threads", threads},
                                  {"size", opt.build_size},
                                  {"seconds", best}});
        }
    rgba = Image();

    // Layouts.
    const int size = 2048;
    const Image image = make_benchmark_texture(size);
    std::printf("\nlookups per layout, %d² RGB float, 1 thread, Mlookups/s\n%-8s %-9s", size,
                "filter", "regime");
    const int layouts[] = {0, 1, 2, 3};
    for (int t : layouts)
        std::printf(" %9s", (std::to_string(1 << t) + "x" + std::to_string(1 << t)).c_str());
    std::printf("\n");
    std::vector<MipPyramid> pyramids;
    for (int t : layouts) {
        MipPyramidOptions po;
        po.tile_log2 = t;
        pyramids.push_back(MipPyramid::build(image, po));
    }
    for (TextureFilter filter : {TextureFilter::trilinear, TextureFilter::footprint_assembly})
        for (const Regime& regime : kRegimes) {
            const std::vector<TextureCoords> lookups = make_lookups(regime, 200000, size, 77u);
            LookupOptions lo;
            lo.filter = filter;
            std::printf("%-8s %-9s", to_string(filter), regime.name);
            // Layouts measured round-robin, best of three rounds each, so that drifts in machine
            // load hit every layout alike.
            std::vector<double> best(pyramids.size(), 0.0);
            for (int round = 0; round < 3; ++round)
                for (std::size_t k = 0; k < pyramids.size(); ++k) {
                    note(std::string("layout ") + std::to_string(layouts[k]));
                    const double rate =
                        measure_rate(lookups.size(), 1, [&](int, std::size_t b, std::size_t e) {
                            float out[4], sink = 0;
                            for (std::size_t i = b; i < e; ++i) {
                                texture_lookup(pyramids[k], lookups[i], lo, out);
                                sink += out[0];
                            }
                            volatile float keep = sink;
                            (void)keep;
                        });
                    best[k] = std::max(best[k], rate);
                }
            for (std::size_t k = 0; k < pyramids.size(); ++k) {
                std::printf(" %9.3f", best[k] / 1e6);
                j["layout"].push_back({{"filter", to_string(filter)},
                                       {"regime", regime.name},
                                       {"tile", 1 << layouts[k]},
                                       {"mlookups_per_s", best[k] / 1e6}});
            }
            std::printf("\n");
        }
    if (!opt.json_path.empty()) {
        write_json(opt.json_path, j);
    }
    return 0;
}

}  // namespace footprint::bench
