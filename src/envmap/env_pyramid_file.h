// envmap/env_pyramid_file.h — an environment map's pyramids kept as a file, so that a big HDR
// environment is filtered once (`footprint maketx --env`) instead of on every run: its MIP levels
// and a lat-long map's polar caps, which take longest to build.
//
// The file is one tiled, MIP-mapped OpenEXR of 32-bit floats with one part (OpenImageIO subimage)
// per face of the map, in face order — a lat-long map's one, a cube's six (+X −X +Y −Y +Z −Z), a
// sphere map's one, a paraboloid's front and back — then a lat-long map's two polar caps (+Y, −Y)
// where it has them. Each part is a face's MIP chain as save_image_level_chains() writes it
// (image/image_io.h), the sphere's and paraboloid's with their continued exterior (what
// environment_map.h's pyramids hold), and carries the attribute "footprint:environment" = the
// layout's name (env_layout_name(): latlong, cube, sphere, paraboloid), which marks the file.
// Loading it gives the map that was saved, whose lookups are bit for bit the original's.
#pragma once

#include <filesystem>

#include <footprint/core/result.h>
#include <footprint/envmap/environment_map.h>

namespace footprint {

// Writes `map` to `file` (.exr) in tiles of tile_size² texels (16 to 1024, a power of two),
// atomically: on failure nothing is left behind and the Error names the file.
Status save_environment_pyramid(const EnvironmentMap& map, const std::filesystem::path& file,
                                int tile_size = 64);

// The map an environment pyramid file holds, read whole. A file that is not one, or whose parts
// do not make its layout's map, is an Error naming it.
Result<EnvironmentMap> load_environment_pyramid(const std::filesystem::path& file);

// Whether `file` is an environment pyramid file (its header only is read; false for a file that
// cannot be opened).
bool is_environment_pyramid_file(const std::filesystem::path& file);

}  // namespace footprint
