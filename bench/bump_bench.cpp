#include "bump_bench.h"

#include <tbb/global_control.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "bench_lookups.h"
#include "bench_texture_content.h"
#include "bench_util.h"
#include "bump/bump_pyramid.h"
#include "bump/slope_map.h"

namespace footprint::bench {

namespace {

// A height map with bumps at several scales: the red channel of the texture benchmark's content.
Image make_height_map(int size) {
    const Image content = make_benchmark_texture(size);
    Image height(size, size, 1);
    for (std::size_t i = 0; i < height.pixel_count(); ++i) height.pixels[i] = content.pixels[3 * i];
    return height;
}

HeightMapOptions height_options(int size) {
    HeightMapOptions o;
    o.height_scale = 0.02f;                                // world height per unit of map value
    o.texel_size_u = o.texel_size_v = 1.0f / float(size);  // a unit square
    return o;
}

}  // namespace

int run_bump_bench(const BumpBenchOptions& opt) {
    const ProgressNote note(opt.quiet);
    nlohmann::json j;
    j["benchmark"] = "bump";

    note("making the height map");
    {
        const Image height = make_height_map(opt.build_size);
        std::printf("bump pyramid build from a %d² height map (best of 3)\n%7s %12s %12s %10s\n",
                    opt.build_size, "threads", "slopes s", "pyramid s", "total s");
        for (int threads : {1, 2}) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            double best_slopes = 1e300, best_pyramid = 1e300;
            for (int r = 0; r < 3; ++r) {
                note("building, " + std::to_string(threads) + " thread(s)");
                auto start = Clock::now();
                Result<Image> slopes =
                    slopes_from_height_map(height, height_options(opt.build_size));
                if (!slopes) throw std::runtime_error(slopes.error().message);
                best_slopes = std::min(best_slopes, seconds_since(start));
                start = Clock::now();
                Result<BumpPyramid> pyramid = BumpPyramid::build(*slopes);
                if (!pyramid) throw std::runtime_error(pyramid.error().message);
                best_pyramid = std::min(best_pyramid, seconds_since(start));
            }
            std::printf("%7d %12.3f %12.3f %10.3f\n", threads, best_slopes, best_pyramid,
                        best_slopes + best_pyramid);
            j["build"].push_back({{"threads", threads},
                                  {"size", opt.build_size},
                                  {"slopes_seconds", best_slopes},
                                  {"pyramid_seconds", best_pyramid}});
        }
    }

    note("making the lookup maps");
    const Image height = make_height_map(opt.lookup_size);
    Result<Image> slopes = slopes_from_height_map(height, height_options(opt.lookup_size));
    if (!slopes) throw std::runtime_error(slopes.error().message);
    Result<BumpPyramid> bump = BumpPyramid::build(*slopes);
    if (!bump) throw std::runtime_error(bump.error().message);
    const MipPyramid colour = MipPyramid::build(make_benchmark_texture(opt.lookup_size));

    std::printf(
        "\nfiltered bump lookups, %d² bump map, Mlookups/s (colour: RGB texture_lookup, same "
        "footprints)\n",
        opt.lookup_size);
    std::printf("%-10s %-9s %7s %10s %10s %7s\n", "filter", "regime", "threads", "bump", "colour",
                "ratio");
    const TextureFilter filters[] = {TextureFilter::nearest, TextureFilter::bilinear,
                                     TextureFilter::trilinear, TextureFilter::footprint_assembly,
                                     TextureFilter::ewa};
    for (const Regime& regime : kRegimes) {
        const std::vector<TextureCoords> lookups = make_lookups(
            regime, opt.lookups_per_regime, opt.lookup_size, 4321u + unsigned(regime.major * 8));
        for (TextureFilter filter : filters) {
            LookupOptions lo;
            lo.filter = filter;
            for (int threads : {1, 2}) {
                note(std::string(to_string(filter)) + ", " + regime.name);
                const double bump_rate =
                    measure_rate(lookups.size(), threads, [&](int, std::size_t b, std::size_t e) {
                        float sink = 0;
                        for (std::size_t i = b; i < e; ++i)
                            sink += bump_lookup(*bump, lookups[i], lo).covariance.xx;
                        volatile float keep = sink;
                        (void)keep;
                    });
                const double colour_rate =
                    measure_rate(lookups.size(), threads, [&](int, std::size_t b, std::size_t e) {
                        float out[4], sink = 0;
                        for (std::size_t i = b; i < e; ++i) {
                            texture_lookup(colour, lookups[i], lo, out);
                            sink += out[0];
                        }
                        volatile float keep = sink;
                        (void)keep;
                    });
                std::printf("%-10s %-9s %7d %10.3f %10.3f %7.2f\n", to_string(filter), regime.name,
                            threads, bump_rate / 1e6, colour_rate / 1e6, bump_rate / colour_rate);
                j["cases"].push_back({{"filter", to_string(filter)},
                                      {"regime", regime.name},
                                      {"threads", threads},
                                      {"bump_mlookups_per_s", bump_rate / 1e6},
                                      {"colour_mlookups_per_s", colour_rate / 1e6}});
            }
        }
    }
    if (!opt.json_path.empty()) {
        write_json(opt.json_path, j);
    }
    return 0;
}

}  // namespace footprint::bench
