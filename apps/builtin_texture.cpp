#include "builtin_texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "math/sample_patterns.h"

namespace footprint {

namespace {

std::uint32_t hash3(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return hash32(a ^ hash32(b ^ hash32(c)));
}

struct Rgb {
    float r, g, b;
};

}  // namespace

Image make_builtin_texture(int size) {
    size = std::max(size, 16);
    Image image(size, size, 3);
    const int cell = std::max(size / 8, 2);          // checker square
    const int line_period = std::max(size / 32, 2);  // thin red lines
    const double zone_radius = 0.5 * size;
    const double centre = 0.5 * size;
    const int margin = std::max(cell / 16, 1);
    constexpr int kGlyphW = 5, kGlyphH = 7, kAdvanceX = 6, kAdvanceY = 9;

    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const int cx = x / cell, cy = y / cell;
            const bool light = (cx + cy) % 2 == 0;
            Rgb c;
            if (light) {
                // Slightly different paper per square, so the squares are told apart far away.
                const float tint = 0.06f * static_cast<float>(hash3(cx, cy, 7) % 5) / 4.0f;
                c = {0.72f + tint, 0.64f + 0.5f * tint, 0.46f};
                const int lx = x - cx * cell - margin, ly = y - cy * cell - margin;
                const int text_w = cell - 2 * margin, text_h = cell - 2 * margin;
                if (lx >= 0 && ly >= 0 && lx < text_w && ly < text_h) {
                    const int col = lx / kAdvanceX, row = ly / kAdvanceY;
                    const int gx = lx % kAdvanceX, gy = ly % kAdvanceY;
                    const bool inside_line =
                        (col + 1) * kAdvanceX <= text_w && (row + 1) * kAdvanceY <= text_h;
                    if (inside_line && gx < kGlyphW && gy < kGlyphH) {
                        const std::uint32_t square = static_cast<std::uint32_t>(cy * 64 + cx);
                        const std::uint32_t g = hash3(square, row, col);
                        const bool space = g % 7 == 0;  // word gaps
                        const std::uint64_t bits =
                            (static_cast<std::uint64_t>(hash32(g)) << 32) | hash32(g + 1);
                        const bool ink = !space && ((bits >> (gy * kGlyphW + gx)) & 1u) &&
                                         ((bits >> (40 + gy)) & 1u) == ((bits >> (50 + gx)) & 1u);
                        if (ink)
                            c = hash32(square) % 3 == 0 ? Rgb{0.55f, 0.03f, 0.02f}
                                                        : Rgb{0.02f, 0.02f, 0.04f};
                    }
                }
            } else {
                c = {0.02f, 0.04f, 0.11f};
                const double dx = x + 0.5 - centre, dy = y + 0.5 - centre;
                const double r2 = dx * dx + dy * dy;
                if (r2 < zone_radius * zone_radius) {
                    // Local frequency dφ/dr / 2π = r / (2R): ½ cycle per texel at r = R.
                    const double phase = std::numbers::pi * r2 / (2.0 * zone_radius);
                    const double third = 2.0 * std::numbers::pi / 3.0;
                    c.r += 0.60f * static_cast<float>(0.5 + 0.5 * std::cos(phase));
                    c.g += 0.60f * static_cast<float>(0.5 + 0.5 * std::cos(phase + third));
                    c.b += 0.60f * static_cast<float>(0.5 + 0.5 * std::cos(phase + 2 * third));
                }
            }
            if (x % cell == 0 || y % cell == 0)
                c = {0.9f, 0.9f, 0.9f};
            else if (x % line_period == 0 || y % line_period == 0)
                c = {0.8f, 0.08f, 0.04f};
            float* p = image.at(x, y);
            p[0] = c.r;
            p[1] = c.g;
            p[2] = c.b;
        }
    }
    return image;
}

}  // namespace footprint
