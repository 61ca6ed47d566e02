// image/exr_parts.h — OpenEXR files of several MIP-mapped parts, written with OpenEXR itself
// (private to the image module: save_image_level_chains() calls it).
//
// OpenImageIO writes a tiled MIP-mapped OpenEXR of one part, but not of several (its writer
// refuses to append a MIP level to a part of a multi-part file), so those go through OpenEXR's
// MultiPartOutputFile. The parts are what save_image_levels() writes for one: 32-bit float
// channels, tiles of options.tile_size², MIPMAP_LEVELS rounded down, the options' attributes,
// "textureformat" and "wrapmodes" as maketx writes them; all share one display window (OpenEXR
// requires it), the largest part's.
#pragma once

#include <vector>

#include "core/result.h"
#include "image/image_io.h"

namespace footprint::detail {

// The file's bytes. The parts' levels are checked by the caller (levels_problem()).
Result<std::vector<unsigned char>> encode_exr_parts(const std::vector<LevelChain>& parts,
                                                    const LevelsSaveOptions& options);

}  // namespace footprint::detail
