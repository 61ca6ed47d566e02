// apps/env_command.h — the `footprint env convert` command, callable without a command line
// (footprint_main.cpp only parses arguments into EnvConvertCommandOptions).
//
//   footprint env convert IN [IN...] --to cube|latlong|sphere|paraboloid -o OUT [-o OUT...]
//                         [--size N] [--from LAYOUT] [--from-cube-layout A] [--cube-layout A]
//                         [--repair-non-finite] [--quiet]
//
// Inputs (envmap/env_image_io.h): 1 file (lat-long, sphere, a cube cross/strip, an OpenEXR
// environment map, or — with --from paraboloid — front|back side by side), 2 files (paraboloid
// front, back) or 6 (cube faces +X −X +Y −Y +Z −Z). The layout is detected from the file count,
// the OpenEXR "envmap" header and the aspect ratio; --from and --from-cube-layout override it.
// Outputs: cube → 1 file in --cube-layout (default hcross) or 6 face files; paraboloid → 1 file
// (front | back side by side) or 2; lat-long and sphere → 1. --size as in envmap/env_convert.h
// (cube face edge, lat-long width, sphere / paraboloid face edge); 0 keeps the source's angular
// resolution. Every output texel is filtered over its footprint (footprint assembly by default).
// An input texel that is NaN or ±Inf makes the command fail naming the file and the texel;
// --repair-non-finite replaces each by the mean of its finite neighbours instead and prints one
// warning per repaired file ("footprint: warning: 'sky.exr': replaced 3 non-finite values ...").
// No output may be an input or another output (compared as files, not as spellings).
//
// Returns the exit status: 0 on success; 1 on bad input (an unknown --to / --from / layout /
// value, a missing or unreadable file, a size that does not fit the layout, a bad output
// path, an output that is an input, a failed write), after printing exactly one line "footprint:
// <what is wrong>" to stderr that names the file or value. Command-line usage errors (status 2) are
// the parser's (footprint_main.cpp). All output paths are checked before any work; files are
// written atomically (save_image).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace footprint {

struct EnvConvertCommandOptions {
    std::vector<std::filesystem::path> inputs;
    std::vector<std::filesystem::path> outputs;
    std::string to;    // cube | latlong | sphere | paraboloid (required)
    std::string from;  // "" (detect) or a layout name
    std::string from_cube_layout =
        "auto";  // auto | hcross | vcross | 3x2 | 2x3 | column | row | openexr
    std::string cube_layout = "hcross";  // output: hcross | vcross | 3x2 | 2x3 | column | row
    int size = 0;                        // 0: keep the angular resolution; else 1 … 16384
    bool repair_non_finite = false;      // repair NaN / ±Inf input texels instead of refusing
    bool quiet = false;
};
int run_env_convert_command(const EnvConvertCommandOptions& options);

}  // namespace footprint
