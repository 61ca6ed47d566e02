// examples/filament/filament_tools.h — what Filament's own tools make of footprint's inputs,
// cached on disk: the environment prefiltered by `cmgen`, the roughness MIP chain from
// `roughness-prefilter`. Both tools are run as programs (libfilament-tools), so the peer gets
// exactly what Filament's documentation tells an engine to ship.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <footprint/core/result.h>
#include <footprint/image/image.h>
#include "scenes.h"

namespace footprint::filament_example {

// Loads a map (a file: colour maps sRGB-decoded by their metadata, `linear` for data such as
// normal maps; or the generated image) as a linear float image. Errors name the file.
Result<Image> load_map(const MapSource& map, bool linear);

// The files cmgen deployed for an environment: the IBL cube (roughness levels, RGB_11_11_10 KTX,
// spherical harmonics in its metadata) and the skybox cube.
struct PrefilteredEnvironment {
    std::filesystem::path ibl_ktx;
    std::filesystem::path skybox_ktx;
};

// The lat-long `latlong` (footprint's orientation: s = 0 at +Z, ¼ at −X, ½ at −Z, ¾ at +X, top row
// +Y) resampled to a cube cross of `face_size` in the GL face convention that Filament's cube
// textures use, and prefiltered by `cmgen --format=ktx --no-mirror --size=face_size`. The result
// is cached in `cache_dir` under a hash of the pixels, so a scene pays cmgen's few seconds once.
Result<PrefilteredEnvironment> prefilter_environment(const Image& latlong,
                                                     const std::filesystem::path& cache_dir,
                                                     int face_size);

// Filament's roughness MIP chain for a normal map and the authored perceptual roughness, from
// `roughness-prefilter` (one image per level, level 0 first, 1 channel, as large as the larger
// input). `roughness` is a 1×1 image (a constant: --roughness=R) or a map (channel 0; a glTF's
// metallic-roughness G channel times its factor: --roughness-map). Each map must be square with a
// power-of-two size (the tool's rule); the error says so, naming it (`label`, `roughness_label`).
Result<std::vector<Image>> prefilter_roughness(const Image& normal_map, const std::string& label,
                                               const Image& roughness,
                                               const std::string& roughness_label,
                                               const std::filesystem::path& cache_dir);

// footprint's MIP pyramid of a colour map (texture/mip_pyramid.h: box downsampling, repeat wrap,
// any size), level 0 down to 1×1: the levels fp_texture's probes read (docs/method.md, "MIP
// pyramids"), as `footprint bake` writes them. Every material gets these levels, so that the
// comparison measures the filters and not two ways of building a chain.
std::vector<Image> colour_pyramid(const Image& image);

// footprint's bump moment pyramid of a normal map (bump/bump_pyramid.h, box downsampling, repeat
// wrap), as the two textures glsl/footprint/bump.glsl reads: moments0 = (μ'1, μ'2, M2'11, M2'12)
// and moments1 = M2'22, level 0 down to 1×1, and the map's mean slope (slope_offset).
struct BumpMoments {
    std::vector<Image> moments0, moments1;
    float slope_offset[2] = {0, 0};
};
Result<BumpMoments> make_bump_moments(const Image& normal_map, const std::string& label);

// Runs a command line through /bin/sh; its output goes to `log`. Fails with the command and the
// log's tail when it exits non-zero.
Status run_tool(const std::string& command, const std::filesystem::path& log);

}  // namespace footprint::filament_example
