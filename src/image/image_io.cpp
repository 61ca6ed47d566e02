// image/image_io.cpp — image files through OpenImageIO (a private dependency of this module).
#include "image/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <openexr.h>
#include <tiffio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "image/color.h"
#include "image/exr_decode.h"
#include "image/exr_parts.h"
#include "image/format_checks.h"
#include "image/image_input.h"
#include "image/image_io_detail.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

// Largest image accepted, in float values (16 GiB): guards against corrupt headers that claim
// absurd sizes.
constexpr std::uint64_t kMaxValues = std::uint64_t{1} << 32;

std::string quoted(const fs::path& file) {
    // Built with += : GCC 12 gives a false -Wrestrict for "'" + std::string at -O3.
    std::string s = "'";
    s += file.string();
    s += '\'';
    return s;
}

Error write_error(const fs::path& file, const std::string& cause) {
    return Error{"cannot write " + quoted(file) + ": " + cause};
}

std::string with_oiio_message(std::string cause, const std::string& oiio_message) {
    std::string message = detail::one_line(oiio_message);
    if (!message.empty()) cause += " (OpenImageIO: " + message + ")";
    return cause;
}

std::string lower_extension(const fs::path& file) {
    std::string ext = file.extension().string();
    for (char& c : ext) {
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    }
    return ext;
}

bool says_linear(const std::string& color_space) {
    std::string s = color_space;
    for (char& c : s) {
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    }
    return s == "linear" || s == "lin_srgb" || s == "lin_rec709" || s == "scene_linear";
}

void decode_srgb(Image& image, const OIIO::TypeDesc& format, int alpha_channel) {
    // 8- and 16-bit files hold exact codes k / (2^bits − 1): decode them through a table.
    std::vector<float> table;
    float scale = 0.0f;
    if (format == OIIO::TypeDesc::UINT8 || format == OIIO::TypeDesc::UINT16) {
        const int max_code = format == OIIO::TypeDesc::UINT8 ? 255 : 65535;
        table.resize(static_cast<std::size_t>(max_code) + 1);
        for (int k = 0; k <= max_code; ++k) {
            table[static_cast<std::size_t>(k)] =
                srgb_to_linear(static_cast<float>(k) / static_cast<float>(max_code));
        }
        scale = static_cast<float>(max_code);
    }
    const int channels = image.channels;
    const std::size_t n = image.pixels.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (static_cast<int>(i % static_cast<std::size_t>(channels)) == alpha_channel) continue;
        float& v = image.pixels[i];
        if (!table.empty()) {
            const long k = std::lround(std::clamp(v, 0.0f, 1.0f) * scale);
            v = table[static_cast<std::size_t>(k)];
        } else {
            // A float file forced to sRGB: the curve goes on above 1 (as scRGB's does) but
            // saturates at the largest float, where it would overflow to +Inf (above ~1e16), so
            // that an image whose file values were finite stays finite.
            v = std::min(srgb_to_linear(v), std::numeric_limits<float>::max());
        }
    }
}

std::string value_text(float v) {
    return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf";
}

// "texel (x, y) channel c" of the value at `index` of `image`'s pixels.
std::string texel_text(const Image& image, std::size_t index) {
    const std::size_t channels = static_cast<std::size_t>(image.channels);
    const std::size_t pixel = index / channels;
    const std::size_t width = static_cast<std::size_t>(image.width);
    return "texel (" + std::to_string(pixel % width) + ", " + std::to_string(pixel / width) +
           ") channel " + std::to_string(index % channels);
}

// The mean of the finite values of the same channel among the 8 neighbours of the value at
// `index` (0 if none is finite).
float finite_neighbour_mean(const Image& image, std::size_t index) {
    const std::size_t channels = static_cast<std::size_t>(image.channels);
    const int c = static_cast<int>(index % channels);
    const std::size_t pixel = index / channels;
    const int x = static_cast<int>(pixel % static_cast<std::size_t>(image.width));
    const int y = static_cast<int>(pixel / static_cast<std::size_t>(image.width));
    double sum = 0.0;
    int count = 0;
    for (int ny = std::max(0, y - 1); ny <= std::min(image.height - 1, y + 1); ++ny) {
        for (int nx = std::max(0, x - 1); nx <= std::min(image.width - 1, x + 1); ++nx) {
            const float v = image.at(nx, ny)[c];
            if ((nx != x || ny != y) && std::isfinite(v)) {
                sum += v;
                ++count;
            }
        }
    }
    return count > 0 ? static_cast<float>(sum / count) : 0.0f;
}

// Applies options.non_finite to the NaN and ±Inf values of `image` (image_io.h); the error when
// they are refused.
std::optional<Error> handle_non_finite(Image& image, const fs::path& file,
                                       const ImageLoadOptions& options) {
    if (options.non_finite == NonFinitePolicy::keep) return std::nullopt;
    std::vector<std::size_t> bad;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        if (!std::isfinite(image.pixels[i])) bad.push_back(i);
    }
    if (bad.empty()) return std::nullopt;
    const std::string first = ", the first at " + texel_text(image, bad[0]) + " (" +
                              value_text(image.pixels[bad[0]]) + ")";
    const std::string n = std::to_string(bad.size());
    if (options.non_finite == NonFinitePolicy::refuse) {
        return detail::read_error(file, n + (bad.size() == 1 ? " value is" : " values are") +
                                            " not finite (NaN or infinite)" + first);
    }
    // Repair from the file's values only, so the result does not depend on the order.
    std::vector<float> repaired(bad.size());
    for (std::size_t k = 0; k < bad.size(); ++k) {
        repaired[k] = finite_neighbour_mean(image, bad[k]);
    }
    for (std::size_t k = 0; k < bad.size(); ++k) image.pixels[bad[k]] = repaired[k];
    if (options.warn) {
        options.warn(quoted(file) + ": replaced " + n + " non-finite value" +
                     (bad.size() == 1 ? "" : "s") +
                     " (NaN or infinite) by the mean of the finite neighbours" + first);
    }
    return std::nullopt;
}

const char* const kSupportedList = ".png .jpg .jpeg .exr .hdr .tif .tiff";

enum class FileKind { png, jpeg, tiff, exr, hdr, unknown };

FileKind kind_of(const fs::path& file) {
    const std::string ext = lower_extension(file);
    if (ext == ".png") return FileKind::png;
    if (ext == ".jpg" || ext == ".jpeg") return FileKind::jpeg;
    if (ext == ".tif" || ext == ".tiff") return FileKind::tiff;
    if (ext == ".exr") return FileKind::exr;
    if (ext == ".hdr") return FileKind::hdr;
    return FileKind::unknown;
}

// A name for the temporary file beside `file`: ".<stem>.tmp-<random><ext>", extension last so
// that OpenImageIO picks the right writer.
fs::path temporary_path(const fs::path& file) {
    static thread_local std::mt19937_64 rng{std::random_device{}()};
    const fs::path dir = file.parent_path();
    std::error_code ec;
    fs::path tmp;
    for (int attempt = 0; attempt < 16; ++attempt) {
        char hex[17];
        std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(rng()));
        std::string name = ".";
        name += file.stem().string();
        name += ".tmp-";
        name += hex;
        name += file.extension().string();
        tmp = dir / name;
        if (!fs::exists(tmp, ec)) break;
    }
    return tmp;
}

// The pixels of a file to write: already in the file's channels, encoding and sample type.
struct EncodedPixels {
    int width = 0, height = 0, channels = 0;
    OIIO::TypeDesc file_format = OIIO::TypeDesc::FLOAT;
    OIIO::TypeDesc data_format = OIIO::TypeDesc::FLOAT;
    const void* data = nullptr;
    bool linear = false;
    std::optional<ImageBand> band = std::nullopt;  // EXR: the data window in the display window
};

// Encodes `pixels` as the format of `file`'s extension into memory with OpenImageIO. The writers
// see only memory, so a full disk cannot make them produce a short file unnoticed; the bytes are
// written by write_temporary. Returns the cause on failure.
Result<std::vector<unsigned char>> encode_with_oiio(const fs::path& file, FileKind kind,
                                                    const EncodedPixels& pixels) {
    std::vector<unsigned char> bytes;  // the memory outlives the writer (encode_levels())
    OIIO::Filesystem::IOVecOutput memory(bytes);
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) {
        return Error{
            with_oiio_message("OpenImageIO has no writer for this format", OIIO::geterror())};
    }
    if (!out->supports("ioproxy")) {
        return Error{std::string("OpenImageIO's ") + out->format_name() +
                     " writer cannot encode into memory"};
    }
    out->set_ioproxy(&memory);
    const int channels = pixels.channels;
    OIIO::ImageSpec spec(pixels.width, pixels.height, channels, pixels.file_format);
    switch (channels) {
        case 1:
            spec.channelnames = {"Y"};
            break;
        case 2:
            spec.channelnames = {"Y", "A"};
            break;
        case 3:
            spec.channelnames = {"R", "G", "B"};
            break;
        default:
            spec.channelnames = {"R", "G", "B", "A"};
            break;
    }
    spec.alpha_channel = (channels == 2 || channels == 4) ? channels - 1 : -1;
    if (pixels.band) {
        spec.y = pixels.band->y;
        spec.full_width = pixels.band->full_width;
        spec.full_height = pixels.band->full_height;
    }
    // OpenImageIO 2.4 writes a TIFF's Exif block (which an sRGB colour space brings) over the
    // main directory when the TIFF goes to memory: an sRGB TIFF is written without it.
    if (kind != FileKind::tiff || pixels.linear) {
        spec.attribute("oiio:ColorSpace", pixels.linear ? "Linear" : "sRGB");
    }
    spec.attribute("oiio:UnassociatedAlpha", 1);  // write alpha as given, never divide by it
    // An empty DateTime keeps the writers from stamping the current time (EXR capDate, TIFF
    // DateTime): the same pixels give the same bytes.
    spec.attribute("DateTime", "");
    if (!out->open(file.string(), spec)) {
        return Error{with_oiio_message("cannot encode the image", out->geterror())};
    }
    if (!out->write_image(pixels.data_format, pixels.data)) {
        std::string cause = with_oiio_message("encoding the pixels failed", out->geterror());
        out->close();
        return Error{cause};
    }
    if (!out->close()) {
        return Error{with_oiio_message("finishing the encoding failed", out->geterror())};
    }
    out.reset();  // its last writes, before the bytes move (see encode_levels())
    if (bytes.empty()) return Error{"OpenImageIO encoded nothing"};
    return bytes;
}

std::atomic<detail::WriteCall> write_call{nullptr};

long system_write(int fd, const void* data, std::size_t size) {
    return static_cast<long>(::write(fd, data, size));
}

std::string errno_text(int error) {
    return std::generic_category().message(error);
}

// Writes `bytes` to a new temporary file beside `file`, every write, the fsync and the close
// checked. Returns its path, or the cause (the temporary file then removed).
Result<fs::path> write_temporary(const fs::path& file, std::string_view bytes) {
    const fs::path tmp = temporary_path(file);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) return Error{"cannot create a temporary file beside it: " + errno_text(errno)};
    const detail::WriteCall hook = write_call.load();
    const detail::WriteCall write = hook != nullptr ? hook : system_write;
    int error = 0;
    std::size_t done = 0;
    while (done < bytes.size() && error == 0) {
        const long n = write(fd, bytes.data() + done, bytes.size() - done);
        if (n > 0) {
            done += static_cast<std::size_t>(n);
        } else if (n < 0 && errno == EINTR) {
            continue;
        } else {
            error = n < 0 ? errno : EIO;  // write() returning 0 for a non-empty buffer
        }
    }
    if (error == 0 && ::fsync(fd) != 0) error = errno;
    if (::close(fd) != 0 && error == 0) error = errno;
    if (error != 0) {
        ::unlink(tmp.c_str());
        return Error{errno_text(error)};
    }
    return tmp;
}

}  // namespace

bool is_supported_image_extension(const fs::path& file) {
    return kind_of(file) != FileKind::unknown;
}

// ColorEncoding::automatic's rule: integer samples are sRGB-encoded unless the metadata says
// linear.
bool detail::decodes_srgb(ColorEncoding encoding, const OIIO::ImageSpec& spec) {
    switch (encoding) {
        case ColorEncoding::srgb:
            return true;
        case ColorEncoding::linear:
            return false;
        case ColorEncoding::automatic:
            return automatic_decodes_srgb(spec);
    }
    return false;
}

bool detail::automatic_decodes_srgb(const OIIO::ImageSpec& spec) {
    return !spec.format.is_floating_point() &&
           !says_linear(spec.get_string_attribute("oiio:ColorSpace"));
}

bool is_srgb_encoded(const fs::path& file) {
    Result<std::unique_ptr<OIIO::ImageInput>> in = detail::open_image_input(file);
    return in && detail::automatic_decodes_srgb((*in)->spec());
}

namespace {

// Bytes of the file's own texels read_float_texels() converts at a time.
constexpr std::size_t kBandBytes = std::size_t{4} << 20;

// Rows of a band: kBandBytes of rows or one row, whole tiles high, at most the image.
int band_rows(const OIIO::ImageSpec& spec) {
    const std::size_t row_bytes = spec.scanline_bytes(/*native=*/true);
    std::int64_t rows = static_cast<std::int64_t>(std::max<std::size_t>(kBandBytes / row_bytes, 1));
    if (spec.tile_height > 0)
        rows = (rows + spec.tile_height - 1) / spec.tile_height * spec.tile_height;
    return static_cast<int>(std::min<std::int64_t>(rows, spec.height));
}

// Whether the open level `spec` is read a row at a time: a TIFF of strips. OpenImageIO 2.4's reader
// of several rows of strips at once overruns its buffers on some files (a MinIsWhite file of
// several channels, a deflated strip that fails to read; fixed upstream in 2026, OpenImageIO #5083
// and #5336); a row at a time it takes its single-row path. Except 64-bit samples, which that
// path drops (it decodes them into scratch memory it never copies out).
bool reads_row_by_row(const OIIO::ImageInput& in, const OIIO::ImageSpec& spec) {
    return std::string_view(in.format_name()) == "tiff" && spec.tile_width <= 0 &&
           spec.format.size() < 8;
}

// Converts `rows` rows of the file's own texels (`spec`'s native layout) to float texels: all
// channels at once, or, where the channels differ in type, one channel at a time.
bool convert_band(const OIIO::ImageSpec& spec, int rows, const std::byte* band, float* out) {
    const int channels = spec.nchannels;
    if (spec.channelformats.empty())
        return OIIO::convert_image(channels, spec.width, rows, 1, band, spec.format,
                                   OIIO::AutoStride, OIIO::AutoStride, OIIO::AutoStride, out,
                                   OIIO::TypeDesc::FLOAT, OIIO::AutoStride, OIIO::AutoStride,
                                   OIIO::AutoStride);
    const auto from_pixel = static_cast<OIIO::stride_t>(spec.pixel_bytes(/*native=*/true));
    const auto to_pixel = static_cast<OIIO::stride_t>(sizeof(float) * channels);
    std::size_t offset = 0;
    for (int c = 0; c < channels; ++c) {
        const OIIO::TypeDesc type = spec.channelformats[c];
        if (!OIIO::convert_image(1, spec.width, rows, 1, band + offset, type, from_pixel,
                                 from_pixel * spec.width, OIIO::AutoStride, out + c,
                                 OIIO::TypeDesc::FLOAT, to_pixel, to_pixel * spec.width,
                                 OIIO::AutoStride))
            return false;
        offset += type.size();
    }
    return true;
}

// Level `level` of the open file's first subimage as float texels. OpenImageIO 2.4 converts
// through a buffer of 64 MiB of scanlines whatever the image's size, even to the file's own type;
// only a request for the native layout (TypeDesc::UNKNOWN) reads straight into the caller's
// memory. So float files are read as they are, and others a band at a time and converted here.
bool read_float_texels(OIIO::ImageInput& in, int level, const OIIO::ImageSpec& spec,
                       std::vector<float>& texels) {
    const int channels = spec.nchannels;
    const bool row_by_row = reads_row_by_row(in, spec);
    if (spec.format == OIIO::TypeDesc::FLOAT && spec.channelformats.empty() && !row_by_row)
        return in.read_image(0, level, 0, channels, OIIO::TypeDesc::UNKNOWN, texels.data());
    const int rows = row_by_row ? 1 : band_rows(spec);
    std::vector<std::byte> band(static_cast<std::size_t>(rows) * spec.scanline_bytes(true));
    for (int y = 0; y < spec.height; y += rows) {
        const int y_end = std::min(y + rows, spec.height);
        const bool read = spec.tile_width > 0
                              ? in.read_tiles(0, level, spec.x, spec.x + spec.width, spec.y + y,
                                              spec.y + y_end, spec.z, spec.z + 1, 0, channels,
                                              OIIO::TypeDesc::UNKNOWN, band.data())
                              : in.read_scanlines(0, level, spec.y + y, spec.y + y_end, spec.z, 0,
                                                  channels, OIIO::TypeDesc::UNKNOWN, band.data());
        float* out = texels.data() + static_cast<std::size_t>(y) * spec.width * channels;
        if (!read || !convert_band(spec, y_end - y, band.data(), out)) return false;
    }
    return true;
}

// How a level of an OpenEXR file was read through OpenEXR's core library.
enum class ExrRead {
    done,      // the texels are read
    refused,   // a chunk is corrupt: the cause says which
    elsewhere  // not a layout read here (subsampled channels, types OpenImageIO reads otherwise)
};

// Native rows decoded at a time by one thread (a band of whole chunks).
constexpr std::size_t kExrBandBytes = std::size_t{1} << 20;

// Level `level` of the first part of the OpenEXR file `file`, whose header OpenImageIO gives as
// `spec`, as float texels: its chunks decoded through OpenEXR's core library (image/exr_decode.h),
// which refuses a chunk whose codec unpacks fewer bytes than its rows take, where OpenEXR 3.1's
// C++ reader would leave those rows as they were. Each band of rows is decoded into OpenImageIO's
// native layout of `spec` and converted as read_float_texels() converts it, so a valid file reads
// to the same floats; bands are decoded in parallel, as OpenEXR's C++ reader decodes chunks.
ExrRead read_exr_texels(const fs::path& file, int level, const OIIO::ImageSpec& spec,
                        std::vector<float>& texels, std::string& cause) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    detail::keep_exr_errors(init);
    exr_context_t context = nullptr;
    const exr_result_t started = exr_start_read(&context, file.c_str(), &init);
    const std::unique_ptr<exr_context_t, void (*)(exr_context_t*)> finish(
        &context, [](exr_context_t* c) { exr_finish(c); });
    if (started != EXR_ERR_SUCCESS) return ExrRead::elsewhere;
    constexpr int part = 0;  // OpenImageIO's first subimage
    // Only the codecs whose chunks OpenEXR 3.1's C++ reader leaves short. Its PIZ, PXR24, B44 and
    // DWA decoders refuse a chunk that ends before its rows do; the core library's PIZ takes a
    // third more time than the C++ reader's, its B44 gives other halves, and it has no DWA.
    exr_compression_t compression{};
    if (exr_get_compression(context, part, &compression) != EXR_ERR_SUCCESS ||
        (compression != EXR_COMPRESSION_NONE && compression != EXR_COMPRESSION_RLE &&
         compression != EXR_COMPRESSION_ZIPS && compression != EXR_COMPRESSION_ZIP))
        return ExrRead::elsewhere;
    exr_storage_t storage{};
    const exr_attr_chlist_t* list = nullptr;
    exr_attr_box2i_t window{};
    if (exr_get_storage(context, part, &storage) != EXR_ERR_SUCCESS ||
        (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED) ||
        exr_get_channels(context, part, &list) != EXR_ERR_SUCCESS ||
        list->num_channels != spec.nchannels ||
        exr_get_data_window(context, part, &window) != EXR_ERR_SUCCESS || window.min.x != spec.x ||
        window.min.y != spec.y)
        return ExrRead::elsewhere;

    // Where each of the file's channels goes in OpenImageIO's native pixel (spec's channel order).
    const int channels = spec.nchannels;
    std::vector<int> element_bytes(channels);
    std::vector<std::size_t> offsets(channels);
    std::vector<bool> placed(channels, false);
    std::size_t offset = 0;
    for (int k = 0; k < channels; ++k) {
        const OIIO::TypeDesc type =
            spec.channelformats.empty() ? spec.format : spec.channelformats[k];
        int i = 0;
        while (i < channels &&
               std::string_view(list->entries[i].name.str,
                                std::size_t(list->entries[i].name.length)) != spec.channelnames[k])
            ++i;
        if (i == channels || placed[i]) return ExrRead::elsewhere;
        const exr_attr_chlist_entry_t& entry = list->entries[i];
        const OIIO::TypeDesc stored = entry.pixel_type == EXR_PIXEL_HALF    ? OIIO::TypeDesc::HALF
                                      : entry.pixel_type == EXR_PIXEL_FLOAT ? OIIO::TypeDesc::FLOAT
                                                                            : OIIO::TypeDesc::UINT;
        if (entry.x_sampling != 1 || entry.y_sampling != 1 || type != stored)
            return ExrRead::elsewhere;
        placed[i] = true;
        element_bytes[i] = static_cast<int>(type.size());
        offsets[i] = offset;
        offset += type.size();
    }
    const std::size_t pixel_bytes = offset;
    const std::size_t row_bytes = pixel_bytes * static_cast<std::size_t>(spec.width);
    if (pixel_bytes != spec.pixel_bytes(/*native=*/true)) return ExrRead::elsewhere;

    // Chunks: blocks of rows, or tiles of MIP level `level` (OpenImageIO reads a ripmap's l × l).
    const bool tiled = storage == EXR_STORAGE_TILED;
    int chunk_width = spec.width, chunk_rows = 0;
    if (tiled) {
        std::uint32_t tile_width = 0, tile_height = 0;
        exr_tile_level_mode_t mode{};
        std::int32_t level_width = 0, level_height = 0;
        if (exr_get_tile_descriptor(context, part, &tile_width, &tile_height, &mode, nullptr) !=
                EXR_ERR_SUCCESS ||
            (mode == EXR_TILE_ONE_LEVEL && level != 0) ||
            exr_get_level_sizes(context, part, level, level, &level_width, &level_height) !=
                EXR_ERR_SUCCESS ||
            level_width != spec.width || level_height != spec.height ||
            static_cast<int>(tile_width) != spec.tile_width ||
            static_cast<int>(tile_height) != spec.tile_height)
            return ExrRead::elsewhere;
        chunk_width = spec.tile_width;
        chunk_rows = spec.tile_height;
    } else {
        if (level != 0 ||
            exr_get_scanlines_per_chunk(context, part, &chunk_rows) != EXR_ERR_SUCCESS ||
            chunk_rows <= 0 || std::int64_t{window.max.x} - window.min.x + 1 != spec.width)
            return ExrRead::elsewhere;
    }

    const bool float_native = spec.format == OIIO::TypeDesc::FLOAT && spec.channelformats.empty();
    const std::size_t chunk_band_bytes = row_bytes * static_cast<std::size_t>(chunk_rows);
    const int band_rows =
        chunk_rows * static_cast<int>(std::max<std::size_t>(
                         kExrBandBytes / std::max<std::size_t>(chunk_band_bytes, 1), 1));
    const std::int64_t bands = (std::int64_t{spec.height} + band_rows - 1) / band_rows;
    std::vector<std::string> band_causes(static_cast<std::size_t>(bands));

    // Each task decodes a run of bands with one decoder and one set of buffers, reused from chunk
    // to chunk, so that a large file's buffers are not mapped and faulted in afresh for each
    // band.
    const auto read_bands = [&](std::int64_t first, std::int64_t end) {
        std::vector<std::uint8_t> band, planes;
        std::vector<std::uint8_t*> plane_of(channels);
        try {
            if (!float_native) band.resize(static_cast<std::size_t>(band_rows) * row_bytes);
            planes.resize(static_cast<std::size_t>(chunk_width) * chunk_rows * pixel_bytes);
        } catch (const std::bad_alloc&) {
            band_causes[static_cast<std::size_t>(first)] = "not enough memory to decode its texels";
            return;
        }
        detail::ExrChunkDecoder decoder(context, part);
        for (std::int64_t b = first; b < end; ++b) {
            std::string& why = band_causes[static_cast<std::size_t>(b)];
            const int y0 = static_cast<int>(b) * band_rows;
            const int y1 = std::min(y0 + band_rows, spec.height);
            float* out = texels.data() + static_cast<std::size_t>(y0) * spec.width * channels;
            std::uint8_t* rows = float_native ? reinterpret_cast<std::uint8_t*>(out) : band.data();
            for (int y = y0; y < y1 && why.empty(); y += chunk_rows) {
                const int height = std::min(chunk_rows, spec.height - y);
                for (int x = 0; x < spec.width && why.empty(); x += chunk_width) {
                    const int width = std::min(chunk_width, spec.width - x);
                    const auto which = [&] {
                        return tiled ? "the chunk of tile (" + std::to_string(x / chunk_width) +
                                           ", " + std::to_string(y / chunk_rows) + ")"
                                     : "chunk " + std::to_string(y / chunk_rows) + " (rows " +
                                           std::to_string(spec.y + y) + " to " +
                                           std::to_string(spec.y + y + height - 1) + ")";
                    };
                    exr_chunk_info_t chunk{};
                    const exr_result_t found =
                        tiled ? exr_read_tile_chunk_info(context, part, x / chunk_width,
                                                         y / chunk_rows, level, level, &chunk)
                              : exr_read_scanline_chunk_info(context, part, spec.y + y, &chunk);
                    if (found != EXR_ERR_SUCCESS || chunk.width != width ||
                        chunk.height != height) {
                        why = which() + " is missing or corrupt";
                        break;
                    }
                    // Uncompressed rows are read straight from the file, past a chunk that
                    // holds fewer bytes than they take.
                    if (compression == EXR_COMPRESSION_NONE &&
                        chunk.packed_size != chunk.unpacked_size) {
                        why = which() + " holds " + std::to_string(chunk.packed_size) +
                              " bytes, but its rows take " + std::to_string(chunk.unpacked_size);
                        break;
                    }
                    std::size_t at = 0;
                    for (int i = 0; i < channels; ++i) {
                        plane_of[i] = planes.data() + at;
                        at += static_cast<std::size_t>(width) * height * element_bytes[i];
                    }
                    std::string exr_why;
                    if (!decoder.decode(chunk, plane_of.data(), /*as_float=*/false, exr_why)) {
                        why = which() +
                              " is corrupt or unpacks to fewer bytes than its rows take "
                              "(OpenEXR: " +
                              exr_why + ")";
                        break;
                    }
                    detail::interleave_exr_planes(channels, plane_of.data(), element_bytes.data(),
                                                  offsets.data(), width, height,
                                                  rows +
                                                      static_cast<std::size_t>(y - y0) * row_bytes +
                                                      static_cast<std::size_t>(x) * pixel_bytes,
                                                  pixel_bytes, row_bytes);
                }
            }
            if (why.empty() && !float_native &&
                !convert_band(spec, y1 - y0, reinterpret_cast<const std::byte*>(band.data()), out))
                why = "its texels cannot be converted to floats";
        }
    };
    if (bands == 1)
        read_bands(0, 1);
    else
        parallel_for<std::int64_t>(0, bands, 1, read_bands);
    for (const std::string& why : band_causes) {
        if (why.empty()) continue;
        cause = "the OpenEXR file is corrupt: " + why;
        return ExrRead::refused;
    }
    return ExrRead::done;
}

// A TIFF compressed by a codec libtiff lacks cannot be decoded, yet OpenImageIO would allocate the
// level and try every strip.
std::optional<std::string> tiff_codec_problem(const OIIO::ImageSpec& spec) {
    const int code = spec.get_int_attribute("tiff:Compression", COMPRESSION_NONE);
    if (code >= 0 && code <= std::numeric_limits<std::uint16_t>::max() &&
        TIFFIsCODECConfigured(static_cast<std::uint16_t>(code)))
        return std::nullopt;
    return "its compression (TIFF code " + std::to_string(code) + ") is not one libtiff can decode";
}

// The fewest bytes that can hold `spec`'s texels at the best ratio the file's coding allows, or 0
// where no useful bound is known. (An OpenEXR is bounded when it is opened: exr_size_problem.)
std::uint64_t fewest_bytes_for_texels(const OIIO::ImageInput& in, const OIIO::ImageSpec& spec) {
    const std::uint64_t texels =
        static_cast<std::uint64_t>(spec.width) * static_cast<std::uint64_t>(spec.height);
    // Radiance stores four bytes a texel, or runs of at most 127 of a byte in two bytes for each
    // of its four channels: 8 bytes per 127 texels at best.
    if (std::string_view(in.format_name()) == "hdr") return texels / 16;
    if (std::string_view(in.format_name()) != "tiff") return 0;
    // A TIFF's texels take at least a bit uncompressed (a 1-bit image or palette index); deflate
    // codes at most 258 bytes in two bits, packbits 128 bytes in two.
    const std::string compression = spec.get_string_attribute("compression");
    if (compression == "none") return texels / 8;
    if (compression == "zip") return texels / 8 / 1032;
    if (compression == "packbits") return texels / 8 / 64;
    return 0;
}

// Why the level `spec` describes cannot be read, judged from its header and the file's size
// before its texels are allocated: a header of a few hundred bytes can claim gigabytes, which
// would otherwise be allocated and read for seconds before the data runs out.
std::optional<std::string> undecodable_level(const OIIO::ImageInput& in,
                                             const OIIO::ImageSpec& spec, const fs::path& file) {
    if (std::string_view(in.format_name()) == "tiff") {
        if (auto cause = tiff_codec_problem(spec)) return cause;
    }
    std::error_code size_error;
    const std::uintmax_t file_bytes = fs::file_size(file, size_error);
    if (size_error || file_bytes >= fewest_bytes_for_texels(in, spec)) return std::nullopt;
    return detail::claims_more_texels_than_bytes(static_cast<std::uint64_t>(spec.width),
                                                 static_cast<std::uint64_t>(spec.height),
                                                 file_bytes);
}

// MIP level `level` of the open file's first subimage, checked, read and decoded; `where` leads
// the cause in messages ("MIP level 3: ", or nothing for an image's only level).
Result<Image> read_level(OIIO::ImageInput& in, int level, const fs::path& file,
                         const ImageLoadOptions& options, const std::string& where) {
    const auto fail = [&](const std::string& cause) {
        (void)in.geterror();  // drop pending messages so OpenImageIO does not print them
        return detail::read_error(file, where + cause);
    };
    if (!in.seek_subimage(0, level)) return fail("the file has no such MIP level");
    const OIIO::ImageSpec spec = in.spec();
    if (spec.deep) return fail("deep images are not supported");
    if (spec.width <= 0 || spec.height <= 0 || spec.depth <= 0) {
        return fail("the image has zero size (" + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + ")");
    }
    if (spec.depth != 1) return fail("it is a 3D volume image; footprint reads 2D images");
    if (spec.nchannels < 1 || spec.nchannels > 4) {
        return fail("it has " + std::to_string(spec.nchannels) +
                    " channels; footprint reads 1 to 4");
    }
    const std::uint64_t values = static_cast<std::uint64_t>(spec.width) *
                                 static_cast<std::uint64_t>(spec.height) *
                                 static_cast<std::uint64_t>(spec.nchannels);
    if (values > kMaxValues) {
        return fail("the image is too large (" + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + " x " + std::to_string(spec.nchannels) + ")");
    }
    if (auto cause = undecodable_level(in, spec, file)) return fail(*cause);

    Image image;
    try {
        image = Image(spec.width, spec.height, spec.nchannels);
    } catch (const std::bad_alloc&) {
        return fail("not enough memory for " + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + " pixels");
    }
    std::string exr_cause;
    const ExrRead exr = std::string_view(in.format_name()) == "openexr"
                            ? read_exr_texels(file, level, spec, image.pixels, exr_cause)
                            : ExrRead::elsewhere;
    if (exr == ExrRead::refused) return detail::read_error(file, where + exr_cause);
    if ((exr == ExrRead::elsewhere && !read_float_texels(in, level, spec, image.pixels)) ||
        in.has_error()) {
        return detail::read_error(
            file, where + with_oiio_message("the file is truncated or corrupt", in.geterror()));
    }
    if (auto error = handle_non_finite(image, file, options)) return *error;

    if (detail::decodes_srgb(options.encoding, spec)) {
        int alpha = spec.alpha_channel;
        if (alpha < 0 || alpha >= spec.nchannels) {
            alpha = (spec.nchannels == 2 || spec.nchannels == 4) ? spec.nchannels - 1 : -1;
        }
        decode_srgb(image, spec.format, alpha);
    }
    return image;
}

}  // namespace

Result<Image> load_image(const fs::path& file, const ImageLoadOptions& options) {
    Result<std::unique_ptr<OIIO::ImageInput>> in = detail::open_image_input(file);
    if (!in) return in.error();
    Result<Image> image = read_level(**in, 0, file, options, "");
    (*in)->close();
    return image;
}

Result<ImageBand> load_image_band(const fs::path& file) {
    Result<std::unique_ptr<OIIO::ImageInput>> in = detail::open_image_input(file);
    if (!in) return in.error();
    const OIIO::ImageSpec spec = (*in)->spec();
    (*in)->close();
    if (spec.x != spec.full_x || spec.width != spec.full_width || spec.full_y != 0 || spec.y < 0 ||
        spec.y + spec.height > spec.full_height)
        return Error{"cannot read '" + file.string() + "' as a band of rows: its data window " +
                     std::to_string(spec.width) + "x" + std::to_string(spec.height) + " at (" +
                     std::to_string(spec.x) + ", " + std::to_string(spec.y) +
                     ") is not whole rows of its " + std::to_string(spec.full_width) + "x" +
                     std::to_string(spec.full_height) + " image"};
    return ImageBand{spec.y, spec.full_width, spec.full_height};
}

Result<std::vector<Image>> load_image_levels(const fs::path& file,
                                             const ImageLoadOptions& options) {
    Result<std::unique_ptr<OIIO::ImageInput>> in = detail::open_image_input(file);
    if (!in) return in.error();
    std::vector<Image> levels;
    for (int level = 0; level == 0 || (*in)->seek_subimage(0, level); ++level) {
        const std::string where =
            level == 0 ? std::string() : "MIP level " + std::to_string(level) + ": ";
        Result<Image> image = read_level(**in, level, file, options, where);
        if (!image) {
            (*in)->close();
            return image.error();
        }
        levels.push_back(std::move(*image));
    }
    (void)(*in)->geterror();  // the failed seek past the last level
    (*in)->close();
    return levels;
}

namespace {

// Why `image` cannot be written (the cause), or nullopt.
std::optional<std::string> image_problem(const Image& image, int max_channels = 4) {
    if (image.width <= 0 || image.height <= 0) {
        return "the image is empty (" + std::to_string(image.width) + " x " +
               std::to_string(image.height) + ")";
    }
    if (image.channels < 1 || image.channels > max_channels) {
        return "the image has " + std::to_string(image.channels) +
               " channels; footprint writes 1 to " + std::to_string(max_channels);
    }
    const std::uint64_t values = static_cast<std::uint64_t>(image.width) *
                                 static_cast<std::uint64_t>(image.height) *
                                 static_cast<std::uint64_t>(image.channels);
    if (values != image.pixels.size()) {
        return "the image holds " + std::to_string(image.pixels.size()) + " values but " +
               std::to_string(image.width) + " x " + std::to_string(image.height) + " x " +
               std::to_string(image.channels) + " needs " + std::to_string(values);
    }
    return std::nullopt;
}

// Why nothing can be written at `file` (its directory is missing, or it is a directory), or
// nullopt.
std::optional<std::string> location_problem(const fs::path& file) {
    std::error_code ec;
    const fs::path dir = file.parent_path();
    if (!dir.empty()) {
        const fs::file_status st = fs::status(dir, ec);
        if (st.type() == fs::file_type::not_found) {
            return "directory " + quoted(dir) + " does not exist";
        }
        if (st.type() != fs::file_type::directory) return quoted(dir) + " is not a directory";
    }
    if (fs::is_directory(file, ec)) return std::string("it is a directory");
    return std::nullopt;
}

bool is_integer_format(FileKind kind) {
    return kind == FileKind::png || kind == FileKind::jpeg || kind == FileKind::tiff;
}

// Why `file` (of `kind`) cannot be written with `options`, or nullopt.
std::optional<std::string> target_problem(const fs::path& file, FileKind kind,
                                          const ImageSaveOptions& options) {
    if (kind == FileKind::unknown) {
        const std::string ext = file.extension().string();
        return (ext.empty() ? std::string("no file extension")
                            : "unsupported extension '" + ext + "'") +
               " (supported: " + kSupportedList + ")";
    }
    if (is_integer_format(kind) && options.bits != 8 && options.bits != 16) {
        return "bits must be 8 or 16, not " + std::to_string(options.bits);
    }
    if (kind == FileKind::jpeg && options.bits != 8) {
        return "JPEG files hold 8 bits per channel only, not " + std::to_string(options.bits);
    }
    if (options.band && kind != FileKind::exr) {
        return "a band of a larger image is written as an OpenEXR data window: the file must be "
               ".exr";
    }
    return location_problem(file);
}

// The channel count a file of `kind` gets for an image of `channels` (image_io.h, Format limits).
int file_channels(FileKind kind, int channels) {
    if (kind == FileKind::hdr) return 3;
    if (kind == FileKind::jpeg && (channels == 2 || channels == 4)) return channels - 1;
    return channels;
}

// `image` in the file's channels and encoding; integer formats clamped to [0, 1] (NaN → 0).
std::vector<float> convert_for_file(const Image& image, int out_channels, bool srgb,
                                    bool integer_format) {
    const int in_channels = image.channels;
    const bool out_alpha = out_channels == 2 || out_channels == 4;
    const bool grey_in = in_channels <= 2;
    std::vector<float> converted(image.pixel_count() * static_cast<std::size_t>(out_channels));
    const std::size_t pixels = image.pixel_count();
    for (std::size_t p = 0; p < pixels; ++p) {
        const float* src = image.pixels.data() + p * static_cast<std::size_t>(in_channels);
        float* dst = converted.data() + p * static_cast<std::size_t>(out_channels);
        for (int c = 0; c < out_channels; ++c) {
            const bool is_alpha = out_alpha && c == out_channels - 1;
            float v = is_alpha ? src[in_channels - 1] : src[grey_in ? 0 : c];
            if (!is_alpha && srgb) v = linear_to_srgb(v);
            if (integer_format) v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
            dst[c] = v;
        }
    }
    return converted;
}

// Values in [0, 1] as integer codes 0 … max (round to nearest), rather than trusting the
// library's conversion.
template <class Code>
std::vector<Code> quantise(const std::vector<float>& values, float max) {
    std::vector<Code> codes(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        codes[i] = static_cast<Code>(std::lround(values[i] * max));
    }
    return codes;
}

// The bytes of `file` holding `image` (validated, converted, quantised and encoded), or the
// error naming `file`.
Result<std::vector<unsigned char>> encode_image(const Image& image, const fs::path& file,
                                                const ImageSaveOptions& options) {
    if (auto problem = image_problem(image)) return write_error(file, *problem);
    const FileKind kind = kind_of(file);
    if (auto problem = target_problem(file, kind, options)) return write_error(file, *problem);
    if (const std::optional<ImageBand>& b = options.band;
        b && (b->full_width != image.width || b->y < 0 || b->y + image.height > b->full_height))
        return write_error(
            file, "rows " + std::to_string(b->y) + " to " + std::to_string(b->y + image.height) +
                      " of a " + std::to_string(image.width) + "-wide image are not a band of a " +
                      std::to_string(b->full_width) + "x" + std::to_string(b->full_height) +
                      " image");

    const bool integer_format = is_integer_format(kind);
    const bool srgb = options.encoding == ColorEncoding::srgb ||
                      (options.encoding == ColorEncoding::automatic && integer_format);
    EncodedPixels pixels{image.width, image.height, file_channels(kind, image.channels)};
    pixels.linear = !srgb;
    pixels.band = options.band;
    std::vector<float> converted;
    std::vector<std::uint8_t> codes8;
    std::vector<std::uint16_t> codes16;
    try {
        converted = convert_for_file(image, pixels.channels, srgb, integer_format);
        pixels.data = converted.data();
        if (integer_format && options.bits == 16) {
            codes16 = quantise<std::uint16_t>(converted, 65535.0f);
            pixels.file_format = pixels.data_format = OIIO::TypeDesc::UINT16;
            pixels.data = codes16.data();
        } else if (integer_format) {
            codes8 = quantise<std::uint8_t>(converted, 255.0f);
            pixels.file_format = pixels.data_format = OIIO::TypeDesc::UINT8;
            pixels.data = codes8.data();
        } else if (kind == FileKind::exr && options.exr_half) {
            pixels.file_format = OIIO::TypeDesc::HALF;
        }
    } catch (const std::bad_alloc&) {
        return write_error(file, "not enough memory to convert the image");
    }
    Result<std::vector<unsigned char>> bytes = encode_with_oiio(file, kind, pixels);
    if (!bytes) return write_error(file, bytes.error().message);
    return bytes;
}

// Removes the temporary files of a save that failed.
void remove_all(const std::vector<fs::path>& temporaries) {
    std::error_code ignored;
    for (const fs::path& tmp : temporaries) fs::remove(tmp, ignored);
}

// Renames each temporary file onto its target, in order. On failure the remaining temporary
// files are removed and the message names the targets already replaced.
Status rename_all(const std::vector<fs::path>& temporaries, const std::vector<fs::path>& targets) {
    for (std::size_t i = 0; i < temporaries.size(); ++i) {
        std::error_code ec;
        fs::rename(temporaries[i], targets[i], ec);
        if (!ec) continue;
        remove_all({temporaries.begin() + static_cast<std::ptrdiff_t>(i), temporaries.end()});
        std::string cause = "cannot move the finished file into place: " + ec.message();
        if (i > 0) {
            cause += " (already replaced:";
            for (std::size_t k = 0; k < i; ++k) cause += " " + quoted(targets[k]);
            cause += ")";
        }
        return write_error(targets[i], cause);
    }
    return {};
}

}  // namespace

Status save_image(const Image& image, const fs::path& file, const ImageSaveOptions& options) {
    return save_images({{&image, file}}, options);
}

Status save_images(const std::vector<ImageToSave>& images, const ImageSaveOptions& options) {
    std::vector<fs::path> temporaries, targets;
    for (const ImageToSave& item : images) {
        if (item.image == nullptr) {
            remove_all(temporaries);
            return write_error(item.file, "no image given");
        }
        Result<std::vector<unsigned char>> bytes = encode_image(*item.image, item.file, options);
        if (!bytes) {
            remove_all(temporaries);
            return bytes.error();
        }
        const std::string_view view(reinterpret_cast<const char*>(bytes->data()), bytes->size());
        Result<fs::path> tmp = write_temporary(item.file, view);
        if (!tmp) {
            remove_all(temporaries);
            return write_error(item.file, tmp.error().message);
        }
        temporaries.push_back(*tmp);
        targets.push_back(item.file);
    }
    return rename_all(temporaries, targets);
}

Status write_file_atomically(const fs::path& file, std::string_view bytes) {
    if (file.filename().empty()) return write_error(file, "not a file name");
    if (auto problem = location_problem(file)) return write_error(file, *problem);
    Result<fs::path> tmp = write_temporary(file, bytes);
    if (!tmp) return write_error(file, tmp.error().message);
    return rename_all({*tmp}, {file});
}

namespace {

// Why `levels` are not a MIP chain that save_image_levels can write, or nullopt.
std::optional<std::string> levels_problem(const std::vector<Image>& levels,
                                          const LevelsSaveOptions& options) {
    if (levels.empty()) return std::string("no levels given");
    const auto names = static_cast<int>(options.channel_names.size());
    if (names > 0 && (names > 8 || levels[0].channels != names))
        return std::to_string(names) + " channel names for " + std::to_string(levels[0].channels) +
               " channels (1 to 8 named channels can be written)";
    for (std::size_t l = 0; l < levels.size(); ++l) {
        const std::string level = "MIP level " + std::to_string(l) + ": ";
        if (auto problem = image_problem(levels[l], names > 0 ? names : 4)) return level + *problem;
        if (levels[l].channels != levels[0].channels)
            return level + "it has " + std::to_string(levels[l].channels) +
                   " channels, level 0 has " + std::to_string(levels[0].channels);
        if (l == 0) continue;
        const int w = std::max(1, levels[l - 1].width / 2),
                  h = std::max(1, levels[l - 1].height / 2);
        if (levels[l].width != w || levels[l].height != h)
            return level + "it is " + std::to_string(levels[l].width) + " x " +
                   std::to_string(levels[l].height) + ", not " + std::to_string(w) + " x " +
                   std::to_string(h);
    }
    const Image& last = levels.back();
    if (last.width != 1 || last.height != 1)
        return "the levels stop at " + std::to_string(last.width) + " x " +
               std::to_string(last.height) + ", not 1 x 1";
    return std::nullopt;
}

// The type of a float attribute of n values: OpenEXR keeps 2 and 3 as its v2f and v3f.
OIIO::TypeDesc float_attribute_type(std::size_t n) {
    if (n == 2) return OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::VEC2);
    if (n == 3) return OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::VEC3);
    return OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, static_cast<int>(n));
}

// The spec of a level of width × height texels: what maketx writes for a MIP-mapped texture
// (OpenImageIO's OpenEXR writer makes a "Plain Texture" of tiles a MIPMAP_LEVELS file), levels
// rounded down, max(1, ⌊W/2⌋), and the options' attributes.
OIIO::ImageSpec level_spec(int width, int height, int channels, const LevelsSaveOptions& options) {
    static const std::vector<std::string> kNames[4] = {
        {"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
    const bool named = !options.channel_names.empty();
    spec.channelnames = named ? options.channel_names : kNames[channels - 1];
    spec.alpha_channel = !named && (channels == 2 || channels == 4) ? channels - 1 : -1;
    for (const LevelsSaveOptions::FloatAttribute& a : options.float_attributes)
        spec.attribute(a.name, float_attribute_type(a.values.size()), a.values.data());
    for (const auto& [name, value] : options.string_attributes) spec.attribute(name, value);
    spec.tile_width = spec.tile_height = options.tile_size;
    spec.attribute("textureformat", "Plain Texture");
    spec.attribute("openexr:levelmode", 1);
    spec.attribute("openexr:roundingmode", 0);
    spec.attribute("oiio:ColorSpace", "Linear");
    spec.attribute("DateTime", "");  // the same levels give the same bytes
    if (!options.wrap_modes.empty()) spec.attribute("wrapmodes", options.wrap_modes);
    return spec;
}

// The levels as one tiled, MIP-mapped OpenEXR file of floats, in memory.
Result<std::vector<unsigned char>> encode_levels(const std::vector<Image>& levels,
                                                 const fs::path& file,
                                                 const LevelsSaveOptions& options) {
    // OpenImageIO's OpenEXR writer writes a tiled file's chunk tables as it is destroyed, not as
    // it closes: the memory outlives it, and it is destroyed before the bytes move out, or every
    // entry of the tables stays 0 (which OpenEXR's readers take for a file whose writer stopped).
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    auto out = OIIO::ImageOutput::create("levels.exr");
    if (!out || !out->supports("mipmap") || !out->supports("ioproxy"))
        return Error{with_oiio_message("OpenImageIO cannot write MIP-mapped OpenEXR into memory",
                                       OIIO::geterror())};
    out->set_ioproxy(&memory);
    for (std::size_t l = 0; l < levels.size(); ++l) {
        const OIIO::ImageSpec spec =
            level_spec(levels[l].width, levels[l].height, levels[l].channels, options);
        const auto mode = l == 0 ? OIIO::ImageOutput::Create : OIIO::ImageOutput::AppendMIPLevel;
        if (!out->open(file.string(), spec, mode) ||
            !out->write_image(OIIO::TypeDesc::FLOAT, levels[l].pixels.data())) {
            std::string cause = with_oiio_message(
                "encoding MIP level " + std::to_string(l) + " failed", out->geterror());
            out->close();
            return Error{cause};
        }
    }
    if (!out->close())
        return Error{with_oiio_message("finishing the encoding failed", out->geterror())};
    out.reset();
    return bytes;
}

}  // namespace

Status save_image_levels(const std::vector<Image>& levels, const fs::path& file,
                         const LevelsSaveOptions& options) {
    return save_image_level_chains({{std::string(), levels}}, file, options);
}

Status save_image_level_chains(const std::vector<LevelChain>& parts, const fs::path& file,
                               const LevelsSaveOptions& options) {
    if (kind_of(file) != FileKind::exr)
        return write_error(file, "MIP levels are written as OpenEXR; name the file .exr");
    if (parts.empty()) return write_error(file, "no MIP chains given");
    for (std::size_t p = 0; p < parts.size(); ++p)
        if (auto problem = levels_problem(parts[p].levels, options))
            return write_error(
                file,
                (parts.size() > 1 ? "part " + std::to_string(p) + ": " : std::string()) + *problem);
    if (!(options.tile_size >= 16 && options.tile_size <= 1024))
        return write_error(
            file, "tile size " + std::to_string(options.tile_size) + " is outside 16 to 1024");
    Result<std::vector<unsigned char>> bytes = parts.size() == 1
                                                   ? encode_levels(parts[0].levels, file, options)
                                                   : detail::encode_exr_parts(parts, options);
    if (!bytes) return write_error(file, bytes.error().message);
    return write_file_atomically(
        file, std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()));
}

namespace {

// OpenImageIO's output to an open file, every write checked as write_temporary() checks its
// writes (through the test seam too): the first error is kept, and every write after it fails.
class CheckedFileOutput final : public OIIO::Filesystem::IOProxy {
  public:
    explicit CheckedFileOutput(int fd) : IOProxy("", Write), fd_(fd) {}
    const char* proxytype() const override { return "footprint-checked-file"; }
    std::size_t write(const void* data, std::size_t size) override {
        const std::size_t done = pwrite(data, size, m_pos);
        m_pos += static_cast<std::int64_t>(done);
        return done;
    }
    std::size_t pwrite(const void* data, std::size_t size, std::int64_t offset) override {
        if (error_ == 0 && ::lseek(fd_, offset, SEEK_SET) < 0) error_ = errno;
        const detail::WriteCall hook = write_call.load();
        const detail::WriteCall write = hook != nullptr ? hook : system_write;
        std::size_t done = 0;
        while (done < size && error_ == 0) {
            const long n = write(fd_, static_cast<const char*>(data) + done, size - done);
            if (n > 0) {
                done += static_cast<std::size_t>(n);
            } else if (n < 0 && errno == EINTR) {
                continue;
            } else {
                error_ = n < 0 ? errno : EIO;
            }
        }
        end_ = std::max(end_, static_cast<std::size_t>(offset) + done);
        return done;
    }
    std::size_t size() const override { return end_; }
    int error() const { return error_; }

  private:
    int fd_;
    int error_ = 0;
    std::size_t end_ = 0;
};

}  // namespace

struct LevelsWriter::State {
    fs::path file, temporary;
    LevelsSaveOptions options;
    int fd = -1;
    std::unique_ptr<CheckedFileOutput> proxy;
    std::unique_ptr<OIIO::ImageOutput> out;
    std::vector<Image> shapes;  // the levels written so far, as sizes only (levels_problem())
    bool failed = false;

    ~State() { abandon(); }
    // Drops the file being written: nothing is left behind.
    void abandon() {
        out.reset();
        if (fd >= 0) ::close(fd);
        fd = -1;
        if (!temporary.empty()) ::unlink(temporary.c_str());
        temporary.clear();
    }
    Error fail(const std::string& cause) {
        failed = true;
        abandon();
        return write_error(file, cause);
    }
    // The cause of a failed write: the file's own error, else OpenImageIO's.
    std::string cause(const std::string& what) {
        if (proxy && proxy->error() != 0) return errno_text(proxy->error());
        return with_oiio_message(what, out ? out->geterror() : std::string());
    }
};

LevelsWriter::LevelsWriter(std::unique_ptr<State> state) : state_(std::move(state)) {}
LevelsWriter::LevelsWriter(LevelsWriter&&) noexcept = default;
LevelsWriter& LevelsWriter::operator=(LevelsWriter&&) noexcept = default;
LevelsWriter::~LevelsWriter() = default;

Result<LevelsWriter> LevelsWriter::open(const fs::path& file, const LevelsSaveOptions& options) {
    if (kind_of(file) != FileKind::exr)
        return write_error(file, "MIP levels are written as OpenEXR; name the file .exr");
    if (!(options.tile_size >= 16 && options.tile_size <= 1024))
        return write_error(
            file, "tile size " + std::to_string(options.tile_size) + " is outside 16 to 1024");
    if (options.channel_names.size() > 8)
        return write_error(file, std::to_string(options.channel_names.size()) +
                                     " channel names (1 to 8 named channels can be written)");
    if (auto problem = location_problem(file)) return write_error(file, *problem);
    auto state = std::make_unique<State>();
    state->file = file;
    state->options = options;
    state->temporary = temporary_path(file);
    state->fd = ::open(state->temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (state->fd < 0) {
        const int error = errno;
        state->temporary.clear();
        return write_error(file, "cannot create a temporary file beside it: " + errno_text(error));
    }
    state->proxy = std::make_unique<CheckedFileOutput>(state->fd);
    state->out = OIIO::ImageOutput::create("levels.exr");
    if (!state->out || !state->out->supports("mipmap") || !state->out->supports("ioproxy"))
        return state->fail(
            with_oiio_message("OpenImageIO cannot write MIP-mapped OpenEXR", OIIO::geterror()));
    state->out->set_ioproxy(state->proxy.get());
    return LevelsWriter(std::move(state));
}

Status LevelsWriter::write(const Image& level) {
    State& s = *state_;
    if (s.failed) return write_error(s.file, "an earlier level failed");
    // The level's shape against the levels before it, as save_image_levels() checks a chain.
    s.shapes.push_back(Image{});
    Image& shape = s.shapes.back();
    shape.width = level.width, shape.height = level.height, shape.channels = level.channels;
    const auto l = s.shapes.size() - 1;
    const auto names = static_cast<int>(s.options.channel_names.size());
    std::optional<std::string> problem = image_problem(level, names > 0 ? names : 4);
    if (!problem && names > 0 && level.channels != names)
        problem = std::to_string(names) + " channel names for " + std::to_string(level.channels) +
                  " channels";
    if (!problem && l > 0) {
        const Image& before = s.shapes[l - 1];
        const int w = std::max(1, before.width / 2), h = std::max(1, before.height / 2);
        if (before.width == 1 && before.height == 1)
            problem = std::string("the chain already ended at 1 x 1");
        else if (level.channels != before.channels)
            problem = "it has " + std::to_string(level.channels) + " channels, level 0 has " +
                      std::to_string(before.channels);
        else if (level.width != w || level.height != h)
            problem = "it is " + std::to_string(level.width) + " x " +
                      std::to_string(level.height) + ", not " + std::to_string(w) + " x " +
                      std::to_string(h);
    }
    if (problem) return s.fail("MIP level " + std::to_string(l) + ": " + *problem);
    // As encode_levels() writes a level, so that the bytes are the same.
    const OIIO::ImageSpec spec = level_spec(level.width, level.height, level.channels, s.options);
    const auto mode = l == 0 ? OIIO::ImageOutput::Create : OIIO::ImageOutput::AppendMIPLevel;
    if (!s.out->open(s.file.string(), spec, mode) ||
        !s.out->write_image(OIIO::TypeDesc::FLOAT, level.pixels.data()))
        return s.fail(s.cause("encoding MIP level " + std::to_string(l) + " failed"));
    return {};
}

Status LevelsWriter::finish() {
    State& s = *state_;
    if (s.failed) return write_error(s.file, "an earlier level failed");
    if (s.shapes.empty()) return s.fail("no levels given");
    if (const Image& last = s.shapes.back(); last.width != 1 || last.height != 1)
        return s.fail("the levels stop at " + std::to_string(last.width) + " x " +
                      std::to_string(last.height) + ", not 1 x 1");
    // OpenImageIO's OpenEXR writer writes the chunk tables as it is destroyed (encode_levels()).
    const bool closed = s.out->close();
    const std::string oiio_message = s.out->geterror();
    s.out.reset();
    if (!closed || s.proxy->error() != 0)
        return s.fail(s.proxy->error() != 0
                          ? errno_text(s.proxy->error())
                          : with_oiio_message("finishing the encoding failed", oiio_message));
    int error = ::fsync(s.fd) != 0 ? errno : 0;
    if (::close(s.fd) != 0 && error == 0) error = errno;
    s.fd = -1;
    if (error != 0) return s.fail(errno_text(error));
    const fs::path temporary = std::exchange(s.temporary, fs::path());
    s.failed = true;  // finished: nothing more can be written
    return rename_all({temporary}, {s.file});
}

namespace detail {

WriteCall replace_write_call_for_testing(WriteCall call) {
    return write_call.exchange(call);
}

}  // namespace detail

}  // namespace footprint
