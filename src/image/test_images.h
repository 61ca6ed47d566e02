// image/test_images.h — images for tests and benchmarks (header only).
#pragma once

#include <random>

#include "image/image.h"

namespace footprint {

// Uniform random values in [0, 1), reproducible from the seed.
inline Image random_image(int width, int height, int channels, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0, 1);
    Image image(width, height, channels);
    for (float& v : image.pixels) v = u(rng);
    return image;
}

}  // namespace footprint
