#include "texsys/exr_tiles.h"

#include <openexr.h>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <string_view>
#include <vector>

namespace footprint::texsys {

namespace {

// The message of the last error OpenEXR's core library reported on this thread: its error
// callback gets no pointer of ours, and a context is shared by the threads reading it.
thread_local std::string last_exr_error;

void keep_exr_error(exr_const_context_t, exr_result_t, const char* message) {
    last_exr_error = message;
}

std::string exr_error(exr_result_t result) {
    return last_exr_error.empty() ? exr_get_default_error_message(result) : last_exr_error;
}

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
    init.error_handler_fn = keep_exr_error;
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
    for (int i = 0; i < list->num_channels; ++i) {
        const exr_attr_chlist_entry_t& entry = list->entries[i];
        if (entry.x_sampling != 1 || entry.y_sampling != 1 || entry.pixel_type == EXR_PIXEL_UINT)
            return nullptr;
        found += std::count(channels.begin(), channels.end(),
                            std::string_view(entry.name.str, std::size_t(entry.name.length)));
    }
    if (found != channels.size()) return nullptr;
    return std::unique_ptr<ExrTiles>(new ExrTiles(std::move(context), part, channels,
                                                  static_cast<int>(tile_width),
                                                  static_cast<int>(tile_height)));
}

bool ExrTiles::read(int level, int x0, int x1, int y0, int y1, float* texels,
                    std::string& why) const {
    const exr_const_context_t c = context_->context;
    const int channels = static_cast<int>(channels_.size());
    const std::size_t row_floats = static_cast<std::size_t>(x1 - x0) * channels;
    // Each channel is decoded into a plane of its own, then interleaved: OpenEXR 3.1's decoder
    // writes half channels interleaved straight to floats in the file's order, whatever the
    // pointers ask (ExrTiles.LevelsReadAsOpenImageIOReadsThem catches it).
    thread_local std::vector<float> planes;
    const std::size_t plane_floats = static_cast<std::size_t>(tile_width_) * tile_height_;
    if (planes.size() < plane_floats * channels) planes.resize(plane_floats * channels);
    for (int ty = y0 / tile_height_; ty * tile_height_ < y1; ++ty) {
        for (int tx = x0 / tile_width_; tx * tile_width_ < x1; ++tx) {
            last_exr_error.clear();
            exr_chunk_info_t chunk{};
            exr_decode_pipeline_t decoder = EXR_DECODE_PIPELINE_INITIALIZER;
            exr_result_t result = exr_read_tile_chunk_info(c, part_, tx, ty, level, level, &chunk);
            if (result == EXR_ERR_SUCCESS)
                result = exr_decoding_initialize(c, part_, &chunk, &decoder);
            if (result == EXR_ERR_SUCCESS) {
                for (int i = 0; i < decoder.channel_count; ++i) {
                    exr_coding_channel_info_t& channel = decoder.channels[i];
                    const auto k = std::find(channels_.begin(), channels_.end(),
                                             std::string_view(channel.channel_name)) -
                                   channels_.begin();
                    channel.decode_to_ptr =
                        k == channels ? nullptr
                                      : reinterpret_cast<std::uint8_t*>(&planes[k * plane_floats]);
                    channel.user_data_type = EXR_PIXEL_FLOAT;
                    channel.user_bytes_per_element = sizeof(float);
                    channel.user_pixel_stride = sizeof(float);
                    channel.user_line_stride =
                        static_cast<std::int32_t>(chunk.width * sizeof(float));
                }
                result = exr_decoding_choose_default_routines(c, part_, &decoder);
            }
            if (result == EXR_ERR_SUCCESS) result = exr_decoding_run(c, part_, &decoder);
            exr_decoding_destroy(c, &decoder);
            if (result != EXR_ERR_SUCCESS) {
                why = "OpenEXR: " + exr_error(result);
                return false;
            }
            float* corner = texels + static_cast<std::size_t>(ty * tile_height_ - y0) * row_floats +
                            static_cast<std::size_t>(tx * tile_width_ - x0) * channels;
            for (int y = 0; y < chunk.height; ++y) {
                float* row = corner + y * row_floats;
                for (int x = 0; x < chunk.width; ++x)
                    for (int k = 0; k < channels; ++k)
                        row[x * channels + k] =
                            planes[k * plane_floats + static_cast<std::size_t>(y) * chunk.width +
                                   x];
            }
        }
    }
    return true;
}

}  // namespace footprint::texsys
