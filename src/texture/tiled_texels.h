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
// until the lookup that asked for them has returned (the texture system pins them until then), or
// for as long as the source keeps them (TiledTexels::Slots).
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

// The shape of `pyramid`'s levels in tiles of 2^tile_log2 texels: its sizes, wrap modes and
// prefilter variances, so that a TiledTexels of its tiles filters as the pyramid does.
TiledShape tiled_shape(const MipPyramid& pyramid, int tile_log2);

class TiledTexels {
  public:
    // One tile of a level: where it lies on the level, how large it is and its texels.
    struct Window {
        int level = -1;  // none
        int x0 = 0, y0 = 0;
        unsigned width = 0, height = 0;
        std::ptrdiff_t pitch_floats = 0;
        const float* texels = nullptr;
    };
    // The tiles at hand: most taps of a lookup fall in a tile that its previous taps on the same
    // level read, and most lookups in tiles that the previous lookup read. A slot for each of four
    // levels (a trilinear probe reads two) and each parity of a tile's column and row, so that the
    // up to four tiles that a bilinear sample's taps straddle do not take each other's place.
    // A caller may keep them from one lookup to the next on the same levels while the source
    // keeps their tiles, and clear() them when it lets go of one.
    class Slots {
      public:
        // User-provided: clang 14 otherwise finds Slots not default-constructible inside
        // TiledTexels (Window's member initialisers are parsed after the enclosing class).
        Slots() {}
        void clear() {
            for (Window& slot : slots_) slot.level = -1;  // holds nothing
        }

      private:
        friend class TiledTexels;
        Window slots_[16];
    };

    // `slots`: the tiles at hand, empty or kept from a lookup on the same levels.
    TiledTexels(const TiledShape& shape, const TileSource& source, Slots& slots)
        : shape_(shape), source_(source), stride_(texel_stride(shape.channels)), slots_(slots) {}
    // With slots of its own, empty.
    TiledTexels(const TiledShape& shape, const TileSource& source)
        : shape_(shape),
          source_(source),
          stride_(texel_stride(shape.channels)),
          own_slots_(std::in_place),
          slots_(*own_slots_) {}
    TiledTexels(const TiledTexels&) = delete;
    TiledTexels& operator=(const TiledTexels&) = delete;

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

    // The tile at hand that holds texel (x, y) of level l, or null.
    const Window* tile_at_hand(int l, int x, int y) const {
        const Window& slot = slot_of(l, x >> shape_.tile_log2, y >> shape_.tile_log2);
        const bool holds = slot.level == l && static_cast<unsigned>(x - slot.x0) < slot.width &&
                           static_cast<unsigned>(y - slot.y0) < slot.height;
        return holds ? &slot : nullptr;
    }
    // The tile of level l that holds texel (x, y), x ∈ [0, width), y ∈ [0, height).
    const Window& tile_holding(int l, int x, int y) const {
        if (const Window* tile = tile_at_hand(l, x, y)) return *tile;
        return load_tile(l, x >> shape_.tile_log2, y >> shape_.tile_log2);
    }

    // Texel (x, y) of level l, x ∈ [0, width), y ∈ [0, height).
    const float* texel(int l, int x, int y) const {
        const Window& tile = tile_holding(l, x, y);
        return tile.texels + (y - tile.y0) * tile.pitch_floats + (x - tile.x0) * stride_;
    }

    // The four taps of a bilinear sample at position p of level l, wrapped as wrapped_taps().
    BilinearTaps taps(int l, const BilinearPosition& p) const {
        // Most taps lie in a tile at hand (a line of probes walks through a tile): addressed
        // there without a wrap test or a tile lookup. A position outside the level cannot pass,
        // as no tile reaches beyond it.
        const Window& slot = slot_of(l, p.x0 >> shape_.tile_log2, p.y0 >> shape_.tile_log2);
        const unsigned x = static_cast<unsigned>(p.x0 - slot.x0);
        const unsigned y = static_cast<unsigned>(p.y0 - slot.y0);
        if (slot.level == l && x < slot.width - 1 && y < slot.height - 1) {
            const float* upper = slot.texels + y * slot.pitch_floats + x * stride_;
            return row_major_taps(upper, slot.pitch_floats, stride_, p.fx, p.fy);
        }
        return taps_elsewhere(l, p).taps;
    }

    // Taps as taps() gives them, with where their upper-left tap was read (wrapped), for a caller
    // that keeps that tile at hand for the taps that follow (TiledLine): taps() of taps that are
    // not all in a tile at hand.
    struct PlacedTaps {
        BilinearTaps taps;
        const Window* tile;  // the tile of the upper-left tap
        int x, y;            // the upper-left tap on the level
    };
    PlacedTaps taps_elsewhere(int l, const BilinearPosition& p) const;

  private:
    Window& slot_of(int l, int tx, int ty) const {
        return slots_.slots_[(l & 3) * 4 + (tx & 1) * 2 + (ty & 1)];
    }
    // Tile (tx, ty) of level l, from the source into its slot.
    const Window& load_tile(int l, int tx, int ty) const;

    const TiledShape& shape_;
    const TileSource& source_;
    int stride_;
    std::optional<Slots> own_slots_;
    Slots& slots_;
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

typedef unsigned UInt4 __attribute__((vector_size(16)));

// Whether a comparison's four lanes are all true (−1): both its 64-bit halves are (fewer
// instructions than four lanes taken out one by one).
inline bool all_lanes(Int4 mask) {
    typedef long long Long2 __attribute__((vector_size(16)));
    const Long2 halves = Long2(mask);
    return (halves[0] & halves[1]) == -1;
}

// A straight line of probes: probe i at centre + (first + i)·step (normalised coordinates).
struct ProbeLine {
    Vec2 centre, step;
    float first;
};

// The probes of a line through tiles (blend_line_ahead()), probe i of `line` on `levels`:
// positioned on both levels at once (bilinear_positions()' arithmetic), their taps on each level
// addressed in the tile the level's previous taps came from — its window, held here for both
// levels at once — and through TiledTexels::taps_elsewhere() where they leave it (into another
// tile, across a tile's edge, or beyond the level's edge, wrapped), which moves the window to the
// tile they went to.
template <int S>
class TiledLine {
  public:
    TiledLine(const TiledTexels& texels, TrilinearLevels levels, const ProbeLine& line)
        : texels_(texels),
          levels_(levels),
          centre_{line.centre.x, line.centre.y, line.centre.x, line.centre.y},
          step_{line.step.x, line.step.y, line.step.x, line.step.y},
          first_(line.first),
          level_{levels.l0, levels.w > 0.0f ? levels.l0 + 1 : levels.l0} {
        const int fine = level_[0], coarse = level_[1];
        size_ = __builtin_convertvector((Int4{texels.width(fine), texels.height(fine),
                                              texels.width(coarse), texels.height(coarse)}),
                                        Float4);
        // The windows start at the tiles at hand that hold the first probe, if any do.
        const Int4 first = position(0).lower;
        for (int k = 0; k < 2; ++k)
            if (const TiledTexels::Window* tile =
                    texels.tile_at_hand(level_[k], first[2 * k], first[2 * k + 1]))
                take_window(k, *tile, 0, 0);
    }

    ProbeTaps place(int i) {
        const auto [lower, fraction] = position(i);
        // The upper-left taps' place in the windows: all four taps inside where it is 0 to
        // span − 1 (unsigned: a negative offset is beyond every span).
        const Int4 offset = lower - origin_;
        const Int4 inside = UInt4(offset) < UInt4(span_);
        const ProbeTaps taps = all_lanes(inside) ? ProbeTaps{window_taps(0, offset, fraction),
                                                             window_taps(1, offset, fraction)}
                                                 : taps_moving(lower, fraction, inside);
        prefetch_probe(taps, levels_, S);
        return taps;
    }
    Texel<S> fine(const ProbeTaps& taps) const { return blend_taps<S>(taps.fine); }
    Texel<S> coarse(const ProbeTaps& taps) const { return blend_taps<S>(taps.coarse); }

  private:
    // Probe i's upper-left taps and fractions on both levels (bilinear_positions()' arithmetic),
    // its position computed as assemble() computes it (footprint_assembly_filter.h), for both
    // levels' coordinates at once.
    FloorAndFraction position(int i) const {
        const float k = first_ + static_cast<float>(i);
        return floor_and_fraction((centre_ + k * step_) * size_ - 0.5f);
    }
    // The taps on level k at `offset` in its window (fine x, y, coarse x, y).
    BilinearTaps window_taps(int k, Int4 offset, Float4 fraction) const {
        return row_major_taps(tile_[k] + offset[2 * k + 1] * pitch_[k] + offset[2 * k] * S,
                              pitch_[k], S, fraction[2 * k], fraction[2 * k + 1]);
    }
    // The taps of a probe that leaves a window (`inside` its windows: fine x, y, coarse x, y),
    // through TiledTexels::taps_elsewhere() on the levels it leaves, whose windows move to the
    // tiles their taps came from. Out of line, so that place() stays small enough to inline.
    [[gnu::noinline]] ProbeTaps taps_moving(Int4 lower, Float4 fraction, Int4 inside) {
        ProbeTaps taps;
        const int levels = levels_.w > 0.0f ? 2 : 1;
        for (int k = 0; k < levels; ++k) {
            BilinearTaps& level_taps = k == 0 ? taps.fine : taps.coarse;
            if (inside[2 * k] & inside[2 * k + 1]) {
                level_taps = window_taps(k, lower - origin_, fraction);
                continue;
            }
            const int l = level_[k], x = lower[2 * k], y = lower[2 * k + 1];
            const bool on_level =
                x >= 0 && y >= 0 && x + 1 < texels_.width(l) && y + 1 < texels_.height(l);
            const TiledTexels::PlacedTaps placed =
                texels_.taps_elsewhere(l, {x, y, fraction[2 * k], fraction[2 * k + 1], on_level});
            level_taps = placed.taps;
            // Where the texture repeats, its copies beyond the level's edge are the level's tiles
            // again: the window is the copy that holds (x, y), whole periods away.
            take_window(k, *placed.tile, texels_.wrap_s() == WrapMode::repeat ? x - placed.x : 0,
                        texels_.wrap_t() == WrapMode::repeat ? y - placed.y : 0);
        }
        if (levels == 1) {  // the coarse level is the fine one
            origin_[2] = origin_[0], origin_[3] = origin_[1];
            span_[2] = span_[0], span_[3] = span_[1];
            tile_[1] = tile_[0], pitch_[1] = pitch_[0];
        }
        return taps;
    }
    // Level k's window: `tile`, shifted by (dx, dy).
    void take_window(int k, const TiledTexels::Window& tile, int dx, int dy) {
        origin_[2 * k] = tile.x0 + dx, origin_[2 * k + 1] = tile.y0 + dy;
        span_[2 * k] = static_cast<int>(tile.width) - 1;
        span_[2 * k + 1] = static_cast<int>(tile.height) - 1;
        tile_[k] = tile.texels;
        pitch_[k] = tile.pitch_floats;
    }

    const TiledTexels& texels_;
    TrilinearLevels levels_;
    Float4 centre_, step_;  // the line's (s, t, s, t)
    float first_;
    int level_[2];  // fine, coarse (the fine level again when levels.w = 0)
    Float4 size_;   // the levels' widths and heights
    // The windows (fine x, y, coarse x, y): their first texel on the level, and the upper-left
    // taps they hold all four taps of, 0 to span − 1 on from there (none at first).
    Int4 origin_{}, span_{};
    const float* tile_[2] = {};  // the windows' texels
    std::ptrdiff_t pitch_[2] = {};
};

// A line of `count` probes through tiles on `levels` (TiledLine), blended and written to out.
inline void blend_probe_line_in_tiles(const TiledTexels& texels, int count, const float* weights,
                                      TrilinearLevels levels, const ProbeLine& line, float* out) {
    dispatch_stride(texels.stride(), [&]<int S>() {
        const Texel<S> result =
            blend_line_ahead<S>(count, weights, levels.w, TiledLine<S>(texels, levels, line));
        store(result, texels.channels(), out);
    });
}

// texture_lookup() through tiles: bit for bit the MipPyramid's lookup of the same levels (any
// filter; summed_area falls back to trilinear, as on a pyramid built without a SAT).
void texture_lookup(const TiledTexels& texels, const TextureCoords& coords,
                    const LookupOptions& options, float* out);

}  // namespace footprint::detail
