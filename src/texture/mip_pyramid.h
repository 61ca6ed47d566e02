// texture/mip_pyramid.h — MIP pyramids of any size and channel count, stored for fast lookups.
//
// Level sizes follow spec §1: W_l = max(1, ⌊W_0/2^l⌋), H_l likewise, down to 1×1. Non-power-of-two
// and odd sizes are handled exactly: texel i of level l covers the level-(l−1) interval
// [i·r, (i+1)·r) with r = W_{l−1}/W_l (r = 2.5 for 5 → 2), so the levels stay aligned in (s, t).
//
// Downsampling filters (DownsampleFilter):
//   box   the papers' 2×2 box (for odd sizes its exact generalisation: the mean over the
//         covered interval, with fractional weights for partly covered texels). Each level then
//         holds the plain average of the level-0 texels it covers, which is what footprint
//         assembly's kernel-covariance rule (spec §2.6, (T²/4 − 1/12)·I per probe) assumes and
//         what the bump pyramid's moment recursion (spec §5.3) needs.
//   tent  the linear B-spline (support ±1 output texel) integrated exactly over the source
//         texels. Chosen as the higher-quality filter because its frequency response is sinc²:
//         side lobes at −26 dB instead of the box's −13 dB, so far less aliasing leaks into
//         coarse levels, while the kernel stays short (4 taps per axis for r = 2), positive (no
//         ringing on HDR data, unlike Lanczos) and — being a B-spline — a partition of unity,
//         so with repeat wrap every level keeps the image mean exactly for any size. The price
//         is more blur: each tent level adds r²/6 instead of the box's r²/12 of variance.
// Both filters keep the mean of every level equal to the image mean under repeat wrap.
//
// Memory layout (TexelLayout): each level is stored in square tiles of 2^k × 2^k texels, tiles
// row-major, texels row-major inside a tile, channels interleaved and padded to a stride of
// 1, 2, 4 or 8 floats (RGB is stored as RGBA-aligned 16-byte texels). tile_log2 = 0 is the plain
// row-major layout. All levels live in one allocation, level-major. The default was chosen by
// `footprint-bench pyramid`, which times lookups in each layout (docs/performance.md).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include <footprint/core/result.h>
#include <footprint/image/image.h>
#include <footprint/math/vec.h>
#include <footprint/texture/texel_storage.h>
#include <footprint/texture/wrap.h>

namespace footprint {

class SummedAreaTable;

enum class DownsampleFilter { box, tent };

struct MipPyramidOptions {
    WrapMode wrap_s = WrapMode::repeat;
    WrapMode wrap_t = WrapMode::repeat;
    DownsampleFilter downsample = DownsampleFilter::box;
    int tile_log2 = 0;  // tiles of 2^k × 2^k texels; 0 = row-major, the fastest measured (above)
    bool summed_area_table = false;  // also build a SAT of level 0 (TextureFilter::summed_area)
    // Texels stored around every level, beyond its edges (row-major layout only): a sample whose
    // taps reach at most `border` texels beyond the level reads them like any other (no wrap or
    // seam logic). They start at zero; the pyramid's owner fills them (writable_texel()) — an
    // environment map's cube faces with their neighbours' texels, so that bilinear taps cross
    // face edges without a test.
    int border = 0;
};

class MipPyramid {
  public:
    static constexpr int kMaxChannels = 8;

    MipPyramid();
    ~MipPyramid();
    MipPyramid(MipPyramid&&) noexcept;
    MipPyramid& operator=(MipPyramid&&) noexcept;

    // Builds every level from a level-0 image of any size ≥ 1×1 with 1..kMaxChannels channels
    // (asserts on an empty image or a bad channel count: validate user images before).
    // Runs on oneTBB's task arena (`footprint-bench pyramid` times it).
    static MipPyramid build(const Image& level0, const MipPyramidOptions& options = {});

    // A pyramid from ready-made levels (a MIP chain from a file, or a test's coloured levels).
    // levels[l] must be max(1, ⌊W0/2^l⌋) × max(1, ⌊H0/2^l⌋) down to 1×1, all with one channel
    // count; returns an Error naming the first level that is not. prefilter_variance() assumes the
    // box.
    static Result<MipPyramid> from_levels(const std::vector<Image>& levels,
                                          const MipPyramidOptions& options = {});

    int channels() const { return channels_; }
    int stride() const { return stride_; }  // floats per stored texel (≥ channels)
    int level_count() const { return static_cast<int>(levels_.size()); }
    int max_level() const { return level_count() - 1; }
    int width(int level) const { return levels_[level].width; }
    int height(int level) const { return levels_[level].height; }
    WrapMode wrap_s() const { return options_.wrap_s; }
    WrapMode wrap_t() const { return options_.wrap_t; }
    int border() const { return options_.border; }
    const MipPyramidOptions& options() const { return options_; }
    bool empty() const { return levels_.empty(); }

    // Read access to one level: texel(x, y) is `stride()` floats, the first `channels()`
    // meaningful; x ∈ [0, width), y ∈ [0, height), or up to `border` texels beyond. The address
    // separates into a column and a row part, texel(x, y) = base + column(x) + row(y), for tiles
    // too, so that a bilinear sample's four taps cost two of each. Built once per level: level()
    // hands out a reference.
    struct LevelView {
        const float* base;
        int width, height;
        int tiles_x, tile_log2, stride;
        int inner_mask;  // 2^tile_log2 − 1: a texel's column (or row) inside its tile; 0 row-major
        std::ptrdiff_t row_floats;  // row-major: floats from one row to the next
        int border;                 // texels stored beyond each edge (MipPyramidOptions::border)
        // Offsets in floats from base (row-major, the default layout, needs no tile arithmetic).
        std::ptrdiff_t column(int x) const {
            if (tile_log2 == 0) return static_cast<std::ptrdiff_t>(x) * stride;
            return ((static_cast<std::ptrdiff_t>(x >> tile_log2) << (2 * tile_log2)) +
                    (x & inner_mask)) *
                   stride;
        }
        std::ptrdiff_t row(int y) const {
            if (tile_log2 == 0) return static_cast<std::ptrdiff_t>(y) * row_floats;
            return ((static_cast<std::ptrdiff_t>(y >> tile_log2) * tiles_x << (2 * tile_log2)) +
                    ((y & inner_mask) << tile_log2)) *
                   stride;
        }
        const float* texel(int x, int y) const { return base + row(y) + column(x); }
    };
    const LevelView& level(int l) const { return views_[l]; }
    const float* texel(int l, int x, int y) const { return level(l).texel(x, y); }

    // The stored texel (x, y) of level l, x ∈ [−border, width + border), y likewise, for the
    // pyramid's owner to fill its border.
    float* writable_texel(int l, int x, int y) {
        return storage_.data() + (level(l).texel(x, y) - storage_.data());
    }

    // Per-axis variance (level-0 texels², about level-0 texel centres) of the downsampling kernel
    // that made level l from level 0: (T²−1)/12 for the box pyramid with texel size T. EWA
    // subtracts it so that its kernel covariance is K/4 on any level (ewa.h).
    Vec2 prefilter_variance(int l) const { return levels_[l].prefilter_variance; }

    // A copy of one level as a plain image (for inspection, tests and the demo).
    Image level_image(int level) const;

    // The summed-area table of level 0, or nullptr unless options.summed_area_table was set.
    const SummedAreaTable* summed_area_table() const { return sat_.get(); }

  private:
    struct Level {
        int width = 0, height = 0;
        int tiles_x = 0;
        std::size_t offset = 0;  // in floats
        Vec2 prefilter_variance;
    };
    void allocate(int width, int height, int channels, const MipPyramidOptions& options);
    void store_level(int level, const std::vector<float>& row_major);
    void store_level(int level, const Image& image);

    MipPyramidOptions options_;
    int channels_ = 0;
    int stride_ = 0;
    int tile_log2_ = 0;
    std::vector<Level> levels_;
    std::vector<LevelView> views_;  // one per level, into storage_
    detail::TexelStorage storage_;
    std::unique_ptr<SummedAreaTable> sat_;
};

// MipPyramid::build()'s levels made one at a time, for writing a pyramid out without holding it
// whole (`footprint maketx`, the texture system's cache): take(level) is called for level 0
// (level0 itself), 1, … down to 1×1, each level what build(level0, options)'s level_image(l)
// holds, bit for bit. Besides level0, at most two levels are held at once (level l while level
// l + 1 is made from it), as plain images of level0's channels: together a third of level0's size.
// Stops at take's first error and returns it. options.tile_log2, border and summed_area_table do
// not apply.
Status for_each_mip_level(const Image& level0, const MipPyramidOptions& options,
                          const std::function<Status(const Image& level)>& take);

// The prefilter variances (MipPyramid::prefilter_variance()) that build() gives the levels of a
// width × height pyramid made with `filter`, level 0 first.
std::vector<Vec2> mip_prefilter_variances(int width, int height, DownsampleFilter filter);

// The number of stored floats per texel for a channel count: 1, 2, 4 or 8.
constexpr int texel_stride(int channels) {
    return channels <= 1 ? 1 : channels == 2 ? 2 : channels <= 4 ? 4 : 8;
}

}  // namespace footprint
