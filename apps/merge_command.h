// apps/merge_command.h — `footprint merge`: the bands of a render split across machines
// (`footprint render --tile I/N`) assembled into the whole image.
//
//   footprint merge TILE.exr... -o OUT [--exposure E] [--quiet]
//
// Each TILE is an OpenEXR band (image/image_io.h's ImageBand): its pixels, linear as rendered,
// and its rows' place in the full image. The bands must come from one image (the same full size)
// and cover every row exactly once, in any order on the command line; OUT is then written as
// `footprint render -o OUT` writes the whole image (PNG/JPEG/TIFF sRGB after 2^exposure, EXR/HDR
// linear), so that its pixels are bit for bit the whole render's and its bytes the same file.
//
// Returns 0, or 1 after one line "footprint: <what is wrong>" naming the file and the rows at fault
// (a missing band: "rows 120 to 179 are in no tile"; two that overlap; tiles of different
// images). Nothing is written then; OUT is written atomically.
#pragma once

#include <filesystem>
#include <vector>

namespace footprint {

struct MergeCommandOptions {
    std::vector<std::filesystem::path> tiles;
    std::filesystem::path output;
    float exposure = 0;  // stops, for integer outputs, as footprint render's
    bool quiet = false;
};
int run_merge_command(const MergeCommandOptions& options);

}  // namespace footprint
