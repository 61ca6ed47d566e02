// apps/maketx_command.h — `footprint maketx`: a texture's MIP pyramid, prepared once, as a file.
//
//   footprint maketx IN -o OUT.exr [--wrap MODE[,MODE]] [--downsample box|tent] [--tile-size N]
//
// Reads IN (any image load_image reads: integer files are sRGB-decoded to linear, float files are
// linear), builds its MIP pyramid (MipPyramid::build: every level down to 1×1, --downsample's
// filter, box by default) and writes every level as one tiled, MIP-mapped OpenEXR file of 32-bit
// floats (save_image_levels), the wrap modes in OpenImageIO's "wrapmodes" attribute. The texture
// system (texture_system.h) then reads it tile by tile, and so do OpenImageIO's TextureSystem and
// other renderers' texture caches: the role of OpenImageIO's `maketx`, with footprint's pyramid.
//   --wrap        repeat (or periodic) | clamp | mirror, for s and t, or "S,T" (default repeat)
//   --tile-size   16 … 1024, a power of two (default 64, the texture system's default tiles)
// Prints one line on stderr: "footprint: wrote OUT.exr (W×H, N levels, C channels, tiles T²)".
// Returns 0, or 1 after one line "footprint: …" naming the file or value at fault (unreadable
// input, an output that is not .exr or cannot be written — nothing is left behind then).
#pragma once

#include <filesystem>
#include <string>

#include "texture/mip_pyramid.h"

namespace footprint {

struct MaketxCommandOptions {
    std::filesystem::path input, output;
    std::string wrap = "repeat";
    DownsampleFilter downsample = DownsampleFilter::box;
    int tile_size = 64;
};
int run_maketx_command(const MaketxCommandOptions& options);

}  // namespace footprint
