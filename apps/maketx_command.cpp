#include "maketx_command.h"

#include <bit>
#include <cstdio>
#include <optional>
#include <vector>

#include "image/image_io.h"

namespace footprint {

namespace {

int fail(const std::string& message) {
    std::fprintf(stderr, "footprint: %s\n", message.c_str());
    return 1;
}

// "repeat" or "repeat,clamp" as (s, t).
struct WrapModes {
    WrapMode s, t;
};
std::optional<WrapModes> parse_wraps(const std::string& text) {
    const std::size_t comma = text.find(',');
    const std::optional<WrapMode> s = parse_wrap_mode(text.substr(0, comma));
    const std::optional<WrapMode> t =
        comma == std::string::npos ? s : parse_wrap_mode(text.substr(comma + 1));
    if (!s || !t) return std::nullopt;
    return WrapModes{*s, *t};
}
}  // namespace

int run_maketx_command(const MaketxCommandOptions& options) {
    const std::optional<WrapModes> wraps = parse_wraps(options.wrap);
    if (!wraps)
        return fail("--wrap '" + options.wrap +
                    "': expected repeat, clamp or mirror, or two of them as S,T");
    if (options.tile_size < 16 || options.tile_size > 1024 ||
        !std::has_single_bit(static_cast<unsigned>(options.tile_size)))
        return fail("--tile-size " + std::to_string(options.tile_size) +
                    ": expected a power of two from 16 to 1024");
    if (options.output.extension() != ".exr")
        return fail("cannot write '" + options.output.string() +
                    "': maketx writes tiled MIP-mapped OpenEXR files (.exr)");
    Result<Image> image = load_image(options.input);
    if (!image) return fail(image.error().message);

    MipPyramidOptions pyramid_options;
    pyramid_options.wrap_s = wraps->s;
    pyramid_options.wrap_t = wraps->t;
    pyramid_options.downsample = options.downsample;
    const MipPyramid pyramid = MipPyramid::build(*image, pyramid_options);
    std::vector<Image> levels;
    for (int l = 0; l < pyramid.level_count(); ++l) levels.push_back(pyramid.level_image(l));
    LevelsSaveOptions save;
    save.wrap_modes = oiio_wrap_modes(wraps->s, wraps->t);
    save.tile_size = options.tile_size;
    if (Status saved = save_image_levels(levels, options.output, save); !saved)
        return fail(saved.error().message);
    std::fprintf(stderr, "footprint: wrote %s (%dx%d, %d levels, %d channel%s, tiles %d²)\n",
                 options.output.string().c_str(), image->width, image->height,
                 pyramid.level_count(), image->channels, image->channels == 1 ? "" : "s",
                 options.tile_size);
    return 0;
}

}  // namespace footprint
