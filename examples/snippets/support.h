// support.h — what the snippet programs share: small images made in code and written as the
// files the snippets read, and a check that stops a program with a message.
#pragma once

#include <footprint/footprint.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace snippets {

// Stops the program with `what` unless `ok`.
inline void check(bool ok, const std::string& what) {
    if (ok) return;
    std::fprintf(stderr, "snippet check failed: %s\n", what.c_str());
    std::exit(1);
}

// Stops the program with the error of a failed step.
template <class T>
T checked(footprint::Result<T> result, const std::string& what) {
    check(result.ok(), what + ": " + (result ? "" : result.error().message));
    return std::move(*result);
}

inline void checked(const footprint::Status& status, const std::string& what) {
    check(status.ok(), what + ": " + (status ? "" : status.error().message));
}

// A 64 × 64 RGB brick-like pattern in linear light.
inline footprint::Image bricks() {
    footprint::Image image(64, 64, 3);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const bool mortar = y % 16 == 0 || (x + (y / 16) % 2 * 16) % 32 == 0;
            image.at(x, y, 0) = mortar ? 0.8f : 0.5f;
            image.at(x, y, 1) = mortar ? 0.8f : 0.2f;
            image.at(x, y, 2) = mortar ? 0.8f : 0.1f;
        }
    return image;
}

// A 64 × 64 OpenGL normal map of sinusoidal bumps, in [0, 1] as a file stores it.
inline footprint::Image bump_normals() {
    footprint::Image slopes(64, 64, 2);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            slopes.at(x, y, 0) = 0.4f * std::cos(0.7854f * static_cast<float>(x));
            slopes.at(x, y, 1) = 0.3f * std::sin(0.3927f * static_cast<float>(y));
        }
    return footprint::normals_from_slopes(slopes);
}

// A 64 × 32 lat-long RGB sky: bright above the horizon, dark below, a warm band around it.
inline footprint::Image latlong_sky() {
    footprint::Image image(64, 32, 3);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) {
            const float height = std::cos(3.14159265f * (static_cast<float>(y) + 0.5f) / 32);
            image.at(x, y, 0) = 0.5f + 0.5f * height + (std::fabs(height) < 0.2f ? 1.0f : 0.0f);
            image.at(x, y, 1) = 0.5f + 0.4f * height;
            image.at(x, y, 2) = 0.6f + 0.3f * height + 0.1f * static_cast<float>(x % 8) / 8;
        }
    return image;
}

// Writes the files the snippets name into the working directory: bricks.png, bricks_normal.png,
// albedo.exr, sky.exr, sky.hdr.
inline void write_files() {
    using namespace footprint;
    checked(save_image(bricks(), "bricks.png"), "bricks.png");
    checked(save_image(bricks(), "albedo.exr"), "albedo.exr");
    ImageSaveOptions data;
    data.encoding = ColorEncoding::linear;
    checked(save_image(bump_normals(), "bricks_normal.png", data), "bricks_normal.png");
    checked(save_image(latlong_sky(), "sky.exr"), "sky.exr");
    checked(save_image(latlong_sky(), "sky.hdr"), "sky.hdr");
}

// `image` as a tiled, MIP-mapped texture file written by OpenImageIO's make_texture (what
// `maketx` writes, a .tx).
inline void write_tx(const footprint::Image& image, const std::string& file) {
    OIIO::ImageBuf source(
        OIIO::ImageSpec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT),
        const_cast<float*>(image.pixels.data()));
    check(OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, source, file,
                                           OIIO::ImageSpec()),
          file + ": " + OIIO::geterror());
}

// Whether every one of `n` floats is finite.
inline bool finite(const float* values, int n) {
    for (int i = 0; i < n; ++i)
        if (!std::isfinite(values[i])) return false;
    return true;
}

}  // namespace snippets
