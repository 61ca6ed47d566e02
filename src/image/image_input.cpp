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
#include <system_error>
#include <vector>

namespace footprint::detail {
namespace {

namespace fs = std::filesystem;

// What a file's first bytes say it is: only these formats have checks of their own.
enum class Signature { png, exr, other };

// Checks that `file` is an existing, non-empty, readable regular file (clearer messages than
// OpenImageIO gives for these cases), opens it as `in` and reads its signature (`in` is left after
// a PNG's).
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
    std::optional<std::string> tiles;
    if (result == EXR_ERR_SUCCESS) {
        tiles = exr_tile_problem(context);
        exr_finish(&context);
    }
    // The core library's lenient parse skips an attribute it finds corrupt, reports it and
    // succeeds; OpenEXR's C++ reader would still read that attribute. So any report refuses.
    if (result == EXR_ERR_SUCCESS && first_error.empty()) return tiles;
    if (first_error.empty()) first_error = exr_get_default_error_message(result);
    return "the OpenEXR header is corrupt (OpenEXR: " + first_error + ")";
}

// The first subimage or MIP level (a TIFF directory) of the open `input` whose tiles
// tile_problem() refuses, and why; `input` is left at its first subimage.
std::optional<std::string> level_tile_problem(OIIO::ImageInput& input) {
    for (int subimage = 0; input.seek_subimage(subimage, 0); ++subimage) {
        for (int level = 0; input.seek_subimage(subimage, level); ++level) {
            const OIIO::ImageSpec& spec = input.spec();
            if (spec.tile_width <= 0) continue;
            std::optional<std::string> cause = tile_problem(
                static_cast<std::uint64_t>(spec.tile_width),
                static_cast<std::uint64_t>(spec.tile_height),
                static_cast<std::uint64_t>(spec.width), static_cast<std::uint64_t>(spec.height));
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
        if (auto cause = level_tile_problem(*input)) return read_error(file, *cause);
    return input;
}

}  // namespace footprint::detail
