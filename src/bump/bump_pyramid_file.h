// bump/bump_pyramid_file.h — a bump + roughness pyramid kept as a file, so that a big normal map
// is prepared once (`footprint maketx --bump`) and read tile by tile by the texture system
// (texture_system.h) instead of being decoded and filtered on every run.
//
// The file is one tiled, MIP-mapped OpenEXR of 32-bit floats, as save_image_levels() writes a MIP
// chain (image/image_io.h), holding BumpPyramid::moments() exactly: five channels named
//     mean.x  mean.y  square.xx  square.xy  square.yy     (μ'1, μ'2, M2'11, M2'12, M2'22)
// OpenImageIO's "wrapmodes", and the attribute "footprint:slope_offset" (two floats,
// BumpPyramid::slope_offset()), which marks the file as a bump pyramid. Any OpenEXR reader sees the
// moments as five float channels; footprint reads them back bit for bit.
//
// The slopes are stored as the pyramid holds them. `footprint maketx --bump` stores a normal map's
// slopes at strength 1 without micro-roughness, and a material applies its own strength and
// micro-roughness when it looks the file up (BumpLookupOptions, bump_pyramid.h).
#pragma once

#include <filesystem>
#include <optional>

#include <footprint/bump/bump_pyramid.h>
#include <footprint/core/result.h>

namespace footprint {

// Writes `pyramid` to `file` (.exr) in tiles of tile_size² texels (16 to 1024, a power of two),
// atomically: on failure nothing is left behind and the Error names the file.
Status save_bump_pyramid(const BumpPyramid& pyramid, const std::filesystem::path& file,
                         int tile_size = 64);

// The pyramid a bump pyramid file holds, read whole, bit for bit as it was saved. A file that is
// not one (no "footprint:slope_offset", other channels, levels missing) is an Error naming it.
Result<BumpPyramid> load_bump_pyramid(const std::filesystem::path& file);

// Whether `file` is a bump pyramid file — an image whose header has "footprint:slope_offset" — and
// then its slope offset; nullopt otherwise, and for a file that cannot be opened (the header only
// is read).
std::optional<Vec2> bump_pyramid_file_offset(const std::filesystem::path& file);

}  // namespace footprint
