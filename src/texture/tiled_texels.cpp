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

Vec2 TiledTexels::prefilter_variance(int l) const {
    if (!shape_.prefilter_variance.empty()) return shape_.prefilter_variance[l];
    const float t = static_cast<float>(width(0)) / static_cast<float>(width(l));  // from_levels()
    return {(t * t - 1) / 12, (t * t - 1) / 12};
}

std::optional<TiledTexels::Window> TiledTexels::window(int l, float s0, float t0, float s1,
                                                       float t1) const {
    constexpr float kMargin = 1.0f / 64;  // line_inside()'s, for positions rounded otherwise
    const float w = static_cast<float>(width(l)), h = static_cast<float>(height(l));
    const float x_low = std::min(s0, s1) * w - 0.5f - kMargin;
    const float x_high = std::max(s0, s1) * w - 0.5f + kMargin;
    const float y_low = std::min(t0, t1) * h - 0.5f - kMargin;
    const float y_high = std::max(t0, t1) * h - 0.5f + kMargin;
    // The taps' columns ⌊X⌋ and ⌊X⌋ + 1 on the level itself; false for NaN.
    if (!(x_low >= 0 && y_low >= 0 && x_high < w - 1 && y_high < h - 1)) return std::nullopt;
    const int k = shape_.tile_log2;
    const int xa = static_cast<int>(x_low), xb = static_cast<int>(x_high) + 1;
    const int ya = static_cast<int>(y_low), yb = static_cast<int>(y_high) + 1;
    if ((xa >> k) != (xb >> k) || (ya >> k) != (yb >> k)) return std::nullopt;
    const int tx = xa >> k, ty = ya >> k;
    return Window{tile(l, tx, ty), tx << k, ty << k,
                  static_cast<std::ptrdiff_t>(pitch(l, tx)) * stride_, stride_};
}

}  // namespace footprint::detail
