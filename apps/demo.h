// apps/demo.h — `footprint demo`: the papers' figures (apps/demo_scenes.h) rendered with every
// filter mode and a ground-truth reference. What `make demo` runs.
//
// Writes into out_dir (created if missing), for each scene:
//   <scene>/reference.png, <scene>/<mode>.png for bilinear trilinear fa fa-rough ewa-rough
//   <scene>/contact_sheet.png   reference first, then the modes in that order, 3 columns, each
//                               panel labelled under it: mode, spp, RMSE against the reference
//                               (not for the reference itself), render time
// and demo.json: per scene its title and assets, per mode the RMSE against the reference (linear
// light, all pixels), seconds and lookups. Prints a table to stdout; progress bars on stderr when
// it is a terminal and not quiet. Returns 0, or 1 after one line "footprint: …" on stderr naming
// what failed; files are written atomically, and a run that fails removes the files and folders
// it had written (command_util.h's RunOutputs).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace footprint {

struct DemoCommandOptions {
    std::filesystem::path out_dir = "out";
    std::vector<std::string> scenes;  // empty: all
    int width = 320;                  // height = width · 9/16; 16 … 4096
    int reference_spp = 64;           // 1 … 65536
    int threads = 0;                  // 0: all cores
    bool quiet = false;
};
int run_demo_command(const DemoCommandOptions& options);

}  // namespace footprint
