// texsys/texture_file.h — one texture file of a TextureSystem: what is known of it once opened,
// and how its tiles are read (private to the texture system).
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <OpenImageIO/imageio.h>

#include "core/result.h"
#include "texsys/exr_tiles.h"
#include "texsys/texel_access.h"
#include "texture/mip_pyramid.h"
#include "texture/tiled_texels.h"
#include "texture_system.h"

namespace footprint {

class TextureHandle {
  public:
    TextureHandle(std::string name, std::uint32_t id) : name(std::move(name)), id(id) {}

    // Opens the file: its header for stored levels, else the image, whose pyramid is built (and,
    // with options.cache_dir, written there and opened as stored), as `as` says (subimage, wrap
    // modes). Sets `error` on failure; where the pyramid cannot be written to options.cache_dir,
    // with fall_back_to_memory, holds it in memory and sets `warning` instead.
    void open(const TextureSystemOptions& options, const detail::OpenAs& as = {},
              bool fall_back_to_memory = false);

    // Opens part `part` of the file (an environment pyramid file's face or polar cap,
    // envmap/tiled_environment.h) to be read tile by tile as `part_shape`, which its headers gave.
    void open_part(int part, const detail::TiledShape& part_shape,
                   const TextureSystemOptions& options);

    // Reads tile (tx, ty) of level l into `texels` (TiledTexels' layout: row-major, stride floats
    // per texel). A failed read gives zeros and sets read_error.
    void read_tile(int l, int tx, int ty, float* texels);
    // The floats of tile (tx, ty) of level l.
    std::size_t tile_floats(int l, int tx, int ty) const;
    // A tiled file's levels read whole into a pyramid (outside the cache), or the read's error.
    Result<MipPyramid> read_whole();

    const std::string name;
    const std::uint32_t id;
    std::once_flag opened;
    std::optional<Error> error;    // set by open(): the file cannot be looked up
    std::optional<Error> warning;  // set by open(): the file is looked up, not as asked
    std::atomic<bool> error_reported{false};
    TextureInfo info;

    // Tiled (info.tiled): the levels' shape, read through `input`.
    detail::TiledShape shape;
    // A bump pyramid file's (bump/bump_pyramid_file.h): its slope offset.
    std::optional<Vec2> slope_offset;
    // Otherwise: the pyramid, in memory.
    std::shared_ptr<const MipPyramid> pyramid;
    // A tiled file read whole (TextureSystem::pyramid()), while someone holds it.
    std::mutex whole_mutex;
    std::weak_ptr<const MipPyramid> whole;

    // A read that failed after the file opened (a truncated tile): the file's error from then on.
    std::atomic<bool> read_failed{false};
    std::mutex read_error_mutex;
    std::optional<Error> read_error;

    // A UDIM set (the name holds "<UDIM>"): its files by tile number, opened on first use.
    bool udim = false;
    std::mutex udim_mutex;
    std::map<int, TextureHandle*> udim_tiles;

  private:
    // Opens `file`, which holds stored levels, to be read tile by tile.
    void open_stored(const std::string& file, const TextureSystemOptions& options);
    // ... through `input`, already open on it.
    void open_stored(const std::string& file, std::unique_ptr<OIIO::ImageInput> input,
                     const TextureSystemOptions& options);
    void fail_read(const std::string& why);

    // The tiles are read through `exr_tiles_` where it reads them (an OpenEXR file's), else
    // through `input_`, one read at a time.
    std::unique_ptr<texsys::ExrTiles> exr_tiles_;
    std::mutex read_mutex_;
    std::unique_ptr<OIIO::ImageInput> input_;
    int subimage_ = 0;          // the part (OpenImageIO subimage) read
    bool wraps_given_ = false;  // open() was given wrap modes: the file's own do not apply
    int file_tile_width_ = 0, file_tile_height_ = 0;
    bool srgb_ = false;  // decode the colour channels (not alpha) from sRGB
    int alpha_ = -1;     // the alpha channel, or −1
};

// The file in options.cache_dir that holds the pyramids of `kind` ("texture", "bump", "env") built
// for `file` wrapping as (wrap_s, wrap_t): named by the source's absolute path, size and
// modification time and by what shapes the pyramid, so that a changed source is built again.
std::filesystem::path cached_pyramid_file(const std::filesystem::path& file,
                                          const TextureSystemOptions& options, WrapMode wrap_s,
                                          WrapMode wrap_t, std::string_view kind);

}  // namespace footprint
