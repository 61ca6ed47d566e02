// image/image_input.cpp — opening a file for OpenImageIO's reader, after the checks that run
// before it sees the file (image_input.h, format_checks.h).
#include "image/image_input.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <system_error>

#include "image/format_checks.h"

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

Result<std::unique_ptr<OIIO::ImageInput>> open_image_input(const fs::path& file) {
    std::ifstream in;
    const Result<Signature> signature = open_checked(file, in);
    if (!signature) return signature.error();
    if (*signature == Signature::png)
        if (auto cause = png_problem(in)) return read_error(file, *cause);
    if (*signature == Signature::jpeg)
        if (auto cause = jpeg_problem(in)) return read_error(file, *cause);
    // An OpenEXR is vetted whatever its extension: any reader handed it would trust its header.
    if (*signature == Signature::exr)
        if (auto cause = exr_problem(file, in)) return read_error(file, *cause);
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
    OIIO::ImageSpec config, spec;
    config.attribute("oiio:UnassociatedAlpha", 1);  // keep straight alpha as stored
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
