// texture/tiled_texels.h — a pyramid whose texels are read tile by tile (private to the library).
//
// The filters of texture_lookup() read texels through one of two sources, with the same
// arithmetic: a MipPyramid (every level in memory), or TiledTexels, whose levels are cut into
// square tiles of 2^k × 2^k texels that a TileSource hands out on demand — the texture system's
// bounded cache (texture_system.h). A tile holds its texels row-major, `stride` floats each
// (texel_stride(channels), as a MipPyramid stores them); tiles on a level's right and bottom edges
// are as wide and as high as what is left of the level. Taps are wrapped exactly as
// wrapped_taps() wraps them, and blended by the same blend_taps(), so a lookup through tiles
// returns bit for bit what the same lookup on a MipPyramid of the same levels returns, whichever
// tiles the cache happens to hold.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "math/vec.h"
#include "texture/mip_pyramid.h"
#include "texture/sampling.h"
#include "texture/texture_lookup.h"

namespace footprint::detail {

// Where TiledTexels gets its tiles. tile() returns the texels of tile (tx, ty) of level l, valid
// until the lookup that asked for them has returned (the texture system pins them until then).
class TileSource {
  public:
    virtual const float* tile(int level, int tx, int ty) const = 0;

  protected:
    ~TileSource() = default;
};

// The shape of a tiled pyramid: its levels' sizes (MipPyramid's level sizes) and how it wraps.
struct TiledShape {
    // Level l is widths[l] × heights[l], level 0 first, down to 1×1 (MipPyramid's level sizes).
    // Per level, the variance of the kernel that made it (MipPyramid::prefilter_variance());
    // empty: the box's, as MipPyramid::from_levels() assumes for a stored chain.
    TiledShape(std::vector<int> widths, std::vector<int> heights, int channels, int tile_log2,
               WrapMode wrap_s, WrapMode wrap_t, std::vector<Vec2> prefilter_variance = {});
    TiledShape() = default;

    int channels = 0;
    int tile_log2 = 6;  // 64 × 64 texels
    WrapMode wrap_s = WrapMode::repeat, wrap_t = WrapMode::repeat;
    std::vector<Vec2> prefilter_variance;
    // The levels' sizes as LevelViews (their base null: positions only, for bilinear_position()).
    std::vector<MipPyramid::LevelView> levels;
};

class TiledTexels {
  public:
    TiledTexels(const TiledShape& shape, const TileSource& source)
        : shape_(shape), source_(source), stride_(texel_stride(shape.channels)) {}

    // What the filters ask of a texel source (as MipPyramid's members of the same names).
    int channels() const { return shape_.channels; }
    int stride() const { return stride_; }
    int level_count() const { return static_cast<int>(shape_.levels.size()); }
    int max_level() const { return level_count() - 1; }
    int width(int l) const { return shape_.levels[l].width; }
    int height(int l) const { return shape_.levels[l].height; }
    WrapMode wrap_s() const { return shape_.wrap_s; }
    WrapMode wrap_t() const { return shape_.wrap_t; }
    Vec2 prefilter_variance(int l) const;  // TiledShape::prefilter_variance
    const MipPyramid::LevelView& level(int l) const { return shape_.levels[l]; }

    // Texel (x, y) of level l, x ∈ [0, width), y ∈ [0, height).
    const float* texel(int l, int x, int y) const {
        const Slot& slot = tile_holding(l, x, y);
        return slot.tile + (y - slot.y0) * slot.pitch_floats + (x - slot.x0) * stride_;
    }

    // The four taps of a bilinear sample at position p of level l, wrapped as wrapped_taps().
    BilinearTaps taps(int l, const BilinearPosition& p) const {
        // Most taps lie in the tile the level's previous taps came from (a line of probes walks
        // through a tile): addressed there without a wrap test or a tile lookup. A position
        // outside the level cannot pass, as no tile reaches beyond it.
        const Slot& slot = slots_[l % kSlots];
        const unsigned x = static_cast<unsigned>(p.x0 - slot.x0);
        const unsigned y = static_cast<unsigned>(p.y0 - slot.y0);
        if (slot.level == l && x < slot.width - 1 && y < slot.height - 1) {
            const float* upper = slot.tile + y * slot.pitch_floats + x * stride_;
            return row_major_taps(upper, slot.pitch_floats, stride_, p.fx, p.fy);
        }
        return taps_elsewhere(l, p);
    }

    // The part of level l that one tile holds, for a run of taps that all lie in it: their
    // addresses without a tile lookup or a wrap test each.
    struct Window {
        const float* tile;
        int x0, y0;  // the tile's first texel on the level
        std::ptrdiff_t pitch_floats;
        int stride;
        BilinearTaps taps(const BilinearPosition& p) const {
            const float* upper = tile + (p.y0 - y0) * pitch_floats + (p.x0 - x0) * stride;
            const float* lower = upper + pitch_floats;
            return {upper, upper + stride, lower, lower + stride, p.fx, p.fy};
        }
    };
    // The tile of level l that holds every tap of bilinear samples in the box of corners (s0, t0)
    // and (s1, t1) (to line_inside()'s margin), if one does and none of them is wrapped.
    std::optional<Window> window(int l, float s0, float t0, float s1, float t1) const;

  private:
    // One tile of a level: where it lies on the level and how large it is.
    struct Slot {
        int level = -1;  // none
        int x0 = 0, y0 = 0;
        unsigned width = 0, height = 0;
        std::ptrdiff_t pitch_floats = 0;
        const float* tile = nullptr;
    };

    // The slot of level l, holding the tile of texel (x, y) of the level: most taps of a lookup
    // fall in the tile its previous tap on the same level read. One slot per level (a trilinear
    // probe alternates between two) keeps that tile at hand.
    const Slot& tile_holding(int l, int x, int y) const {
        const Slot& slot = slots_[l % kSlots];
        if (slot.level == l && static_cast<unsigned>(x - slot.x0) < slot.width &&
            static_cast<unsigned>(y - slot.y0) < slot.height)
            return slot;
        return load_tile(l, x >> shape_.tile_log2, y >> shape_.tile_log2);
    }
    // Tile (tx, ty) of level l, from the source into the level's slot.
    const Slot& load_tile(int l, int tx, int ty) const;
    // taps() of taps that are not all in the level's slot's tile: wrapped, and each from its own
    // tile when they straddle a tile's edge (1 in 2^k per axis).
    BilinearTaps taps_elsewhere(int l, const BilinearPosition& p) const;

    const TiledShape& shape_;
    const TileSource& source_;
    int stride_;
    static constexpr int kSlots = 4;
    mutable Slot slots_[kSlots];
};

// The texel-source functions the filters call (sampling.h has the MipPyramid's): a trilinear
// probe's taps, a bilinear sample of one level, and one texel.
inline ProbeTaps probe_taps(const TiledTexels& texels, float s, float t, TrilinearLevels levels) {
    return trilinear_taps(texels, s, t, levels,
                          [&](const MipPyramid::LevelView&, int l, const BilinearPosition& p) {
                              return texels.taps(l, p);
                          });
}
template <int S>
inline Texel<S> sample_bilinear(const TiledTexels& texels, int l, float s, float t) {
    return blend_taps<S>(texels.taps(l, bilinear_position(texels.level(l), s, t)));
}
inline const float* level_texel(const TiledTexels& texels, int l, int x, int y) {
    return texels.texel(l, x, y);
}

// blend_probe_line_inside() for tiles: a line of `count` probes on `levels`, probe i at
// position_of(i) = c + k·Δ, blended and written to out when its ends' taps (and so all of them)
// lie in one tile on each level without wrapping — true; otherwise nothing written, false. The
// taps are those probe_taps() gives, addressed through the two windows.
template <class PositionOf>
bool blend_probe_line_in_tiles(const TiledTexels& texels, int count, const float* weights,
                               TrilinearLevels levels, PositionOf&& position_of, float* out) {
    const auto a = position_of(0), b = position_of(count - 1);
    const int coarse_level = levels.w > 0.0f ? levels.l0 + 1 : levels.l0;
    const auto fine = texels.window(levels.l0, a.x, a.y, b.x, b.y);
    if (!fine) return false;
    const auto coarse = texels.window(coarse_level, a.x, a.y, b.x, b.y);
    if (!coarse) return false;
    const MipPyramid::LevelView &fine_view = texels.level(levels.l0),
                                &coarse_view = texels.level(coarse_level);
    dispatch_stride(texels.stride(), [&]<int S>() {
        const Texel<S> result =
            blend_probe_line<S>(count, weights, levels, texels.stride(), [&](int i) {
                const auto p = position_of(i);
                if (levels.w == 0.0f)
                    return ProbeTaps{fine->taps(bilinear_position(fine_view, p.x, p.y)), {}};
                const BilinearPositionPair q = bilinear_positions(fine_view, coarse_view, p.x, p.y);
                return ProbeTaps{fine->taps(q.fine), coarse->taps(q.coarse)};
            });
        store(result, texels.channels(), out);
    });
    return true;
}

// texture_lookup() through tiles: bit for bit the MipPyramid's lookup of the same levels (any
// filter; summed_area falls back to trilinear, as on a pyramid built without a SAT).
void texture_lookup(const TiledTexels& texels, const TextureCoords& coords,
                    const LookupOptions& options, float* out);

}  // namespace footprint::detail
