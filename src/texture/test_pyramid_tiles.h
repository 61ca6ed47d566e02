// texture/test_pyramid_tiles.h — a TileSource over a MipPyramid in memory (test support, not part
// of the library): the tiles of tiled_texels.h cut from the pyramid's levels, each a separate
// allocation (so that a tap read from the wrong tile, or with the wrong pitch, reads other
// texels), counted as they are asked for.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <tuple>
#include <vector>

#include "texture/mip_pyramid.h"
#include "texture/tiled_texels.h"

namespace footprint::test {

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

}  // namespace footprint::test
