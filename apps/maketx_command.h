// apps/maketx_command.h — `footprint maketx`: a texture's MIP pyramid, prepared once, as a file.
//
//   footprint maketx IN -o OUT.exr [--wrap MODE[,MODE]] [--downsample box|tent] [--tile-size N]
//                    [--bump [--height] [--invalid-normals clamp]] [--env LAYOUT]
//
// Reads IN (any image load_image reads: integer files are sRGB-decoded to linear, float files are
// linear), builds its MIP pyramid (MipPyramid::build: every level down to 1×1, --downsample's
// filter, box by default) and writes every level as one tiled, MIP-mapped OpenEXR file of 32-bit
// floats (save_image_levels), the wrap modes in OpenImageIO's "wrapmodes" attribute. The texture
// system (texture_system.h) then reads it tile by tile, and so do OpenImageIO's TextureSystem and
// other renderers' texture caches: the role of OpenImageIO's `maketx`, with footprint's pyramid.
//   --wrap        repeat (or periodic) | clamp | mirror, for s and t, or "S,T" (default repeat)
//   --tile-size   16 … 1024, a power of two (default 64, the texture system's default tiles)
//   --bump        IN is a bump map: write its bump + roughness pyramid (bump/bump_pyramid_file.h:
//                 the 5 moment channels and the slope offset) of its slopes at strength 1 without
//                 micro-roughness, which the texture system reads tile by tile and the renderer
//                 scales by a material's strength and micro-roughness. IN is a tangent-space
//                 normal map (OpenGL convention, read as data, not sRGB), or with --height a
//                 height map (channel 0; slopes per unit of (u, v), one map period = 1). A normal
//                 map's invalid texels are an error naming the first, unless --invalid-normals
//                 clamp replaces them (slope_map.h).
//   --env         IN is an environment map (one file: a lat-long, a cube cross or strip, a sphere
//                 or a paraboloid pair, laid out as LAYOUT says — latlong, cube, sphere,
//                 paraboloid — or as load_environment() detects with "auto"): write its pyramids
//                 (and a lat-long map's polar caps) as an environment pyramid file
//                 (envmap/env_pyramid_file.h), which the texture system and a scene's environment
//                 load without building them. --wrap and --downsample do not apply.
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
    bool bump = false;                   // --bump
    bool height = false;                 // --height: IN is a height map
    bool clamp_invalid_normals = false;  // --invalid-normals clamp
    std::string env;                     // --env LAYOUT (or "auto"); empty: not an environment
    bool quiet = false;                  // --quiet: no "wrote" line (errors still)
};
int run_maketx_command(const MaketxCommandOptions& options);

}  // namespace footprint
