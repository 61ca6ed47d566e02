// image/exr_decode.cpp — an OpenEXR part's chunks decoded through OpenEXR's core library
// (exr_decode.h).
#include "image/exr_decode.h"

#include <cstring>

namespace footprint::detail {
namespace {

// The first message OpenEXR's core library reported on this thread since the last decode began:
// its error callback gets no pointer of ours, and a context is shared by the threads reading it.
// (The first, "Unable to decompress image data 384 -> 6000", says more than the last, "Decode
// pipeline unable to decompress data".)
thread_local std::string first_exr_error;

void keep_first_exr_error(exr_const_context_t, exr_result_t, const char* message) {
    if (first_exr_error.empty() && message != nullptr) first_exr_error = message;
}

template <std::size_t kBytes>
void interleave_plane(const std::uint8_t* plane, int width, int height, std::uint8_t* pixels,
                      std::size_t pixel_bytes, std::size_t row_bytes) {
    for (int y = 0; y < height; ++y) {
        const std::uint8_t* from = plane + static_cast<std::size_t>(y) * width * kBytes;
        std::uint8_t* to = pixels + static_cast<std::size_t>(y) * row_bytes;
        for (int x = 0; x < width; ++x)
            std::memcpy(to + x * pixel_bytes, from + x * kBytes, kBytes);
    }
}

}  // namespace

void keep_exr_errors(exr_context_initializer_t& init) {
    init.error_handler_fn = keep_first_exr_error;
}

ExrChunkDecoder::~ExrChunkDecoder() {
    if (started_) exr_decoding_destroy(context_, &pipeline_);
}

bool ExrChunkDecoder::decode(const exr_chunk_info_t& chunk, std::uint8_t* const* planes,
                             bool as_float, std::string& why) {
    first_exr_error.clear();
    exr_result_t result = EXR_ERR_SUCCESS;
    if (!started_) {
        result = exr_decoding_initialize(context_, part_, &chunk, &pipeline_);
        started_ = result == EXR_ERR_SUCCESS;
    } else {
        result = exr_decoding_update(context_, part_, &chunk, &pipeline_);
    }
    if (result == EXR_ERR_SUCCESS) {
        for (int i = 0; i < pipeline_.channel_count; ++i) {
            exr_coding_channel_info_t& channel = pipeline_.channels[i];
            // Planes, not interleaved pixels: OpenEXR 3.1's decoder writes half channels
            // interleaved straight to floats in the file's order, whatever the pointers ask
            // (ExrTiles.LevelsReadAsOpenImageIOReadsThem catches it).
            const int bytes =
                as_float ? static_cast<int>(sizeof(float)) : channel.bytes_per_element;
            channel.decode_to_ptr = planes[i];
            channel.user_data_type =
                as_float ? static_cast<std::uint16_t>(EXR_PIXEL_FLOAT) : channel.data_type;
            channel.user_bytes_per_element = static_cast<std::int8_t>(bytes);
            channel.user_pixel_stride = bytes;
            channel.user_line_stride = static_cast<std::int32_t>(chunk.width * bytes);
        }
        result = exr_decoding_choose_default_routines(context_, part_, &pipeline_);
    }
    if (result == EXR_ERR_SUCCESS) result = exr_decoding_run(context_, part_, &pipeline_);
    if (result == EXR_ERR_SUCCESS) return true;
    why = first_exr_error.empty() ? exr_get_default_error_message(result) : first_exr_error;
    // A pipeline that failed part-way starts afresh for the next chunk.
    exr_decoding_destroy(context_, &pipeline_);
    pipeline_ = exr_decode_pipeline_t{};
    started_ = false;
    return false;
}

void interleave_exr_planes(int channels, const std::uint8_t* const* planes,
                           const int* element_bytes, const std::size_t* offsets, int width,
                           int height, std::uint8_t* pixels, std::size_t pixel_bytes,
                           std::size_t row_bytes) {
    for (int k = 0; k < channels; ++k) {
        if (planes[k] == nullptr) continue;
        if (element_bytes[k] == 2)
            interleave_plane<2>(planes[k], width, height, pixels + offsets[k], pixel_bytes,
                                row_bytes);
        else
            interleave_plane<4>(planes[k], width, height, pixels + offsets[k], pixel_bytes,
                                row_bytes);
    }
}

}  // namespace footprint::detail
