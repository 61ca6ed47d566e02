// metrics/test_rmse.h — test support: the RMSE by which tests compare images, as `footprint eval`
// measures it (compare_images(), metrics/image_metrics.h).
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "metrics/image_metrics.h"

namespace footprint::test {

// RMSE of `a` against `b` in linear light, over the pixels where `mask` (if any) is nonzero; a
// failure (images of different sizes, a bad mask) fails the test and gives infinity.
inline double rmse(const Image& a, const Image& b, const Image* mask = nullptr) {
    MetricsOptions options;
    options.mask = mask;
    const Result<ImageComparison> d = compare_images(a, b, options);
    EXPECT_TRUE(d) << d.error().message;
    return d ? d->rmse : INFINITY;
}

}  // namespace footprint::test
