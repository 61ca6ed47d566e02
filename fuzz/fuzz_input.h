// fuzz/fuzz_input.h — what the fuzz targets share (test support): reading typed values off the
// fuzzer's bytes, a scratch file to hand a loader, and the finiteness check that makes a NaN or an
// infinity in a result a crash the fuzzer reports.
#pragma once

#include <unistd.h>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>

namespace footprint::fuzz {

// Consumes the input front to back; once it runs out every value is 0 (so a short input is still
// a complete, valid call).
class FuzzInput {
  public:
    FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

    std::size_t remaining() const { return size_ - pos_; }
    std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
    std::uint32_t u32() {
        std::uint32_t v = 0;
        for (int i = 0; i < 4; ++i) v |= std::uint32_t(byte()) << (8 * i);
        return v;
    }
    // An integer in [lo, hi].
    int in_range(int lo, int hi) {
        return lo + static_cast<int>(u32() % static_cast<std::uint32_t>(hi - lo + 1));
    }
    // A float chosen to reach the edge cases: one byte picks a special value (NaN, ±Inf, ±0,
    // denormals, ±1e30, FLT_MAX, …), a small ordinary value or raw bits (any float at all).
    float any_float() {
        static constexpr float kSpecial[] = {0.0f,
                                             -0.0f,
                                             1.0f,
                                             -1.0f,
                                             0.5f,
                                             1e-3f,
                                             1e30f,
                                             -1e30f,
                                             1e-40f /* denormal */,
                                             -1e-40f,
                                             1.17549435e-38f /* FLT_MIN */,
                                             3.40282347e38f /* FLT_MAX */,
                                             std::numeric_limits<float>::infinity(),
                                             -std::numeric_limits<float>::infinity(),
                                             std::numeric_limits<float>::quiet_NaN(),
                                             1e-20f};
        const std::uint8_t kind = byte();
        if (kind < 64) return kSpecial[kind % std::size(kSpecial)];
        if (kind < 192)
            return static_cast<float>(static_cast<std::int16_t>(u32() & 0xffff)) / 1024.0f;
        return std::bit_cast<float>(u32());
    }
    // The rest of the input.
    std::string_view rest() {
        std::string_view r(reinterpret_cast<const char*>(data_) + pos_, size_ - pos_);
        pos_ = size_;
        return r;
    }

  private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
};

// A scratch folder of this process (for loaders that take a path), removed at a normal exit (the
// replay's; libFuzzer leaves it: fuzz/run.sh points TMPDIR into the build folder).
inline const std::filesystem::path& scratch_dir() {
    static const std::filesystem::path dir = [] {
        std::filesystem::path d = std::filesystem::temp_directory_path() /
                                  ("footprint-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        std::atexit([] {
            std::error_code ignored;
            std::filesystem::remove_all(scratch_dir(), ignored);
        });
        return d;
    }();
    return dir;
}

// Writes `bytes` to scratch_dir()/name and returns the path.
inline std::filesystem::path write_scratch(const std::string& name, std::string_view bytes) {
    const std::filesystem::path file = scratch_dir() / name;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return file;
}

// A result that must be finite: anything else is reported as a crash, with what was wrong.
inline void require_finite(const float* values, int n, const char* what) {
    for (int i = 0; i < n; ++i) {
        if (!std::isfinite(values[i])) {
            std::fprintf(stderr, "fuzz: %s returned a non-finite value (%g in channel %d)\n", what,
                         static_cast<double>(values[i]), i);
            __builtin_trap();
        }
    }
}

// A condition the library promises (an error with a message, a size it reported): a crash if not.
inline void require(bool condition, const char* what) {
    if (!condition) {
        std::fprintf(stderr, "fuzz: broken promise: %s\n", what);
        __builtin_trap();
    }
}

}  // namespace footprint::fuzz
