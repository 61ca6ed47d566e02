// image/image_input.cpp — the checks before OpenImageIO's readers see a file (image_input.h).
#include "image/image_input.h"

#include <openexr.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace footprint::detail {
namespace {

namespace fs = std::filesystem;

// What a file's first bytes say it is: only these formats have checks of their own.
enum class Signature { png, exr, jpeg, other };

// Checks that `file` is an existing, non-empty, readable regular file (clearer messages than
// OpenImageIO gives for these cases), opens it as `in` and reads its signature (`in` is left after
// a PNG's or a JPEG's).
Result<Signature> open_checked(const fs::path& file, std::ifstream& in) {
    std::error_code ec;
    const fs::file_status st = fs::status(file, ec);
    if (st.type() == fs::file_type::not_found) return read_error(file, "no such file");
    if (ec) return read_error(file, ec.message());
    if (st.type() == fs::file_type::directory) return read_error(file, "it is a directory");
    if (st.type() != fs::file_type::regular) return read_error(file, "it is not a regular file");
    const std::uintmax_t size = fs::file_size(file, ec);
    if (!ec && size == 0) return read_error(file, "the file is empty");
    errno = 0;
    in.open(file, std::ios::binary);
    if (!in) {
        return read_error(file, "cannot open it: " + std::generic_category().message(errno));
    }
    constexpr std::array<char, 8> kPng = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};
    constexpr std::array<char, 4> kExr = {'\x76', '\x2f', '\x31', '\x01'};
    std::array<char, 8> head{};
    in.read(head.data(), head.size());
    const auto read = static_cast<std::size_t>(in.gcount());
    if (read == kPng.size() && head == kPng) return Signature::png;
    if (read >= kExr.size() && std::equal(kExr.begin(), kExr.end(), head.begin()))
        return Signature::exr;
    if (read >= 2 && head[0] == '\xff' && head[1] == '\xd8') {
        in.clear();
        in.seekg(2);
        return Signature::jpeg;
    }
    return Signature::other;
}

// CRC-32 as PNG uses it (ISO 3309, polynomial 0xEDB88320), updated over `size` bytes.
std::uint32_t crc32_update(std::uint32_t crc, const unsigned char* data, std::size_t size) {
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t n = 0; n < 256; ++n) {
            std::uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    for (std::size_t i = 0; i < size; ++i) crc = table[(crc ^ data[i]) & 0xffu] ^ (crc >> 8);
    return crc;
}

// Walks the chunks of a PNG file (`in` just after its signature) and returns the cause if it is
// truncated or a critical chunk is corrupt. libpng reports these itself, but it also prints them
// to stderr and OpenImageIO 2.4 leaks memory on that path, so they are caught here first.
std::optional<std::string> png_problem(std::istream& in) {
    std::vector<unsigned char> buffer(1 << 16);
    bool first = true;
    for (;;) {
        std::array<unsigned char, 8> header{};
        if (!in.read(reinterpret_cast<char*>(header.data()), header.size())) {
            return std::string("the file is truncated (the PNG ends before its IEND chunk)");
        }
        const std::uint32_t length = (std::uint32_t{header[0]} << 24) |
                                     (std::uint32_t{header[1]} << 16) |
                                     (std::uint32_t{header[2]} << 8) | std::uint32_t{header[3]};
        const std::string type(reinterpret_cast<const char*>(header.data()) + 4, 4);
        const bool letters = std::all_of(type.begin(), type.end(), [](char c) {
            return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
        });
        if (length > 0x7fffffffu || !letters || (first && type != "IHDR")) {
            return std::string("the file is corrupt (invalid PNG chunk header)");
        }
        first = false;
        const bool critical = type[0] >= 'A' && type[0] <= 'Z';
        std::uint32_t crc = crc32_update(0xffffffffu, header.data() + 4, 4);
        std::uint32_t left = length;
        while (left > 0) {
            const std::size_t n = std::min<std::size_t>(left, buffer.size());
            if (!in.read(reinterpret_cast<char*>(buffer.data()), static_cast<std::streamsize>(n))) {
                return "the file is truncated (PNG chunk '" + type + "' is cut off)";
            }
            if (critical) crc = crc32_update(crc, buffer.data(), n);
            left -= static_cast<std::uint32_t>(n);
        }
        std::array<unsigned char, 4> stored{};
        if (!in.read(reinterpret_cast<char*>(stored.data()), stored.size())) {
            return "the file is truncated (PNG chunk '" + type + "' is cut off)";
        }
        const std::uint32_t expected = (std::uint32_t{stored[0]} << 24) |
                                       (std::uint32_t{stored[1]} << 16) |
                                       (std::uint32_t{stored[2]} << 8) | std::uint32_t{stored[3]};
        if (critical && (crc ^ 0xffffffffu) != expected) {
            return "the file is corrupt (checksum mismatch in PNG chunk '" + type + "')";
        }
        if (type == "IEND") return std::nullopt;
    }
}

// Whether the `declared` bytes of a JPEG marker's data, of which `data` is what the file holds,
// are a proper prefix of `id`: a block that starts like one OpenImageIO 2.4 parses, cut short.
bool cut_short(std::string_view data, std::size_t declared, std::string_view id) {
    return declared < id.size() && id.substr(0, data.size()) == data;
}

// Why OpenImageIO 2.4's JPEG reader would read past the data of the marker `code` (`data`, the
// `declared` bytes or as many as the file holds), if it would: it compares each block's start with
// the identifiers of Exif, XMP, ICC and IPTC blocks as C strings and trusts the lengths inside
// (fixed upstream in 2026, OpenImageIO #5081 and #5174).
std::optional<std::string> jpeg_marker_problem(int code, std::string_view data,
                                               std::size_t declared) {
    using namespace std::string_view_literals;
    constexpr int kApp1 = 0xe1, kApp2 = 0xe2, kApp13 = 0xed;
    // "Photoshop 3.0", its NUL, "8BIM", resource 1028 (IPTC); 4 bytes later, the IPTC length.
    constexpr std::string_view kIptc =
        "Photoshop 3.0\0"
        "8BIM\x04\x04"sv;
    constexpr std::size_t kIptcData = kIptc.size() + 6;
    const bool short_block =
        (code == kApp1 && (cut_short(data, declared, "Exif\0\0"sv) ||
                           cut_short(data, declared, "http://ns.adobe.com/xap/1.0/\0"sv))) ||
        (code == kApp2 && cut_short(data.substr(0, 12), declared, "ICC_PROFILE\0\0\0"sv)) ||
        (code == kApp13 && cut_short(data.substr(0, kIptc.size()), declared,
                                     std::string(kIptc) + std::string(6, '\0')));
    if (short_block) {
        return "the file is corrupt (its JPEG APP" + std::to_string(code - 0xe0) +
               " block is cut short)";
    }
    if (code == kApp13 && declared >= kIptcData && data.size() >= kIptcData &&
        data.substr(0, kIptc.size()) == kIptc) {
        const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(data[i]); };
        const std::size_t iptc_bytes =
            (std::size_t{byte(kIptcData - 2)} << 8) | byte(kIptcData - 1);
        if (kIptcData + iptc_bytes > declared)
            return std::string(
                "the file is corrupt (its JPEG IPTC block claims more bytes than "
                "its APP13 block holds)");
    }
    return std::nullopt;
}

// Walks the marker segments of a JPEG file (`in` just after its SOI) up to its first scan, as
// libjpeg does, and returns why OpenImageIO 2.4's reader would read past one of them, if it would.
// A file cut short is left to libjpeg to report.
std::optional<std::string> jpeg_problem(std::istream& in) {
    for (;;) {
        int code = in.get();
        while (code != EOF && code != 0xff) code = in.get();  // libjpeg skips stray bytes
        while (code == 0xff) code = in.get();                 // and fill bytes
        if (code == EOF || code == 0xda || code == 0xd9) return std::nullopt;  // SOS, EOI
        if (code == 0x01 || (code >= 0xd0 && code <= 0xd8)) continue;          // no length
        const int high = in.get(), low = in.get();
        if (low == EOF || ((high << 8) | low) < 2) return std::nullopt;
        const std::size_t declared = static_cast<std::size_t>((high << 8) | low) - 2;
        std::string data(declared, '\0');
        in.read(data.data(), static_cast<std::streamsize>(declared));
        data.resize(static_cast<std::size_t>(in.gcount()));
        if (auto cause = jpeg_marker_problem(code, data, declared)) return cause;
        if (data.size() < declared) return std::nullopt;
    }
}

// A tile may hold as many texels as its image, or 1024² where the image is smaller. A corrupt
// header can claim tiles of millions of rows for a few texels, and readers allocate a whole tile
// for every tile they read.
constexpr std::uint64_t kSmallImageTileTexels = std::uint64_t{1} << 20;

std::optional<std::string> tile_problem(std::uint64_t tile_width, std::uint64_t tile_height,
                                        std::uint64_t width, std::uint64_t height) {
    const std::uint64_t limit = std::max(width * height, kSmallImageTileTexels);
    if (tile_height == 0 || tile_width <= limit / tile_height) return std::nullopt;
    return "its tiles (" + std::to_string(tile_width) + " x " + std::to_string(tile_height) +
           " texels) are larger than the image (" + std::to_string(width) + " x " +
           std::to_string(height) + ") and than 1024 x 1024: the header is corrupt";
}

// The message of the first error OpenEXR's core library reports while exr_start_read() runs on
// this thread. Its error callback gets no pointer of ours (the context's user_data belongs to
// the default file reader), so the destination is a thread-local.
thread_local std::string* exr_first_error = nullptr;

void keep_first_exr_error(exr_const_context_t, exr_result_t, const char* message) {
    if (exr_first_error != nullptr && exr_first_error->empty()) *exr_first_error = message;
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
        const auto extent = [](int min, int max) {
            return static_cast<std::uint64_t>(std::int64_t{max} - min + 1);
        };
        if (auto cause = tile_problem(tile_width, tile_height, extent(window.min.x, window.max.x),
                                      extent(window.min.y, window.max.y))) {
            return "part " + std::to_string(part) + ": " + *cause;
        }
    }
    return std::nullopt;
}

// The most uncompressed bytes one byte of an OpenEXR part's compression can hold: deflate (zip,
// zips, and pxr24 after its rounding) codes at most 258 bytes in two bits, run lengths (rle) 128
// bytes in two; 0 where no useful bound is known (PIZ, B44, DWA).
std::uint64_t exr_best_ratio(exr_compression_t compression) {
    switch (compression) {
        case EXR_COMPRESSION_NONE:
            return 1;
        case EXR_COMPRESSION_RLE:
            return 64;
        case EXR_COMPRESSION_ZIPS:
        case EXR_COMPRESSION_ZIP:
        case EXR_COMPRESSION_PXR24:
            return 1032;
        default:
            return 0;
    }
}

// The fewest bytes part `part` of an open OpenEXR file takes: each chunk (a block of rows or a
// tile) an 8-byte entry in the chunk table and a header of at least 8 bytes, and its texels'
// channels at least 2 bytes each (half; OpenImageIO reads no subsampled channels) at the best
// ratio its compression allows.
std::uint64_t exr_fewest_bytes(exr_const_context_t context, int part) {
    constexpr std::uint64_t kFewestBytesPerChunk = 16, kFewestBytesPerValue = 2;
    std::int32_t chunks = 0;
    exr_compression_t compression{};
    exr_attr_box2i_t window{};
    const exr_attr_chlist_t* channels = nullptr;
    if (exr_get_chunk_count(context, part, &chunks) != EXR_ERR_SUCCESS || chunks < 0 ||
        exr_get_compression(context, part, &compression) != EXR_ERR_SUCCESS ||
        exr_get_data_window(context, part, &window) != EXR_ERR_SUCCESS ||
        exr_get_channels(context, part, &channels) != EXR_ERR_SUCCESS || channels == nullptr)
        return 0;
    const std::uint64_t table = static_cast<std::uint64_t>(chunks) * kFewestBytesPerChunk;
    const std::uint64_t ratio = exr_best_ratio(compression);
    if (ratio == 0) return table;
    const auto extent = [](int min, int max) {
        return static_cast<std::uint64_t>(std::max<std::int64_t>(std::int64_t{max} - min + 1, 0));
    };
    const std::uint64_t values = extent(window.min.x, window.max.x) *
                                 extent(window.min.y, window.max.y) *
                                 static_cast<std::uint64_t>(std::max(channels->num_channels, 0));
    return std::max(table, values * kFewestBytesPerValue / ratio);
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
        return std::string(parts > 1 ? "part " + std::to_string(part) + ": " : "") +
               "the file is truncated: its header claims " +
               std::to_string(std::int64_t{window.max.x} - window.min.x + 1) + " x " +
               std::to_string(std::int64_t{window.max.y} - window.min.y + 1) +
               " texels, more than its " + std::to_string(file_bytes) + " bytes can hold";
    }
    return std::nullopt;
}

// The first problem OpenEXR's core library finds in the headers of the OpenEXR file `file`.
// OpenEXRCore checks every attribute against the format's rules and the file's length before it
// allocates; OpenEXR 3.1's C++ reader, which OpenImageIO 2.4 reads with, allocates what a corrupt
// size claims.
std::optional<std::string> exr_header_problem(const fs::path& file) {
    std::string first_error;
    exr_first_error = &first_error;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = keep_first_exr_error;
    exr_context_t context = nullptr;
    const exr_result_t result = exr_start_read(&context, file.c_str(), &init);
    exr_first_error = nullptr;
    std::optional<std::string> layout;
    if (result == EXR_ERR_SUCCESS) {
        std::error_code size_error;
        const std::uintmax_t file_bytes = fs::file_size(file, size_error);
        layout = exr_tile_problem(context);
        if (!layout && !size_error) layout = exr_size_problem(context, file_bytes);
        exr_finish(&context);
    }
    // The core library's lenient parse skips an attribute it finds corrupt, reports it and
    // succeeds; OpenEXR's C++ reader would still read that attribute. So any report refuses.
    if (result == EXR_ERR_SUCCESS && first_error.empty()) return layout;
    if (first_error.empty()) first_error = exr_get_default_error_message(result);
    return "the OpenEXR header is corrupt (OpenEXR: " + first_error + ")";
}

// Why OpenImageIO 2.4 cannot safely read the TIFF directory `spec` describes, if it cannot: CMYK
// it converts to RGB writes four channels into room for three when the file is tiled, or of
// fewer than 8 bits a sample (fixed upstream in 2026, OpenImageIO #5082 and #5296).
std::optional<std::string> tiff_cmyk_problem(const OIIO::ImageSpec& spec) {
    if (spec.get_string_attribute("tiff:ColorSpace") != "CMYK" || spec.nchannels != 3)
        return std::nullopt;
    const int bits = spec.get_int_attribute("oiio:BitsPerSample", 8);
    if (spec.tile_width <= 0 && bits >= 8) return std::nullopt;
    return std::string("it is a CMYK TIFF ") +
           (spec.tile_width > 0 ? "in tiles" : "of " + std::to_string(bits) + "-bit samples") +
           ", which OpenImageIO 2.4 overruns its buffers converting to RGB: convert it to RGB";
}

// The first subimage or MIP level (a TIFF directory) of the open `input` whose tiles
// tile_problem() refuses or whose CMYK tiff_cmyk_problem() does, and why; `input` is left at its
// first subimage.
std::optional<std::string> level_problem(OIIO::ImageInput& input) {
    for (int subimage = 0; input.seek_subimage(subimage, 0); ++subimage) {
        for (int level = 0; input.seek_subimage(subimage, level); ++level) {
            const OIIO::ImageSpec& spec = input.spec();
            std::optional<std::string> cause = tiff_cmyk_problem(spec);
            if (!cause && spec.tile_width > 0) {
                cause = tile_problem(static_cast<std::uint64_t>(spec.tile_width),
                                     static_cast<std::uint64_t>(spec.tile_height),
                                     static_cast<std::uint64_t>(spec.width),
                                     static_cast<std::uint64_t>(spec.height));
            }
            if (!cause) continue;
            if (subimage == 0 && level == 0) return cause;
            return "subimage " + std::to_string(subimage) + ", MIP level " + std::to_string(level) +
                   ": " + *cause;
        }
    }
    input.seek_subimage(0, 0);
    (void)input.geterror();  // the failed seek's message, which would fail the next read
    return std::nullopt;
}

}  // namespace

Error read_error(const fs::path& file, const std::string& cause) {
    return Error{"cannot read '" + file.string() + "': " + cause};
}

std::string one_line(const std::string& message) {
    std::string out;
    std::size_t start = 0;
    while (start <= message.size()) {
        std::size_t end = message.find('\n', start);
        if (end == std::string::npos) end = message.size();
        std::string line = message.substr(start, end - start);
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        if (!line.empty()) {
            if (!out.empty()) out += "; ";
            out += line;
        }
        start = end + 1;
    }
    return out;
}

Result<std::unique_ptr<OIIO::ImageInput>> open_image_input(const fs::path& file,
                                                           const OIIO::ImageSpec& config) {
    std::ifstream in;
    const Result<Signature> signature = open_checked(file, in);
    if (!signature) return signature.error();
    if (*signature == Signature::png)
        if (auto cause = png_problem(in)) return read_error(file, *cause);
    if (*signature == Signature::jpeg)
        if (auto cause = jpeg_problem(in)) return read_error(file, *cause);
    // An OpenEXR is vetted whatever its extension: any reader handed it would trust its header.
    if (*signature == Signature::exr)
        if (auto cause = exr_header_problem(file)) return read_error(file, *cause);
    in.close();
    // Created from the extension alone ("exr", not the file's name), the reader is the only one
    // that sees the file.
    std::string extension = file.extension().string();
    if (extension.empty()) return read_error(file, "it has no extension (which picks the reader)");
    extension.erase(0, 1);
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::create(extension);
    if (!input) {
        (void)OIIO::geterror();
        return read_error(file, "OpenImageIO has no reader for ." + extension + " files");
    }
    OIIO::ImageSpec spec;
    if (!input->open(file.string(), spec, config)) {
        std::string cause = std::string("OpenImageIO's ") + input->format_name() +
                            " reader cannot read it: it is corrupt, truncated or of another format";
        const std::string message = one_line(input->geterror());
        if (!message.empty()) cause += " (OpenImageIO: " + message + ")";
        (void)OIIO::geterror();
        return read_error(file, cause);
    }
    if (*signature != Signature::exr)  // an OpenEXR's parts are checked above
        if (auto cause = level_problem(*input)) return read_error(file, *cause);
    return input;
}

}  // namespace footprint::detail
