// apps/gpu_test_support.h — (tests) the GPU path against the CPU renderer: the CPU mode each GPU
// mode reproduces, the tolerances that hold the two together, and small helpers.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "gpu/gpu_renderer.h"
#include "metrics/test_rmse.h"
#include "render/renderer.h"

namespace footprint::test {

// The CPU mode each GPU mode reproduces (hw-aniso has none).
inline std::optional<FilterMode> cpu_counterpart(GpuFilter f) {
    switch (f) {
        case GpuFilter::point:
            return FilterMode::bilinear;
        case GpuFilter::trilinear:
            return FilterMode::trilinear;
        case GpuFilter::fa:
            return FilterMode::fa;
        case GpuFilter::fa_rough:
            return FilterMode::fa_rough;
        case GpuFilter::hw_aniso:
            return std::nullopt;
    }
    return std::nullopt;
}

// GPU against CPU, RMSE in linear light, per mode. Both run the same steps on the same pyramids;
// what differs: the GPU's geometry is float around the camera (the CPU's double), and its
// bilinear taps weigh with 8 fractional bits on most hardware. `point` reads level 0 of every map
// at one position per pixel, so a position moved by rounding lands on texel-scale contrast (the
// aliased detail is all there is); the filtered modes read levels whose contrast per texel is
// lower. Measured on llvmpipe: point ≤ 6e-4, the filtered modes ≤ 1.3e-4 (docs/gpu.md). The
// tolerances are 5 to 8 times that, and 10 times below the smallest difference between two CPU
// modes on a demo scene (apps/gpu_scenes_test.cpp checks it), so that a wrong sign or a transposed
// matrix fails.
inline double gpu_cpu_tolerance(GpuFilter f) {
    return f == GpuFilter::point ? 3e-3 : 1e-3;
}

inline Image gpu_render(GpuRenderer& renderer, GpuFilter filter) {
    GpuRenderOptions options;
    options.filter = filter;
    Result<Image> image = renderer.render(options);
    EXPECT_TRUE(image) << image.error().message;
    return image ? *image : Image{};
}

}  // namespace footprint::test
