// texsys/exr_tiles.h — a tiled OpenEXR part's tiles, decoded through OpenEXR's core library
// (private to the texture system).
//
// The texture system reads most tiles it ever reads while a lookup waits, so a tile's read is on
// its path. OpenImageIO 2.4's OpenEXR reader hands each tile to OpenEXR's thread pool and back
// (a wake-up and a sleep per tile) and reads one tile of a file at a time; OpenEXR's core library
// decodes a chunk on the calling thread and reads a file's chunks from any number of threads at
// once. OpenImageIO still opens the file and gives its header (format_checks.h has checked it);
// this only decodes the tiles.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace footprint::texsys {

class ExrTiles {
  public:
    // The tiles of part `part`, whose channels `channels` (by name, in this order) are read, or
    // null where the core library does not read them as OpenImageIO would: a file that is not
    // OpenEXR, a part that is not a MIP-mapped tiled image, subsampled or integer channels,
    // a channel missing.
    static std::unique_ptr<ExrTiles> open(const std::filesystem::path& file, int part,
                                          const std::vector<std::string>& channels);
    ~ExrTiles();
    ExrTiles(const ExrTiles&) = delete;
    ExrTiles& operator=(const ExrTiles&) = delete;

    // Decodes the region [x0, x1) × [y0, y1) of MIP level `level`, which starts on a tile's corner
    // and ends on one or at the level's edge, into `texels`: rows of (x1 − x0) texels of the
    // channels asked for, as floats. Safe from any number of threads at once. On failure returns
    // false and sets `why`.
    bool read(int level, int x0, int x1, int y0, int y1, float* texels, std::string& why) const;

    int tile_width() const { return tile_width_; }
    int tile_height() const { return tile_height_; }

  private:
    struct Context;
    ExrTiles(std::unique_ptr<Context> context, int part, std::vector<std::string> channels,
             int tile_width, int tile_height);

    std::unique_ptr<Context> context_;
    int part_;
    std::vector<std::string> channels_;  // read, in this order
    int tile_width_, tile_height_;
    // For each of the part's channels (the file's order): its index in channels_, or −1 where it
    // is not read; where its float lands in a texel (bytes); its floats' size.
    std::vector<int> channel_of_;
    std::vector<std::size_t> offsets_;
    std::vector<int> element_bytes_;
};

}  // namespace footprint::texsys
