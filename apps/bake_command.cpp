#include "bake_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <system_error>
#include <vector>

#include "bump/bump_pyramid.h"
#include "bump/slope_map.h"
#include "cli_options.h"
#include "command_util.h"
#include "envmap/env_convert.h"
#include "envmap/env_image_io.h"
#include "envmap/env_pyramid_file.h"
#include "ktx_writer.h"

namespace footprint {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kKinds[] = {"color", "bump", "env"};
constexpr IntRange kCubeSizes{1, 16384};
constexpr int kExrTileSize = 64;  // the texture system's default tiles, as maketx's default

// The file's first row is the image's top row (t = 0 in footprint's (s, t), docs/method.md).
constexpr const char* kOrientationKey = "KTXorientation";
constexpr const char* kTopRowFirst = "S=r,T=d";

// What a bake wrote, for the "wrote" line.
struct Baked {
    std::string files, what;
    int width = 0, height = 0, levels = 0;
    std::string format;  // "RGBA16F", "3 channels, 32-bit float", …
};

// A level as the RGBA texels a KTX file holds: grey in R, G and B; alpha 1 where there is none.
Image to_rgba(const Image& image) {
    Image rgba(image.width, image.height, 4, 1.0f);
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        const float* in = &image.pixels[i * image.channels];
        float* out = &rgba.pixels[i * 4];
        if (image.channels <= 2) {
            out[0] = out[1] = out[2] = in[0];
            if (image.channels == 2) out[3] = in[1];
        } else {
            std::copy_n(in, image.channels, out);
        }
    }
    return rgba;
}

std::string format_name(bool float32) {
    return float32 ? "RGBA32F" : "RGBA16F";
}

// Where a KTX encoding fails, the file it was for.
Result<std::string> encode(const KtxTexture& texture, const fs::path& file) {
    Result<std::string> bytes = encode_ktx(texture);
    if (!bytes)
        return Error{"cannot write " + quoted(file) + ": " + bytes.error().message +
                     (texture.type == KtxPixelType::half_float &&
                              bytes.error().message.find("half floats") != std::string::npos
                          ? " (--float32 writes RGBA32F)"
                          : "")};
    return bytes;
}

// `texture` as the KTX file `file`, written completely or not at all.
Status write_ktx(const KtxTexture& texture, const fs::path& file) {
    Result<std::string> bytes = encode(texture, file);
    if (!bytes) return bytes.error();
    return write_file_atomically(file, *bytes);
}

// Why `file` cannot be written (checked before any work), or nullopt.
std::optional<std::string> output_problem(const fs::path& file) {
    const std::string extension = file.extension().string();
    if (file.filename().empty() || (extension != ".ktx" && extension != ".exr"))
        return "cannot write " + quoted(file) +
               ": footprint bake writes KTX 1 (.ktx) or OpenEXR (.exr) files";
    return output_location_problem(file);
}

bool is_ktx(const fs::path& file) {
    return file.extension() == ".ktx";
}

Result<Baked> bake_color(const BakeCommandOptions& options, WrapMode wrap_s, WrapMode wrap_t) {
    ImageLoadOptions load;
    load.encoding = options.encoding;
    Result<Image> image = load_image(options.input, load);
    if (!image) return image.error();
    // The pyramid the texture lookups filter (texture/mip_pyramid.h), level by level.
    MipPyramidOptions pyramid_options;
    pyramid_options.wrap_s = wrap_s;
    pyramid_options.wrap_t = wrap_t;
    pyramid_options.downsample = options.downsample.value_or(DownsampleFilter::box);
    const MipPyramid pyramid = MipPyramid::build(*image, pyramid_options);
    std::vector<Image> levels;
    for (int l = 0; l < pyramid.level_count(); ++l) levels.push_back(pyramid.level_image(l));

    Baked baked{options.output.string(), "color", image->width, image->height,
                pyramid.level_count(),   ""};
    if (!is_ktx(options.output)) {
        LevelsSaveOptions save;
        save.wrap_modes = oiio_wrap_modes(wrap_s, wrap_t);
        save.tile_size = kExrTileSize;
        if (Status saved = save_image_levels(levels, options.output, save); !saved)
            return saved.error();
        baked.format = std::to_string(image->channels) + " channel" +
                       (image->channels == 1 ? "" : "s") + ", 32-bit float";
        return baked;
    }
    KtxTexture ktx;
    ktx.type = options.float32 ? KtxPixelType::float32 : KtxPixelType::half_float;
    for (const Image& level : levels) ktx.levels.push_back({to_rgba(level)});
    ktx.key_values = {
        {kOrientationKey, kTopRowFirst},
        {"footprint", "color: MIP pyramid, linear light (" + std::string(to_string(wrap_s)) + "," +
                          to_string(wrap_t) + " wrap)"}};
    if (Status written = write_ktx(ktx, options.output); !written) return written.error();
    baked.format = format_name(options.float32);
    return baked;
}

// The offset as text, exactly (9 significant digits give a float back bit for bit).
std::string offset_text(Vec2 offset) {
    char text[64];
    std::snprintf(text, sizeof text, "%.9g %.9g", offset.x, offset.y);
    return text;
}

Result<Baked> bake_bump(const BakeCommandOptions& options, WrapMode wrap_s, WrapMode wrap_t) {
    Result<Image> slopes =
        load_bump_slopes(options.input, options.height, options.clamp_invalid_normals);
    if (!slopes) return slopes.error();
    BumpPyramidOptions pyramid_options;
    pyramid_options.wrap_s = wrap_s;
    pyramid_options.wrap_t = wrap_t;
    pyramid_options.downsample = options.downsample.value_or(DownsampleFilter::box);
    Result<BumpPyramid> pyramid = BumpPyramid::build(*slopes, pyramid_options);
    if (!pyramid) return Error{quoted(options.input) + ": " + pyramid.error().message};
    // The five moment channels (μ'1, μ'2, M2'11, M2'12, M2'22) of each level (docs/method.md §5.3:
    // filtering the first and second moments linearly is the recursion), split into two RGBA maps.
    const MipPyramid& moments = pyramid->moments();
    std::vector<Image> a_levels, b_levels;
    for (int l = 0; l < moments.level_count(); ++l) {
        const Image level = moments.level_image(l);
        Image& a = a_levels.emplace_back(level.width, level.height, 4);
        Image& b = b_levels.emplace_back(level.width, level.height, 4);
        for (std::size_t i = 0; i < level.pixel_count(); ++i) {
            std::copy_n(&level.pixels[i * 5], 4, &a.pixels[i * 4]);
            const float rest[4] = {level.pixels[i * 5 + 4], 0, 0, 1};
            std::copy_n(rest, 4, &b.pixels[i * 4]);
        }
    }
    const std::string offset = offset_text(pyramid->slope_offset());
    Baked baked{"", "bump moments", slopes->width, slopes->height, moments.level_count(), ""};
    if (!is_ktx(options.output)) {
        std::vector<Image> levels;
        for (std::size_t l = 0; l < a_levels.size(); ++l) {
            Image& both = levels.emplace_back(a_levels[l].width, a_levels[l].height, 8);
            for (std::size_t i = 0; i < both.pixel_count(); ++i) {
                std::copy_n(&a_levels[l].pixels[i * 4], 4, &both.pixels[i * 8]);
                std::copy_n(&b_levels[l].pixels[i * 4], 4, &both.pixels[i * 8 + 4]);
            }
        }
        LevelsSaveOptions save;
        save.wrap_modes = oiio_wrap_modes(wrap_s, wrap_t);
        save.tile_size = kExrTileSize;
        save.channel_names = {"a.R", "a.G", "a.B", "a.A", "b.R", "b.G", "b.B", "b.A"};
        const Vec2 o = pyramid->slope_offset();
        save.float_attributes = {{"footprint:bake_slope_offset", {o.x, o.y}}};
        save.string_attributes = {{"footprint:bake", "bump"}};
        if (Status saved = save_image_levels(levels, options.output, save); !saved)
            return saved.error();
        baked.files = options.output.string();
        baked.format = "layers a and b, 32-bit float";
        return baked;
    }
    RunOutputs outputs;  // both files, or neither
    for (const char map : {'a', 'b'}) {
        const fs::path file = bump_ktx_file(options.output, map);
        KtxTexture ktx;
        ktx.type = options.float32 ? KtxPixelType::float32 : KtxPixelType::half_float;
        for (const Image& level : map == 'a' ? a_levels : b_levels) ktx.levels.push_back({level});
        ktx.key_values = {
            {kOrientationKey, kTopRowFirst},
            {"footprint", map == 'a' ? "bump moments A = (mean.x, mean.y, square.xx, square.xy)"
                                     : "bump moments B = (square.yy, 0, 0, 1)"},
            {"footprint:slope_offset", offset}};
        Result<std::string> bytes = encode(ktx, file);
        if (!bytes) return bytes.error();
        if (Status written = outputs.write(file, *bytes); !written) return written.error();
        baked.files += (baked.files.empty() ? "" : " and ") + file.string();
    }
    outputs.keep();
    baked.format = format_name(options.float32);
    return baked;
}

Result<Baked> bake_env(const BakeCommandOptions& options) {
    EnvImageOptions load;
    load.image.encoding = options.encoding;
    Result<EnvImages> images = load_environment_images({options.input}, load);
    if (!images) return images.error();
    Result<EnvironmentMap> source = make_environment_map(*images);
    if (!source) return Error{quoted(options.input) + ": " + source.error().message};
    // A cube of the size asked for stays as it is; anything else is resampled into one, each
    // texel filtered over its footprint (envmap/env_convert.h).
    const bool keep = source->layout() == EnvLayout::cube &&
                      (!options.size || *options.size == source->face(0).width(0));
    EnvironmentMap cube = std::move(*source);
    if (!keep) {
        EnvConvertOptions convert;
        convert.size = options.size.value_or(0);
        Result<EnvImages> faces = convert_environment(cube, EnvLayout::cube, convert);
        if (!faces) return Error{quoted(options.input) + ": " + faces.error().message};
        Result<EnvironmentMap> converted = make_environment_map(*faces);
        if (!converted) return Error{quoted(options.input) + ": " + converted.error().message};
        cube = std::move(*converted);
    }
    const MipPyramid& face0 = cube.face(0);
    Baked baked{options.output.string(), "env cube map",      face0.width(0),
                face0.height(0),         face0.level_count(), ""};
    if (!is_ktx(options.output)) {
        if (Status saved = save_environment_pyramid(cube, options.output, kExrTileSize); !saved)
            return saved.error();
        baked.format = "6 parts, 32-bit float";
        return baked;
    }
    KtxTexture ktx;
    ktx.type = options.float32 ? KtxPixelType::float32 : KtxPixelType::half_float;
    for (int l = 0; l < face0.level_count(); ++l) {
        std::vector<Image>& faces = ktx.levels.emplace_back();
        for (int f = 0; f < 6; ++f) faces.push_back(to_rgba(cube.face(f).level_image(l)));
    }
    // No KTXorientation: a cube map's faces are oriented by GL's cube map rule itself.
    ktx.key_values = {{"footprint",
                       "env: cube map, faces +X -X +Y -Y +Z -Z as OpenGL's cube map "
                       "rule reads them, linear light"}};
    if (Status written = write_ktx(ktx, options.output); !written) return written.error();
    baked.format = format_name(options.float32);
    return baked;
}

}  // namespace

fs::path bump_ktx_file(const fs::path& output, char map) {
    fs::path file = output;
    file.replace_filename(output.stem().string() + "_" + map + output.extension().string());
    return file;
}

int run_bake_command(const BakeCommandOptions& options) {
    if (const auto problem = unknown_value_problem(options.kind, kKinds))
        return fail("kind: " + *problem);
    const bool color = options.kind == "color", bump = options.kind == "bump",
               env = options.kind == "env";
    // The options a kind does not take are refused, not ignored.
    if (!bump && (options.height || options.clamp_invalid_normals))
        return fail(std::string(options.height ? "--height" : "--invalid-normals") +
                    " describes a bump map: it applies to footprint bake bump only");
    if (!color && !env && options.encoding != ColorEncoding::automatic)
        return fail(std::string(options.encoding == ColorEncoding::srgb ? "--srgb" : "--linear") +
                    ": a bump map's values are data, never sRGB-decoded");
    if (env && (options.wrap || options.downsample))
        return fail(std::string(options.wrap ? "--wrap" : "--downsample") +
                    ": a cube map's faces are clamped and box-filtered (footprint bake env)");
    if (!env && options.size) return fail("--size applies to footprint bake env only");
    if (options.size)
        if (const auto problem = range_problem("--size", *options.size, kCubeSizes))
            return fail(*problem);
    const std::string wrap = options.wrap.value_or("repeat");
    const std::size_t comma = wrap.find(',');
    const WrapModes wraps{parse_wrap_mode(wrap.substr(0, comma)),
                          parse_wrap_mode(comma == std::string::npos ? wrap.substr(0, comma)
                                                                     : wrap.substr(comma + 1))};
    if (!wraps.s || !wraps.t || std::count(wrap.begin(), wrap.end(), ',') > 1)
        return fail("--wrap '" + wrap +
                    "': expected repeat (or periodic), clamp or mirror, or two of them as S,T");

    std::vector<fs::path> files{options.output};
    if (bump && is_ktx(options.output))
        files = {bump_ktx_file(options.output, 'a'), bump_ktx_file(options.output, 'b')};
    if (const auto problem = output_problem(options.output)) return fail(*problem);
    for (const fs::path& file : files) {
        std::error_code ec;
        if (fs::is_directory(file, ec))
            return fail("cannot write " + quoted(file) + ": it is a directory");
        if (fs::equivalent(file, options.input, ec))
            return fail("cannot write " + quoted(file) + ": it is the input");
    }

    const auto start = std::chrono::steady_clock::now();
    Result<Baked> baked = color  ? bake_color(options, *wraps.s, *wraps.t)
                          : bump ? bake_bump(options, *wraps.s, *wraps.t)
                                 : bake_env(options);
    if (!baked) return fail(baked.error().message);
    if (!options.quiet)
        std::fprintf(
            stderr, "footprint: wrote %s (%s, %dx%d, %d levels, %s, %.2f s)\n",
            baked->files.c_str(), baked->what.c_str(), baked->width, baked->height, baked->levels,
            baked->format.c_str(),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return 0;
}

}  // namespace footprint
