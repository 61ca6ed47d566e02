#include "bench_texture_content.h"

#include <cmath>
#include <cstdint>

namespace footprint::bench {

namespace {

// A hash of an integer lattice point to [0, 1).
float lattice(int x, int y, std::uint32_t seed) {
    std::uint32_t h = static_cast<std::uint32_t>(x) * 0x8da6b343u ^
                      static_cast<std::uint32_t>(y) * 0xd8163841u ^ seed;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return float(h & 0xffffffu) / float(0x1000000);
}

// Bilinear value noise of the given period (texels), periodic over `size`.
float value_noise(int x, int y, int period, int size, std::uint32_t seed) {
    const int cells = size / period;
    const float fx = float(x % period) / float(period), fy = float(y % period) / float(period);
    const int cx = x / period, cy = y / period;
    auto at = [&](int i, int j) { return lattice(i % cells, j % cells, seed); };
    const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
    const float top = at(cx, cy) + sx * (at(cx + 1, cy) - at(cx, cy));
    const float bottom = at(cx, cy + 1) + sx * (at(cx + 1, cy + 1) - at(cx, cy + 1));
    return top + sy * (bottom - top);
}

}  // namespace

Image make_benchmark_texture(int size) {
    Image image(size, size, 3);
    const float two_pi = 6.28318530718f;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            float* p = image.at(x, y);
            float noise = 0, amplitude = 0.5f;
            for (int period = 256; period >= 4; period /= 4, amplitude *= 0.6f)
                noise += amplitude * value_noise(x, y, period, size, 17u + period);
            const bool checker = ((x / 8) + (y / 8)) % 2 == 0;
            p[0] = 0.45f * noise + (checker ? 0.4f : 0.0f);
            // Orientation turns once across the image; the phase is integrated so the grating is
            // smooth.
            const float angle = two_pi * float(x + y) / float(2 * size);
            const float phase = (float(x) * std::cos(angle) + float(y) * std::sin(angle)) / 3.3f;
            p[1] = 0.5f + 0.45f * std::sin(two_pi * phase);
            p[2] =
                0.2f + 0.5f * float(y) / float(size) + 0.25f * (lattice(x / 2, y / 2, 99u) - 0.5f);
        }
    return image;
}

}  // namespace footprint::bench
