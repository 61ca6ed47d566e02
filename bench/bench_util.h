// bench/bench_util.h — timing and reporting helpers shared by the benchmarks.
//
// Rates are measured as the best of several repetitions of a fixed batch (wall clock, steady
// clock), after one warm-up pass over all items, with the batch sized from a short calibration run
// so each repetition takes ~0.25 s. Best-of-N rejects interference from other processes.
// Multi-threaded rates split the batch over std::threads, each with its own per-thread state.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

namespace footprint::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Runs work(thread_index, begin, end) over [0, count) split evenly across `threads` threads and
// returns the wall-clock seconds.
inline double run_split(std::size_t count, int threads,
                        const std::function<void(int, std::size_t, std::size_t)>& work) {
    const auto start = Clock::now();
    if (threads <= 1) {
        work(0, 0, count);
    } else {
        std::vector<std::thread> pool;
        for (int i = 0; i < threads; ++i)
            pool.emplace_back(work, i, count * i / threads, count * (i + 1) / threads);
        for (std::thread& t : pool) t.join();
    }
    return seconds_since(start);
}

// Items per second of `work` over a pool of `available` pre-generated items (indices wrap):
// calibrates the batch size to ~target_seconds, then keeps the best of `repetitions` runs.
inline double measure_rate(std::size_t available, int threads,
                           const std::function<void(int, std::size_t, std::size_t)>& work,
                           double target_seconds = 0.25, int repetitions = 5) {
    // Warm-up over every item: both sides are measured with their data in cache, whatever ran
    // before.
    run_split(available, threads, work);
    std::size_t batch = std::min<std::size_t>(available, 2000);
    double t = run_split(batch, threads, work);
    while (t < 0.02 && batch < available) {
        batch = std::min(available, batch * 4);
        t = run_split(batch, threads, work);
    }
    const double rate_guess = double(batch) / std::max(t, 1e-9);
    batch = std::clamp<std::size_t>(std::size_t(rate_guess * target_seconds), 1000, available);
    double best = 1e300;
    for (int r = 0; r < repetitions; ++r) best = std::min(best, run_split(batch, threads, work));
    return double(batch) / best;
}

// Lookups/s of `lookup(first, count, out)` over `lookups`, called on `batch` ≤ 64 lookups at a
// time (out: their results, lookup by lookup, at most 4 floats each), the best of `rounds`
// measure_rate rounds (a rate disturbed by what ran just before is re-measured).
template <class Lookup, class F>
double batch_rate(const std::vector<Lookup>& lookups, int threads, int rounds, int batch,
                  const F& lookup) {
    double rate = 0;
    for (int round = 0; round < rounds; ++round)
        rate = std::max(
            rate, measure_rate(lookups.size(), threads, [&](int, std::size_t b, std::size_t e) {
                float out[64 * 4], sink = 0;
                for (std::size_t i = b; i < e; i += std::size_t(batch)) {
                    const int count = int(std::min<std::size_t>(std::size_t(batch), e - i));
                    lookup(&lookups[i], count, out);
                    sink += out[0];
                }
                volatile float keep = sink;
                (void)keep;
            }));
    return rate;
}

// The same for a single-lookup call `lookup(q, out)`.
template <class Lookup, class F>
double lookup_rate(const std::vector<Lookup>& lookups, int threads, int rounds, const F& lookup) {
    return batch_rate(lookups, threads, rounds, 1,
                      [&](const Lookup* q, int, float* out) { lookup(*q, out); });
}

// One line of progress on stderr, redrawn in place; silent unless stderr is a terminal.
class ProgressNote {
  public:
    explicit ProgressNote(bool quiet) : enabled_(!quiet && isatty(STDERR_FILENO)) {}
    ~ProgressNote() { operator()(""); }
    void operator()(const std::string& what) const {
        if (enabled_) std::fprintf(stderr, "\r\033[K%s", what.c_str());
    }

  private:
    bool enabled_;
};

// null for NaN/Inf (a peer that was not measured), the number otherwise.
inline nlohmann::json number_or_null(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

// One measured case of a benchmark against OpenImageIO: ours and the peer on the same lookups.
struct PeerCase {
    std::string filter, regime;
    int threads;
    double ours_rate, oiio_rate;  // lookups/s (oiio: NaN when not measured)
    double ours_rmse, oiio_rmse;

    // The JSON shape every peer benchmark writes (docs/performance.md).
    nlohmann::json to_json() const {
        return {{"filter", filter},
                {"regime", regime},
                {"threads", threads},
                {"ours_mlookups_per_s", ours_rate / 1e6},
                {"oiio_mlookups_per_s", number_or_null(oiio_rate / 1e6)},
                {"ours_rmse", ours_rmse},
                {"oiio_rmse", number_or_null(oiio_rmse)}};
    }
};

// A speed target of a peer benchmark — ours at least `factor` × OpenImageIO's lookups/s on one
// thread — for one filter and regime. Each side is timed through its single-lookup call and, where
// the case "<filter>-batch" exists, through its batched call on the same lookups: the target
// compares each side's faster API (OpenImageIO's batched calls are no faster than its single
// ones), and the single calls' own ratio is kept beside it.
struct SpeedTarget {
    const PeerCase* single;
    const PeerCase* batch;  // null: no batched case

    double ours_rate() const {
        return batch ? std::max(single->ours_rate, batch->ours_rate) : single->ours_rate;
    }
    double oiio_rate() const {
        return batch ? std::max(single->oiio_rate, batch->oiio_rate) : single->oiio_rate;
    }
    double ratio() const { return ours_rate() / oiio_rate(); }
    double single_call_ratio() const { return single->ours_rate / single->oiio_rate; }
    // Which of our calls the ratio is of.
    const char* ours_api() const {
        return batch && batch->ours_rate > single->ours_rate ? "batched" : "single calls";
    }

    // Prints "  <filter> <regime> speed R× met|NOT met (ours <api>; single calls alone R×)", no
    // newline, and returns its JSON: filter, regime, speed_ratio, speed_met, ours_api,
    // single_call_speed_ratio.
    nlohmann::json report(double factor, int filter_width) const {
        const bool met = ratio() >= factor;
        std::printf("  %-*s %-9s speed %6.2f× %-7s (ours %s; single calls alone %.2f×)",
                    filter_width, single->filter.c_str(), single->regime.c_str(), ratio(),
                    met ? "met" : "NOT met", ours_api(), single_call_ratio());
        return {{"filter", single->filter}, {"regime", single->regime},
                {"speed_ratio", ratio()},   {"speed_met", met},
                {"ours_api", ours_api()},   {"single_call_speed_ratio", single_call_ratio()}};
    }
};

// The speed targets of `filters` in every regime measured on one thread.
inline std::vector<SpeedTarget> speed_targets(const std::vector<PeerCase>& cases,
                                              const std::vector<std::string>& filters) {
    std::vector<SpeedTarget> targets;
    for (const PeerCase& c : cases) {
        if (c.threads != 1 || std::find(filters.begin(), filters.end(), c.filter) == filters.end())
            continue;
        SpeedTarget t{&c, nullptr};
        for (const PeerCase& b : cases)
            if (b.threads == 1 && b.regime == c.regime && b.filter == c.filter + "-batch")
                t.batch = &b;
        targets.push_back(t);
    }
    return targets;
}

// The terminal table of a peer benchmark's cases (the filter column `filter_width` wide).
inline void print_peer_cases(const std::vector<PeerCase>& cases, int filter_width) {
    std::printf("%-*s %-9s %7s %12s %12s %8s %11s %11s\n", filter_width, "filter", "regime",
                "threads", "ours Ml/s", "OIIO Ml/s", "ratio", "ours RMSE", "OIIO RMSE");
    for (const PeerCase& c : cases)
        std::printf("%-*s %-9s %7d %12.3f %12.3f %8.2f %11.5f %11.5f\n", filter_width,
                    c.filter.c_str(), c.regime.c_str(), c.threads, c.ours_rate / 1e6,
                    c.oiio_rate / 1e6, c.ours_rate / c.oiio_rate, c.ours_rmse, c.oiio_rmse);
}

// Writes JSON to a temporary file beside `path` and renames it into place (never a partial file).
inline void write_json(const std::string& path, const nlohmann::json& j) {
    const std::filesystem::path target(path);
    if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
    const std::filesystem::path tmp = target.string() + ".tmp";
    {
        std::ofstream out(tmp);
        out << j.dump(2) << "\n";
        if (!out) throw std::runtime_error("cannot write '" + path + "'");
    }
    std::filesystem::rename(tmp, target);
}

}  // namespace footprint::bench
