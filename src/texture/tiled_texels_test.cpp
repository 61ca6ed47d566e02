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
#include "texture/test_pyramid_tiles.h"
#include "texture/texture_lookup.h"

namespace footprint {
namespace {

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
            const detail::TiledShape shape =
                detail::tiled_shape(pyramid, 4);  // 16 × 16: many crossings
            const test::PyramidTiles tiles(pyramid, shape.tile_log2);
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
