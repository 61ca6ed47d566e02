// texture/test_taps.h — comparing bilinear taps in tests (header only; needs GoogleTest).
#pragma once

#include <gtest/gtest.h>

#include "texture/sampling.h"

namespace footprint::test {

// Whether two samples read the same texels with the same fractions; on failure, how far apart
// their taps are (in floats) and both fractions.
inline ::testing::AssertionResult same_taps(const detail::BilinearTaps& got,
                                            const detail::BilinearTaps& want) {
    if (got.a == want.a && got.b == want.b && got.c == want.c && got.d == want.d &&
        got.fx == want.fx && got.fy == want.fy)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "taps a, b, c, d off by " << got.a - want.a << ", " << got.b - want.b << ", "
           << got.c - want.c << ", " << got.d - want.d << " floats; fractions (" << got.fx << ", "
           << got.fy << ") against (" << want.fx << ", " << want.fy << ")";
}

}  // namespace footprint::test
