// image/format_checks.cpp — the checks of PNG and JPEG blocks, tiles and TIFF directories
// (format_checks.h).
#include "image/format_checks.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <string_view>
#include <vector>

namespace footprint::detail {
namespace {

std::string lowercase(std::string_view text) {
    std::string lower(text);
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return lower;
}

// Whether the `declared` bytes of a JPEG marker's data, of which `data` is what the file holds,
// are a proper prefix of `id`: a block that starts like one OpenImageIO 2.4 parses, cut short.
bool cut_short(std::string_view data, std::size_t declared, std::string_view id) {
    return declared < id.size() && id.substr(0, data.size()) == data;
}

// Why OpenImageIO 2.4's Exif decoder would read past the Exif block `exif` (the TIFF header and
// directories after "Exif\0\0"), if it would. It reads the 8-byte header whatever the block's
// size; reads the entry count of a sub-directory (Exif, GPS, interoperability) whose offset lies
// in the block's last byte; and sizes an entry's data by a table of types 0 to 13, taking any
// other type as 2^64 − 1 bytes, which wraps its bounds check (fixed upstream in 2026, OpenImageIO
// #5322 and #5399). Directories are walked as it walks them, a Canon maker note among them.
std::optional<std::string> exif_problem(std::string_view exif) {
    constexpr std::uint16_t kExifIfd = 0x8769, kGpsIfd = 0x8825, kInteropIfd = 0xa005,
                            kMake = 0x010f, kMakerNote = 0x927c, kLargestType = 13;
    if (exif.size() < 8) return std::string("its Exif block is cut short");
    const bool little = exif.substr(0, 2) == "II";
    if (!little && exif.substr(0, 2) != "MM") return std::nullopt;  // not decoded
    const auto u = [&](std::size_t at, int bytes) {
        std::uint32_t v = 0;
        for (int i = 0; i < bytes; ++i) {
            const auto b = static_cast<unsigned char>(exif[at + static_cast<std::size_t>(i)]);
            v |= std::uint32_t{b} << (8 * (little ? i : bytes - 1 - i));
        }
        return v;
    };
    std::vector<std::uint32_t> todo{u(4, 4)};  // IFD0; sub-directories join as they are found
    std::vector<std::uint32_t> seen;
    std::uint32_t maker_note = 0;
    bool canon = false;
    for (std::size_t next = 0; next < todo.size(); ++next) {
        const std::size_t ifd = todo[next];
        if (ifd + 2 > exif.size()) {
            if (next == 0) return std::nullopt;  // IFD0's bounds are checked
            return std::string("its Exif block is corrupt (a directory at its last byte)");
        }
        const std::size_t entries = u(ifd, 2);
        for (std::size_t e = 0; e < entries && ifd + 2 + 12 * (e + 1) < exif.size(); ++e) {
            const std::size_t at = ifd + 2 + 12 * e;
            const std::uint32_t tag = u(at, 2), type = u(at + 2, 2), value = u(at + 8, 4);
            if (type > kLargestType)
                return "its Exif block is corrupt (an entry of type " + std::to_string(type) + ")";
            if (tag == kMake && value < exif.size())  // "Canon" and its NUL: past the entry
                canon = lowercase(exif.substr(value, 5)) == "canon";
            if (tag == kMakerNote) maker_note = value;
            const bool sub = tag == kExifIfd || tag == kGpsIfd || tag == kInteropIfd;
            if (sub && value < exif.size() &&
                std::find(seen.begin(), seen.end(), value) == seen.end() &&
                !(tag == kGpsIfd && value + 2 <= exif.size() && u(value, 2) > 32)) {
                seen.push_back(value);
                todo.push_back(value);
            }
        }
        if (next + 1 == todo.size() && canon && maker_note > 0 && maker_note + 2 <= exif.size()) {
            todo.push_back(maker_note);  // decoded as a directory, with its bounds checked
            canon = false;
        }
    }
    return std::nullopt;
}

// The Exif block in the text of a PNG's "Raw profile type exif" (ImageMagick's): "exif", a
// length, then hex digits; decoded as OpenImageIO 2.4 decodes it (any other character skipped).
std::string decode_raw_exif_profile(std::string_view text) {
    const auto skip_space = [&] {
        while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())))
            text.remove_prefix(1);
    };
    skip_space();
    if (text.substr(0, 4) != "exif") return {};
    text.remove_prefix(4);
    skip_space();
    if (!text.empty() && (text.front() == '-' || text.front() == '+')) text.remove_prefix(1);
    const std::size_t digits = text.find_first_not_of("0123456789");
    if (digits == 0 || text.substr(0, digits).find_first_not_of('0') == std::string_view::npos)
        return {};  // no length, or 0
    text.remove_prefix(std::min(digits, text.size()));
    skip_space();
    const auto nibble = [](char c) {
        return c <= '9' ? c - '0' : std::tolower(static_cast<unsigned char>(c)) - 'a' + 10;
    };
    std::string decoded;
    while (text.size() >= 2) {
        if (!std::isxdigit(static_cast<unsigned char>(text.front()))) {
            text.remove_prefix(1);
            continue;
        }
        decoded += static_cast<char>((nibble(text[0]) << 4) | nibble(text[1]));
        text.remove_prefix(2);
    }
    return decoded;
}

// What the zlib stream `compressed` inflates to, or nothing if it is corrupt, cut short or
// inflates past `limit` bytes (libpng drops such a chunk).
std::optional<std::string> inflated(std::string_view compressed, std::size_t limit) {
    z_stream z{};
    if (inflateInit(&z) != Z_OK) return std::nullopt;
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
    z.avail_in = static_cast<uInt>(compressed.size());
    std::string out;
    std::array<char, 1 << 16> buffer{};
    int result = Z_OK;
    while (result == Z_OK && out.size() <= limit) {
        z.next_out = reinterpret_cast<Bytef*>(buffer.data());
        z.avail_out = static_cast<uInt>(buffer.size());
        result = inflate(&z, Z_NO_FLUSH);
        out.append(buffer.data(), buffer.size() - z.avail_out);
    }
    inflateEnd(&z);
    if (result != Z_STREAM_END || out.size() > limit) return std::nullopt;
    return out;
}

// The text of the PNG text chunk `type` (tEXt, zTXt or iTXt) whose data after its keyword is
// `rest`, as libpng hands it to OpenImageIO (inflated, up to `limit` bytes); nothing if libpng
// would drop the chunk.
std::optional<std::string> png_text(const std::string& type, std::string_view rest,
                                    std::size_t limit) {
    if (type == "tEXt") return std::string(rest);
    if (type == "zTXt") {  // a compression method (0: zlib), the stream
        if (rest.empty() || rest[0] != 0) return std::nullopt;
        return inflated(rest.substr(1), limit);
    }
    // iTXt: a compression flag and method, a language tag and a translated keyword, the text.
    if (rest.size() < 2) return std::nullopt;
    const bool compressed = rest[0] != 0;
    rest.remove_prefix(2);
    for (int field = 0; field < 2; ++field) {
        const std::size_t nul = rest.find('\0');
        if (nul == std::string_view::npos) return std::nullopt;
        rest.remove_prefix(nul + 1);
    }
    return compressed ? inflated(rest, limit) : std::string(rest);
}

// Why OpenImageIO 2.4's Exif decoder (exif_problem) would read past the Exif block of the PNG
// chunk `type` holding `data`, if it would: an eXIf chunk, or the "Raw profile type exif" of a
// text chunk (inflated up to `limit` bytes).
std::optional<std::string> png_exif_problem(const std::string& type, std::string_view data,
                                            std::size_t limit) {
    std::string exif;
    if (type == "eXIf") {
        exif = data;
    } else {
        const std::size_t end = data.find('\0');  // the keyword's
        if (end == std::string_view::npos ||
            lowercase(data.substr(0, end)) != "raw profile type exif")
            return std::nullopt;
        const std::optional<std::string> text = png_text(type, data.substr(end + 1), limit);
        if (!text) return std::nullopt;
        exif = decode_raw_exif_profile(*text);
        if (lowercase(std::string_view(exif).substr(0, 4)) != "exif")
            return std::nullopt;  // OpenImageIO decodes only these
    }
    if (exif.compare(0, 6, std::string("Exif\0\0", 6)) == 0) exif.erase(0, 6);
    if (auto cause = exif_problem(exif)) return "the file is corrupt (" + *cause + ")";
    return std::nullopt;
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
    if (code == kApp1 && data.substr(0, 6) == "Exif\0\0"sv) {
        // libjpeg pads a block the file cuts short with end-of-image markers.
        std::string block(data);
        for (std::size_t i = 0; block.size() < declared; ++i) block += i % 2 ? '\xd9' : '\xff';
        if (auto cause = exif_problem(std::string_view(block).substr(6)))
            return "the file is corrupt (" + *cause + ")";
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

// A Huffman-coded JPEG frame: its size, and the fewest bits its scans take. Every 8 × 8 block of
// every component has its DC coefficient coded in at least one bit (a code of one bit and no bits
// of difference), sequential or progressive.
struct HuffmanFrame {
    std::uint64_t width = 0, height = 0, fewest_scan_bits = 0;
};

// The frame whose SOF marker holds `data`; nothing where it says nothing usable (a height left to
// a DNL marker, which libjpeg refuses anyway).
std::optional<HuffmanFrame> huffman_frame(std::string_view data) {
    const auto byte = [&](std::size_t i) {
        return static_cast<std::uint64_t>(static_cast<unsigned char>(data[i]));
    };
    if (data.size() < 6) return std::nullopt;
    HuffmanFrame frame{(byte(3) << 8) | byte(4), (byte(1) << 8) | byte(2)};
    const std::size_t components = byte(5);
    if (data.size() < 6 + 3 * components) return std::nullopt;
    const auto h = [&](std::size_t c) { return byte(7 + 3 * c) >> 4; };
    const auto v = [&](std::size_t c) { return byte(7 + 3 * c) & 15; };
    std::uint64_t h_max = 0, v_max = 0;
    for (std::size_t c = 0; c < components; ++c) {
        h_max = std::max(h_max, h(c));
        v_max = std::max(v_max, v(c));
    }
    if (frame.height == 0 || h_max == 0 || v_max == 0) return std::nullopt;
    // A component sampled at factor/max of the image's size covers that many texels, in blocks.
    const auto blocks = [](std::uint64_t size, std::uint64_t factor, std::uint64_t max) {
        return ((size * factor + max - 1) / max + 7) / 8;
    };
    for (std::size_t c = 0; c < components; ++c)
        frame.fewest_scan_bits +=
            blocks(frame.width, h(c), h_max) * blocks(frame.height, v(c), v_max);
    return frame;
}

// Why the scans of a JPEG (`in` at its first scan) cannot all be there: the rest of the file is
// shorter than `frame` needs at the least. libjpeg would fill the missing blocks with grey, after
// OpenImageIO allocated the image and read every row.
std::optional<std::string> jpeg_scans_problem(std::istream& in, const HuffmanFrame& frame) {
    const std::streampos scans = in.tellg();
    in.seekg(0, std::ios::end);
    const std::streampos end = in.tellg();
    if (scans < 0 || end < scans) return std::nullopt;
    const auto bytes = static_cast<std::uint64_t>(end - scans);
    if (bytes >= (frame.fewest_scan_bits + 7) / 8) return std::nullopt;
    return claims_more_texels_than_bytes(frame.width, frame.height, bytes, "bytes of scans");
}

// A tile may hold as many texels as its image, or 1024² where the image is smaller. A corrupt
// header can claim tiles of millions of rows for a few texels, and readers allocate a whole tile
// for every tile they read.
constexpr std::uint64_t kSmallImageTileTexels = std::uint64_t{1} << 20;

}  // namespace

// Walks the chunks of a PNG file (`in` just after its signature) and returns the cause if it is
// truncated or a critical chunk is corrupt. libpng reports these itself, but it also prints them
// to stderr and OpenImageIO 2.4 leaks memory on that path, so they are caught here first.
std::optional<std::string> png_problem(std::istream& in) {
    // Exif and text chunks up to this size, inflated or not, are kept for png_exif_problem
    // (libpng's default limit on an ancillary chunk is 8 MiB: it drops larger ones).
    constexpr std::uint32_t kKeptChunkBytes = 8u << 20;
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
        const bool kept = (type == "eXIf" || type == "tEXt" || type == "zTXt" || type == "iTXt") &&
                          length <= kKeptChunkBytes;
        std::string data;
        uLong crc = crc32(0, header.data() + 4, 4);  // zlib's CRC-32, PNG's
        std::uint32_t left = length;
        while (left > 0) {
            const std::size_t n = std::min<std::size_t>(left, buffer.size());
            if (!in.read(reinterpret_cast<char*>(buffer.data()), static_cast<std::streamsize>(n))) {
                return "the file is truncated (PNG chunk '" + type + "' is cut off)";
            }
            if (critical || kept) crc = crc32(crc, buffer.data(), static_cast<uInt>(n));
            if (kept) data.append(reinterpret_cast<const char*>(buffer.data()), n);
            left -= static_cast<std::uint32_t>(n);
        }
        std::array<unsigned char, 4> stored{};
        if (!in.read(reinterpret_cast<char*>(stored.data()), stored.size())) {
            return "the file is truncated (PNG chunk '" + type + "' is cut off)";
        }
        const std::uint32_t expected = (std::uint32_t{stored[0]} << 24) |
                                       (std::uint32_t{stored[1]} << 16) |
                                       (std::uint32_t{stored[2]} << 8) | std::uint32_t{stored[3]};
        if (critical && crc != expected) {
            return "the file is corrupt (checksum mismatch in PNG chunk '" + type + "')";
        }
        if (kept && crc == expected) {  // libpng drops it otherwise
            if (auto cause = png_exif_problem(type, data, kKeptChunkBytes)) return cause;
        }
        if (type == "IEND") return std::nullopt;
    }
}

// Walks the marker segments of a JPEG file (`in` just after its SOI) up to its first scan, as
// libjpeg does, and returns why OpenImageIO 2.4's reader would read past one of them, if it would,
// or why the scans cannot hold the texels the frame claims. Another file cut short is left to
// libjpeg to report.
std::optional<std::string> jpeg_problem(std::istream& in) {
    std::optional<HuffmanFrame> frame;
    for (;;) {
        int code = in.get();
        while (code != EOF && code != 0xff) code = in.get();  // libjpeg skips stray bytes
        while (code == 0xff) code = in.get();                 // and fill bytes
        if (code == 0x00) continue;  // a stuffed zero (FF 00) is stray bytes too, not a marker
        if (code == 0xda) return frame ? jpeg_scans_problem(in, *frame) : std::nullopt;  // SOS
        if (code == EOF || code == 0xd9) return std::nullopt;                            // EOI
        if (code == 0x01 || (code >= 0xd0 && code <= 0xd8)) continue;  // no length
        const int high = in.get(), low = in.get();
        if (low == EOF || ((high << 8) | low) < 2) return std::nullopt;
        const std::size_t declared = static_cast<std::size_t>((high << 8) | low) - 2;
        std::string data(declared, '\0');
        in.read(data.data(), static_cast<std::streamsize>(declared));
        data.resize(static_cast<std::size_t>(in.gcount()));
        if (auto cause = jpeg_marker_problem(code, data, declared)) return cause;
        if (data.size() < declared) return std::nullopt;
        // SOF0–SOF7 but DHT: Huffman-coded frames. Arithmetic coding (SOF9 and up) can take a
        // fraction of a bit a block, and gives no bound.
        if (code >= 0xc0 && code <= 0xc7 && code != 0xc4 && !frame) frame = huffman_frame(data);
    }
}
std::optional<std::string> tile_problem(std::uint64_t tile_width, std::uint64_t tile_height,
                                        std::uint64_t width, std::uint64_t height) {
    const std::uint64_t limit = std::max(width * height, kSmallImageTileTexels);
    if (tile_height == 0 || tile_width <= limit / tile_height) return std::nullopt;
    return "its tiles (" + std::to_string(tile_width) + " x " + std::to_string(tile_height) +
           " texels) are larger than the image (" + std::to_string(width) + " x " +
           std::to_string(height) + ") and than 1024 x 1024: the header is corrupt";
}
std::string claims_more_texels_than_bytes(std::uint64_t width, std::uint64_t height,
                                          std::uint64_t bytes, std::string_view counted) {
    return "the file is truncated: its header claims " + std::to_string(width) + " x " +
           std::to_string(height) + " texels, more than its " + std::to_string(bytes) + " " +
           std::string(counted) + " can hold";
}
// CMYK that OpenImageIO converts to RGB writes four channels into room for three when the file
// is tiled, or of fewer than 8 bits a sample (fixed upstream in 2026, OpenImageIO #5082, #5296).
std::optional<std::string> tiff_cmyk_problem(const OIIO::ImageSpec& spec) {
    if (spec.get_string_attribute("tiff:ColorSpace") != "CMYK" || spec.nchannels != 3)
        return std::nullopt;
    const int bits = spec.get_int_attribute("oiio:BitsPerSample", 8);
    if (spec.tile_width <= 0 && bits >= 8) return std::nullopt;
    return std::string("it is a CMYK TIFF ") +
           (spec.tile_width > 0 ? "in tiles" : "of " + std::to_string(bits) + "-bit samples") +
           ", which OpenImageIO 2.4 overruns its buffers converting to RGB: convert it to RGB";
}

}  // namespace footprint::detail
