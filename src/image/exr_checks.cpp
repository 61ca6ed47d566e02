// image/exr_checks.cpp — the checks of an OpenEXR file's headers (format_checks.h), through
// OpenEXR's core library and a walk of the headers as OpenEXR's C++ reader makes it.
#include <openexr.h>

#include <algorithm>
#include <array>
#include <istream>
#include <limits>
#include <string_view>
#include <utility>
#include <vector>

#include "core/result.h"
#include "image/format_checks.h"

namespace footprint::detail {
namespace {

namespace fs = std::filesystem;

// The message of the first error OpenEXR's core library reports while exr_start_read() runs on
// this thread. Its error callback gets no pointer of ours (the context's user_data belongs to
// the default file reader), so the destination is a thread-local.
thread_local std::string* exr_first_error = nullptr;

void keep_first_exr_error(exr_const_context_t, exr_result_t, const char* message) {
    if (exr_first_error != nullptr && exr_first_error->empty()) *exr_first_error = message;
}

// A data window's width and height in texels; 0 for an inverted (corrupt) one.
struct WindowExtent {
    std::uint64_t width = 0, height = 0;
};
WindowExtent extent_of(const exr_attr_box2i_t& window) {
    const auto extent = [](int min, int max) {
        return static_cast<std::uint64_t>(std::max<std::int64_t>(std::int64_t{max} - min + 1, 0));
    };
    return {extent(window.min.x, window.max.x), extent(window.min.y, window.max.y)};
}

// The first part of an open OpenEXR file whose tiles tile_problem() refuses, and why.
std::optional<std::string> exr_tile_problem(exr_const_context_t context) {
    int parts = 0;
    if (exr_get_count(context, &parts) != EXR_ERR_SUCCESS) return std::nullopt;
    for (int part = 0; part < parts; ++part) {
        exr_storage_t storage{};
        std::uint32_t tile_width = 0, tile_height = 0;
        exr_tile_level_mode_t levels{};
        exr_tile_round_mode_t rounding{};
        exr_attr_box2i_t window{};
        if (exr_get_storage(context, part, &storage) != EXR_ERR_SUCCESS ||
            (storage != EXR_STORAGE_TILED && storage != EXR_STORAGE_DEEP_TILED) ||
            exr_get_tile_descriptor(context, part, &tile_width, &tile_height, &levels, &rounding) !=
                EXR_ERR_SUCCESS ||
            exr_get_data_window(context, part, &window) != EXR_ERR_SUCCESS) {
            continue;
        }
        const WindowExtent extent = extent_of(window);
        if (auto cause = tile_problem(tile_width, tile_height, extent.width, extent.height)) {
            return "part " + std::to_string(part) + ": " + *cause;
        }
    }
    return std::nullopt;
}

// a × b, or the largest value where it would pass 2^64: a corrupt window's extents, times the
// channels, can.
std::uint64_t saturating_product(std::uint64_t a, std::uint64_t b) {
    return b != 0 && a > std::numeric_limits<std::uint64_t>::max() / b
               ? std::numeric_limits<std::uint64_t>::max()
               : a * b;
}

// The most uncompressed bytes one byte of an OpenEXR part's compression (its attribute's byte)
// can hold: deflate (zip, zips, and pxr24 after its rounding) codes at most 258 bytes in two bits,
// run lengths (rle) 128 bytes in two, and PIZ's Huffman coder at most 255 of its 16-bit words in 9
// bits (a code of a bit that repeats the last word, and its 8-bit count), 453⅓ bytes in one; 0
// where no useful bound is known (DWA) or where it depends on the channels' types (B44:
// b44_fewest_bytes).
std::uint64_t exr_best_ratio(std::uint8_t compression) {
    switch (compression) {
        case EXR_COMPRESSION_NONE:
            return 1;
        case EXR_COMPRESSION_RLE:
            return 64;
        case EXR_COMPRESSION_ZIPS:
        case EXR_COMPRESSION_ZIP:
        case EXR_COMPRESSION_PXR24:
            return 1032;
        case EXR_COMPRESSION_PIZ:
            return 454;
        default:
            return 0;
    }
}

// The fewest bytes B44 codes `texels` texels of `channels` in: 14 bytes a 4 × 4 block of a half
// channel, or in B44A (`flat_blocks`) 3 for a block of one value; float and uint channels it
// leaves as they are, 4 bytes a value.
std::uint64_t b44_fewest_bytes(const exr_attr_chlist_t& channels, std::uint64_t texels,
                               bool flat_blocks) {
    const std::uint64_t half_block_bytes = flat_blocks ? 3 : 14;
    std::uint64_t bytes = 0;
    for (int c = 0; c < channels.num_channels; ++c) {
        const std::uint64_t channel = channels.entries[c].pixel_type == EXR_PIXEL_HALF
                                          ? saturating_product(texels / 16, half_block_bytes)
                                          : saturating_product(texels, 4);
        bytes = std::min(bytes, std::numeric_limits<std::uint64_t>::max() - channel) + channel;
    }
    return bytes;
}

// The bytes a texel of `channels` takes before a lossless codec packs it: 2 a half value, 4 a
// float or uint value, but 3 a float value where PXR24 (`pxr24`) rounds it to 24 bits first.
std::uint64_t exr_texel_bytes(const exr_attr_chlist_t& channels, bool pxr24) {
    std::uint64_t bytes = 0;
    for (int c = 0; c < channels.num_channels; ++c) {
        switch (channels.entries[c].pixel_type) {
            case EXR_PIXEL_HALF:
                bytes += 2;
                break;
            case EXR_PIXEL_FLOAT:
                bytes += pxr24 ? 3 : 4;
                break;
            default:
                bytes += 4;
                break;
        }
    }
    return bytes;
}

// The fewest bytes part `part` of an open OpenEXR file takes: each chunk (a block of rows or a
// tile) an 8-byte entry in the chunk table and a header of at least 8 bytes, and its texels
// (OpenImageIO reads no subsampled channels) at the best ratio its compression allows, or as B44
// codes them.
std::uint64_t exr_fewest_bytes(exr_const_context_t context, int part) {
    constexpr std::uint64_t kFewestBytesPerChunk = 16;
    std::int32_t chunks = 0;
    const exr_attribute_t* compression = nullptr;
    exr_attr_box2i_t window{};
    const exr_attr_chlist_t* channels = nullptr;
    if (exr_get_chunk_count(context, part, &chunks) != EXR_ERR_SUCCESS || chunks < 0 ||
        exr_get_attribute_by_name(context, part, "compression", &compression) != EXR_ERR_SUCCESS ||
        compression == nullptr || compression->type != EXR_ATTR_COMPRESSION ||
        exr_get_data_window(context, part, &window) != EXR_ERR_SUCCESS ||
        exr_get_channels(context, part, &channels) != EXR_ERR_SUCCESS || channels == nullptr)
        return 0;
    const std::uint64_t table = static_cast<std::uint64_t>(chunks) * kFewestBytesPerChunk;
    const WindowExtent extent = extent_of(window);
    const std::uint64_t texels = saturating_product(extent.width, extent.height);
    const std::uint8_t codec = compression->uc;
    if (codec == EXR_COMPRESSION_B44 || codec == EXR_COMPRESSION_B44A)
        return std::max(table, b44_fewest_bytes(*channels, texels, codec == EXR_COMPRESSION_B44A));
    const std::uint64_t ratio = exr_best_ratio(codec);
    if (ratio == 0) return table;
    const std::uint64_t texel_bytes = exr_texel_bytes(*channels, codec == EXR_COMPRESSION_PXR24);
    return std::max(table, saturating_product(texels, texel_bytes) / ratio);
}

// Why the open OpenEXR file of `file_bytes` bytes cannot hold what its headers claim, if it
// cannot. A few hundred bytes of header can claim gigabytes, for which OpenEXR's reader allocates
// line buffers as it opens the file, and footprint the image, before the data runs out.
std::optional<std::string> exr_size_problem(exr_const_context_t context,
                                            std::uintmax_t file_bytes) {
    int parts = 0;
    if (exr_get_count(context, &parts) != EXR_ERR_SUCCESS) return std::nullopt;
    for (int part = 0; part < parts; ++part) {
        exr_attr_box2i_t window{};
        if (exr_fewest_bytes(context, part) <= file_bytes ||
            exr_get_data_window(context, part, &window) != EXR_ERR_SUCCESS)
            continue;
        const WindowExtent extent = extent_of(window);
        return std::string(parts > 1 ? "part " + std::to_string(part) + ": " : "") +
               claims_more_texels_than_bytes(extent.width, extent.height, file_bytes);
    }
    return std::nullopt;
}

// Whether OpenEXR's core library reads the leader of each chunk of the tiled part `part`: tile by
// tile, level by level (mipmaps l × l, ripmaps every lx × ly).
bool exr_tiles_readable(exr_const_context_t context, int part) {
    exr_tile_level_mode_t mode{};
    std::int32_t levels_x = 0, levels_y = 0;
    if (exr_get_tile_descriptor(context, part, nullptr, nullptr, &mode, nullptr) !=
            EXR_ERR_SUCCESS ||
        exr_get_tile_levels(context, part, &levels_x, &levels_y) != EXR_ERR_SUCCESS)
        return false;
    for (int ly = 0; ly < levels_y; ++ly) {
        for (int lx = 0; lx < levels_x; ++lx) {
            if (mode != EXR_TILE_RIPMAP_LEVELS && lx != ly) continue;
            std::int32_t width = 0, height = 0, tile_width = 0, tile_height = 0;
            if (exr_get_level_sizes(context, part, lx, ly, &width, &height) != EXR_ERR_SUCCESS ||
                exr_get_tile_sizes(context, part, lx, ly, &tile_width, &tile_height) !=
                    EXR_ERR_SUCCESS ||
                tile_width <= 0 || tile_height <= 0)
                return false;
            for (int ty = 0; ty * tile_height < height; ++ty) {
                for (int tx = 0; tx * tile_width < width; ++tx) {
                    exr_chunk_info_t chunk{};
                    if (exr_read_tile_chunk_info(context, part, tx, ty, lx, ly, &chunk) !=
                        EXR_ERR_SUCCESS)
                        return false;
                }
            }
        }
    }
    return true;
}

// Whether OpenEXR's core library reads the leader of each chunk (block of rows) of the part
// `part`, which is stored in scanlines.
bool exr_scanlines_readable(exr_const_context_t context, int part) {
    exr_attr_box2i_t window{};
    std::int32_t rows_per_chunk = 0;
    if (exr_get_data_window(context, part, &window) != EXR_ERR_SUCCESS ||
        exr_get_scanlines_per_chunk(context, part, &rows_per_chunk) != EXR_ERR_SUCCESS ||
        rows_per_chunk <= 0)
        return false;
    for (std::int64_t y = window.min.y; y <= window.max.y; y += rows_per_chunk) {
        exr_chunk_info_t chunk{};
        if (exr_read_scanline_chunk_info(context, part, static_cast<int>(y), &chunk) !=
            EXR_ERR_SUCCESS)
            return false;
    }
    return true;
}

// The first part of the open OpenEXR file with a chunk whose place in the chunk table or whose
// leader (its coordinates and size) OpenEXR's core library finds corrupt. OpenEXR 3.1's C++
// reader, OpenImageIO's, rebuilds a table with missing entries by walking the chunks, and can then
// read a part as zeros without an error: a silent black image. The core library, which rebuilds
// the table the same way, checks each chunk it finds.
std::optional<std::string> exr_chunk_problem(exr_const_context_t context) {
    int parts = 0;
    if (exr_get_count(context, &parts) != EXR_ERR_SUCCESS) return std::nullopt;
    for (int part = 0; part < parts; ++part) {
        exr_storage_t storage{};
        if (exr_get_storage(context, part, &storage) != EXR_ERR_SUCCESS) continue;
        const bool tiled = storage == EXR_STORAGE_TILED || storage == EXR_STORAGE_DEEP_TILED;
        std::string report;
        exr_first_error = &report;
        const bool readable =
            tiled ? exr_tiles_readable(context, part) : exr_scanlines_readable(context, part);
        exr_first_error = nullptr;
        if (readable) continue;
        return "the OpenEXR file is corrupt (" +
               (parts > 1 ? "part " + std::to_string(part) + ": " : std::string()) +
               "a chunk of texels is missing or corrupt" +
               (report.empty() ? "" : "; OpenEXR: " + report) + ")";
    }
    return std::nullopt;
}

// A NUL-terminated name of at most 255 characters from `in`, as OpenEXR's C++ reader reads one;
// nothing if the file ends first or the name is longer (that reader then fails by itself).
std::optional<std::string> read_exr_name(std::istream& in) {
    std::string name;
    for (int c = in.get(); c != 0; c = in.get()) {
        if (c == EOF || name.size() == 255) return std::nullopt;
        name += static_cast<char>(c);
    }
    return name;
}

std::optional<std::uint32_t> read_u32_le(std::istream& in) {
    std::array<unsigned char, 4> b{};
    if (!in.read(reinterpret_cast<char*>(b.data()), b.size())) return std::nullopt;
    return std::uint32_t{b[0]} | (std::uint32_t{b[1]} << 8) | (std::uint32_t{b[2]} << 16) |
           (std::uint32_t{b[3]} << 24);
}

// The bytes OpenEXR 3.1's C++ reader reads for the value of an attribute of type `type` whatever
// the size the file states for it, or nothing for the types it reads by that size (strings,
// vectors, previews, whose size it checks against their width and height, unknown types) or by
// their contents (chlist).
std::optional<std::uint64_t> exr_fixed_value_bytes(std::string_view type) {
    static constexpr std::array<std::pair<std::string_view, std::uint64_t>, 24> kBytes{
        {{"box2i", 16},
         {"box2f", 16},
         {"chromaticities", 32},
         {"compression", 1},
         {"deepImageState", 1},
         {"double", 8},
         {"envmap", 1},
         {"float", 4},
         {"int", 4},
         {"keycode", 28},
         {"lineOrder", 1},
         {"m33d", 72},
         {"m33f", 36},
         {"m44d", 128},
         {"m44f", 64},
         {"rational", 8},
         {"tiledesc", 9},
         {"timecode", 8},
         {"v2d", 16},
         {"v2f", 8},
         {"v2i", 8},
         {"v3d", 24},
         {"v3f", 12},
         {"v3i", 12}}};
    for (const auto& [name, bytes] : kBytes)
        if (name == type) return bytes;
    return std::nullopt;
}

// The bytes OpenEXR 3.1's C++ reader reads for the value of the attribute of `type` and stated
// `size` that starts where `in` is, leaving `in` there; nothing if the file ends first.
std::optional<std::uint64_t> exr_value_bytes(std::istream& in, std::string_view type,
                                             std::uint32_t size) {
    if (const auto fixed = exr_fixed_value_bytes(type)) return fixed;
    if (type != "chlist") return size;
    // Channels up to an empty name, each its name and 16 bytes.
    const std::streampos start = in.tellg();
    for (std::optional<std::string> name; (name = read_exr_name(in)) && !name->empty();)
        in.seekg(16, std::ios::cur);
    const std::optional<std::uint64_t> bytes =
        in ? std::optional<std::uint64_t>(in.tellg() - start) : std::nullopt;
    in.clear();
    in.seekg(start);
    return bytes;
}

// An attribute as OpenEXR 3.1's C++ reader reads it: its name, type and the bytes of its value.
struct ExrCxxAttribute {
    std::string name, type, value;
};

// The headers of an OpenEXR file as OpenEXR 3.1's C++ reader reads them: each part's attributes,
// and where the chunk tables that follow them start, unless that reader fails before it gets
// there.
struct ExrCxxHeaders {
    std::vector<std::vector<ExrCxxAttribute>> parts;
    std::optional<std::uint64_t> tables_at;
};

// The headers of the OpenEXR file `in` (of `file_bytes` bytes) as OpenEXR 3.1's C++ reader,
// which OpenImageIO 2.4 reads with, walks them: names of up to 255 characters in any file, and
// each value read by its type (see exr_value_bytes), so that on a corrupt file its walk can part
// from the core library's; or why that reader would allocate more for a value than the file
// holds.
Result<ExrCxxHeaders> exr_cxx_headers(std::istream& in, std::uintmax_t file_bytes) {
    constexpr std::uint32_t kMultiPart = 0x1000;
    constexpr std::uint64_t kKeptValueBytes = 1024;  // enough for every value compared below
    in.clear();
    in.seekg(4);  // after the magic number
    const std::optional<std::uint32_t> version = read_u32_le(in);
    ExrCxxHeaders headers;
    if (!version) return headers;
    do {
        std::vector<ExrCxxAttribute>& header = headers.parts.emplace_back();
        std::optional<std::string> name;
        while ((name = read_exr_name(in)) && !name->empty()) {
            const std::optional<std::string> type = read_exr_name(in);
            const std::optional<std::uint32_t> size = type ? read_u32_le(in) : std::nullopt;
            if (!size || *size > 0x7fffffffu) return headers;  // the reader fails by itself
            const std::optional<std::uint64_t> bytes = exr_value_bytes(in, *type, *size);
            const auto at = static_cast<std::uint64_t>(in.tellg());
            if (!bytes || at + *bytes > file_bytes) {
                return Error{"the OpenEXR header is corrupt (its attribute '" + *name +
                             "' claims more bytes than the file holds)"};
            }
            std::string value(std::min(*bytes, kKeptValueBytes), '\0');
            in.read(value.data(), static_cast<std::streamsize>(value.size()));
            header.push_back({*name, *type, std::move(value)});
            in.seekg(static_cast<std::streamoff>(at + *bytes));
        }
        if (!name) return headers;  // the reader fails by itself
    } while ((*version & kMultiPart) && in.peek() != 0 && in.peek() != EOF);
    // A multi-part file's headers end with an empty one.
    if ((*version & kMultiPart) && in.get() != 0) return headers;
    headers.tables_at = static_cast<std::uint64_t>(in.tellg());
    return headers;
}

// The chunks of all parts of the open OpenEXR file: its chunk tables' entries.
std::uint64_t exr_chunks(exr_const_context_t context) {
    int parts = 0;
    std::uint64_t chunks = 0;
    if (exr_get_count(context, &parts) != EXR_ERR_SUCCESS) return 0;
    for (int part = 0; part < parts; ++part) {
        std::int32_t count = 0;
        if (exr_get_chunk_count(context, part, &count) == EXR_ERR_SUCCESS && count > 0)
            chunks += static_cast<std::uint64_t>(count);
    }
    return chunks;
}

// Whether the chunk tables of the OpenEXR file `in`, `chunks` offsets of 8 bytes from `tables_at`,
// miss an entry: one ≤ 0 as a signed offset, or the file ends first. OpenEXR writes the tables
// last, and its C++ reader takes such a table for one whose writer stopped, and walks the chunks to
// find their places instead.
bool exr_tables_incomplete(std::istream& in, std::uint64_t tables_at, std::uint64_t chunks) {
    in.clear();
    in.seekg(static_cast<std::streamoff>(tables_at));
    for (std::uint64_t i = 0; i < chunks; ++i) {
        std::array<unsigned char, 8> b{};
        if (!in.read(reinterpret_cast<char*>(b.data()), b.size())) return true;
        std::uint64_t offset = 0;
        for (std::size_t k = 0; k < b.size(); ++k) offset |= std::uint64_t{b[k]} << (8 * k);
        if (static_cast<std::int64_t>(offset) <= 0) return true;
    }
    return false;
}

std::int32_t i32_le(std::string_view bytes, std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i)
        v |= std::uint32_t{static_cast<unsigned char>(bytes[at + i])} << (8 * i);
    return static_cast<std::int32_t>(v);
}

// Whether the attribute `cxx`, as the C++ reader read it, has the type and the value of `core`,
// the same as the core library read it, for the types that size what OpenImageIO reads (channel
// lists, compression, windows, tiles). Raw bytes, never enums: a corrupt file's rounding mode can
// be 7.
bool exr_value_agrees(const exr_attribute_t& core, const ExrCxxAttribute& cxx) {
    const std::string_view v = cxx.value;
    const auto byte = [&](std::size_t at) { return static_cast<unsigned char>(v[at]); };
    if (cxx.type != core.type_name) return false;
    switch (core.type) {
        case EXR_ATTR_BOX2I:
            return v.size() == 16 && core.box2i->min.x == i32_le(v, 0) &&
                   core.box2i->min.y == i32_le(v, 4) && core.box2i->max.x == i32_le(v, 8) &&
                   core.box2i->max.y == i32_le(v, 12);
        case EXR_ATTR_COMPRESSION:
            return v.size() == 1 && core.uc == byte(0);
        case EXR_ATTR_TILEDESC:
            return v.size() == 9 &&
                   core.tiledesc->x_size == static_cast<std::uint32_t>(i32_le(v, 0)) &&
                   core.tiledesc->y_size == static_cast<std::uint32_t>(i32_le(v, 4)) &&
                   core.tiledesc->level_and_round == byte(8);
        case EXR_ATTR_CHLIST: {  // names, each followed by 16 bytes, up to an empty one
            std::size_t at = 0;
            for (int c = 0; c < core.chlist->num_channels; ++c) {
                const exr_attr_string_t& name = core.chlist->entries[c].name;
                const std::string entry =
                    std::string(name.str, static_cast<std::size_t>(name.length)) + '\0';
                if (v.substr(at, entry.size()) != entry) return false;
                at += entry.size() + 16;
            }
            return v.substr(at) == std::string_view("\0", 1);
        }
        default:
            return true;
    }
}

// Why OpenImageIO 2.4 would read the headers of the open OpenEXR file, `cxx` as OpenEXR's C++
// reader reads them, otherwise than the core library's checks saw them, if it would: footprint's
// checks of sizes, tiles and chunks hold for what OpenImageIO reads only if that reader finds the
// same attributes, and the same values for those that size the image.
std::optional<std::string> exr_reader_agreement_problem(
    exr_const_context_t context, const std::vector<std::vector<ExrCxxAttribute>>& cxx) {
    int parts = 0;
    if (exr_get_count(context, &parts) != EXR_ERR_SUCCESS) return std::nullopt;
    // The core library lists a header's attributes in the file's order, then the required ones
    // the file lacks, with their defaults (as the C++ reader's defaults stand in for them).
    constexpr std::array<std::string_view, 8> kRequired{
        "channels",  "compression",      "dataWindow",         "displayWindow",
        "lineOrder", "pixelAspectRatio", "screenWindowCenter", "screenWindowWidth"};
    bool agree = cxx.size() == static_cast<std::size_t>(parts);
    for (int part = 0; agree && part < parts; ++part) {
        int count = 0;
        const std::vector<ExrCxxAttribute>& header = cxx[static_cast<std::size_t>(part)];
        agree = exr_get_attribute_count(context, part, &count) == EXR_ERR_SUCCESS &&
                static_cast<std::size_t>(count) >= header.size();
        for (int i = 0; agree && i < count; ++i) {
            const exr_attribute_t* core = nullptr;
            const auto at = static_cast<std::size_t>(i);
            agree = exr_get_attribute_by_index(context, part, EXR_ATTR_LIST_FILE_ORDER, i, &core) ==
                        EXR_ERR_SUCCESS &&
                    core != nullptr &&
                    (at < header.size()
                         ? header[at].name == core->name && exr_value_agrees(*core, header[at])
                         : std::find(kRequired.begin(), kRequired.end(),
                                     std::string_view(core->name)) != kRequired.end());
        }
    }
    if (agree) return std::nullopt;
    return std::string("the OpenEXR header is corrupt (OpenEXR's two readers read it differently)");
}

// The first problem of an OpenEXR file, open as `context` and as `in`, that the core library
// does not report as it opens it.
std::optional<std::string> exr_layout_problem(exr_const_context_t context, std::istream& in) {
    in.clear();
    in.seekg(0, std::ios::end);
    const std::streampos end = in.tellg();
    if (end < 0) return std::string("its size cannot be read");
    const auto file_bytes = static_cast<std::uintmax_t>(end);
    const Result<ExrCxxHeaders> cxx = exr_cxx_headers(in, file_bytes);
    if (!cxx) return cxx.error().message;
    if (auto cause = exr_reader_agreement_problem(context, cxx->parts)) return cause;
    if (auto cause = exr_tile_problem(context)) return cause;
    if (auto cause = exr_size_problem(context, file_bytes)) return cause;
    // Reading the chunks' leaders costs a read a chunk (thousands for a large tiled pyramid), so
    // they are read only where OpenEXR's C++ reader would not find the chunks from the tables.
    if (cxx->tables_at && !exr_tables_incomplete(in, *cxx->tables_at, exr_chunks(context)))
        return std::nullopt;
    return exr_chunk_problem(context);
}

}  // namespace

// The first problem OpenEXR's core library finds in the OpenEXR file `file` (open as `in`), in its
// headers or its chunks. OpenEXRCore checks every attribute against the format's rules and the
// file's length before it allocates, and each chunk's place and leader; OpenEXR 3.1's C++ reader,
// which OpenImageIO 2.4 reads with, allocates what a corrupt size claims, and reads some missing
// chunks as zeros.
std::optional<std::string> exr_problem(const fs::path& file, std::istream& in) {
    std::string first_error;
    exr_first_error = &first_error;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = keep_first_exr_error;
    exr_context_t context = nullptr;
    const exr_result_t result = exr_start_read(&context, file.c_str(), &init);
    exr_first_error = nullptr;
    std::optional<std::string> layout;
    if (result == EXR_ERR_SUCCESS) {
        if (first_error.empty()) layout = exr_layout_problem(context, in);
        exr_finish(&context);
    }
    // The core library's lenient parse skips an attribute it finds corrupt, reports it and
    // succeeds; OpenEXR's C++ reader would still read that attribute. So any report refuses.
    if (result == EXR_ERR_SUCCESS && first_error.empty()) return layout;
    if (first_error.empty()) first_error = exr_get_default_error_message(result);
    return "the OpenEXR header is corrupt (OpenEXR: " + first_error + ")";
}

}  // namespace footprint::detail
