// gpu/gpu_test_device.h — test support: the headless GPU device, or a skip that says why.
//
// Where no EGL device exists the GPU tests skip with the reason, unless FOOTPRINT_REQUIRE_GPU is
// set (CI sets it: there a missing device is a failure, not a skip).
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

#include "gpu/gpu_renderer.h"

namespace footprint::test {

// Whether this process made its device (tests/test_main.cpp ends such a process without the
// sanitizer build's leak check).
inline bool gpu_device_created = false;

// One device per test process (a context is cheap, but every test needs one current).
inline GpuDevice* gpu_device_or_null(std::string* why) {
    static Result<GpuDevice> device = GpuDevice::headless();
    gpu_device_created = device.ok();
    if (device) return &*device;
    *why = device.error().message;
    return nullptr;
}

inline bool gpu_required() {
    const char* env = std::getenv("FOOTPRINT_REQUIRE_GPU");
    return env && *env && std::string(env) != "0";
}

}  // namespace footprint::test

// In a TEST body: the device, or GTEST_SKIP (GTEST_FAIL with FOOTPRINT_REQUIRE_GPU) naming why.
#define FOOTPRINT_GPU_DEVICE_OR_SKIP()                                                        \
    do {                                                                                      \
        std::string why_no_gpu;                                                               \
        if (!::footprint::test::gpu_device_or_null(&why_no_gpu)) {                            \
            if (::footprint::test::gpu_required()) FAIL() << "no GPU device: " << why_no_gpu; \
            GTEST_SKIP() << "no GPU device: " << why_no_gpu;                                  \
        }                                                                                     \
    } while (0)
