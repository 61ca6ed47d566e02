// apps/bake_command.h — `footprint bake`: the maps a real-time engine loads, level by level as
// footprint builds them (docs/engine.md#what-to-bake, docs/cli.md#footprint-bake).
//
//   footprint bake color IN -o OUT.ktx|OUT.exr [--srgb|--linear] [--float32] [--wrap MODE[,MODE]]
//                        [--downsample box|tent]
//   footprint bake bump  IN -o OUT.ktx|OUT.exr [--height] [--invalid-normals error|clamp]
//                        [--float32] [--wrap MODE[,MODE]] [--downsample box|tent]
//   footprint bake env   IN -o OUT.ktx|OUT.exr [--size N] [--srgb|--linear] [--float32]
//
// color  IN's MIP pyramid (MipPyramid::build, the pyramid the texture lookups filter: every level
//        down to 1×1, --downsample's filter). Integer files are sRGB-decoded (--srgb / --linear
//        force the choice), float files taken as linear; the levels are linear light, HDR stays
//        HDR. KTX: RGBA16F (RGBA32F with --float32), grey replicated to RGB, alpha 1 where IN has
//        none. EXR: what `footprint maketx` writes (tiled, MIP-mapped, IN's channels, 32-bit).
// bump   IN's bump + roughness moment pyramid (BumpPyramid, docs/method.md §5) of the slopes at
//        strength 1 without micro-roughness, as `maketx --bump` reads IN (a tangent-space normal
//        map, OpenGL convention, read as data; or with --height a height map). Per level, two
//        RGBA maps of the centred moments μ' = μ − offset, M2' = K + μ'μ'ᵀ:
//            A = (μ'1, μ'2, M2'11, M2'12)     B = (M2'22, 0, 0, 1)
//        and the offset in the key/value "footprint:slope_offset" (KTX) / attribute (EXR).
//        KTX: OUT_a.ktx and OUT_b.ktx (OUT.ktx's stem + "_a" / "_b"); EXR: one file OUT.exr with
//        the channels a.R a.G a.B a.A b.R b.G b.B b.A (layers "a" and "b").
// env    IN (a lat-long, cube cross or strip, sphere map or OpenEXR envmap, detected as
//        load_environment_images does) as a cube map of face edge --size (default: the source's
//        angular resolution, env_convert.h), resampled by footprint's filtered conversion, then
//        each face's MIP pyramid as EnvironmentMap::from_cube_faces builds it. KTX: a cube map
//        (numberOfFaces 6, +X −X +Y −Y +Z −Z, OpenGL's cube map rule: texture(samplerCube, r)
//        reads the direction r of footprint's environment). EXR: an environment pyramid file
//        (env_pyramid_file.h: one MIP-mapped part per face, in that order and orientation).
//
// Every file is checked before any work and written atomically (a temporary name, then a
// rename); the two files of a bump KTX are both written or neither. Prints one line on stderr:
// "footprint: wrote OUT.ktx (color, 512x256, 10 levels, RGBA16F)". Returns 0, or 1 after one line
// "footprint: …" naming the file, option or value at fault: an unknown kind, an extension it
// cannot write ("cannot write 'a.png': footprint bake writes KTX 1 (.ktx) or OpenEXR (.exr)"),
// a missing output folder, an unreadable input, an input that is not a normal map, a value that
// half floats cannot hold (--float32 writes it), an option the kind does not take.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "image/image_io.h"
#include "texture/mip_pyramid.h"

namespace footprint {

struct BakeCommandOptions {
    std::string kind;  // color | bump | env
    std::filesystem::path input, output;
    ColorEncoding encoding = ColorEncoding::automatic;  // --srgb / --linear (color, env)
    bool float32 = false;                               // --float32: RGBA32F instead of RGBA16F
    std::optional<std::string> wrap;                    // --wrap (color, bump); repeat if none
    std::optional<DownsampleFilter> downsample;         // --downsample (color, bump); box if none
    bool height = false;                                // --height (bump)
    bool clamp_invalid_normals = false;                 // --invalid-normals clamp (bump)
    std::optional<int> size;  // --size (env): the cube's face edge, 1 to 16384
    bool quiet = false;       // --quiet: no "wrote" line (errors still)
};
int run_bake_command(const BakeCommandOptions& options);

// The two files `footprint bake bump -o OUT.ktx` writes: OUT_a.ktx and OUT_b.ktx.
std::filesystem::path bump_ktx_file(const std::filesystem::path& output, char map);

}  // namespace footprint
