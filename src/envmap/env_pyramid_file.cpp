#include "envmap/env_pyramid_file.h"

#include <OpenImageIO/imageio.h>

#include <string>
#include <vector>

#include "image/image_io.h"

namespace footprint {

namespace {

constexpr const char* kLayoutAttribute = "footprint:environment";

Error cannot_read(const std::filesystem::path& file, const std::string& why) {
    return Error{"cannot read '" + file.string() + "': " + why};
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
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(file.string());
    if (!in) {
        Result<Image> image = load_image(file);  // names the cause best (no such file, …)
        return image ? cannot_read(file, OIIO::geterror()) : image.error();
    }
    const std::optional<EnvLayout> layout =
        parse_env_layout(in->spec().get_string_attribute(kLayoutAttribute));
    if (!layout)
        return cannot_read(file,
                           "it is not an environment pyramid (footprint maketx --env writes them)");
    std::vector<std::vector<Image>> parts;
    while (in->seek_subimage(static_cast<int>(parts.size()), 0)) {
        Result<std::vector<Image>> part = read_part(*in, static_cast<int>(parts.size()));
        if (!part) return cannot_read(file, part.error().message);
        parts.push_back(std::move(*part));
    }
    (void)in->geterror();
    const auto faces = static_cast<std::size_t>(face_count(*layout));
    if (parts.size() < faces) return cannot_read(file, "parts are missing");
    const std::vector<std::vector<Image>> caps(parts.begin() + faces, parts.end());
    parts.resize(faces);
    Result<EnvironmentMap> map = EnvironmentMap::from_face_levels(*layout, parts, caps);
    if (!map) return cannot_read(file, map.error().message);
    return map;
}

bool is_environment_pyramid_file(const std::filesystem::path& file) {
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(file.string());
    if (!in) {
        (void)OIIO::geterror();
        return false;
    }
    return in->spec().find_attribute(kLayoutAttribute) != nullptr;
}

}  // namespace footprint
