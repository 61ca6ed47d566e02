// image/image_io.h — reading and writing image files (PNG, JPEG, EXR, HDR, TIFF, …).
//
// load_image() reads any format OpenImageIO reads into an Image, with the reader the file's
// extension names (a PNG named .exr is refused, not guessed); save_image() writes an Image as
// PNG, JPEG, EXR, Radiance HDR or TIFF, chosen by the file's extension.
//
// Conventions
//   * Images are linear light, 1–4 interleaved channels, row-major, top row first (image.h).
//     The channel count says what they are: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA. With 2 and 4
//     channels the last one is alpha; with 1 and 3 there is none.
//   * Loading reads the first subimage at MIP level 0, all channels, converted to float. A file
//     with 0 or more than 4 channels is refused (pick the channels with another tool first).
//   * Alpha is stored as the file holds it: straight (unassociated) in PNG, TIFF and JPEG files,
//     premultiplied by convention in EXR. Nothing is premultiplied or divided on load or save.
//   * Non-finite values in a file (NaN, +Inf, −Inf) are refused by default: the error names the
//     file, how many there are and the first in row-major order ("cannot read 'sky.exr': 3
//     values are not finite (NaN or infinite), the first at texel (4, 7) channel 0 (nan)").
//     ImageLoadOptions::non_finite can repair them instead (each replaced by the mean of
//     the finite values of the same channel among its 8 neighbours in the file, 0 if it has none,
//     reported through ImageLoadOptions::warn) or keep them (for tools that count them).
//   * Images larger than 2^32 values (16 GiB of floats) are refused.
//
// Colour handling (image/color.h holds the exact sRGB curve)
//   Load, ColorEncoding::automatic: integer-valued files (8/16-bit PNG, JPEG, 8/16-bit TIFF)
//     hold sRGB-encoded values and are decoded to linear — unless the file's metadata says it is
//     linear (a PNG with gAMA 1.0, as save_image writes with ColorEncoding::linear). Float files
//     (EXR, HDR, float TIFF) are linear and loaded as stored.
//   Load, srgb / linear: force the choice whatever the file says. Normal maps, height maps and
//     other data textures are not colours: load them with ColorEncoding::linear.
//   Save, automatic: by extension. .png .jpg .jpeg .tif .tiff are written sRGB-encoded, 8 bits
//     per channel (PNG and TIFF 16 bits if options.bits == 16; JPEG is 8-bit only). .exr is
//     written linear, 32-bit float (16-bit half if options.exr_half); .hdr linear RGB (RGBE).
//   Save, srgb / linear: force the encoding. Integer files get their encoding in their metadata
//     (PNG: sRGB chunk or gAMA 1.0), so load with automatic reads them back as they were saved;
//     float files are always loaded as linear by automatic.
//   Encoding to sRGB applies linear_to_srgb() to the colour channels; alpha is never encoded.
//   Integer formats clamp every value to [0, 1] and round to the nearest code (NaN becomes 0).
//   EXR keeps any finite value (float bit-exactly, half to its precision); HDR keeps values
//   above 1 to RGBE precision (1/128 of the pixel's largest component) but has no negatives:
//   they become 0.
//
// Format limits on save
//   JPEG has no alpha: a grey + alpha image is written grey, RGBA is written RGB.
//   HDR holds RGB only: grey is replicated to R = G = B, and alpha is dropped.
//
// Errors (core/result.h): nothing is printed and nothing throws. Every failure returns an Error
// whose message names the file in quotes and the cause: "cannot read 'a.png': no such file",
// "… it is a directory", "… the file is empty", "… OpenImageIO's png reader cannot read it: it is
// corrupt, truncated or of another format (OpenImageIO: …)", "… the file is truncated or corrupt
// (OpenImageIO: …)", "… it has 5 channels; footprint reads 1 to 4", "… the image has zero size";
// "cannot write 'b.exr': directory 'out' does not exist", "… unsupported extension '.bmp'
// (supported: …)", "… No space left on device" (the system's text for a failed write, fsync or
// close). A failed load never returns an image. PNG files are checked for truncation
// and chunk checksum errors, OpenEXR files' headers by OpenEXR's core library ("… the OpenEXR
// header is corrupt (OpenEXR: …)"), before they are decoded.
//
// Atomic, checked saves: OpenImageIO encodes the file into memory (its writers do not all report
// a failed write, e.g. libpng on a full disk), then save_image writes the bytes to a hidden
// temporary file in the target's directory (".<name>.tmp-<random>.<ext>"), checking every write,
// the fsync and the close, and renames it onto the target. On any failure the temporary file is
// removed and the error names the target and the cause ("cannot write 'out.png': No space left
// on device"): the target is either fully replaced or left untouched, nothing else is left.
//
// Reproducible files: the same pixels and options give the same bytes, whenever and wherever they
// are written. No time stamp is written (OpenImageIO's DateTime: EXR capDate, TIFF DateTime; PNG
// gets no tIME chunk), nor a host or user name. TIFF files carry no Exif block (OpenImageIO 2.4
// cannot write one to memory), so an sRGB TIFF says nothing about its encoding; sRGB is what
// readers, and load_image's automatic, assume for 8- and 16-bit TIFF.
//
// All functions are thread-safe for distinct files.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <footprint/core/result.h>
#include <footprint/image/image.h>

namespace footprint {

enum class ColorEncoding { automatic, srgb, linear };

// NaN and ±Inf in a loaded file: an error (refuse), replaced and reported (repair), or left in
// the image (keep).
enum class NonFinitePolicy { refuse, repair, keep };

struct ImageLoadOptions {
    // automatic: integer-valued files are sRGB-encoded and decoded to linear unless their
    // metadata says linear; float files are linear. srgb / linear force the choice. Alpha is
    // never decoded.
    ColorEncoding encoding = ColorEncoding::automatic;
    // What to do with NaN and ±Inf values (see Conventions above).
    NonFinitePolicy non_finite = NonFinitePolicy::refuse;
    // repair: called once if anything was repaired, with a message naming the file, the count
    // and the first value ("'sky.exr': replaced 3 non-finite values (NaN or infinite) by the
    // mean of the finite neighbours, the first at texel (4, 7) channel 0 (nan)"). May be empty.
    std::function<void(const std::string&)> warn = {};
};

// Reads `file` (any format OpenImageIO reads, by its extension) into a linear-light float Image
// with 1–4 channels.
Result<Image> load_image(const std::filesystem::path& file, const ImageLoadOptions& options = {});

// Every MIP level `file` stores (those of its first subimage: OpenImageIO maketx's .tx files,
// tiled MIP-mapped OpenEXR and TIFF), level 0 first, each read and decoded as load_image reads an
// image; a file without MIP levels gives its one image. Errors are load_image's, with the level
// where one is bad ("… MIP level 3: …").
Result<std::vector<Image>> load_image_levels(const std::filesystem::path& file,
                                             const ImageLoadOptions& options = {});

struct LevelsSaveOptions {
    // OpenImageIO's "wrapmodes" attribute, which maketx writes and texture systems read:
    // "periodic,clamp" (s, then t; black, clamp, periodic, mirror). Empty: none written.
    std::string wrap_modes;
    int tile_size = 64;  // tiles of tile_size² texels, 16 to 1024
    // One name per channel, 1 to 8 channels (a bump pyramid's moments); empty: Y, YA, RGB, RGBA
    // for 1–4 channels.
    std::vector<std::string> channel_names;
    // Header attributes of floats besides OpenImageIO's, e.g. {"footprint:slope_offset", {x, y}}.
    struct FloatAttribute {
        std::string name;
        std::vector<float> values;
    };
    std::vector<FloatAttribute> float_attributes;
    std::vector<std::pair<std::string, std::string>> string_attributes;  // likewise, strings
};

// Writes `levels` as one tiled, MIP-mapped OpenEXR file of 32-bit floats (linear, as stored),
// atomically as save_image: level 0 first, each level max(1, ⌊W/2⌋) × max(1, ⌊H/2⌋) of the one
// before down to 1×1 (OpenEXR's round-down chain, MipPyramid's level sizes), 1–4 channels alike.
// Errors name the file and, where the levels are wrong, the level.
Status save_image_levels(const std::vector<Image>& levels, const std::filesystem::path& file,
                         const LevelsSaveOptions& options = {});

// save_image_levels()' file written a level at a time, for a chain too large to hold whole
// (for_each_mip_level(), texture/mip_pyramid.h, makes one level at a time): the same bytes as
// save_image_levels() of the same levels and options, each level encoded as it comes into a
// temporary file beside the target (".<name>.tmp-<random>.exr", every write checked as save_image
// checks them), which finish() syncs and renames onto it. A writer destroyed before finish(), or
// one whose write failed, removes its temporary file: the target is either the complete file or
// left untouched, and concurrent writers of one target each rename a complete file onto it.
class LevelsWriter {
  public:
    // A writer of `file`'s levels, or the error naming it (not .exr, no such directory, options
    // save_image_levels() refuses).
    static Result<LevelsWriter> open(const std::filesystem::path& file,
                                     const LevelsSaveOptions& options = {});
    LevelsWriter(LevelsWriter&&) noexcept;
    LevelsWriter& operator=(LevelsWriter&&) noexcept;
    ~LevelsWriter();

    // The next level: level 0 first (1–4 channels, or as many as options.channel_names), then each
    // max(1, ⌊W/2⌋) × max(1, ⌊H/2⌋) of the one before. A level that does not fit is an error naming
    // it; any error ends the writer (its temporary file removed).
    Status write(const Image& level);
    // After the 1×1 level: the file made complete and moved onto the target.
    Status finish();

  private:
    struct State;
    explicit LevelsWriter(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

// Several MIP chains as the parts of one such file (OpenEXR multi-part; OpenImageIO's subimages),
// each written as save_image_levels() writes its one, part i named parts[i].name (OpenEXR requires
// distinct names when there is more than one part); the options apply to every part.
struct LevelChain {
    std::string name;
    std::vector<Image> levels;
};
Status save_image_level_chains(const std::vector<LevelChain>& parts,
                               const std::filesystem::path& file,
                               const LevelsSaveOptions& options = {});

// A band of rows of a larger image, as an OpenEXR file's data window inside its display window:
// rows [y, y + the image's height) of a full_width × full_height image, whose width it has (a
// render split across machines: `footprint render --tile`, `footprint merge`).
struct ImageBand {
    int y = 0;
    int full_width = 0, full_height = 0;
};

struct ImageSaveOptions {
    // automatic: sRGB for .png .jpg .jpeg .tif .tiff, linear for .exr .hdr. srgb / linear force
    // the encoding for any format.
    ColorEncoding encoding = ColorEncoding::automatic;
    int bits = 8;           // 8 or 16 for PNG and TIFF; JPEG accepts only 8; ignored for EXR/HDR
    bool exr_half = false;  // EXR: write 16-bit half floats instead of 32-bit floats
    // EXR only (an error for the other formats, which have no data window): the image is this
    // band of a larger one.
    std::optional<ImageBand> band = std::nullopt;
};

// Where `file`'s pixels sit in its full image (its header only): an OpenEXR band's rows, or the
// whole image (y = 0, the full size its own) for every other file. A data window that is not a
// band of whole rows is refused, naming the file.
Result<ImageBand> load_image_band(const std::filesystem::path& file);

// Writes `image` to `file`, the format chosen by the extension (see is_supported_image_extension).
// The target is replaced atomically; on failure nothing is left behind.
Status save_image(const Image& image, const std::filesystem::path& file,
                  const ImageSaveOptions& options = {});

struct ImageToSave {
    const Image* image = nullptr;
    std::filesystem::path file;
};
// Writes several images as one step: every file is encoded and written under its temporary name
// first, and only when all of them are complete are they renamed onto their targets. On failure
// nothing is left behind and no target is touched (unless a rename itself fails, which the
// message then says).
Status save_images(const std::vector<ImageToSave>& images, const ImageSaveOptions& options = {});

// Whether load_image with ColorEncoding::automatic decodes `file` from sRGB: integer samples whose
// metadata does not say linear (see "Colour handling" above). Reads only the header; false when it
// cannot be read.
bool is_srgb_encoded(const std::filesystem::path& file);

// Writes `bytes` to `file` as save_image writes an encoded image: through a temporary file in the
// same directory, every write, the fsync and the close checked, then a rename. For reports (JSON,
// CSV, HTML) that must not be left half-written either.
Status write_file_atomically(const std::filesystem::path& file, std::string_view bytes);

// True if save_image can write `file`'s extension (case-insensitive): .png .jpg .jpeg .exr .hdr
// .tif .tiff. load_image reads these and any other format OpenImageIO supports (by extension).
bool is_supported_image_extension(const std::filesystem::path& file);

}  // namespace footprint
