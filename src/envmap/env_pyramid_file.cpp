#include "envmap/env_pyramid_file.h"

#include <OpenImageIO/imageio.h>

#include <string>
#include <vector>

#include "envmap/tiled_environment.h"
#include "image/image_input.h"
#include "image/image_io.h"

namespace footprint {

namespace {

constexpr const char* kLayoutAttribute = "footprint:environment";

Error cannot_read(const std::filesystem::path& file, const std::string& why) {
    return Error{"cannot read '" + file.string() + "': " + why};
}

// An environment pyramid file opened, and its layout; an Error naming it where it cannot be opened
// or is not one.
struct OpenedPyramid {
    std::unique_ptr<OIIO::ImageInput> in;
    EnvLayout layout;
};
Result<OpenedPyramid> open_pyramid(const std::filesystem::path& file) {
    Result<std::unique_ptr<OIIO::ImageInput>> opened = detail::open_image_input(file);
    if (!opened) return opened.error();
    std::unique_ptr<OIIO::ImageInput> in = std::move(*opened);
    const std::optional<EnvLayout> layout =
        parse_env_layout(in->spec().get_string_attribute(kLayoutAttribute));
    if (!layout)
        return cannot_read(file,
                           "it is not an environment pyramid (footprint maketx --env writes them)");
    return OpenedPyramid{std::move(in), *layout};
}

// A pyramid's levels as images.
std::vector<Image> levels_of(const MipPyramid& pyramid) {
    std::vector<Image> levels;
    for (int l = 0; l < pyramid.level_count(); ++l) levels.push_back(pyramid.level_image(l));
    return levels;
}

// Every MIP level of the part the input is at, read as floats.
Result<std::vector<Image>> read_part(OIIO::ImageInput& in, int part) {
    std::vector<Image> levels;
    for (int l = 0; in.seek_subimage(part, l); ++l) {
        const OIIO::ImageSpec& spec = in.spec();
        Image& level = levels.emplace_back(spec.width, spec.height, spec.nchannels);
        if (!in.read_image(part, l, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, level.pixels.data()))
            return Error{"part " + std::to_string(part) + " MIP level " + std::to_string(l) +
                         ": the file is truncated or corrupt (" + in.geterror() + ")"};
    }
    (void)in.geterror();  // the failed seek past the last level
    return levels;
}

}  // namespace

Status save_environment_pyramid(const EnvironmentMap& map, const std::filesystem::path& file,
                                int tile_size) {
    const std::string layout = env_layout_name(map.layout());
    std::vector<LevelChain> parts;
    for (int f = 0; f < map.face_count(); ++f)
        parts.push_back({layout + " face " + std::to_string(f), levels_of(map.face(f))});
    for (int pole = 0; pole < 2 && map.polar_cap(pole); ++pole)
        parts.push_back({layout + (pole == 0 ? " polar cap +Y" : " polar cap -Y"),
                         levels_of(*map.polar_cap(pole))});
    LevelsSaveOptions options;
    options.tile_size = tile_size;
    options.string_attributes.push_back({kLayoutAttribute, layout});
    return save_image_level_chains(parts, file, options);
}

Result<EnvironmentMap> load_environment_pyramid(const std::filesystem::path& file) {
    Result<OpenedPyramid> opened = open_pyramid(file);
    if (!opened) return opened.error();
    OIIO::ImageInput* in = opened->in.get();
    const EnvLayout layout = opened->layout;
    std::vector<std::vector<Image>> parts;
    while (in->seek_subimage(static_cast<int>(parts.size()), 0)) {
        Result<std::vector<Image>> part = read_part(*in, static_cast<int>(parts.size()));
        if (!part) return cannot_read(file, part.error().message);
        parts.push_back(std::move(*part));
    }
    (void)in->geterror();
    const auto faces = static_cast<std::size_t>(face_count(layout));
    if (parts.size() < faces) return cannot_read(file, "parts are missing");
    const std::vector<std::vector<Image>> caps(parts.begin() + faces, parts.end());
    parts.resize(faces);
    Result<EnvironmentMap> map = EnvironmentMap::from_face_levels(layout, parts, caps);
    if (!map) return cannot_read(file, map.error().message);
    return map;
}

namespace detail {

namespace {

// The shape of part `part`'s levels, as read from its headers; an error where it is not a tiled
// MIP chain of MipPyramid's level sizes down to 1×1 and 1 to 8 channels.
Result<TiledShape> part_shape(OIIO::ImageInput& in, int part, int tile_log2, WrapMode wrap_s,
                              WrapMode wrap_t) {
    const std::string what = "part " + std::to_string(part);
    if (!in.seek_subimage(part, 0)) return Error{what + " is missing"};
    const OIIO::ImageSpec spec = in.spec();
    if (spec.tile_width <= 0) return Error{what + " is not tiled"};
    if (spec.nchannels < 1 || spec.nchannels > MipPyramid::kMaxChannels)
        return Error{what + " has " + std::to_string(spec.nchannels) + " channels"};
    std::vector<int> widths, heights;
    for (int w = spec.width, h = spec.height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
        const int l = static_cast<int>(widths.size());
        if (!in.seek_subimage(part, l) || in.spec().width != w || in.spec().height != h)
            return Error{what + " MIP level " + std::to_string(l) + " is missing or not " +
                         std::to_string(w) + "x" + std::to_string(h)};
        widths.push_back(w);
        heights.push_back(h);
        if (w == 1 && h == 1) break;
    }
    if (in.seek_subimage(part, static_cast<int>(widths.size())))
        return Error{what + " has levels below 1x1"};
    (void)in.geterror();
    return TiledShape(std::move(widths), std::move(heights), spec.nchannels, tile_log2, wrap_s,
                      wrap_t);
}

}  // namespace

Result<TiledEnvShape> environment_pyramid_shape(const std::filesystem::path& file, int tile_log2) {
    Result<OpenedPyramid> opened = open_pyramid(file);
    if (!opened) return opened.error();
    OIIO::ImageInput* in = opened->in.get();
    const EnvLayout layout = opened->layout;
    TiledEnvShape shape;
    shape.layout = layout;
    const int faces = face_count(layout);
    int parts = 0;
    while (in->seek_subimage(parts, 0)) ++parts;
    (void)in->geterror();
    shape.polar_caps = parts == faces + 2;
    if (parts < faces || (parts != faces && !(shape.polar_caps && layout == EnvLayout::latlong)))
        return cannot_read(file, std::to_string(parts) + " parts do not make a " +
                                     env_layout_name(layout) + " map");
    for (int p = 0; p < parts; ++p) {
        // As EnvironmentMap::from_face_levels() holds them.
        const bool seam = layout == EnvLayout::latlong && p < faces;
        Result<TiledShape> part = part_shape(
            *in, p, tile_log2, seam ? WrapMode::repeat : WrapMode::clamp, WrapMode::clamp);
        if (!part) return cannot_read(file, part.error().message);
        const MipPyramid::LevelView& level0 = part->levels[0];
        const MipPyramid::LevelView& first = p == 0 ? level0 : shape.parts[0].levels[0];
        const bool square = level0.width == level0.height;
        if (part->channels != (p == 0 ? part->channels : shape.parts[0].channels))
            return cannot_read(file, "part " + std::to_string(p) + " differs in channels");
        if (p < faces && (level0.width != first.width || level0.height != first.height ||
                          (layout != EnvLayout::latlong && !square)))
            return cannot_read(file, "face " + std::to_string(p) + " is not the size of face 0" +
                                         (layout != EnvLayout::latlong ? " or not square" : ""));
        if (p >= faces &&
            (!square || (p > faces && level0.width != shape.parts[faces].levels[0].width)))
            return cannot_read(file, "the polar caps are not square faces of one size");
        shape.parts.push_back(std::move(*part));
    }
    return shape;
}

}  // namespace detail

bool is_environment_pyramid_file(const std::filesystem::path& file) {
    Result<std::unique_ptr<OIIO::ImageInput>> in = detail::open_image_input(file);
    return in && (*in)->spec().find_attribute(kLayoutAttribute) != nullptr;
}

}  // namespace footprint
