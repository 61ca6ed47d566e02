#include "texture/mip_pyramid.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <string>

#include "core/parallel.h"
#include "texture/downsample.h"
#include "texture/summed_area_table.h"

namespace footprint {

namespace {

// The image's texels row-major with each texel padded from `channels` to `stride` floats, rows
// `pitch` floats apart.
void copy_padded(const Image& image, int stride, float* padded, std::ptrdiff_t pitch) {
    parallel_for_each(0, image.height, [&](int y) {
        for (int x = 0; x < image.width; ++x)
            std::copy_n(image.at(x, y), image.channels, &padded[y * pitch + x * stride]);
    });
}

std::vector<float> padded_to_stride(const Image& image, int stride) {
    std::vector<float> padded(image.pixel_count() * stride, 0.0f);
    copy_padded(image, stride, padded.data(), std::ptrdiff_t(image.width) * stride);
    return padded;
}

// The prefilter variance of a level of dw × dh made from one of sw × sh whose variance is
// `before`, in a pyramid whose level 0 is width × height: variances add through the chain, and a
// step's variance in level-0 units scales with the source level's texel size squared.
Vec2 next_prefilter_variance(Vec2 before, int width, int height, int sw, int sh, int dw, int dh,
                             DownsampleFilter filter) {
    const double tx = double(width) / sw, ty = double(height) / sh;
    return {float(before.x + tx * tx * detail::tap_variance(sw, dw, filter)),
            float(before.y + ty * ty * detail::tap_variance(sh, dh, filter))};
}

}  // namespace

MipPyramid::MipPyramid() = default;
MipPyramid::~MipPyramid() = default;
MipPyramid::MipPyramid(MipPyramid&&) noexcept = default;
MipPyramid& MipPyramid::operator=(MipPyramid&&) noexcept = default;

void MipPyramid::allocate(int width, int height, int channels, const MipPyramidOptions& options) {
    options_ = options;
    channels_ = channels;
    stride_ = texel_stride(channels);
    tile_log2_ = options.tile_log2;
    assert(options.border >= 0 && (options.border == 0 || options.tile_log2 == 0));
    const int border = options.border;
    // Level geometry (spec §1) and one allocation for all levels, each padded to whole tiles.
    const int tile = 1 << tile_log2_;
    std::size_t total = 0;
    levels_.clear();
    for (int w = width, h = height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
        Level l;
        l.width = w;
        l.height = h;
        l.tiles_x = (w + tile - 1) / tile;
        const int tiles_y = (h + tile - 1) / tile;
        l.offset = total;
        total += static_cast<std::size_t>(l.tiles_x * tile + 2 * border) *
                 (tiles_y * tile + 2 * border) * stride_;
        levels_.push_back(l);
        if (w == 1 && h == 1) break;
    }
    storage_ = detail::TexelStorage(total);
    views_.clear();
    for (const Level& l : levels_) {
        const std::ptrdiff_t row_floats = std::ptrdiff_t(l.width + 2 * border) * stride_;
        views_.push_back({storage_.data() + l.offset + border * (row_floats + stride_), l.width,
                          l.height, l.tiles_x, tile_log2_, stride_, tile - 1, row_floats, border});
    }
}

MipPyramid MipPyramid::build(const Image& level0, const MipPyramidOptions& options) {
    assert(!level0.empty() && level0.channels >= 1 && level0.channels <= kMaxChannels);
    assert(options.tile_log2 >= 0 && options.tile_log2 <= 6);
    MipPyramid p;
    p.allocate(level0.width, level0.height, level0.channels, options);

    // Row-major storage is its own scratch: each level is downsampled straight from the previous
    // one in place (between their borders, if any). Tiled layouts go through row-major buffers and
    // are scattered into tiles.
    const bool in_place = p.tile_log2_ == 0;
    std::vector<float> current;
    if (in_place) {
        copy_padded(level0, p.stride_, p.writable_texel(0, 0, 0), p.views_[0].row_floats);
    } else {
        current = padded_to_stride(level0, p.stride_);
        p.store_level(0, current);
    }

    for (int l = 1; l < p.level_count(); ++l) {
        const int sw = p.width(l - 1), sh = p.height(l - 1), dw = p.width(l), dh = p.height(l);
        if (in_place) {
            detail::downsample<float, float>(p.writable_texel(l - 1, 0, 0), sw, sh,
                                             p.writable_texel(l, 0, 0), dw, dh, p.stride_, options,
                                             p.views_[l - 1].row_floats, p.views_[l].row_floats);
        } else {
            std::vector<float> next(static_cast<std::size_t>(dw) * dh * p.stride_);
            detail::downsample<float, float>(current.data(), sw, sh, next.data(), dw, dh, p.stride_,
                                             options);
            current = std::move(next);
            p.store_level(l, current);
        }
        p.levels_[l].prefilter_variance =
            next_prefilter_variance(p.levels_[l - 1].prefilter_variance, level0.width,
                                    level0.height, sw, sh, dw, dh, options.downsample);
    }

    if (options.summed_area_table)
        p.sat_ = std::make_unique<SummedAreaTable>(
            SummedAreaTable::build(level0, options.wrap_s, options.wrap_t));
    return p;
}

Result<MipPyramid> MipPyramid::from_levels(const std::vector<Image>& levels,
                                           const MipPyramidOptions& options) {
    if (levels.empty() || levels[0].empty()) return Error{"MIP chain: level 0 is empty"};
    const Image& base = levels[0];
    if (base.channels < 1 || base.channels > kMaxChannels)
        return Error{"MIP chain: " + std::to_string(base.channels) +
                     " channels (1 to 8 supported)"};
    MipPyramid p;
    p.allocate(base.width, base.height, base.channels, options);
    if (levels.size() != p.levels_.size())
        return Error{"MIP chain: " + std::to_string(levels.size()) + " levels given, a " +
                     std::to_string(base.width) + "x" + std::to_string(base.height) +
                     " texture needs " + std::to_string(p.levels_.size())};
    for (int l = 0; l < p.level_count(); ++l) {
        const Image& image = levels[l];
        if (image.width != p.width(l) || image.height != p.height(l) ||
            image.channels != base.channels ||
            image.pixels.size() != image.pixel_count() * image.channels)
            return Error{"MIP chain: level " + std::to_string(l) + " is " +
                         std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                         std::to_string(image.channels) + ", expected " +
                         std::to_string(p.width(l)) + "x" + std::to_string(p.height(l)) + "x" +
                         std::to_string(base.channels)};
        p.store_level(l, image);
        const float t = float(base.width) / float(p.width(l));
        p.levels_[l].prefilter_variance = {(t * t - 1) / 12, (t * t - 1) / 12};
    }
    if (options.summed_area_table)
        p.sat_ = std::make_unique<SummedAreaTable>(
            SummedAreaTable::build(base, options.wrap_s, options.wrap_t));
    return p;
}

void MipPyramid::store_level(int level, const std::vector<float>& row_major) {
    const Level& l = levels_[level];
    if (tile_log2_ == 0) {
        const std::size_t row = static_cast<std::size_t>(l.width) * stride_;
        for (int y = 0; y < l.height; ++y)
            std::copy_n(&row_major[y * row], row, writable_texel(level, 0, y));
        return;
    }
    parallel_for_each(0, l.height, [&](int y) {
        for (int x = 0; x < l.width; ++x) {
            const float* src = &row_major[(static_cast<std::size_t>(y) * l.width + x) * stride_];
            std::copy_n(src, stride_, writable_texel(level, x, y));
        }
    });
}

void MipPyramid::store_level(int level, const Image& image) {
    store_level(level, padded_to_stride(image, stride_));
}

Image MipPyramid::level_image(int level) const {
    Image image(width(level), height(level), channels_);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            std::copy_n(texel(level, x, y), channels_, image.at(x, y));
    return image;
}

Status for_each_mip_level(const Image& level0, const MipPyramidOptions& options,
                          const std::function<Status(const Image& level)>& take) {
    assert(!level0.empty() && level0.channels >= 1 && level0.channels <= MipPyramid::kMaxChannels);
    // The channels are filtered independently, each with the same taps in the same order as
    // build()'s padded texels: stride = channels gives its values without the padding.
    if (Status s = take(level0); !s) return s;
    Image previous;
    const Image* source = &level0;
    while (source->width > 1 || source->height > 1) {
        const int sw = source->width, sh = source->height;
        Image next(std::max(1, sw / 2), std::max(1, sh / 2), level0.channels);
        detail::downsample<float, float>(source->pixels.data(), sw, sh, next.pixels.data(),
                                         next.width, next.height, level0.channels, options);
        if (Status s = take(next); !s) return s;
        previous = std::move(next);  // the level it was made from freed
        source = &previous;
    }
    return {};
}

std::vector<Vec2> mip_prefilter_variances(int width, int height, DownsampleFilter filter) {
    std::vector<Vec2> variances{Vec2{}};
    for (int w = width, h = height; w > 1 || h > 1; w = std::max(1, w / 2), h = std::max(1, h / 2))
        variances.push_back(next_prefilter_variance(
            variances.back(), width, height, w, h, std::max(1, w / 2), std::max(1, h / 2), filter));
    return variances;
}

}  // namespace footprint
