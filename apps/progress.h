// apps/progress.h — a one-line progress indicator on a terminal.
//
//   Progress bar("reference", rows, Progress::stderr_is_terminal() && !quiet);
//   ... bar.advance() from any thread ...
//   bar.finish();   // draws 100 % and the elapsed time, ends the line
//
// Draws "  label [#########.........]  45%" on stderr, redrawn in place ('\r') at most every
// 100 ms, so it costs nothing measurable even when advanced per pixel row from many threads.
// A disabled bar (not a TTY, or --quiet) prints nothing at all. advance() is thread-safe; only one
// thread draws at a time (the others skip the redraw rather than wait).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

namespace footprint {

class Progress {
  public:
    Progress(std::string label, std::uint64_t total, bool enabled, std::FILE* stream = stderr);
    ~Progress();  // finishes the line if finish() was not called
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void advance(std::uint64_t steps = 1);
    void finish();
    bool enabled() const { return enabled_; }

    // isatty(fileno(stderr)).
    static bool stderr_is_terminal();

  private:
    void draw(std::uint64_t done, bool final);

    std::string label_;
    std::uint64_t total_;
    bool enabled_;
    std::FILE* stream_;
    std::atomic<std::uint64_t> done_{0};
    std::mutex draw_mutex_;
    std::chrono::steady_clock::time_point start_, last_draw_;
    bool finished_ = false;
};

}  // namespace footprint
