#include "maketx_command.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <optional>
#include <vector>

#include "bump/bump_pyramid_file.h"
#include "command_util.h"
#include "envmap/env_image_io.h"
#include "envmap/env_pyramid_file.h"
#include "image/image_io.h"

namespace footprint {

namespace {

int make_bump_pyramid(const MaketxCommandOptions& options, WrapMode wrap_s, WrapMode wrap_t) {
    Result<Image> slopes =
        load_bump_slopes(options.input, options.height, options.clamp_invalid_normals);
    if (!slopes) return fail(slopes.error().message);
    BumpPyramidOptions pyramid_options;
    pyramid_options.wrap_s = wrap_s;
    pyramid_options.wrap_t = wrap_t;
    pyramid_options.downsample = options.downsample;
    Result<BumpPyramid> pyramid = BumpPyramid::build(*slopes, pyramid_options);
    if (!pyramid) return fail("'" + options.input.string() + "': " + pyramid.error().message);
    if (Status saved = save_bump_pyramid(*pyramid, options.output, options.tile_size); !saved)
        return fail(saved.error().message);
    if (!options.quiet)
        std::fprintf(stderr,
                     "footprint: wrote %s (%dx%d bump pyramid, %d levels, 5 moment channels, tiles "
                     "%d²)\n",
                     options.output.string().c_str(), slopes->width, slopes->height,
                     pyramid->level_count(), options.tile_size);
    return 0;
}

int make_environment_pyramid(const MaketxCommandOptions& options) {
    EnvImageOptions load;
    if (options.env != "auto") {
        const std::optional<EnvLayout> layout = parse_env_layout(options.env);
        if (!layout)
            return fail("--env '" + options.env +
                        "': expected auto, latlong, cube, sphere or paraboloid");
        load.layout = *layout;
    }
    Result<EnvironmentMap> map = load_environment({options.input}, load);
    if (!map) return fail(map.error().message);
    if (Status saved = save_environment_pyramid(*map, options.output, options.tile_size); !saved)
        return fail(saved.error().message);
    const MipPyramid& face = map->face(0);
    if (!options.quiet)
        std::fprintf(stderr,
                     "footprint: wrote %s (%s environment, %d face%s of %dx%d, %d levels%s, tiles "
                     "%d²)\n",
                     options.output.string().c_str(), env_layout_name(map->layout()),
                     map->face_count(), map->face_count() == 1 ? "" : "s", face.width(0),
                     face.height(0), face.level_count(), map->polar_cap(0) ? ", polar caps" : "",
                     options.tile_size);
    return 0;
}

}  // namespace

int run_maketx_command(const MaketxCommandOptions& options) {
    // The modes footprint filters with, by their names and OpenImageIO's ("periodic"). Not
    // OpenImageIO's "black": footprint reads a file that says it as clamp, but writing one would
    // promise borders footprint's filters do not make.
    const std::size_t comma = options.wrap.find(',');
    const std::string s_name = options.wrap.substr(0, comma);
    const std::string t_name = comma == std::string::npos ? s_name : options.wrap.substr(comma + 1);
    if (s_name == "black" || t_name == "black")
        return fail("--wrap '" + options.wrap +
                    "': footprint's filters have no black wrap (OpenImageIO's); expected repeat "
                    "(or periodic), clamp or mirror, or two of them as S,T");
    const WrapModes wraps{parse_wrap_mode(s_name), parse_wrap_mode(t_name)};
    if (!wraps.s || !wraps.t || std::count(options.wrap.begin(), options.wrap.end(), ',') > 1)
        return fail("--wrap '" + options.wrap +
                    "': expected repeat (or periodic), clamp or mirror, or two of them as S,T");
    if ((options.height || options.clamp_invalid_normals) && !options.bump)
        return fail(std::string(options.height ? "--height" : "--invalid-normals") +
                    " describes a bump map: give --bump too");
    if (options.tile_size < 16 || options.tile_size > 1024 ||
        !std::has_single_bit(static_cast<unsigned>(options.tile_size)))
        return fail("--tile-size " + std::to_string(options.tile_size) +
                    ": expected a power of two from 16 to 1024");
    if (options.output.extension() != ".exr")
        return fail("cannot write '" + options.output.string() +
                    "': maketx writes tiled MIP-mapped OpenEXR files (.exr)");
    if (options.bump && !options.env.empty()) return fail("--bump and --env: give one of them");
    if (options.bump) return make_bump_pyramid(options, *wraps.s, *wraps.t);
    if (!options.env.empty()) return make_environment_pyramid(options);
    Result<Image> image = load_image(options.input);
    if (!image) return fail(image.error().message);

    // Each level is written as soon as it is made, and dropped once the next is made from it: the
    // image and two levels in memory, not the pyramid and its copies (docs/performance.md,
    // "Building pyramids: memory").
    MipPyramidOptions pyramid_options;
    pyramid_options.wrap_s = *wraps.s;
    pyramid_options.wrap_t = *wraps.t;
    pyramid_options.downsample = options.downsample;
    LevelsSaveOptions save;
    save.wrap_modes = oiio_wrap_modes(*wraps.s, *wraps.t);
    save.tile_size = options.tile_size;
    Result<LevelsWriter> writer = LevelsWriter::open(options.output, save);
    if (!writer) return fail(writer.error().message);
    int level_count = 0;
    Status saved = for_each_mip_level(*image, pyramid_options, [&](const Image& level) {
        ++level_count;
        return writer->write(level);
    });
    if (saved) saved = writer->finish();
    if (!saved) return fail(saved.error().message);
    if (!options.quiet)
        std::fprintf(stderr, "footprint: wrote %s (%dx%d, %d levels, %d channel%s, tiles %d²)\n",
                     options.output.string().c_str(), image->width, image->height, level_count,
                     image->channels, image->channels == 1 ? "" : "s", options.tile_size);
    return 0;
}

}  // namespace footprint
