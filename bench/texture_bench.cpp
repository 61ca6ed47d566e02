#include "texture_bench.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <span>
#include <stdexcept>

#include "bench_lookups.h"
#include "bench_texture_content.h"
#include "bench_util.h"
#include "oiio_texture_file.h"
#include "texture/reference_filter.h"
#include "texture/texture_lookup.h"

namespace footprint::bench {

namespace {

struct Filter {
    const char* name;
    TextureFilter filter;
};
constexpr Filter kFilters[] = {
    {"nearest", TextureFilter::nearest},       {"bilinear", TextureFilter::bilinear},
    {"trilinear", TextureFilter::trilinear},   {"brilinear", TextureFilter::brilinear},
    {"fa", TextureFilter::footprint_assembly}, {"ewa", TextureFilter::ewa},
    {"sat", TextureFilter::summed_area}};

bool selected(const std::vector<std::string>& list, const char* name) {
    return list.empty() || std::find(list.begin(), list.end(), name) != list.end();
}

double rmse(const std::vector<float>& a, const std::vector<float>& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += double(a[i] - b[i]) * double(a[i] - b[i]);
    return std::sqrt(sum / double(a.size()));
}

// OpenImageIO's TextureSystem over a .tx file made from the same pixels.
class OiioPeer {
  public:
    OiioPeer(const Image& image, const std::filesystem::path& tx_path)
        : file_(image, tx_path, OIIO::ImageBufAlgo::MakeTxTexture, periodic()) {}

    void lookup(const TextureCoords& c, float* out) const {
        OIIO::TextureOpt options;  // default: smart bicubic, anisotropic (up to 32 probes)
        OIIO::TextureSystem& ts = file_.system();
        ts.texture(file_.handle(), ts.get_perthread_info(), options, c.s, c.t, c.dsdx, c.dtdx,
                   c.dsdy, c.dtdy, 3, out);
    }
    // The batched texture(): `count` ≤ Tex::BatchWidth lookups, given and returned in
    // OpenImageIO's structure-of-arrays layout (results out[channel][lane]).
    struct Batch {
        float s[OIIO::Tex::BatchWidth], t[OIIO::Tex::BatchWidth], dsdx[OIIO::Tex::BatchWidth],
            dtdx[OIIO::Tex::BatchWidth], dsdy[OIIO::Tex::BatchWidth], dtdy[OIIO::Tex::BatchWidth];
    };
    static Batch to_batch(const TextureCoords* c, int count) {
        Batch b{};
        for (int i = 0; i < count; ++i) {
            b.s[i] = c[i].s, b.t[i] = c[i].t;
            b.dsdx[i] = c[i].dsdx, b.dtdx[i] = c[i].dtdx;
            b.dsdy[i] = c[i].dsdy, b.dtdy[i] = c[i].dtdy;
        }
        return b;
    }
    void lookup_batch(const Batch& b, int count, float* out) const {
        OIIO::TextureOptBatch options = default_batch_options();
        OIIO::TextureSystem& ts = file_.system();
        const OIIO::Tex::RunMask mask = first_lanes(count);
        ts.texture(file_.handle(), ts.get_perthread_info(), options, mask, b.s, b.t, b.dsdx, b.dtdx,
                   b.dsdy, b.dtdy, 3, out);
    }

  private:
    static OIIO::ImageSpec periodic() {
        OIIO::ImageSpec config;
        config.attribute("wrapmodes", "periodic,periodic");  // maketx --wrap periodic
        return config;
    }
    OiioTextureFile file_;
};

using Case = PeerCase;

// Lookups per call of the batched APIs: OpenImageIO's Tex::BatchWidth, and as many for ours.
constexpr int kBatch = OIIO::Tex::BatchWidth;
static_assert(kBatch <= 64);

// The filters texture_lookup_batch() requests ahead (the others it runs one lookup at a time).
bool batched(TextureFilter filter) {
    return filter == TextureFilter::bilinear || filter == TextureFilter::trilinear ||
           filter == TextureFilter::brilinear || filter == TextureFilter::footprint_assembly;
}

}  // namespace

int run_texture_bench(const TextureBenchOptions& opt) {
    const ProgressNote note(opt.quiet);

    note("making the texture");
    const Image image = make_benchmark_texture(opt.texture_size);
    MipPyramidOptions po;
    po.summed_area_table = selected(opt.filters, "sat");
    if (opt.tile_log2 >= 0) po.tile_log2 = opt.tile_log2;
    note("building the pyramid");
    const auto build_start = Clock::now();
    const MipPyramid pyramid = MipPyramid::build(image, po);
    const double build_seconds = seconds_since(build_start);

    std::unique_ptr<OiioPeer> oiio;
    if (opt.with_oiio) {
        note("making the OpenImageIO .tx");
        const auto tx = std::filesystem::temp_directory_path() /
                        ("footprint-bench-" + std::to_string(getpid()) + ".tx");
        oiio = std::make_unique<OiioPeer>(image, tx);
    }

    bool any_batched = false;
    for (const Filter& f : kFilters)
        any_batched |= selected(opt.filters, f.name) && batched(f.filter);

    std::vector<Case> cases;
    for (const Regime& regime : kRegimes) {
        if (!selected(opt.regimes, regime.name)) continue;
        const std::vector<TextureCoords> lookups = make_lookups(
            regime, opt.lookups_per_regime, opt.texture_size, 1234u + unsigned(regime.major * 8));
        const std::size_t subset = std::min(opt.error_subset, lookups.size());

        // The ground truth on the subset (slow: dense quadrature), in parallel.
        note(std::string("reference for ") + regime.name);
        std::vector<float> truth(subset * 3);
        ReferenceOptions ro;
        tbb::parallel_for(std::size_t(0), subset, [&](std::size_t i) {
            reference_lookup(image, lookups[i].s, lookups[i].t, footprint_of(pyramid, lookups[i]),
                             ro, &truth[i * 3]);
        });

        // The peer, once per regime and thread count (the same figures go into every filter's
        // row); like ours the best of opt.rounds measure_rate rounds, so that noise favours
        // neither side.
        double oiio_rmse = NAN;
        std::vector<double> oiio_rate(opt.thread_counts.size(), NAN),
            oiio_batch_rate(opt.thread_counts.size(), NAN);
        if (oiio) {
            std::vector<float> got(subset * 3);
            for (std::size_t i = 0; i < subset; ++i)
                oiio->lookup(lookups[i], &got[i * 3]);  // also warms the cache
            oiio_rmse = rmse(got, truth);
            for (std::size_t k = 0; k < opt.thread_counts.size(); ++k) {
                note(std::string("OpenImageIO, ") + regime.name);
                oiio_rate[k] =
                    lookup_rate(lookups, opt.thread_counts[k], opt.rounds,
                                [&](const TextureCoords& c, float* out) { oiio->lookup(c, out); });
                if (any_batched)
                    oiio_batch_rate[k] = batch_rate(
                        lookups, opt.thread_counts[k], opt.rounds, kBatch,
                        [&](const TextureCoords* first, int count, float* out) {
                            oiio->lookup_batch(OiioPeer::to_batch(first, count), count, out);
                        });
            }
        }

        for (const Filter& f : kFilters) {
            if (!selected(opt.filters, f.name)) continue;
            LookupOptions lo;
            lo.filter = f.filter;
            if (opt.max_probes > 0) lo.max_probes = opt.max_probes;
            if (opt.probe_rule == "b") lo.probe_rule = ProbeRule::moment_matched;
            if (opt.probe_rule == "gaussian") lo.probe_rule = ProbeRule::gaussian;
            if (opt.probe_rule == "ext") lo.probe_rule = ProbeRule::ext;
            if (opt.probe_rule == "texram") lo.probe_rule = ProbeRule::texram;
            if (opt.lod_blend == "linear") lo.lod_blend = LodBlend::linear;
            if (opt.lod_blend == "variance") lo.lod_blend = LodBlend::variance_matched;
            if (opt.lod_blend == "automatic") lo.lod_blend = LodBlend::automatic;
            lo.brilinear_band = opt.brilinear_band;
            std::vector<float> got(subset * 3);
            for (std::size_t i = 0; i < subset; ++i)
                texture_lookup(pyramid, lookups[i], lo, &got[i * 3]);
            const double ours_rmse = rmse(got, truth);
            for (std::size_t k = 0; k < opt.thread_counts.size(); ++k) {
                note(std::string(f.name) + ", " + regime.name);
                const double rate = lookup_rate(lookups, opt.thread_counts[k], opt.rounds,
                                                [&](const TextureCoords& c, float* out) {
                                                    texture_lookup(pyramid, c, lo, out);
                                                });
                cases.push_back({f.name, regime.name, opt.thread_counts[k], rate, oiio_rate[k],
                                 ours_rmse, oiio_rmse});
            }
            if (!batched(f.filter)) continue;
            // The batched APIs, both given kBatch lookups per call. Ours must return exactly the
            // single calls' results.
            std::vector<float> batch_got(subset * 3);
            texture_lookup_batch(pyramid, std::span(lookups.data(), subset), lo, batch_got.data());
            if (batch_got != got)
                throw std::runtime_error(std::string(f.name) +
                                         ": texture_lookup_batch differs from single lookups");
            const std::string batch_filter = std::string(f.name) + "-batch";
            for (std::size_t k = 0; k < opt.thread_counts.size(); ++k) {
                note(batch_filter + ", " + regime.name);
                const double rate =
                    batch_rate(lookups, opt.thread_counts[k], opt.rounds, kBatch,
                               [&](const TextureCoords* first, int count, float* out) {
                                   texture_lookup_batch(
                                       pyramid, std::span(first, std::size_t(count)), lo, out);
                               });
                cases.push_back({batch_filter, regime.name, opt.thread_counts[k], rate,
                                 oiio_batch_rate[k], ours_rmse, oiio_rmse});
            }
        }
    }

    std::printf("texture %d² float RGB; pyramid build %.3f s; RMSE on %zu lookups per regime\n",
                opt.texture_size, build_seconds, opt.error_subset);
    print_peer_cases(cases, 15);

    // The targets of footprint assembly: ≥ 5× OpenImageIO's single-thread rate, RMSE no worse.
    nlohmann::json targets = nlohmann::json::array();
    if (oiio) {
        std::printf(
            "targets (1 thread: ours ≥ 5× OIIO, each side's faster API; RMSE no worse than "
            "OIIO's):\n");
        for (const SpeedTarget& t : speed_targets(cases, {"fa"})) {
            nlohmann::json j = t.report(5, 2);
            const bool error_met = t.single->ours_rmse <= t.single->oiio_rmse;
            std::printf("  RMSE %.5f vs %.5f %s\n", t.single->ours_rmse, t.single->oiio_rmse,
                        error_met ? "met" : "NOT met");
            j["rmse_met"] = error_met;
            targets.push_back(j);
        }
    }

    if (!opt.json_path.empty()) {
        nlohmann::json j;
        j["benchmark"] = "texture";
        j["texture_size"] = opt.texture_size;
        j["pyramid_build_seconds"] = build_seconds;
        j["lookups_per_regime"] = opt.lookups_per_regime;
        j["error_subset"] = opt.error_subset;
        j["brilinear_band"] = opt.brilinear_band;
        j["oiio_version"] = OIIO_VERSION_STRING;
        j["hardware_threads"] = std::thread::hardware_concurrency();
        for (const Case& c : cases) j["cases"].push_back(c.to_json());
        j["targets"] = targets;
        write_json(opt.json_path, j);
    }
    return 0;
}

}  // namespace footprint::bench
