#include "texsys/exr_tiles.h"

#include <openexr.h>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "image/exr_decode.h"

namespace footprint::texsys {

namespace {

// OpenEXR's decoder allocates its buffers (the compressed chunk, the decompressed one, its
// scratch) for each tile and frees them after. Freed, they left the top of glibc's heap free
// beyond its trim threshold, which glibc handed back to the kernel, and the next tile faulted the
// pages in again: a texture system's first frame, which reads its tiles, took a third longer
// (docs/performance.md, "The texture system"). So the contexts allocate through each thread's
// last few freed blocks, reused for its next tile.
class FreedBlocks {
  public:
    ~FreedBlocks() {
        for (int i = 0; i < count_; ++i) std::free(blocks_[i]);
        count_ = 0;
        gone_ = true;  // frees after this (a context finished later on this thread) go to free()
    }
    static void* allocate(std::size_t bytes) {
        if (!gone_) {
            FreedBlocks& mine = blocks();
            for (int i = 0; i < mine.count_; ++i) {
                Header* block = mine.blocks_[i];
                if (block->capacity < bytes) continue;
                mine.blocks_[i] = mine.blocks_[--mine.count_];
                return block + 1;
            }
        }
        // Rounded up, so that a block serves the next tile's buffer of a slightly larger size.
        const std::size_t capacity = (bytes + kRounding - 1) / kRounding * kRounding;
        auto* block = static_cast<Header*>(std::malloc(sizeof(Header) + capacity));
        if (!block) return nullptr;
        block->capacity = capacity;
        return block + 1;
    }
    static void release(void* pointer) {
        if (!pointer) return;
        Header* block = static_cast<Header*>(pointer) - 1;
        if (!gone_) {
            FreedBlocks& mine = blocks();
            if (mine.count_ < kBlocks) {
                mine.blocks_[mine.count_++] = block;
                return;
            }
            // Full: keep the larger blocks, which serve any buffer the smaller ones would.
            Header** smallest = std::min_element(
                mine.blocks_, mine.blocks_ + kBlocks,
                [](const Header* a, const Header* b) { return a->capacity < b->capacity; });
            if ((*smallest)->capacity < block->capacity) std::swap(*smallest, block);
        }
        std::free(block);
    }

  private:
    struct alignas(std::max_align_t) Header {
        std::size_t capacity;
    };
    static constexpr int kBlocks = 8;
    static constexpr std::size_t kRounding = 16 << 10;
    static FreedBlocks& blocks() {
        thread_local FreedBlocks mine;
        return mine;
    }
    Header* blocks_[kBlocks] = {};
    int count_ = 0;
    static thread_local bool gone_;
};
thread_local bool FreedBlocks::gone_ = false;

}  // namespace

struct ExrTiles::Context {
    exr_context_t context = nullptr;
    ~Context() { exr_finish(&context); }
};

ExrTiles::ExrTiles(std::unique_ptr<Context> context, int part, std::vector<std::string> channels,
                   int tile_width, int tile_height)
    : context_(std::move(context)),
      part_(part),
      channels_(std::move(channels)),
      tile_width_(tile_width),
      tile_height_(tile_height) {}

ExrTiles::~ExrTiles() = default;

std::unique_ptr<ExrTiles> ExrTiles::open(const std::filesystem::path& file, int part,
                                         const std::vector<std::string>& channels) {
    auto context = std::make_unique<Context>();
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    detail::keep_exr_errors(init);
    init.alloc_fn = FreedBlocks::allocate;
    init.free_fn = FreedBlocks::release;
    if (exr_start_read(&context->context, file.c_str(), &init) != EXR_ERR_SUCCESS) return nullptr;
    exr_const_context_t c = context->context;
    int parts = 0;
    exr_storage_t storage{};
    std::uint32_t tile_width = 0, tile_height = 0;
    exr_tile_level_mode_t levels{};
    exr_tile_round_mode_t rounding{};
    const exr_attr_chlist_t* list = nullptr;
    if (exr_get_count(c, &parts) != EXR_ERR_SUCCESS || part < 0 || part >= parts ||
        exr_get_storage(c, part, &storage) != EXR_ERR_SUCCESS || storage != EXR_STORAGE_TILED ||
        exr_get_tile_descriptor(c, part, &tile_width, &tile_height, &levels, &rounding) !=
            EXR_ERR_SUCCESS ||
        levels != EXR_TILE_MIPMAP_LEVELS || exr_get_channels(c, part, &list) != EXR_ERR_SUCCESS) {
        return nullptr;
    }
    std::size_t found = 0;
    std::vector<int> channel_of(list->num_channels, -1);
    std::vector<std::size_t> offsets(list->num_channels, 0);
    for (int i = 0; i < list->num_channels; ++i) {
        const exr_attr_chlist_entry_t& entry = list->entries[i];
        if (entry.x_sampling != 1 || entry.y_sampling != 1 || entry.pixel_type == EXR_PIXEL_UINT)
            return nullptr;
        const std::string_view name(entry.name.str, std::size_t(entry.name.length));
        found += std::count(channels.begin(), channels.end(), name);
        const auto k = std::find(channels.begin(), channels.end(), name) - channels.begin();
        if (k == static_cast<std::ptrdiff_t>(channels.size())) continue;
        channel_of[i] = static_cast<int>(k);
        offsets[i] = k * sizeof(float);
    }
    if (found != channels.size()) return nullptr;
    auto tiles = std::unique_ptr<ExrTiles>(new ExrTiles(std::move(context), part, channels,
                                                        static_cast<int>(tile_width),
                                                        static_cast<int>(tile_height)));
    tiles->channel_of_ = std::move(channel_of);
    tiles->offsets_ = std::move(offsets);
    tiles->element_bytes_.assign(tiles->channel_of_.size(), static_cast<int>(sizeof(float)));
    return tiles;
}

bool ExrTiles::read(int level, int x0, int x1, int y0, int y1, float* texels,
                    std::string& why) const {
    const exr_const_context_t c = context_->context;
    const int channels = static_cast<int>(channels_.size());
    const std::size_t row_bytes = static_cast<std::size_t>(x1 - x0) * channels * sizeof(float);
    const std::size_t pixel_bytes = channels * sizeof(float);
    // Each channel asked for is decoded into a float plane of its own, then interleaved
    // (image/exr_decode.h).
    thread_local std::vector<float> planes;
    const std::size_t plane_floats = static_cast<std::size_t>(tile_width_) * tile_height_;
    if (planes.size() < plane_floats * channels) planes.resize(plane_floats * channels);
    // Plane i receives the file's channel i (null: not asked for).
    const int file_channels = static_cast<int>(channel_of_.size());
    thread_local std::vector<std::uint8_t*> plane_of;
    plane_of.assign(file_channels, nullptr);
    for (int i = 0; i < file_channels; ++i)
        if (channel_of_[i] >= 0)
            plane_of[i] = reinterpret_cast<std::uint8_t*>(&planes[channel_of_[i] * plane_floats]);
    detail::ExrChunkDecoder decoder(c, part_);
    for (int ty = y0 / tile_height_; ty * tile_height_ < y1; ++ty) {
        for (int tx = x0 / tile_width_; tx * tile_width_ < x1; ++tx) {
            exr_chunk_info_t chunk{};
            if (exr_read_tile_chunk_info(c, part_, tx, ty, level, level, &chunk) !=
                EXR_ERR_SUCCESS) {
                why = "OpenEXR: the chunk of tile (" + std::to_string(tx) + ", " +
                      std::to_string(ty) + ") of level " + std::to_string(level) +
                      " is missing or corrupt";
                return false;
            }
            std::string exr_why;
            if (!decoder.decode(chunk, plane_of.data(), /*as_float=*/true, exr_why)) {
                why = "OpenEXR: " + exr_why;
                return false;
            }
            std::uint8_t* corner = reinterpret_cast<std::uint8_t*>(texels) +
                                   static_cast<std::size_t>(ty * tile_height_ - y0) * row_bytes +
                                   static_cast<std::size_t>(tx * tile_width_ - x0) * pixel_bytes;
            detail::interleave_exr_planes(file_channels, plane_of.data(), element_bytes_.data(),
                                          offsets_.data(), chunk.width, chunk.height, corner,
                                          pixel_bytes, row_bytes);
        }
    }
    return true;
}

}  // namespace footprint::texsys
