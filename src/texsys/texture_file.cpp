#include "texsys/texture_file.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>
#include <vector>

#include "bump/bump_pyramid_file_detail.h"
#include "image/color.h"
#include "image/image_input.h"
#include "image/image_io.h"

namespace footprint {

namespace fs = std::filesystem;

namespace {

void read_wrap_modes(const OIIO::ImageSpec& spec, WrapMode fallback, TextureInfo& info) {
    const WrapModes modes = parse_oiio_wrap_modes(spec.get_string_attribute("wrapmodes"));
    info.wrap_s = modes.s.value_or(fallback);
    info.wrap_t = modes.t.value_or(fallback);
}

// The header attribute of a cached pyramid that holds its levels' prefilter variances
// (MipPyramid::prefilter_variance(), x and y per level), so that lookups on it give the bits of
// the pyramid built in memory.
constexpr const char* kPrefilterVarianceAttribute = "footprint:prefilter_variance";

// The prefilter variances a file's header gives its `levels` levels, or none (a stored chain's,
// the box's, apply).
std::vector<Vec2> stored_prefilter_variances(const OIIO::ImageSpec& spec, std::size_t levels) {
    const OIIO::ParamValue* p = spec.find_attribute(kPrefilterVarianceAttribute);
    if (!p || p->type().basetype != OIIO::TypeDesc::FLOAT ||
        p->type().numelements() * p->type().aggregate != 2 * levels)
        return {};
    const float* v = static_cast<const float*>(p->data());
    std::vector<Vec2> variances(levels);
    for (std::size_t l = 0; l < levels; ++l) variances[l] = {v[2 * l], v[2 * l + 1]};
    return variances;
}

// Writes the pyramid of `image` to `file` as a cached pyramid, a level at a time
// (for_each_mip_level(): the image and two levels in memory, not the pyramid).
Status save_built_levels(const Image& image, const MipPyramidOptions& options, int tile_size,
                         const fs::path& file) {
    LevelsSaveOptions save;
    save.wrap_modes = oiio_wrap_modes(options.wrap_s, options.wrap_t);
    save.tile_size = std::clamp(tile_size, 16, 1024);
    LevelsSaveOptions::FloatAttribute variances{kPrefilterVarianceAttribute, {}};
    for (const Vec2 v : mip_prefilter_variances(image.width, image.height, options.downsample)) {
        variances.values.push_back(v.x);
        variances.values.push_back(v.y);
    }
    save.float_attributes.push_back(std::move(variances));
    Result<LevelsWriter> writer = LevelsWriter::open(file, save);
    if (!writer) return writer.error();
    Status written = for_each_mip_level(image, options,
                                        [&](const Image& level) { return writer->write(level); });
    return written ? writer->finish() : written;
}

}  // namespace

fs::path cached_pyramid_file(const fs::path& file, const TextureSystemOptions& options,
                             WrapMode wrap_s, WrapMode wrap_t, std::string_view kind) {
    std::error_code ec;
    const fs::path absolute = fs::absolute(file, ec);
    const auto size = fs::file_size(file, ec);
    const auto modified = fs::last_write_time(file, ec).time_since_epoch().count();
    std::ostringstream key;
    key << absolute.string() << '|' << size << '|' << modified << '|' << options.tile_size << '|'
        << static_cast<int>(options.downsample) << '|' << static_cast<int>(wrap_s) << '|'
        << static_cast<int>(wrap_t) << '|' << kind << '|' << static_cast<int>(options.color)
        << "|prefilter variances";  // files without them (before they were kept) are rebuilt
    std::ostringstream name;
    name << file.stem().string() << '-' << kind << '-' << std::hex
         << std::hash<std::string>{}(key.str()) << ".exr";
    return options.cache_dir / name.str();
}

void TextureHandle::open(const TextureSystemOptions& options, const detail::OpenAs& as,
                         bool fall_back_to_memory) {
    Result<std::unique_ptr<OIIO::ImageInput>> opened = detail::open_image_input(name);
    if (!opened) {
        error = opened.error();
        return;
    }
    std::unique_ptr<OIIO::ImageInput> in = std::move(*opened);
    subimage_ = as.subimage;
    if (!in->seek_subimage(subimage_, 0)) {
        error = detail::read_error(name, "it has no subimage " + std::to_string(subimage_));
        return;
    }
    const OIIO::ImageSpec spec = in->spec();
    read_wrap_modes(spec, options.default_wrap, info);
    info.wrap_s = as.wrap_s.value_or(info.wrap_s);
    info.wrap_t = as.wrap_t.value_or(info.wrap_t);
    wraps_given_ = as.wrap_s || as.wrap_t;
    int levels = 1;
    while (in->seek_subimage(subimage_, levels)) ++levels;
    // Stored levels: tiled, and every level MipPyramid's size, down to 1×1.
    bool stored =
        spec.tile_width > 0 && spec.nchannels >= 1 && spec.nchannels <= MipPyramid::kMaxChannels;
    for (int l = 0; stored && l < levels; ++l) {
        stored = in->seek_subimage(subimage_, l) &&
                 in->spec().width == std::max(1, spec.width >> l) &&
                 in->spec().height == std::max(1, spec.height >> l);
    }
    stored = stored && std::max(spec.width >> (levels - 1), spec.height >> (levels - 1)) == 1;
    if (stored) {
        open_stored(name, std::move(in), options);
        return;
    }
    in.reset();
    if (subimage_ != 0) {
        error = detail::read_error(name, "subimage " + std::to_string(subimage_) +
                                             " is not a tiled MIP pyramid (other subimages are "
                                             "read only from tiled MIP-mapped files)");
        return;
    }
    // A pyramid built in an earlier run (or by another system) is opened, not built again.
    const fs::path cached =
        options.cache_dir.empty()
            ? fs::path()
            : cached_pyramid_file(name, options, info.wrap_s, info.wrap_t, "texture");
    std::error_code ec;
    if (!cached.empty() && fs::exists(cached, ec)) {
        open_stored(cached.string(), options);
        return;
    }
    ImageLoadOptions load;
    load.encoding = options.color;
    Result<Image> image = load_image(name, load);
    if (!image) {
        error = image.error();
        return;
    }
    if (image->empty() || image->channels > MipPyramid::kMaxChannels) {
        error = detail::read_error(
            name, std::to_string(image->channels) + " channels of " + std::to_string(image->width) +
                      "×" + std::to_string(image->height) + " texels (1 to " +
                      std::to_string(MipPyramid::kMaxChannels) + " channels can be filtered)");
        return;
    }
    MipPyramidOptions pyramid_options;
    pyramid_options.wrap_s = info.wrap_s;
    pyramid_options.wrap_t = info.wrap_t;
    pyramid_options.downsample = options.downsample;
    if (!cached.empty()) {
        Status saved = save_built_levels(*image, pyramid_options, options.tile_size, cached);
        if (saved) {
            image.value() = Image();  // freed before the file is opened
            open_stored(cached.string(), options);
            return;
        }
        if (!fall_back_to_memory) {
            error =
                Error{"cannot cache the MIP levels of '" + name + "': " + saved.error().message};
            return;
        }
        warning = Error{"texture system: cannot cache the MIP levels of '" + name +
                        "' (held in memory instead): " + saved.error().message};
    }
    MipPyramid built = MipPyramid::build(*image, pyramid_options);
    info = {built.width(0), built.height(0), built.channels(), built.level_count(),
            false,          info.wrap_s,     info.wrap_t};
    pyramid = std::make_shared<const MipPyramid>(std::move(built));
}

void TextureHandle::open_stored(const std::string& file, const TextureSystemOptions& options) {
    Result<std::unique_ptr<OIIO::ImageInput>> opened = detail::open_image_input(file);
    if (!opened) {
        error = opened.error();
        return;
    }
    open_stored(file, std::move(*opened), options);
}

void TextureHandle::open_stored(const std::string& file, std::unique_ptr<OIIO::ImageInput> input,
                                const TextureSystemOptions& options) {
    input_ = std::move(input);
    // A tile is one read on the calling thread, as OpenImageIO's image cache reads them: the
    // texture system is called from the host's threads already, and a decoder that hands each
    // tile to its own pool (OpenEXR's) only adds hand-offs and threads competing with them.
    input_->threads(1);
    if (!input_->seek_subimage(subimage_, 0)) {
        error = detail::read_error(file, "part " + std::to_string(subimage_) + " is missing");
        return;
    }
    const OIIO::ImageSpec& spec = input_->spec();
    // The wrap modes open() chose (the source's for a cached file, or the ones asked for); a part
    // of an environment pyramid file is given its own by open_part().
    const WrapMode wrap_s = info.wrap_s, wrap_t = info.wrap_t;
    read_wrap_modes(spec, options.default_wrap, info);
    if (file != name || wraps_given_) info.wrap_s = wrap_s, info.wrap_t = wrap_t;
    info.width = spec.width;
    info.height = spec.height;
    info.channels = spec.nchannels;
    info.tiled = true;
    file_tile_width_ = spec.tile_width;
    file_tile_height_ = spec.tile_height;
    alpha_ = spec.nchannels == 2 || spec.nchannels == 4 ? spec.nchannels - 1 : -1;
    srgb_ = detail::decodes_srgb(options.color, spec);
    slope_offset = detail::slope_offset(spec);
    std::vector<int> widths, heights;
    for (int w = spec.width, h = spec.height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
        widths.push_back(w);
        heights.push_back(h);
        if (w == 1 && h == 1) break;
    }
    info.levels = static_cast<int>(widths.size());
    if (std::string_view(input_->format_name()) == "openexr") {
        exr_tiles_ = texsys::ExrTiles::open(file, subimage_, spec.channelnames);
        if (exr_tiles_ && (exr_tiles_->tile_width() != file_tile_width_ ||
                           exr_tiles_->tile_height() != file_tile_height_))
            exr_tiles_.reset();
    }
    std::vector<Vec2> variances = stored_prefilter_variances(spec, widths.size());
    shape = detail::TiledShape(std::move(widths), std::move(heights), spec.nchannels,
                               std::countr_zero(static_cast<unsigned>(options.tile_size)),
                               info.wrap_s, info.wrap_t, std::move(variances));
}

void TextureHandle::open_part(int part, const detail::TiledShape& part_shape,
                              const TextureSystemOptions& options) {
    subimage_ = part;
    open_stored(name, options);
    if (error) return;
    shape = part_shape;
    info.wrap_s = part_shape.wrap_s;
    info.wrap_t = part_shape.wrap_t;
}

std::size_t TextureHandle::tile_floats(int l, int tx, int ty) const {
    const int size = 1 << shape.tile_log2;
    const int w = std::min(size, shape.levels[l].width - tx * size);
    const int h = std::min(size, shape.levels[l].height - ty * size);
    return static_cast<std::size_t>(w) * h * texel_stride(shape.channels);
}

void TextureHandle::read_tile(int l, int tx, int ty, float* texels) {
    const int size = 1 << shape.tile_log2, channels = shape.channels;
    const int stride = texel_stride(channels);
    const int x0 = tx * size, y0 = ty * size;
    const int level_width = shape.levels[l].width, level_height = shape.levels[l].height;
    const int w = std::min(size, level_width - x0), h = std::min(size, level_height - y0);
    // The file's tiles that cover this one (OpenImageIO reads whole tiles).
    const int xb = x0 / file_tile_width_ * file_tile_width_;
    const int yb = y0 / file_tile_height_ * file_tile_height_;
    const int xe = std::min(level_width,
                            (x0 + w + file_tile_width_ - 1) / file_tile_width_ * file_tile_width_);
    const int ye = std::min(
        level_height, (y0 + h + file_tile_height_ - 1) / file_tile_height_ * file_tile_height_);
    // Read into the thread's buffer, kept from tile to tile: a tile's read, in a cache smaller than
    // the frame's tiles, is otherwise an allocation and its first touch (page faults) each time.
    thread_local std::vector<float> read;
    const std::size_t floats = static_cast<std::size_t>(xe - xb) * (ye - yb) * channels;
    if (read.size() < floats) read.resize(floats);
    bool ok;
    std::string why;
    if (exr_tiles_) {
        ok = exr_tiles_->read(l, xb, xe, yb, ye, read.data(), why);
    } else {
        std::lock_guard lock(read_mutex_);
        ok = input_->read_tiles(subimage_, l, xb, xe, yb, ye, 0, 1, 0, channels,
                                OIIO::TypeDesc::FLOAT, read.data());
        if (!ok) why = input_->geterror();
    }
    if (!ok) {
        std::fill_n(texels, static_cast<std::size_t>(w) * h * stride, 0.0f);
        fail_read((subimage_ > 0 ? "part " + std::to_string(subimage_) + " " : std::string()) +
                  "MIP level " + std::to_string(l) + " tile (" + std::to_string(tx) + ", " +
                  std::to_string(ty) + "): " + why);
        return;
    }
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float* from =
                &read[(static_cast<std::size_t>(y0 + y - yb) * (xe - xb) + (x0 + x - xb)) *
                      channels];
            float* to = &texels[(static_cast<std::size_t>(y) * w + x) * stride];
            for (int c = 0; c < channels; ++c) {
                const float v = srgb_ && c != alpha_ ? srgb_to_linear(from[c]) : from[c];
                to[c] = std::isfinite(v) ? v : 0.0f;  // as the filters' no-NaN promise needs
            }
            std::fill(to + channels, to + stride, 0.0f);  // the padding
        }
    }
}

Result<MipPyramid> TextureHandle::read_whole() {
    const int size = 1 << shape.tile_log2, channels = shape.channels;
    const int stride = texel_stride(channels);
    std::vector<Image> levels;
    std::vector<float> tile(static_cast<std::size_t>(size) * size * stride);
    for (int l = 0; l < info.levels; ++l) {
        const int width = shape.levels[l].width, height = shape.levels[l].height;
        Image& level = levels.emplace_back(width, height, channels);
        for (int ty = 0; ty * size < height; ++ty) {
            for (int tx = 0; tx * size < width; ++tx) {
                read_tile(l, tx, ty, tile.data());
                const int w = std::min(size, width - tx * size);
                const int h = std::min(size, height - ty * size);
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x)
                        std::copy_n(&tile[(static_cast<std::size_t>(y) * w + x) * stride], channels,
                                    level.at(tx * size + x, ty * size + y));
            }
        }
    }
    if (read_failed) {
        std::lock_guard lock(read_error_mutex);
        return *read_error;
    }
    MipPyramidOptions options;
    options.wrap_s = info.wrap_s;
    options.wrap_t = info.wrap_t;
    return MipPyramid::from_levels(levels, options);
}

void TextureHandle::fail_read(const std::string& why) {
    std::lock_guard lock(read_error_mutex);
    if (!read_error) read_error = detail::read_error(name, why);
    read_failed = true;
}

}  // namespace footprint
