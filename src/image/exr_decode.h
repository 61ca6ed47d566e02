// image/exr_decode.h — an OpenEXR part's chunks decoded through OpenEXR's core library, private to
// the modules that read OpenEXR texels (image: load_image's OpenEXR texels; texsys: ExrTiles).
//
// OpenEXR 3.1's C++ reader, OpenImageIO 2.4's, leaves the rest of a chunk's rows as they were when
// its codec unpacks fewer bytes than those rows take: a file whose data window was widened after
// it was written loads without an error, most of its texels zero. The core library checks every
// chunk's unpacked size and refuses the chunk (EXR_ERR_CORRUPT_CHUNK). OpenImageIO still opens
// the file and gives its header; only the texels are decoded here.
#pragma once

#include <openexr.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace footprint::detail {

// Sets `init`'s error handler to one that keeps, on the thread that reports it, the first message
// since the last decode started: ExrChunkDecoder::decode's `why`.
void keep_exr_errors(exr_context_initializer_t& init);

// The pipeline that decodes chunks of one part of an open file, its buffers reused from chunk to
// chunk. One per thread: a context is read from any number of threads at once, a decoder from one.
class ExrChunkDecoder {
  public:
    ExrChunkDecoder(exr_const_context_t context, int part) : context_(context), part_(part) {}
    ~ExrChunkDecoder();
    ExrChunkDecoder(const ExrChunkDecoder&) = delete;
    ExrChunkDecoder& operator=(const ExrChunkDecoder&) = delete;

    // Decodes `chunk` (its leader as exr_read_scanline_chunk_info() or exr_read_tile_chunk_info()
    // gives it) into planes: the part's channel i (the file's order) into planes[i], or not at all
    // where planes[i] is null; rows of chunk.width elements, chunk.height rows, packed. Each
    // element is a float where `as_float`, else as stored (a half's 2 bytes, a float's or a uint's
    // 4). The channels must not be subsampled. On failure (a chunk that cannot be read, is corrupt
    // or unpacks to fewer bytes than its rows take) returns false and sets `why` to OpenEXR's
    // words.
    bool decode(const exr_chunk_info_t& chunk, std::uint8_t* const* planes, bool as_float,
                std::string& why);

  private:
    exr_const_context_t context_;
    int part_;
    exr_decode_pipeline_t pipeline_{};  // OpenEXR's EXR_DECODE_PIPELINE_INITIALIZER: all zero
    bool started_ = false;
};

// Interleaves `channels` planes of `width` × `height` elements into pixels: element x of row y of
// plane k (elements of element_bytes[k] bytes, 2 or 4) goes to pixels + y·row_bytes + x·pixel_bytes
// + offsets[k]. Planes that are null are skipped.
void interleave_exr_planes(int channels, const std::uint8_t* const* planes,
                           const int* element_bytes, const std::size_t* offsets, int width,
                           int height, std::uint8_t* pixels, std::size_t pixel_bytes,
                           std::size_t row_bytes);

}  // namespace footprint::detail
