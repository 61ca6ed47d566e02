// texture/sampling.h — the inner loops every filter shares (private to texture/).
//
// Lookups at random positions are bound by memory latency, and how many lookups the CPU can keep in
// flight at once depends on how few instructions each one takes (footprint-bench texture). So these
// loops are written lean: texel values are returned in registers (Texel<S>), the four bilinear taps
// are addressed from two row and two column offsets (LevelView), and floor() is an integer
// conversion.
// S is the pyramid's texel stride (1, 2, 4 or 8), a compile-time constant so the channel loops
// vectorise. Positions are normalised (s, t) already reduced by reduce_coordinate(); texel
// coordinates follow spec §1 (X = s·W − ½).
#pragma once

#include <algorithm>
#include <cmath>

#include "texture/mip_pyramid.h"
#include "texture/texture_lookup.h"  // LodBlend

namespace footprint::detail {

// S floats in a GCC/Clang vector type: one SSE register for S = 4, so that a texel's arithmetic
// is one instruction per operation (the auto-vectoriser does not reliably pack these loops).
template <int S>
struct Texel {
    typedef float Vector __attribute__((vector_size(S * sizeof(float))));
    Vector v{};

    static Texel load(const float* p) {
        Texel t;
        __builtin_memcpy(&t.v, p, sizeof(Vector));  // unaligned load
        return t;
    }
};

template <int S>
inline void add_scaled(Texel<S>& acc, float w, const Texel<S>& t) {
    acc.v += w * t.v;
}

// Asks for the cache line holding p (no load; any address is fine). Not __builtin_prefetch alone:
// GCC (12) counts a prefetch as free of side effects, so its IPA marks a function that only
// prefetches as pure and deletes every call to it, and a prefetch loop compiles to nothing. An asm
// volatile cannot be deleted.
inline void prefetch(const void* p) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#else
    __builtin_prefetch(p);
#endif
}

// ⌊x⌋ for |x| < 2^31 without a libm call (x86-64's baseline SSE2 has no rounding instruction).
inline int floor_to_int(float x) {
    const int i = static_cast<int>(x);
    return i - (x < static_cast<float>(i));
}

// Four floats or ints in one SSE register: the (x, y) texel coordinates of a trilinear probe's two
// levels, handled at once.
typedef float Float4 __attribute__((vector_size(16)));
typedef int Int4 __attribute__((vector_size(16)));

// ⌊p⌋ and p − ⌊p⌋ of four texel coordinates (|p| < 2^31; one conversion and one compare for all
// four, no libm).
struct FloorAndFraction {
    Int4 lower;
    Float4 fraction;
};
inline FloorAndFraction floor_and_fraction(Float4 p) {
    const Int4 truncated = __builtin_convertvector(p, Int4);
    const Int4 lower = truncated + (p < __builtin_convertvector(truncated, Float4));  // true = −1
    return {lower, p - __builtin_convertvector(lower, Float4)};
}

// A bilinear sample's four taps (a b in the upper row, c d below) and its fractional position.
struct BilinearTaps {
    const float *a, *b, *c, *d;
    float fx, fy;
};

// The texel position of a sample at (s, t) on `view` (spec §1: X = s·W − ½): the upper-left tap
// (x0, y0) and the fractions towards (x0 + 1, y0 + 1).
struct BilinearPosition {
    int x0, y0;
    float fx, fy;
    bool inside;  // all four taps lie on the level or its border (MipPyramidOptions::border)
};
inline BilinearPosition bilinear_position(const MipPyramid::LevelView& view, float s, float t) {
    const float x = s * static_cast<float>(view.width) - 0.5f;
    const float y = t * static_cast<float>(view.height) - 0.5f;
    const int x0 = floor_to_int(x), y0 = floor_to_int(y);
    const int b = view.border;
    return {x0, y0, x - static_cast<float>(x0), y - static_cast<float>(y0),
            x0 >= -b && y0 >= -b && x0 + 1 < view.width + b && y0 + 1 < view.height + b};
}

// The positions of a sample at (s, t) on two levels at once (a trilinear probe's): the same
// arithmetic as bilinear_position(), in one SSE register (one conversion and one compare for all
// four coordinates instead of four of each).
struct BilinearPositionPair {
    BilinearPosition fine, coarse;
};
inline BilinearPositionPair bilinear_positions(const MipPyramid::LevelView& fine,
                                               const MipPyramid::LevelView& coarse, float s,
                                               float t) {
    const Int4 size{fine.width, fine.height, coarse.width, coarse.height};
    const auto [lower, fraction] =
        floor_and_fraction(Float4{s, t, s, t} * __builtin_convertvector(size, Float4) - 0.5f);
    const Int4 border{fine.border, fine.border, coarse.border, coarse.border};
    const Int4 on_level = (lower >= -border) & (lower + 1 < size + border);
    return {{lower[0], lower[1], fraction[0], fraction[1], (on_level[0] & on_level[1]) != 0},
            {lower[2], lower[3], fraction[2], fraction[3], (on_level[2] & on_level[3]) != 0}};
}

// The taps of columns xa, xb and rows ya, yb (each on the level).
inline BilinearTaps taps_at(const MipPyramid::LevelView& view, int xa, int xb, int ya, int yb,
                            float fx, float fy) {
    const float* upper = view.base + view.row(ya);
    const float* lower = view.base + view.row(yb);
    const std::ptrdiff_t ca = view.column(xa), cb = view.column(xb);
    return {upper + ca, upper + cb, lower + ca, lower + cb, fx, fy};
}

// The taps of a row-major level (tile_log2 = 0) from the upper-left one: one texel (`stride`
// floats) right and one row down.
inline BilinearTaps row_major_taps(const float* upper_left, std::ptrdiff_t row_floats, int stride,
                                   float fx, float fy) {
    const float* lower_left = upper_left + row_floats;
    return {upper_left, upper_left + stride, lower_left, lower_left + stride, fx, fy};
}

// Requests the cache lines of a sample's taps (a tap of `stride` floats may straddle a line).
inline void prefetch_taps(const BilinearTaps& taps, int stride) {
    prefetch(taps.a);
    prefetch(taps.b + stride - 1);
    prefetch(taps.c);
    prefetch(taps.d + stride - 1);
}

// The bilinear blend of four taps.
template <int S>
inline Texel<S> blend_taps(const BilinearTaps& taps) {
    const float fx = taps.fx, fy = taps.fy;
    const float wa = (1 - fx) * (1 - fy), wb = fx * (1 - fy), wc = (1 - fx) * fy, wd = fx * fy;
    Texel<S> r;
    r.v = wa * Texel<S>::load(taps.a).v + wb * Texel<S>::load(taps.b).v +
          wc * Texel<S>::load(taps.c).v + wd * Texel<S>::load(taps.d).v;
    return r;
}

// The taps of a bilinear sample of one level at position p; taps beyond the level's edge are
// wrapped.
inline BilinearTaps wrapped_taps(const MipPyramid::LevelView& level, WrapMode wrap_s,
                                 WrapMode wrap_t, const BilinearPosition& p) {
    if (p.inside) return taps_at(level, p.x0, p.x0 + 1, p.y0, p.y0 + 1, p.fx, p.fy);
    return taps_at(level, wrap_index(p.x0, level.width, wrap_s),
                   wrap_index(p.x0 + 1, level.width, wrap_s),
                   wrap_index(p.y0, level.height, wrap_t),
                   wrap_index(p.y0 + 1, level.height, wrap_t), p.fx, p.fy);
}

// Bilinear sample of one level at (s, t); taps beyond the level's edge are wrapped.
template <int S>
inline Texel<S> sample_bilinear(const MipPyramid::LevelView& level, WrapMode wrap_s,
                                WrapMode wrap_t, float s, float t) {
    return blend_taps<S>(wrapped_taps(level, wrap_s, wrap_t, bilinear_position(level, s, t)));
}

// The texel-source functions the filters call on a MipPyramid (tiled_texels.h has TiledTexels'):
// a bilinear sample of level l at (s, t), and texel (x, y) of level l.
template <int S>
inline Texel<S> sample_bilinear(const MipPyramid& pyramid, int l, float s, float t) {
    return sample_bilinear<S>(pyramid.level(l), pyramid.wrap_s(), pyramid.wrap_t(), s, t);
}
inline const float* level_texel(const MipPyramid& pyramid, int l, int x, int y) {
    return pyramid.texel(l, x, y);
}

// Blend weight of the finer level's successor at fractional lod L + w.
inline float lod_blend_weight(float w, LodBlend blend) {
    // Spec §2.8: linear blending gives variance 4^L(1+3w)/4; w' = (4^w − 1)/3 gives 4^{L+w}/4.
    if (blend != LodBlend::variance_matched || w == 0.0f) return w;
    return (std::exp2(2.0f * w) - 1.0f) * (1.0f / 3.0f);
}

// Brilinear as a trilinear probe at another level: lod = L + w becomes L + w' with
// w' = clamp((w − ½)/band + ½, 0, 1), which a linear blend then weighs as brilinear does — and at
// w' = 0 or 1 the probe is a whole level, so it reads that level alone.
inline float brilinear_lod(float lod, float band) {
    const float level = std::floor(lod);
    if (!(band > 0.0f)) return lod - level < 0.5f ? level : level + 1.0f;
    return level + std::clamp((lod - level - 0.5f) / band + 0.5f, 0.0f, 1.0f);
}

// The levels a trilinear probe at a fractional lod ∈ [0, max_level] reads: l0 and, with blend
// weight w > 0, l0 + 1.
struct TrilinearLevels {
    int l0;
    float w;
};
inline TrilinearLevels trilinear_levels(float lod, int max_level, LodBlend blend) {
    const int l0 = std::min(static_cast<int>(lod), max_level);
    return {l0, l0 < max_level ? lod_blend_weight(lod - static_cast<float>(l0), blend) : 0.0f};
}

// A trilinear probe's taps on levels.l0 and, when levels.w > 0, levels.l0 + 1: addressed once,
// then requested (prefetch_probe) and read (blend_probe).
struct ProbeTaps {
    BilinearTaps fine, coarse;  // coarse: only when levels.w > 0
};

// The taps of a trilinear probe at (s, t) on `pyramid`'s levels (a MipPyramid, or TiledTexels):
// both levels positioned at once (bilinear_positions), each level's taps addressed by
// taps_on(view, level, position) — wrapped at a texture's edges, or read across an environment
// map's faces.
template <class Levels, class TapsOn>
inline ProbeTaps trilinear_taps(const Levels& pyramid, float s, float t, TrilinearLevels levels,
                                TapsOn&& taps_on) {
    const MipPyramid::LevelView& fine = pyramid.level(levels.l0);
    if (levels.w == 0.0f) return {taps_on(fine, levels.l0, bilinear_position(fine, s, t)), {}};
    const MipPyramid::LevelView& coarse = pyramid.level(levels.l0 + 1);
    const BilinearPositionPair p = bilinear_positions(fine, coarse, s, t);
    return {taps_on(fine, levels.l0, p.fine), taps_on(coarse, levels.l0 + 1, p.coarse)};
}

// The taps of a trilinear probe of `pyramid` at (s, t); taps beyond a level's edge are wrapped.
inline ProbeTaps probe_taps(const MipPyramid& pyramid, float s, float t, TrilinearLevels levels) {
    return trilinear_taps(pyramid, s, t, levels,
                          [&](const MipPyramid::LevelView& view, int, const BilinearPosition& p) {
                              return wrapped_taps(view, pyramid.wrap_s(), pyramid.wrap_t(), p);
                          });
}

inline void prefetch_probe(const ProbeTaps& taps, TrilinearLevels levels, int stride) {
    prefetch_taps(taps.fine, stride);
    if (levels.w > 0.0f) prefetch_taps(taps.coarse, stride);
}

template <int S>
inline Texel<S> blend_probe(const ProbeTaps& taps, TrilinearLevels levels) {
    Texel<S> r = blend_taps<S>(taps.fine);
    if (levels.w > 0.0f) {
        const Texel<S> coarse = blend_taps<S>(taps.coarse);
        r.v += levels.w * (coarse.v - r.v);
    }
    return r;
}

// A trilinear probe addressed (set in place: {probe_taps(…), levels}) and requested now, read later
// (blend()): what sample_trilinear() returns, for callers that request many probes before reading
// any.
struct RequestedProbe {
    ProbeTaps taps;
    TrilinearLevels levels;

    void request(int stride) const { prefetch_probe(taps, levels, stride); }
    template <int S>
    Texel<S> blend() const {
        return blend_probe<S>(taps, levels);
    }
};

// Trilinear probe at a fractional level lod ∈ [0, max_level] of a MipPyramid or TiledTexels.
template <int S, class Texels>
inline Texel<S> sample_trilinear(const Texels& pyramid, float s, float t, float lod,
                                 LodBlend blend) {
    const TrilinearLevels levels = trilinear_levels(lod, pyramid.max_level(), blend);
    return blend_probe<S>(probe_taps(pyramid, s, t, levels), levels);
}

// The software pipeline every line of probes runs (spec §2.9: Σ weights[i]·probe_i / Σ weights[i],
// each level summed on its own and the two blended once, by coarse_weight = TrilinearLevels::w).
// line.place(i) places probe i, addresses its taps and requests them (prefetch), once;
// line.fine(probe) and line.coarse(probe) read them. Probe i + kAhead is placed while probe i is
// read, so that cache misses overlap (a bounded number in flight) instead of arriving one probe at
// a time.
template <int S, class Line>
inline Texel<S> blend_line_ahead(int count, const float* weights, float coarse_weight,
                                 Line&& line) {
    Texel<S> fine{}, coarse{};
    auto read = [&](const auto& probe, int i) {
        add_scaled(fine, weights[i], line.fine(probe));
        if (coarse_weight > 0.0f) add_scaled(coarse, weights[i], line.coarse(probe));
    };
    if (count == 2) {  // the most common line (near-isotropic footprints): no ring
        const auto first = line.place(0), second = line.place(1);
        read(first, 0);
        read(second, 1);
    } else {
        constexpr int kAhead = 6, kRing = 8;
        decltype(line.place(0)) ring[kRing];
        for (int i = 0; i < std::min(kAhead, count); ++i) ring[i] = line.place(i);
        for (int i = 0; i < count; ++i) {
            if (i + kAhead < count) ring[(i + kAhead) % kRing] = line.place(i + kAhead);
            read(ring[i % kRing], i);
        }
    }
    float weight_sum = 0;
    for (int i = 0; i < count; ++i) weight_sum += weights[i];
    const float weight = 1.0f / weight_sum;
    Texel<S> result = fine;
    result.v *= weight;
    if (coarse_weight > 0.0f) result.v += coarse_weight * (weight * coarse.v - result.v);
    return result;
}

// A line of `count` trilinear probes, all on `levels` (blend_line_ahead): taps_of(i) places probe
// i and addresses its taps (ProbeTaps, read with any level's layout and edges).
template <int S, class TapsOf>
inline Texel<S> blend_probe_line(int count, const float* weights, TrilinearLevels levels,
                                 int stride, TapsOf&& taps_of) {
    struct Line {
        TapsOf& taps_of;
        TrilinearLevels levels;
        int stride;
        ProbeTaps place(int i) const {
            const ProbeTaps taps = taps_of(i);
            prefetch_probe(taps, levels, stride);
            return taps;
        }
        Texel<S> fine(const ProbeTaps& taps) const { return blend_taps<S>(taps.fine); }
        Texel<S> coarse(const ProbeTaps& taps) const { return blend_taps<S>(taps.coarse); }
    };
    return blend_line_ahead<S>(count, weights, levels.w, Line{taps_of, levels, stride});
}

// Whether every probe of a straight line from (s0, t0) to (s1, t1) has its taps on `fine` and
// `coarse` (pass fine twice for one level): then probe_taps_inside() may address them. Tested at
// the ends, whose texel positions X = s·W − ½ must lie in [m, W − 1 − m] on both levels; on a
// level with a border (MipPyramidOptions::border), in [−½ + m, W − ½ − m]: the probes' centres on
// the level itself, s ∈ [0, 1] (a cube map's probe beyond its face is placed on its own face,
// spec §3.1), their taps at most one texel beyond. The probes between the ends lie between them (a
// level is convex), and so do their rounded positions when they are computed as c + k·Δ (every
// step monotone in k in IEEE arithmetic); the margin m = 1/64 texel covers positions rounded
// otherwise (a few ulp of s times W: under 0.002 texel on levels up to 16 384 wide).
inline bool line_inside(const MipPyramid::LevelView& fine, const MipPyramid::LevelView& coarse,
                        float s0, float t0, float s1, float t1) {
    constexpr float kMargin = 1.0f / 64;
    const Float4 size = __builtin_convertvector(
        (Int4{fine.width, fine.height, coarse.width, coarse.height}), Float4);
    const float fine_reach = fine.border > 0 ? 0.5f : 0.0f;
    const float coarse_reach = coarse.border > 0 ? 0.5f : 0.0f;
    const Float4 reach{fine_reach, fine_reach, coarse_reach, coarse_reach};
    const Float4 first = kMargin - reach;
    const Float4 last = size - (1.0f + kMargin) + reach;
    const Float4 a = Float4{s0, t0, s0, t0} * size - 0.5f;
    const Float4 b = Float4{s1, t1, s1, t1} * size - 0.5f;
    const Int4 ok = (a >= first) & (a <= last) & (b >= first) & (b <= last);  // false for NaN
    return (ok[0] & ok[1] & ok[2] & ok[3]) != 0;
}

// The taps of a trilinear probe at (s, t) on levels that hold all of them (line_inside()): what
// trilinear_taps() gives there, without its edge tests.
inline ProbeTaps probe_taps_inside(const MipPyramid::LevelView& fine,
                                   const MipPyramid::LevelView& coarse, float s, float t,
                                   TrilinearLevels levels) {
    if (levels.w == 0.0f) {
        const BilinearPosition p = bilinear_position(fine, s, t);
        return {taps_at(fine, p.x0, p.x0 + 1, p.y0, p.y0 + 1, p.fx, p.fy), {}};
    }
    const BilinearPositionPair p = bilinear_positions(fine, coarse, s, t);
    return {taps_at(fine, p.fine.x0, p.fine.x0 + 1, p.fine.y0, p.fine.y0 + 1, p.fine.fx, p.fine.fy),
            taps_at(coarse, p.coarse.x0, p.coarse.x0 + 1, p.coarse.y0, p.coarse.y0 + 1, p.coarse.fx,
                    p.coarse.fy)};
}

// Writes the first `channels` values of a texel. RGB in texels four floats wide (the common case)
// and texels as wide as their channels are written without the per-channel tests.
template <int S>
inline void store(const Texel<S>& t, int channels, float* out) {
    if (channels == S) {
        __builtin_memcpy(out, &t.v, sizeof(t.v));
        return;
    }
    if constexpr (S == 4) {
        if (channels == 3) {
            out[0] = t.v[0], out[1] = t.v[1], out[2] = t.v[2];
            return;
        }
    }
    for (int k = 0; k < S; ++k)
        if (k < channels) out[k] = t.v[k];
}

// Calls f.template operator()<S>() with the pyramid's stride as a compile-time constant.
template <class F>
inline void dispatch_stride(int stride, F&& f) {
    switch (stride) {
        case 1:
            f.template operator()<1>();
            break;
        case 2:
            f.template operator()<2>();
            break;
        case 4:
            f.template operator()<4>();
            break;
        default:
            f.template operator()<8>();
            break;
    }
}

// A probe of a line inside row-major levels (the default layout): the upper-left tap of each level,
// whose other taps are one texel (S floats) right and one row down, and the fractions (fine x, y,
// coarse x, y). Two pointers and one register instead of ProbeTaps' eight pointers: less to
// address, keep and read back per probe.
struct RowMajorProbe {
    const float* fine;
    const float* coarse;
    Float4 fraction;
};

// A RowMajorProbe's bilinear blend on its fine and on its coarse level.
template <int S>
inline Texel<S> blend_row_major_fine(const RowMajorProbe& probe, std::ptrdiff_t row_floats) {
    return blend_taps<S>(
        row_major_taps(probe.fine, row_floats, S, probe.fraction[0], probe.fraction[1]));
}
template <int S>
inline Texel<S> blend_row_major_coarse(const RowMajorProbe& probe, std::ptrdiff_t row_floats) {
    return blend_taps<S>(
        row_major_taps(probe.coarse, row_floats, S, probe.fraction[2], probe.fraction[3]));
}

// The probes of blend_probe_path_inside() on row-major levels (RowMajorProbe): the positions of
// bilinear_positions(), level sizes converted once per line.
template <int S, class PositionOf>
struct RowMajorLine {
    const MipPyramid::LevelView &fine_level, &coarse_level;
    PositionOf& position_of;
    bool two_levels;
    Float4 size = __builtin_convertvector(
        (Int4{fine_level.width, fine_level.height, coarse_level.width, coarse_level.height}),
        Float4);

    RowMajorProbe place(int i) const {
        const auto position = position_of(i);
        const auto [lower, fraction] = floor_and_fraction(
            Float4{position.x, position.y, position.x, position.y} * size - 0.5f);
        const RowMajorProbe probe{
            fine_level.base + lower[1] * fine_level.row_floats + lower[0] * S,
            coarse_level.base + lower[3] * coarse_level.row_floats + lower[2] * S, fraction};
        request(probe.fine, fine_level.row_floats);
        if (two_levels) request(probe.coarse, coarse_level.row_floats);
        return probe;
    }
    static void request(const float* upper_left, std::ptrdiff_t row_floats) {
        prefetch_taps(row_major_taps(upper_left, row_floats, S, 0, 0), S);
    }
    Texel<S> fine(const RowMajorProbe& probe) const {
        return blend_row_major_fine<S>(probe, fine_level.row_floats);
    }
    Texel<S> coarse(const RowMajorProbe& probe) const {
        return blend_row_major_coarse<S>(probe, coarse_level.row_floats);
    }
};

// The levels a line of probes on `levels` reads (coarse = fine when levels.w = 0), and whether
// every probe of a path within the box of corners `lower` and `upper` has its taps on them
// (line_inside()).
struct LineLevels {
    const MipPyramid::LevelView& fine;
    const MipPyramid::LevelView& coarse;

    LineLevels(const MipPyramid& pyramid, TrilinearLevels levels)
        : fine(pyramid.level(levels.l0)),
          coarse(pyramid.level(levels.w > 0.0f ? levels.l0 + 1 : levels.l0)) {}
    template <class Corner>
    bool hold(Corner lower, Corner upper) const {
        return line_inside(fine, coarse, lower.x, lower.y, upper.x, upper.y);
    }
    bool row_major() const { return fine.tile_log2 == 0 && coarse.tile_log2 == 0; }
};

// A line of at most N probes inside row-major levels, placed and requested now (request()) and
// read later (blend()), for callers that request many lines before reading any so that their
// misses to memory overlap (the environment batch). blend() returns exactly what
// blend_probe_path_inside() returns for the same path.
template <int N>
struct RequestedLine {
    int count = 0;
    float coarse_weight = 0;  // TrilinearLevels::w
    std::ptrdiff_t fine_row_floats = 0, coarse_row_floats = 0;
    float weights[N];
    RowMajorProbe probes[N];

    // blend_probe_path_inside()'s arguments: false, with nothing requested, unless it would read
    // the path by RowMajorLine and count ≤ N.
    template <int S, class Corner, class PositionOf>
    bool request(const MipPyramid& pyramid, int probe_count, const float* probe_weights,
                 TrilinearLevels levels, Corner lower, Corner upper, PositionOf&& position_of) {
        const LineLevels on(pyramid, levels);
        if (probe_count > N || !on.row_major() || !on.hold(lower, upper)) return false;
        const RowMajorLine<S, PositionOf> line{on.fine, on.coarse, position_of, levels.w > 0.0f};
        for (int i = 0; i < probe_count; ++i) {
            probes[i] = line.place(i);
            weights[i] = probe_weights[i];
        }
        count = probe_count;
        coarse_weight = levels.w;
        fine_row_floats = on.fine.row_floats;
        coarse_row_floats = on.coarse.row_floats;
        return true;
    }

    template <int S>
    Texel<S> blend() const {
        struct Requested {
            const RequestedLine& line;
            RowMajorProbe place(int i) const { return line.probes[i]; }
            Texel<S> fine(const RowMajorProbe& probe) const {
                return blend_row_major_fine<S>(probe, line.fine_row_floats);
            }
            Texel<S> coarse(const RowMajorProbe& probe) const {
                return blend_row_major_coarse<S>(probe, line.coarse_row_floats);
            }
        };
        return blend_line_ahead<S>(count, weights, coarse_weight, Requested{*this});
    }
};

// A path of `count` probes on `pyramid`'s `levels`, probe i at position_of(i) (a Vec2 (s, t)),
// every position within the box of corners `lower` and `upper` (to rounding: line_inside()'s
// margin): when line_inside() admits the box, blended without edge tests — RowMajorLine on
// row-major levels, probe_taps_inside() on tiled ones — and written to out, true; otherwise nothing
// written, false, for the caller's edge-aware path.
template <class Corner, class PositionOf>
inline bool blend_probe_path_inside(const MipPyramid& pyramid, int count, const float* weights,
                                    TrilinearLevels levels, Corner lower, Corner upper,
                                    PositionOf&& position_of, float* out) {
    const LineLevels on(pyramid, levels);
    if (!on.hold(lower, upper)) return false;
    const MipPyramid::LevelView &fine = on.fine, &coarse = on.coarse;
    const bool row_major = on.row_major();
    dispatch_stride(pyramid.stride(), [&]<int S>() {
        const Texel<S> result =
            row_major ? blend_line_ahead<S>(
                            count, weights, levels.w,
                            RowMajorLine<S, PositionOf>{fine, coarse, position_of, levels.w > 0.0f})
                      : blend_probe_line<S>(count, weights, levels, pyramid.stride(), [&](int i) {
                            const auto p = position_of(i);
                            return probe_taps_inside(fine, coarse, p.x, p.y, levels);
                        });
        store(result, pyramid.channels(), out);
    });
    return true;
}

// The same for a straight line, positions c + k·Δ: its ends bound it (line_inside()).
template <class PositionOf>
inline bool blend_probe_line_inside(const MipPyramid& pyramid, int count, const float* weights,
                                    TrilinearLevels levels, PositionOf&& position_of, float* out) {
    return blend_probe_path_inside(pyramid, count, weights, levels, position_of(0),
                                   position_of(count - 1), position_of, out);
}

// A bilinear sample of level 0 at reduced (s, t), written to out: the magnification and
// no-MIP path of every filter (on a MipPyramid or TiledTexels, tiled_texels.h).
template <class Texels>
inline void lookup_level0_bilinear(const Texels& pyramid, float s, float t, float* out) {
    dispatch_stride(pyramid.stride(), [&]<int S>() {
        store(sample_bilinear<S>(pyramid, 0, s, t), pyramid.channels(), out);
    });
}

}  // namespace footprint::detail
