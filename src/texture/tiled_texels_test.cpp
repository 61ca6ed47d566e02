#include "texture/tiled_texels.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "image/test_images.h"
#include "texture/texture_lookup.h"

namespace footprint {
namespace {

// Tiles cut from a MipPyramid's levels, each a separate allocation (so that a tap read from the
// wrong tile, or with the wrong pitch, reads other texels), counted as they are asked for.
class PyramidTiles final : public detail::TileSource {
  public:
    PyramidTiles(const MipPyramid& pyramid, int tile_log2)
        : pyramid_(pyramid), tile_log2_(tile_log2) {}

    const float* tile(int l, int tx, int ty) const override {
        auto [it, added] = tiles_.try_emplace({l, tx, ty});
        if (added) {
            const int size = 1 << tile_log2_, x0 = tx * size, y0 = ty * size;
            const int w = std::min(size, pyramid_.width(l) - x0);
            const int h = std::min(size, pyramid_.height(l) - y0);
            EXPECT_GT(w, 0);
            EXPECT_GT(h, 0);
            const int stride = pyramid_.stride();
            it->second.resize(static_cast<std::size_t>(w) * h * stride);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x)
                    std::memcpy(&it->second[(static_cast<std::size_t>(y) * w + x) * stride],
                                pyramid_.texel(l, x0 + x, y0 + y), stride * sizeof(float));
        }
        return it->second.data();
    }
    std::size_t tiles_made() const { return tiles_.size(); }

  private:
    const MipPyramid& pyramid_;
    int tile_log2_;
    mutable std::map<std::tuple<int, int, int>, std::vector<float>> tiles_;
};

detail::TiledShape shape_of(const MipPyramid& pyramid, int tile_log2) {
    std::vector<int> widths, heights;
    std::vector<Vec2> variances;
    for (int l = 0; l < pyramid.level_count(); ++l) {
        widths.push_back(pyramid.width(l));
        heights.push_back(pyramid.height(l));
        variances.push_back(pyramid.prefilter_variance(l));
    }
    return {widths,  heights,          pyramid.channels(), tile_log2,
            pyramid.wrap_s(), pyramid.wrap_t(), variances};
}

// Lookups of every kind: magnified, isotropic and anisotropic minified, larger than the texture,
// near and beyond every edge, with non-finite derivatives and positions.
std::vector<TextureCoords> lookups(int count) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> position(-1.5f, 2.5f), unit(-1, 1), scale(-9, 1);
    std::vector<TextureCoords> all;
    for (int i = 0; i < count; ++i) {
        const float size = std::exp2(scale(rng)), aniso = 1 + 15 * (unit(rng) + 1) / 2;
        const float angle = 3.2f * unit(rng);
        TextureCoords c;
        c.s = position(rng), c.t = position(rng);
        c.dsdx = size * aniso * std::cos(angle), c.dtdx = size * aniso * std::sin(angle);
        c.dsdy = -size * std::sin(angle), c.dtdy = size * std::cos(angle);
        all.push_back(c);
    }
    all.push_back({0.5f, 0.5f, NAN, 0, 0, 0});
    all.push_back({NAN, 0.5f, 0.01f, 0, 0, 0.01f});
    all.push_back({0.999f, 0.001f, 0, 0, 0, 0});
    return all;
}

TEST(TiledTexels, LookupsThroughTilesAreBitForBitThePyramids) {
    constexpr TextureFilter kFilters[] = {TextureFilter::nearest, TextureFilter::bilinear,
                                          TextureFilter::trilinear,
                                          TextureFilter::footprint_assembly, TextureFilter::ewa};
    const std::vector<TextureCoords> coords = lookups(400);
    for (int channels : {1, 3, 5}) {
        for (WrapMode wrap : {WrapMode::repeat, WrapMode::clamp, WrapMode::mirror}) {
            MipPyramidOptions options;
            options.wrap_s = wrap;
            options.wrap_t = wrap == WrapMode::repeat ? WrapMode::clamp : wrap;
            options.downsample = DownsampleFilter::tent;
            const MipPyramid pyramid =
                MipPyramid::build(random_image(77, 45, channels, 3), options);
            const detail::TiledShape shape = shape_of(pyramid, 4);  // 16 × 16: many crossings
            const PyramidTiles tiles(pyramid, shape.tile_log2);
            for (TextureFilter filter : kFilters) {
                LookupOptions lookup;
                lookup.filter = filter;
                for (const TextureCoords& c : coords) {
                    float want[8], got[8];
                    texture_lookup(pyramid, c, lookup, want);
                    const detail::TiledTexels texels(shape, tiles);
                    detail::texture_lookup(texels, c, lookup, got);
                    for (int k = 0; k < channels; ++k)
                        ASSERT_EQ(std::bit_cast<std::uint32_t>(got[k]),
                                  std::bit_cast<std::uint32_t>(want[k]))
                            << to_string(filter) << " " << to_string(wrap) << " channels "
                            << channels << " at (" << c.s << ", " << c.t << ") channel " << k
                            << ": " << got[k] << " against " << want[k];
                }
            }
            EXPECT_GT(tiles.tiles_made(), 15u);  // level 0 alone is 5 × 3 tiles
        }
    }
}

}  // namespace
}  // namespace footprint
