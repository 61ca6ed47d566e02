// texture/texel_storage.h — the one allocation that holds a pyramid's texels.
//
// Lookups at random positions are bound by memory latency, not arithmetic. Two things keep that
// latency down, both measured with `footprint-bench texture`:
//   - 64-byte alignment, so that a tile row (4 RGBA float texels) is exactly one cache line;
//   - on Linux, transparent huge pages (madvise MADV_HUGEPAGE) for allocations of 2 MiB or more,
//     so that random texel reads over a large texture do not also miss the TLB.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace footprint::detail {

class TexelStorage {
  public:
    TexelStorage() = default;

    // `count` floats, zero-initialised.
    explicit TexelStorage(std::size_t count) : size_(count) {
        if (count == 0) return;
        constexpr std::size_t kHugePage = std::size_t(2) << 20;
        const std::size_t bytes = count * sizeof(float);
        const std::size_t alignment = bytes >= kHugePage ? kHugePage : 64;
        const std::size_t rounded = (bytes + alignment - 1) / alignment * alignment;
        void* p = std::aligned_alloc(alignment, rounded);
        if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        if (alignment == kHugePage)
            madvise(p, rounded, MADV_HUGEPAGE);  // a hint; failure is harmless
#endif
        std::memset(p, 0, rounded);
        data_.reset(static_cast<float*>(p));
    }

    float* data() {
        return data_.get();
    }
    const float* data() const {
        return data_.get();
    }
    std::size_t size() const {
        return size_;
    }

  private:
    struct Free {
        void operator()(float* p) const { std::free(p); }
    };
    std::unique_ptr<float[], Free> data_;
    std::size_t size_ = 0;
};

}  // namespace footprint::detail
