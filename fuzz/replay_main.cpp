// fuzz/replay_main.cpp — replays files through a fuzz target without libFuzzer, for the ordinary
// (gcc) builds: `fuzz_<name>_replay [--optional] DIR|FILE ...` calls LLVMFuzzerTestOneInput once
// per file (a folder's regular files, in name order). A crash, a sanitizer report or a trap in the
// target fails the run. A missing path is an error, unless `--optional` precedes it (a target with
// no crash regressions has no folder in tests/data/bad/fuzz/). At least one file must be replayed.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    std::vector<fs::path> files;
    bool optional = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--optional") {
            optional = true;
            continue;
        }
        const fs::path path = arg;
        if (fs::is_directory(path)) {
            std::vector<fs::path> in_dir;
            for (const auto& entry : fs::directory_iterator(path))
                if (entry.is_regular_file() && entry.path().filename() != "README.md")
                    in_dir.push_back(entry.path());
            std::sort(in_dir.begin(), in_dir.end());
            files.insert(files.end(), in_dir.begin(), in_dir.end());
        } else if (fs::is_regular_file(path)) {
            files.push_back(path);
        } else if (!optional) {
            std::fprintf(stderr, "%s: '%s' does not exist\n", argv[0], arg.c_str());
            return 2;
        }
        optional = false;
    }
    if (files.empty()) {
        std::fprintf(stderr, "%s: no files to replay\n", argv[0]);
        return 2;
    }
    for (const fs::path& file : files) {
        std::ifstream in(file, std::ios::binary);
        const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                      std::istreambuf_iterator<char>());
        std::fprintf(stderr, "replaying %s (%zu bytes)\n", file.c_str(), bytes.size());
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    }
    std::printf("%zu files replayed\n", files.size());
    return 0;
}
