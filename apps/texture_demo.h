// apps/texture_demo.h — the `footprint texture-demo` and `footprint plane` commands, callable
// without a command line (footprint_main.cpp only parses arguments into these structs).
//
// Both return the process exit status: 0 on success, 1 on any error, after printing exactly one
// line "footprint: <what is wrong>" to stderr that names the file or option at fault. They never
// throw and never leave a partial output file behind (images are written by save_image, which
// replaces its target atomically; demo.json likewise through a temporary file and a rename), and
// a texture-demo that fails removes the images it had written (command_util.h's RunOutputs).
#pragma once

#include <filesystem>
#include <string>

namespace footprint {

// footprint texture-demo: the built-in texture on the grazing plane (plane_view.h) with every
// filter and a supersampled reference. Writes into out_dir (created if missing):
//   demo_reference.png, demo_<filter>.png for nearest bilinear trilinear fa ewa sat,
//   demo_contact_sheet.png   all images in a grid, 4 columns, reference first, then the filters in
//                            the order above (listed in demo.json), 4-pixel grey gaps;
//   demo.json                sizes, camera, per filter RMSE (linear light, against the reference,
//                            over the plane rows away from the horizon), seconds and lookups, and
//                            the contact sheet's cells (cell_height includes the label strip,
//                            label_height; docs/cli.md).
// Prints a table (filter, RMSE, ms) to stdout; progress bars on stderr if it is a terminal and
// not quiet.
struct TextureDemoOptions {
    std::filesystem::path out_dir = "out";
    int width = 480;            // height = width · 9/16; 16 … 4096
    int samples_per_axis = 16;  // reference: N × N samples per pixel; 1 … 64
    int texture_size = 1024;    // built-in texture, size × size texels; 16 … 8192
    bool quiet = false;
};
int run_texture_demo_command(const TextureDemoOptions& options);

// footprint plane: a texture file on the grazing plane with one filter, written to `output`
// (.png/.jpg/.tif sRGB, .exr/.hdr linear, by extension). Unless quiet, a progress bar on stderr
// when it is a terminal and, when done, the line render prints (apps/cli_options.h):
//   footprint: wrote OUT (WxH, FILTER, T s)
struct PlaneCommandOptions {
    std::filesystem::path texture;
    std::filesystem::path output;
    std::string filter = "fa";       // apps/cli_options.h's plane filters
    int width = 480;                 // height = width · 9/16; 16 … 16384
    double uv_scale = 0.125;         // texture periods per world unit, > 0
    bool repair_non_finite = false;  // NaN / ±Inf texels: repair with a warning, not refuse
    bool quiet = false;
};
int run_plane_command(const PlaneCommandOptions& options);

}  // namespace footprint
