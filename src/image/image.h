// image/image.h — a linear-light float image with 1–4 interleaved channels.
//
// Pixels are stored row-major, top row first, channels interleaved: the value of channel c of
// pixel (x, y) is pixels[(y * width + x) * channels + c]. Values are linear light (sRGB-encoded
// files are decoded on load, see image_io.h); HDR values above 1 are kept as they are.
#pragma once

#include <cstddef>
#include <vector>

namespace footprint {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;

    Image() = default;
    Image(int width_, int height_, int channels_, float fill = 0.0f)
        : width(width_),
          height(height_),
          channels(channels_),
          pixels(static_cast<std::size_t>(width_) * height_ * channels_, fill) {}

    bool empty() const { return pixels.empty(); }
    std::size_t pixel_count() const { return static_cast<std::size_t>(width) * height; }
    std::size_t index(int x, int y) const {
        return (static_cast<std::size_t>(y) * width + x) * channels;
    }
    float* at(int x, int y) { return pixels.data() + index(x, y); }
    const float* at(int x, int y) const { return pixels.data() + index(x, y); }
    float& at(int x, int y, int c) { return pixels[index(x, y) + c]; }
    float at(int x, int y, int c) const { return pixels[index(x, y) + c]; }
};

}  // namespace footprint
