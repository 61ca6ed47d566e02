// fuzz/fuzz_image_load.cpp — image files through our code around OpenImageIO: load_image,
// load_image_levels, the environment loaders with layout detection (envmap/env_image_io.h) and the
// environment pyramid file (envmap/env_pyramid_file.h).
//
// Feeds: the bytes after the first as a file whose extension the first byte picks (.png .jpg .exr
// .hdr .tif), read with the colour and non-finite policies and the cube arrangement the first
// byte's upper bits pick.
// Asserts: each load either fails with a message naming the file or gives images whose sizes,
// channel counts (1–4) and texel counts agree; with NonFinitePolicy::refuse and ::repair every
// texel is finite; an environment has its layout's face count of square (cube, sphere,
// paraboloid) or 2:1-ish (lat-long) faces of one channel count.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "envmap/env_image_io.h"
#include "envmap/env_pyramid_file.h"
#include "fuzz_input.h"
#include "image/image_io.h"

namespace {

using namespace footprint;

void require_named_error(const Error& error, const std::filesystem::path& file) {
    fuzz::require(error.message.find(file.filename().string()) != std::string::npos,
                  "a load error names the file");
}

void require_sound(const Image& image, NonFinitePolicy policy) {
    fuzz::require(image.width >= 1 && image.height >= 1, "an image has at least one texel");
    fuzz::require(image.channels >= 1 && image.channels <= 4, "an image has 1 to 4 channels");
    fuzz::require(image.pixels.size() == image.pixel_count() * image.channels,
                  "an image holds width × height × channels values");
    if (policy != NonFinitePolicy::keep)
        for (float v : image.pixels) fuzz::require(std::isfinite(v), "refused or repaired: finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    static constexpr std::array kExtensions{".png", ".jpg", ".exr", ".hdr", ".tif"};
    const std::uint8_t choice = data[0];
    const std::filesystem::path file =
        fuzz::write_scratch(std::string("image") + kExtensions[choice % kExtensions.size()],
                            std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));

    ImageLoadOptions options;
    options.encoding = static_cast<ColorEncoding>((choice >> 3) % 3);
    options.non_finite = static_cast<NonFinitePolicy>((choice >> 5) % 3);
    if (const Result<Image> image = load_image(file, options); image.ok())
        require_sound(*image, options.non_finite);
    else
        require_named_error(image.error(), file);

    if (const Result<std::vector<Image>> levels = load_image_levels(file, options); levels.ok()) {
        fuzz::require(!levels->empty(), "a file has at least one level");
        for (const Image& level : *levels) require_sound(level, options.non_finite);
    } else {
        require_named_error(levels.error(), file);
    }

    EnvImageOptions env_options;
    env_options.image = options;
    env_options.cube_arrangement = static_cast<CubeArrangement>((choice >> 5) % 8);
    if (const Result<EnvImages> env = load_environment_images({file}, env_options); env.ok()) {
        fuzz::require(static_cast<int>(env->faces.size()) == face_count(env->layout),
                      "an environment has its layout's face count");
        for (const Image& face : env->faces) {
            require_sound(face, options.non_finite);
            fuzz::require(face.channels == env->faces[0].channels, "faces of one channel count");
            if (env->layout != EnvLayout::latlong)
                fuzz::require(face.width == face.height,
                              "cube, sphere, paraboloid faces are square");
        }
        if (const Result<EnvironmentMap> map = make_environment_map(*env); map.ok())
            fuzz::require(map->face_count() == face_count(env->layout), "the map has the faces");
    } else {
        require_named_error(env.error(), file);
    }

    if (const Result<EnvironmentMap> map = load_environment_pyramid(file); map.ok())
        fuzz::require(map->face_count() == face_count(map->layout()), "a pyramid has its faces");
    else
        require_named_error(map.error(), file);
    return 0;
}
