#include "progress.h"

#include <unistd.h>

#include <algorithm>

namespace footprint {

namespace {
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);
constexpr int kBarWidth = 30;
}  // namespace

Progress::Progress(std::string label, std::uint64_t total, bool enabled, std::FILE* stream)
    : label_(std::move(label)),
      total_(total),
      enabled_(enabled),
      stream_(stream),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {
    if (enabled_) draw(0, false);
}

Progress::~Progress() {
    finish();
}

bool Progress::stderr_is_terminal() {
    return isatty(fileno(stderr)) != 0;
}

void Progress::advance(std::uint64_t steps) {
    const std::uint64_t done = done_.fetch_add(steps, std::memory_order_relaxed) + steps;
    if (!enabled_) return;
    std::unique_lock lock(draw_mutex_, std::try_to_lock);
    if (!lock.owns_lock() || finished_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_draw_ < kRedrawInterval) return;
    last_draw_ = now;
    draw(done, false);
}

void Progress::finish() {
    if (!enabled_) return;
    std::lock_guard lock(draw_mutex_);
    if (finished_) return;
    finished_ = true;
    draw(done_.load(std::memory_order_relaxed), true);
}

void Progress::draw(std::uint64_t done, bool final) {
    const double fraction =
        total_ == 0 ? 1.0 : std::min(1.0, static_cast<double>(done) / static_cast<double>(total_));
    const int filled = static_cast<int>(fraction * kBarWidth);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.append(static_cast<std::size_t>(kBarWidth - filled), '.');
    if (final) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        std::fprintf(stream_, "\r  %-10s [%s] %3d%%  %.2f s\n", label_.c_str(), bar.c_str(),
                     static_cast<int>(fraction * 100.0), seconds);
    } else {
        std::fprintf(stream_, "\r  %-10s [%s] %3d%%", label_.c_str(), bar.c_str(),
                     static_cast<int>(fraction * 100.0));
    }
    std::fflush(stream_);
}

}  // namespace footprint
