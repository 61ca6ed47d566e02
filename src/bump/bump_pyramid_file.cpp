#include "bump/bump_pyramid_file.h"

#include <OpenImageIO/imageio.h>

#include <string>
#include <vector>

#include "bump/bump_pyramid_file_detail.h"
#include "image/image_input.h"
#include "image/image_io.h"

namespace footprint {

namespace {

constexpr const char* kOffsetAttribute = "footprint:slope_offset";
const std::vector<std::string> kChannelNames = {"mean.x", "mean.y", "square.xx", "square.xy",
                                                "square.yy"};

Error cannot_read(const std::filesystem::path& file, const std::string& why) {
    return Error{"cannot read '" + file.string() + "': " + why};
}

}  // namespace

std::optional<Vec2> detail::slope_offset(const OIIO::ImageSpec& spec) {
    const OIIO::ParamValue* p = spec.find_attribute(kOffsetAttribute);
    if (!p || p->type().basetype != OIIO::TypeDesc::FLOAT ||
        p->type().numelements() * p->type().aggregate != 2)
        return std::nullopt;
    const float* v = static_cast<const float*>(p->data());
    return Vec2{v[0], v[1]};
}

Status save_bump_pyramid(const BumpPyramid& pyramid, const std::filesystem::path& file,
                         int tile_size) {
    const MipPyramid& moments = pyramid.moments();
    std::vector<Image> levels;
    for (int l = 0; l < moments.level_count(); ++l) levels.push_back(moments.level_image(l));
    LevelsSaveOptions options;
    options.wrap_modes = oiio_wrap_modes(moments.wrap_s(), moments.wrap_t());
    options.tile_size = tile_size;
    options.channel_names = kChannelNames;
    const Vec2 offset = pyramid.slope_offset();
    options.float_attributes.push_back({kOffsetAttribute, {offset.x, offset.y}});
    return save_image_levels(levels, file, options);
}

Result<BumpPyramid> load_bump_pyramid(const std::filesystem::path& file) {
    Result<std::unique_ptr<OIIO::ImageInput>> opened = detail::open_image_input(file);
    if (!opened) return opened.error();
    std::unique_ptr<OIIO::ImageInput> in = std::move(*opened);
    const std::optional<Vec2> offset = detail::slope_offset(in->spec());
    if (!offset || in->spec().channelnames != kChannelNames)
        return cannot_read(file, "it is not a bump pyramid (footprint maketx --bump writes them)");
    const WrapModes wraps = parse_oiio_wrap_modes(in->spec().get_string_attribute("wrapmodes"));
    std::vector<Image> levels;
    for (int l = 0; in->seek_subimage(0, l); ++l) {
        const OIIO::ImageSpec& spec = in->spec();
        Image& level = levels.emplace_back(spec.width, spec.height, spec.nchannels);
        if (!in->read_image(0, l, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, level.pixels.data()))
            return cannot_read(file, "MIP level " + std::to_string(l) +
                                         ": the file is truncated or corrupt (" + in->geterror() +
                                         ")");
    }
    (void)in->geterror();  // the failed seek past the last level
    Result<BumpPyramid> pyramid = BumpPyramid::from_moment_levels(
        levels, *offset, wraps.s.value_or(WrapMode::repeat), wraps.t.value_or(WrapMode::repeat));
    if (!pyramid) return cannot_read(file, pyramid.error().message);
    return pyramid;
}

std::optional<Vec2> bump_pyramid_file_offset(const std::filesystem::path& file) {
    Result<std::unique_ptr<OIIO::ImageInput>> in = detail::open_image_input(file);
    if (!in) return std::nullopt;
    return detail::slope_offset((*in)->spec());
}

}  // namespace footprint
