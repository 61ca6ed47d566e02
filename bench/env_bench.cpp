#include "env_bench.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <stdexcept>

#include "bench_util.h"
#include "env_lookups.h"
#include "envmap/env_convert.h"
#include "envmap/env_layout.h"
#include "envmap/env_reference.h"
#include "envmap/environment_map.h"
#include "oiio_texture_file.h"

namespace footprint::bench {

namespace {

Vec3d to_double(const Vec3& v) {
    return {v.x, v.y, v.z};
}

// ---- Ours: form (a), the footprint computed from the ray differentials inside the call (as
// OpenImageIO's environment() does).

void ours_lookup(const EnvironmentMap& map, const EnvLookup& q, const EnvLookupOptions& options,
                 float* out) {
    environment_lookup(map, q.direction, q.d_dx, q.d_dy, options, out);
}

// ---- OpenImageIO.

// OpenImageIO's lat-long convention (environment.cpp, vector_to_latlong, y up):
//   s = ½ + atan2(−R_x, R_z)/(2π),  t = ½ − atan2(R_y, hypot(R_z, R_x))/π;
// ours (env_layout.h §3.4): s = ½ + atan2(r_x, −r_z)/(2π), t = arccos(r_y/|r|)/π. Both put t = 0 at
// +Y and texel i's centre at s·W − ½, so R = (−r_x, r_y, −r_z) maps one onto the other; the
// start-up check verifies it on the actual files.
OIIO::V3fParam to_oiio(const Vec3& v) {
    return {-v.x, v.y, -v.z};
}

class OiioEnvPeer {
  public:
    OiioEnvPeer(const Image& latlong, const std::filesystem::path& tx_path)
        : file_(latlong, tx_path, OIIO::ImageBufAlgo::MakeTxEnvLatl) {}

    // A default TextureOpt (smart bicubic, anisotropic up to 32 probes), as the texture benchmark.
    void lookup(const EnvLookup& q, float* out) const {
        OIIO::TextureOpt options;
        OIIO::TextureSystem& ts = file_.system();
        ts.environment(file_.handle(), ts.get_perthread_info(), options, to_oiio(q.direction),
                       to_oiio(q.d_dx), to_oiio(q.d_dy), 3, out);
    }
    // The batched environment(): `count` ≤ Tex::BatchWidth lookups in structure-of-arrays layout
    // (OpenImageIO's), results to out[channel][lane].
    struct Batch {
        float r[3][OIIO::Tex::BatchWidth], dx[3][OIIO::Tex::BatchWidth],
            dy[3][OIIO::Tex::BatchWidth];
    };
    static Batch to_batch(const EnvLookup* q, int count) {
        Batch b{};
        for (int i = 0; i < count; ++i) {
            const Vec3 v[3] = {q[i].direction, q[i].d_dx, q[i].d_dy};
            float(*dest[3])[OIIO::Tex::BatchWidth] = {b.r, b.dx, b.dy};
            for (int k = 0; k < 3; ++k)  // to_oiio(): R = (−x, y, −z)
                dest[k][0][i] = -v[k].x, dest[k][1][i] = v[k].y, dest[k][2][i] = -v[k].z;
        }
        return b;
    }
    void lookup_batch(const Batch& b, int count, float* out) const {
        OIIO::TextureOptBatch options = default_batch_options();
        OIIO::TextureSystem& ts = file_.system();
        const OIIO::Tex::RunMask mask = first_lanes(count);
        ts.environment(file_.handle(), ts.get_perthread_info(), options, mask, &b.r[0][0],
                       &b.dx[0][0], &b.dy[0][0], 3, out);
    }

    // A bilinear point sample of level 0 (for the convention check), in OIIO's own direction
    // convention.
    void point(OIIO::V3fParam r, float* out) const {
        OIIO::TextureOpt options;
        options.interpmode = OIIO::TextureOpt::InterpBilinear;
        OIIO::TextureSystem& ts = file_.system();
        ts.environment(file_.handle(), ts.get_perthread_info(), options, r, {0, 0, 0}, {0, 0, 0}, 3,
                       out);
    }

  private:
    OiioTextureFile file_;
};

double rmse(const std::vector<float>& a, const std::vector<float>& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += double(a[i] - b[i]) * double(a[i] - b[i]);
    return std::sqrt(sum / double(a.size()));
}

bool selected(const std::vector<std::string>& list, const char* name) {
    return list.empty() || std::find(list.begin(), list.end(), name) != list.end();
}

// Proves the direction mapping to_oiio(): point lookups of OIIO (bilinear, zero differentials) at
// random directions must match our bilinear point samples of the lat-long level 0 (not our
// filtered lookups, which read the polar caps near the poles). Returns the RMSE of the
// mapping used and of the unmapped directions (which must differ, or the check proves nothing).
struct ConventionCheck {
    double mapped_rmse, unmapped_rmse;
};
ConventionCheck check_oiio_convention(const EnvironmentMap& latlong, const OiioEnvPeer& oiio) {
    constexpr int kDirections = 1000;
    std::mt19937 rng(4242u);
    std::normal_distribution<float> normal;
    std::vector<float> ours(kDirections * 3), mapped(kDirections * 3), unmapped(kDirections * 3);
    for (int i = 0; i < kDirections; ++i) {
        const Vec3 r{normal(rng), normal(rng), normal(rng)};
        environment_bilinear(latlong, r, 0, &ours[i * 3]);
        oiio.point(to_oiio(r), &mapped[i * 3]);
        oiio.point(OIIO::V3fParam(r.x, r.y, r.z), &unmapped[i * 3]);
    }
    return {rmse(ours, mapped), rmse(ours, unmapped)};
}

using Case = PeerCase;

// Lookups per call of the batched APIs: OpenImageIO's Tex::BatchWidth, and as many for ours.
constexpr int kBatch = OIIO::Tex::BatchWidth;
static_assert(kBatch <= 64);

// The "<filter>-footprint" and "<filter>-footprint-batch" cases (EnvBenchOptions::footprints):
// lookups of the footprints of `lookups` computed before the timing, one call per footprint and in
// batches of kBatch footprints. Both must return `expected` (the form (a) lookups' results) on
// its subset.
void time_footprint_lookups(const EnvironmentMap& map, const std::string& filter,
                            const std::string& regime, const std::vector<EnvLookup>& lookups,
                            const std::vector<float>& expected, const EnvBenchOptions& opt,
                            const LookupOptions& lo, double ours_rmse, std::vector<Case>& cases) {
    std::vector<EnvFootprint> footprints(lookups.size());
    for (std::size_t i = 0; i < lookups.size(); ++i)
        footprints[i] = compute_env_footprint(map.layout(), map.texel_scale(), lookups[i].direction,
                                              lookups[i].d_dx, lookups[i].d_dy);
    const std::size_t subset = expected.size() / 3;
    std::vector<float> single(subset * 3), batched(subset * 3);
    for (std::size_t i = 0; i < subset; ++i)
        environment_lookup(map, footprints[i], lo, &single[i * 3]);
    environment_lookup_batch(map, std::span(footprints.data(), subset), lo, batched.data());
    if (single != expected || batched != expected)
        throw std::runtime_error(filter + ": lookups of computed footprints differ from form (a)");
    for (int threads : opt.thread_counts) {
        const double single_rate = lookup_rate(
            footprints, threads, opt.rounds,
            [&](const EnvFootprint& f, float* out) { environment_lookup(map, f, lo, out); });
        const double batch_rate_ = batch_rate(
            footprints, threads, opt.rounds, kBatch,
            [&](const EnvFootprint* first, int count, float* out) {
                environment_lookup_batch(map, std::span(first, std::size_t(count)), lo, out);
            });
        cases.push_back({filter + "-footprint", regime, threads, single_rate, NAN, ours_rmse, NAN});
        cases.push_back(
            {filter + "-footprint-batch", regime, threads, batch_rate_, NAN, ours_rmse, NAN});
    }
}

}  // namespace

int run_env_bench(const EnvBenchOptions& opt) {
    const ProgressNote note(opt.quiet);
    const int width = opt.latlong_width, height = opt.latlong_width / 2;

    note("making the lat-long map");
    const Image latlong_image = make_latlong_image(width, height);

    note("building the lat-long pyramid");
    auto start = Clock::now();
    Result<EnvironmentMap> latlong_result = EnvironmentMap::from_latlong(latlong_image);
    if (!latlong_result) throw std::runtime_error(latlong_result.error().message);
    const double latlong_build_seconds = seconds_since(start);
    const EnvironmentMap& latlong = latlong_result.value();

    // The cube map: the lat-long map resampled by convert_environment (each cube texel the lat-long
    // map filtered over its footprint), then its pyramids.
    note("converting to a cube map");
    start = Clock::now();
    EnvConvertOptions convert;
    convert.size = opt.cube_size;
    Result<EnvImages> cube_images = convert_environment(latlong, EnvLayout::cube, convert);
    if (!cube_images) throw std::runtime_error(cube_images.error().message);
    const double convert_seconds = seconds_since(start);
    note("building the cube pyramids");
    start = Clock::now();
    Result<EnvironmentMap> cube_result = make_environment_map(cube_images.value());
    if (!cube_result) throw std::runtime_error(cube_result.error().message);
    const double cube_build_seconds = seconds_since(start);
    const EnvironmentMap& cube = cube_result.value();

    std::unique_ptr<OiioEnvPeer> oiio;
    ConventionCheck convention{NAN, NAN};
    if (opt.with_oiio) {
        note("making the OpenImageIO .tx (maketx --envlatl)");
        const auto tx = std::filesystem::temp_directory_path() /
                        ("footprint-bench-env-" + std::to_string(getpid()) + ".tx");
        oiio = std::make_unique<OiioEnvPeer>(latlong_image, tx);
        note("checking OpenImageIO's direction convention");
        convention = check_oiio_convention(latlong, *oiio);
        if (!(convention.mapped_rmse < 1e-4) || !(convention.unmapped_rmse > 1e-2))
            throw std::runtime_error(
                "OpenImageIO direction convention check failed: point lookups with R = (-x, y, "
                "-z) differ from ours by RMSE " +
                std::to_string(convention.mapped_rmse) +
                " (unmapped: " + std::to_string(convention.unmapped_rmse) + ")");
    }

    EnvLookupOptions lo;  // footprint assembly, the library defaults, no rotation
    lo.isotropic_ratio = opt.isotropic_ratio;
    lo.probe_rule = opt.probe_rule == "b" ? ProbeRule::moment_matched : ProbeRule::gaussian;
    lo.lod_blend = opt.lod_blend == "linear"     ? LodBlend::linear
                   : opt.lod_blend == "variance" ? LodBlend::variance_matched
                                                 : LodBlend::automatic;
    struct Layout {
        const char* filter;
        const EnvironmentMap* map;
    };
    const Layout layouts[] = {{"latlong-fa", &latlong}, {"cube-fa", &cube}};

    std::vector<Case> cases;
    for (const EnvRegime& regime : kEnvRegimes) {
        if (!selected(opt.regimes, regime.name)) continue;
        const std::vector<EnvLookup> lookups =
            make_env_lookups(regime, opt.lookups_per_regime, width, height,
                             4321u + unsigned(regime.major * 8) + unsigned(regime.lat_min));
        const std::size_t subset = std::min(opt.error_subset, lookups.size());

        // The ground truth on the subset (slow: dense quadrature), in parallel.
        note(std::string("reference for ") + regime.name);
        std::vector<float> truth(subset * 3);
        tbb::parallel_for(std::size_t(0), subset, [&](std::size_t i) {
            const EnvLookup& q = lookups[i];
            const SphereGaussian g = sphere_gaussian_from_ray_differentials(
                to_double(q.direction), to_double(q.d_dx), to_double(q.d_dy));
            environment_reference(latlong, g, &truth[i * 3]);
        });

        // The peer, once per regime and thread count (the same figures go into every row); like
        // ours the best of opt.rounds measure_rate rounds, so that noise favours neither side.
        double oiio_rmse = NAN;
        std::vector<double> oiio_rate(opt.thread_counts.size(), NAN),
            oiio_batch_rate(opt.thread_counts.size(), NAN);
        if (oiio) {
            std::vector<float> got(subset * 3);
            for (std::size_t i = 0; i < subset; ++i) oiio->lookup(lookups[i], &got[i * 3]);
            oiio_rmse = rmse(got, truth);
            for (std::size_t k = 0; k < opt.thread_counts.size(); ++k) {
                note(std::string("OpenImageIO, ") + regime.name + ", " +
                     std::to_string(opt.thread_counts[k]) + " thread(s)");
                oiio_rate[k] =
                    lookup_rate(lookups, opt.thread_counts[k], opt.rounds,
                                [&](const EnvLookup& q, float* out) { oiio->lookup(q, out); });
                oiio_batch_rate[k] = batch_rate(
                    lookups, opt.thread_counts[k], opt.rounds, kBatch,
                    [&](const EnvLookup* first, int count, float* out) {
                        oiio->lookup_batch(OiioEnvPeer::to_batch(first, count), count, out);
                    });
            }
        }

        for (const Layout& layout : layouts) {
            std::vector<float> got(subset * 3);
            for (std::size_t i = 0; i < subset; ++i)
                ours_lookup(*layout.map, lookups[i], lo, &got[i * 3]);
            const double ours_rmse = rmse(got, truth);
            for (std::size_t k = 0; k < opt.thread_counts.size(); ++k) {
                note(std::string(layout.filter) + ", " + regime.name + ", " +
                     std::to_string(opt.thread_counts[k]) + " thread(s)");
                const double rate = lookup_rate(
                    lookups, opt.thread_counts[k], opt.rounds,
                    [&](const EnvLookup& q, float* out) { ours_lookup(*layout.map, q, lo, out); });
                cases.push_back({layout.filter, regime.name, opt.thread_counts[k], rate,
                                 oiio_rate[k], ours_rmse, oiio_rmse});
            }
            // The batched APIs, both given kBatch lookups per call. Ours must return exactly the
            // single calls' results.
            std::vector<float> batched(subset * 3);
            environment_lookup_batch(*layout.map, std::span(lookups.data(), subset), lo,
                                     batched.data());
            if (batched != got)
                throw std::runtime_error(std::string(layout.filter) +
                                         ": environment_lookup_batch differs from single lookups");
            const std::string batch_filter = std::string(layout.filter) + "-batch";
            for (std::size_t k = 0; k < opt.thread_counts.size(); ++k) {
                note(batch_filter + ", " + regime.name + ", " +
                     std::to_string(opt.thread_counts[k]) + " thread(s)");
                const double rate =
                    batch_rate(lookups, opt.thread_counts[k], opt.rounds, kBatch,
                               [&](const EnvLookup* first, int count, float* out) {
                                   environment_lookup_batch(
                                       *layout.map, std::span(first, std::size_t(count)), lo, out);
                               });
                cases.push_back({batch_filter, regime.name, opt.thread_counts[k], rate,
                                 oiio_batch_rate[k], ours_rmse, oiio_rmse});
            }
            if (opt.footprints)
                time_footprint_lookups(*layout.map, layout.filter, regime.name, lookups, got, opt,
                                       lo, ours_rmse, cases);
        }
    }

    std::printf(
        "environment: lat-long %d×%d float RGB (pyramid %.3f s); cube 6×%d² converted from it "
        "(%.3f s, pyramids %.3f s); RMSE against environment_reference() on the lat-long map, %zu "
        "lookups per regime; our probe rule %s, isotropic_ratio %g, lod blend %s\n",
        width, height, latlong_build_seconds, opt.cube_size, convert_seconds, cube_build_seconds,
        opt.error_subset, opt.probe_rule.c_str(), double(opt.isotropic_ratio),
        opt.lod_blend.c_str());
    if (oiio)
        std::printf(
            "OpenImageIO direction R = (-x, y, -z): point-lookup RMSE %.2g vs ours (unmapped R: "
            "%.2g)\n",
            convention.mapped_rmse, convention.unmapped_rmse);
    print_peer_cases(cases, opt.footprints ? 26 : 17);

    // The targets: ≥ 5× OpenImageIO's single-thread rate in every regime; in pole_band an RMSE of
    // at most ¼ of OpenImageIO's.
    nlohmann::json targets = nlohmann::json::array();
    if (oiio) {
        std::printf(
            "targets (1 thread: ours ≥ 5× OIIO, each side's faster API; pole_band: ours RMSE ≤ ¼ "
            "OIIO's):\n");
        for (const SpeedTarget& t : speed_targets(cases, {"latlong-fa", "cube-fa"})) {
            nlohmann::json j = t.report(5, 10);
            if (t.single->regime == "pole_band") {
                const double error_ratio = t.single->ours_rmse / t.single->oiio_rmse;
                const bool error_met = error_ratio <= 0.25;
                std::printf("  RMSE ratio %.3f %s", error_ratio, error_met ? "met" : "NOT met");
                j["rmse_ratio"] = error_ratio;
                j["rmse_met"] = error_met;
            }
            std::printf("\n");
            targets.push_back(j);
        }
    }

    if (!opt.json_path.empty()) {
        nlohmann::json j;
        j["benchmark"] = "env";
        j["latlong_width"] = width;
        j["latlong_height"] = height;
        j["cube_size"] = opt.cube_size;
        j["latlong_build_seconds"] = latlong_build_seconds;
        j["cube_convert_seconds"] = convert_seconds;
        j["cube_build_seconds"] = cube_build_seconds;
        j["lookups_per_regime"] = opt.lookups_per_regime;
        j["error_subset"] = opt.error_subset;
        j["isotropic_ratio"] = opt.isotropic_ratio;
        j["probe_rule"] = opt.probe_rule;
        j["lod_blend"] = opt.lod_blend;
        j["oiio_version"] = OIIO_VERSION_STRING;
        j["oiio_convention_rmse"] = number_or_null(convention.mapped_rmse);
        j["hardware_threads"] = std::thread::hardware_concurrency();
        for (const Case& c : cases) j["cases"].push_back(c.to_json());
        j["targets"] = targets;
        write_json(opt.json_path, j);
    }
    return 0;
}

}  // namespace footprint::bench
