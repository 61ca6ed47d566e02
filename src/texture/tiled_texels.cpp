#include "texture/tiled_texels.h"

#include <algorithm>
#include <utility>

namespace footprint::detail {

TiledShape::TiledShape(std::vector<int> widths, std::vector<int> heights, int channels_,
                       int tile_log2_, WrapMode wrap_s_, WrapMode wrap_t_,
                       std::vector<Vec2> prefilter_variance_)
    : channels(channels_),
      tile_log2(tile_log2_),
      wrap_s(wrap_s_),
      wrap_t(wrap_t_),
      prefilter_variance(std::move(prefilter_variance_)) {
    levels.resize(widths.size());
    for (std::size_t l = 0; l < levels.size(); ++l) {
        levels[l] = {};
        levels[l].width = widths[l];
        levels[l].height = heights[l];
        levels[l].stride = texel_stride(channels);
    }
}

TiledShape tiled_shape(const MipPyramid& pyramid, int tile_log2) {
    std::vector<int> widths, heights;
    std::vector<Vec2> variances;
    for (int l = 0; l < pyramid.level_count(); ++l) {
        widths.push_back(pyramid.width(l));
        heights.push_back(pyramid.height(l));
        variances.push_back(pyramid.prefilter_variance(l));
    }
    return {std::move(widths), std::move(heights), pyramid.channels(),  tile_log2,
            pyramid.wrap_s(),  pyramid.wrap_t(),   std::move(variances)};
}

Vec2 TiledTexels::prefilter_variance(int l) const {
    if (!shape_.prefilter_variance.empty()) return shape_.prefilter_variance[l];
    const float t = static_cast<float>(width(0)) / static_cast<float>(width(l));  // from_levels()
    return {(t * t - 1) / 12, (t * t - 1) / 12};
}

TiledTexels::PlacedTaps TiledTexels::taps_elsewhere(int l, const BilinearPosition& p) const {
    const int w = width(l), h = height(l);
    int xa = p.x0, xb = p.x0 + 1, ya = p.y0, yb = p.y0 + 1;
    if (!p.inside) {
        xa = wrap_index(xa, w, shape_.wrap_s), xb = wrap_index(xb, w, shape_.wrap_s);
        ya = wrap_index(ya, h, shape_.wrap_t), yb = wrap_index(yb, h, shape_.wrap_t);
    }
    const Window& tile = tile_holding(l, xa, ya);
    if (static_cast<unsigned>(xb - tile.x0) < tile.width &&
        static_cast<unsigned>(yb - tile.y0) < tile.height) {  // all four in one tile (as most)
        const float* upper = tile.texels + (ya - tile.y0) * tile.pitch_floats;
        const float* lower = tile.texels + (yb - tile.y0) * tile.pitch_floats;
        const std::ptrdiff_t ca = (xa - tile.x0) * stride_, cb = (xb - tile.x0) * stride_;
        return {{upper + ca, upper + cb, lower + ca, lower + cb, p.fx, p.fy}, &tile, xa, ya};
    }
    const BilinearTaps taps{
        texel(l, xa, ya), texel(l, xb, ya), texel(l, xa, yb), texel(l, xb, yb), p.fx, p.fy};
    return {taps, &tile_holding(l, xa, ya), xa, ya};  // a tile whose slot another took, again
}

const TiledTexels::Window& TiledTexels::load_tile(int l, int tx, int ty) const {
    const int k = shape_.tile_log2;
    const int x0 = tx << k, y0 = ty << k;
    const int width = std::min(1 << k, this->width(l) - x0);
    const int height = std::min(1 << k, this->height(l) - y0);
    Window& slot = slot_of(l, tx, ty);
    slot = {l,
            x0,
            y0,
            static_cast<unsigned>(width),
            static_cast<unsigned>(height),
            static_cast<std::ptrdiff_t>(width) * stride_,
            source_.tile(l, tx, ty)};
    return slot;
}

}  // namespace footprint::detail
