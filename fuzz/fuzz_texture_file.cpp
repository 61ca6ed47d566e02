// fuzz/fuzz_texture_file.cpp — the texture system's file handling (texture_system.h, texsys/):
// tiled MIP-mapped OpenEXR files (`footprint maketx`'s, its --bump and --env pyramids) and plain
// images, truncated, corrupt or with tiles of the wrong size, read tile by tile through a small
// cache and looked up.
//
// Feeds: the bytes after the first as a file whose extension the first byte picks (.exr mostly,
// .png, .tif), opened by a fresh TextureSystem (8² or 16² tiles, 1 MiB, so that tiles are evicted)
// as a texture, a bump map and an environment map, each looked up at a few points through every
// filter.
// Asserts: a lookup that fails says why, naming the file; a lookup given a missing colour succeeds
// and writes that colour where the file cannot be read, and the error is reported once through
// take_errors(); info() agrees with what the lookups see (channels ≥ 1, a level count that fits
// the size); a file that opens gives the same result with its tiles cached or read again.
#include <array>
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz_input.h"
#include "texture_system.h"

namespace {

using namespace footprint;
using fuzz::FuzzInput;

// The file's name (the folder is the scratch folder).
void require_names(const Error& error, const std::string&) {
    fuzz::require(error.message.find("texture.") != std::string::npos, "an error names the file");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    static constexpr std::array kExtensions{".exr", ".exr", ".exr", ".exr", ".exr", ".png", ".tif"};
    const std::uint8_t choice = data[0];
    const std::filesystem::path file =
        fuzz::write_scratch(std::string("texture") + kExtensions[choice % kExtensions.size()],
                            std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));
    const std::string name = file.string();

    TextureSystemOptions ts_options;
    ts_options.max_memory_mb = 1;
    ts_options.tile_size = (choice & 0x80) ? 16 : 8;
    Result<std::unique_ptr<TextureSystem>> created = TextureSystem::create(ts_options);
    fuzz::require(created.ok(), "a texture system with valid options is made");
    TextureSystem& ts = **created;

    // Fixed lookups (the bytes are the file's): a point, a magnified, a minified and an
    // anisotropic footprint, through every filter.
    static constexpr std::array<TextureCoords, 4> kCoords{{{0.3f, 0.7f, 0, 0, 0, 0},
                                                           {0.5f, 0.5f, 1e-3f, 0, 0, 1e-3f},
                                                           {0.9f, 0.1f, 0.5f, 0.1f, -0.1f, 0.5f},
                                                           {-0.2f, 1.3f, 0.4f, 0, 0, 0.01f}}};
    static constexpr std::array<float, MipPyramid::kMaxChannels> kMissing{0.25f, 0.5f, 0.75f, 1,
                                                                          1,     1,    1,     1};
    const Result<TextureInfo> info = ts.info(name);
    if (info.ok()) {
        fuzz::require(info->width >= 1 && info->height >= 1 && info->channels >= 1,
                      "info gives a size and channels");
        fuzz::require(info->levels >= 1 && info->levels <= 32, "info gives a level count");
    } else {
        require_names(info.error(), name);
    }
    std::array<float, MipPyramid::kMaxChannels> out{}, again{};
    for (int filter = 0; filter <= 6; ++filter) {
        LookupOptions options;
        options.filter = static_cast<TextureFilter>(filter);
        for (const TextureCoords& coords : kCoords) {
            const Status status = ts.texture(name, coords, options, out);
            fuzz::require(info.ok() || !status.ok(),
                          "a file whose info failed cannot be looked up");
            if (!status.ok()) {
                require_names(status.error(), name);
                fuzz::require(ts.texture(name, coords, options, out, kMissing).ok(),
                              "with a missing colour a lookup succeeds");
                fuzz::require(out[0] == kMissing[0], "the missing colour is written");
                continue;
            }
            fuzz::require(ts.texture(name, coords, options, again).ok(), "a lookup repeats");
            fuzz::require(
                std::memcmp(out.data(), again.data(), sizeof(float) * info->channels) == 0,
                "a lookup gives the same bits again");
        }
    }

    // The same file as a bump map and as an environment map.
    SlopeStatistics slopes;
    if (const Status status = ts.bump(name, kCoords[2], BumpLookupOptions{}, &slopes); !status.ok())
        require_names(status.error(), name);
    for (const Vec3 r : {Vec3{0, 0, 1}, Vec3{1, 1, -1}, Vec3{0, -1, 0}}) {
        if (const Status status = ts.environment(name, r, Vec3{0.01f, 0, 0}, Vec3{0, 0.01f, 0},
                                                 EnvLookupOptions{}, out);
            !status.ok()) {
            require_names(status.error(), name);
            fuzz::require(ts.environment(name, r, Vec3{0.01f, 0, 0}, Vec3{0, 0.01f, 0},
                                         EnvLookupOptions{}, out, kMissing)
                              .ok(),
                          "with a missing colour an environment lookup succeeds");
        }
    }
    for (const Error& error : ts.take_errors()) require_names(error, name);
    return 0;
}
