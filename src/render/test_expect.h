// render/test_expect.h — test support: the assertions the render tests share.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>

#include "image/image.h"

namespace footprint::test {

// `a` and `b` hold the same floats, bit for bit; `what` names the comparison in a failure, which
// also gives the first value that differs.
inline void expect_bit_identical(const Image& a, const Image& b, const std::string& what) {
    ASSERT_EQ(a.pixels.size(), b.pixels.size()) << what;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        ASSERT_EQ(std::bit_cast<std::uint32_t>(a.pixels[i]),
                  std::bit_cast<std::uint32_t>(b.pixels[i]))
            << what << ": value " << i << " is " << a.pixels[i] << " against " << b.pixels[i];
}

}  // namespace footprint::test
