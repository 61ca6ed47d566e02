// footprint-env-instructions — one batch of environment lookups, for counting instructions.
//
// Wall-clock rates on a shared machine (footprint-bench env) drift from run to run by more than
// the change a small step makes. Instructions per lookup, counted by callgrind, are exact and
// repeatable: bench/env-instructions.sh runs this program under
//   valgrind --tool=callgrind --toggle-collect='footprint::bench::run_*'
// so that only the lookups are counted (not building the map or the lookups), and divides by the
// lookup count. It prints the mean of the results and a hash of their bits (FNV-1a, 64 bits), which
// tells whether a change kept the results bit for bit.
//
// Usage: footprint-env-instructions LAYOUT REGIME FORM [LOOKUPS]
//   LAYOUT latlong | cube;  REGIME tiny | moderate | aniso32 | pole_band;  FORM single | batch
//   FORM probes: no lookups; prints how many trilinear probes the regime's lookups take (the
//   footprint assembly plan of each, on the face or polar cap it is filtered on), which is what
//   their instruction counts mostly follow.
// The map is smaller than the benchmark's (1024×512 lat-long, 6×512² cube converted from it), so
// that building it under valgrind takes seconds; the footprints are sized in its texels.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "env_lookups.h"
#include "envmap/env_convert.h"
#include "envmap/env_footprint.h"
#include "envmap/env_image_io.h"
#include "envmap/environment_map.h"
#include "envmap/polar_caps.h"
#include "math/footprint_ellipse.h"
#include "texture/footprint_assembly.h"

namespace footprint::bench {

// Out of line, both: callgrind counts only the calls of footprint::bench::run_* (see above), so
// they must stay functions of their own, whatever the optimiser would inline.
[[gnu::noinline]] void run_single(const EnvironmentMap& map, const std::vector<EnvLookup>& lookups,
                                  const EnvLookupOptions& options, float* out) {
    for (std::size_t i = 0; i < lookups.size(); ++i)
        environment_lookup(map, lookups[i].direction, lookups[i].d_dx, lookups[i].d_dy, options,
                           out + 3 * i);
}

[[gnu::noinline]] void run_batch(const EnvironmentMap& map, const std::vector<EnvLookup>& lookups,
                                 const EnvLookupOptions& options, float* out) {
    environment_lookup_batch(map, lookups, options, out);
}

// The probe count of each lookup, as environment_lookup() plans it: on the polar cap of a lat-long
// map near a pole, else on the face of the footprint's centre. Prints the histogram and the mean.
void print_probe_counts(const EnvironmentMap& map, const std::vector<EnvLookup>& lookups,
                        const LookupOptions& options) {
    std::map<int, std::size_t> histogram;
    std::vector<float> anisotropy;  // λ1 / max(λ2, 1), as the plans see it
    double sum = 0;
    for (const EnvLookup& q : lookups) {
        const EnvFootprint f =
            compute_env_footprint(map.layout(), map.texel_scale(), q.direction, q.d_dx, q.d_dy);
        Sym2 k = f.matrix;
        int max_level = map.face(f.coords.face).max_level();
        const bool has_caps = map.layout() == EnvLayout::latlong && map.polar_cap(0);
        if (const PolarCapFootprint cap =
                has_caps ? polar_cap_footprint(map, f) : PolarCapFootprint{};
            cap.valid) {
            k = cap.matrix;
            max_level = cap.cap->max_level();
        }
        const FootprintEllipse ellipse = make_footprint_ellipse(k);
        anisotropy.push_back(ellipse.major_radius / std::max(ellipse.minor_radius, 1.0f));
        const ProbePlan plan = plan_probes(ellipse, options.probe_rule, options.max_probes,
                                           max_level, options.lod_bias, options.isotropic_ratio);
        ++histogram[plan.count];
        sum += plan.count;
    }
    std::printf("probes per lookup: mean %.2f;", sum / static_cast<double>(lookups.size()));
    for (const auto& [count, lookups_with_it] : histogram)
        std::printf(
            " %d: %.1f %%", count,
            100.0 * static_cast<double>(lookups_with_it) / static_cast<double>(lookups.size()));
    std::sort(anisotropy.begin(), anisotropy.end());
    std::printf("\nanisotropy λ1/max(λ2, 1) percentiles:");
    for (int percent : {10, 25, 50, 75, 90})
        std::printf(" %d: %.2f", percent, anisotropy[(anisotropy.size() - 1) * percent / 100]);
    std::printf("\n");
}

int run(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr,
                     "usage: footprint-env-instructions latlong|cube "
                     "tiny|moderate|aniso32|pole_band single|batch|probes [lookups]\n");
        return 2;
    }
    const std::string layout = argv[1], regime_name = argv[2], form = argv[3];
    const EnvRegime* regime = nullptr;
    for (const EnvRegime& r : kEnvRegimes)
        if (regime_name == r.name) regime = &r;
    if (!regime || (layout != "latlong" && layout != "cube") ||
        (form != "single" && form != "batch" && form != "probes")) {
        std::fprintf(stderr, "footprint-env-instructions: unknown layout, regime or form\n");
        return 2;
    }
    const int count = argc > 4 ? std::atoi(argv[4]) : 20000;
    if (count < 1) {
        std::fprintf(stderr, "footprint-env-instructions: lookups must be at least 1\n");
        return 2;
    }
    constexpr int kWidth = 1024, kHeight = 512;
    const Image latlong_image = make_latlong_image(kWidth, kHeight);
    Result<EnvironmentMap> map = EnvironmentMap::from_latlong(latlong_image);
    if (map && layout == "cube") {
        EnvConvertOptions convert;
        convert.size = kHeight;
        Result<EnvImages> faces = convert_environment(*map, EnvLayout::cube, convert);
        if (!faces) {
            std::fprintf(stderr, "footprint-env-instructions: %s\n", faces.error().message.c_str());
            return 1;
        }
        map = make_environment_map(*faces);
    }
    if (!map) {
        std::fprintf(stderr, "footprint-env-instructions: %s\n", map.error().message.c_str());
        return 1;
    }
    const std::vector<EnvLookup> lookups =
        make_env_lookups(*regime, static_cast<std::size_t>(count), kWidth, kHeight, 7);
    const EnvLookupOptions options;
    if (form == "probes") {
        print_probe_counts(*map, lookups, options);
        return 0;
    }
    std::vector<float> out(3 * lookups.size());
    // One uncounted lookup of each regime first: one-time initialisation on first use (a
    // function-local table) is not a lookup's cost.
    for (const EnvRegime& r : kEnvRegimes)
        for (const EnvLookup& q : make_env_lookups(r, 1, kWidth, kHeight, 1))
            environment_lookup(*map, q.direction, q.d_dx, q.d_dy, options, out.data());
    if (form == "batch")
        run_batch(*map, lookups, options, out.data());
    else
        run_single(*map, lookups, options, out.data());
    double sum = 0;
    std::uint64_t bits_hash = 14695981039346656037ull;  // FNV-1a
    for (float v : out) {
        sum += v;
        std::uint32_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        for (int byte = 0; byte < 4; ++byte) {
            bits_hash ^= (bits >> (8 * byte)) & 0xffu;
            bits_hash *= 1099511628211ull;
        }
    }
    std::printf("%s %s %s: %d lookups, mean %.7f, results %016llx\n", layout.c_str(), regime->name,
                form.c_str(), count, sum / static_cast<double>(out.size()),
                static_cast<unsigned long long>(bits_hash));
    return 0;
}

}  // namespace footprint::bench

int main(int argc, char** argv) {
    return footprint::bench::run(argc, argv);
}
