// core/parallel.h — loops on oneTBB's worker threads (internal; every parallel loop goes here).
//
//   parallel_for(0, rows, 8, [&](int first, int last) { for (int y = first; y < last; ++y) … });
//   parallel_for_each(0, rows, [&](int y) { … });
//
// parallel_for runs body(first, last) over subranges of [begin, end), each at least `grain` long
// where it can be (tbb::parallel_for over a blocked_range); parallel_for_each runs body(i) for
// every i. Either returns when every body has returned; bodies run concurrently, in any order.
//
// Why not tbb::parallel_for directly: oneTBB guarantees that what the caller did before the loop
// happens before every body, and every body before the loop returns, but Debian's libtbb is not
// built with ThreadSanitizer, which so cannot see the synchronisation that makes it so and would
// report every hand-over as a race. In the ThreadSanitizer build (make test-tsan) these loops
// state that guarantee to it; bodies get no ordering among themselves, so a race between two
// bodies is still reported. Elsewhere the annotations are empty.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#if defined(__SANITIZE_THREAD__)
#define FOOTPRINT_TSAN_ANNOTATE 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define FOOTPRINT_TSAN_ANNOTATE 1
#endif
#endif

#ifdef FOOTPRINT_TSAN_ANNOTATE
extern "C" void __tsan_acquire(void* addr);
extern "C" void __tsan_release(void* addr);
#endif

namespace footprint {

namespace detail {

// What one thread did before release(&x) happens before what another does after acquire(&x).
struct HappensBefore {
#ifdef FOOTPRINT_TSAN_ANNOTATE
    void release() {
        __tsan_release(this);
    }
    void acquire() {
        __tsan_acquire(this);
    }
#else
    void release() {}
    void acquire() {}
#endif
};

}  // namespace detail

template <class Int, class Body>
void parallel_for(Int begin, Int end, Int grain, const Body& body) {
    detail::HappensBefore start, done;
    start.release();
    tbb::parallel_for(tbb::blocked_range<Int>(begin, end, grain),
                      [&](const tbb::blocked_range<Int>& range) {
                          start.acquire();
                          body(range.begin(), range.end());
                          done.release();
                      });
    done.acquire();
}

template <class Int, class Body>
void parallel_for_each(Int begin, Int end, const Body& body) {
    parallel_for(begin, end, Int(1), [&](Int first, Int last) {
        for (Int i = first; i < last; ++i) body(i);
    });
}

}  // namespace footprint
