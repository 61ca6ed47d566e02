// bump/bump_pyramid_file_detail.h — (private to bump and texsys) bump_pyramid_file_offset() on a
// header already open, so that the texture system reads a file's header once.
#pragma once

#include <OpenImageIO/imageio.h>

#include <optional>

#include "math/vec.h"

namespace footprint::detail {

// The slope offset a header holds if it is a bump pyramid file's ("footprint:slope_offset", two
// floats), else nullopt.
std::optional<Vec2> slope_offset(const OIIO::ImageSpec& spec);

}  // namespace footprint::detail
