// image/image_io.h — reading and writing image files (PNG, JPEG, EXR, HDR, TIFF, …).
//
// load_image() reads any format OpenImageIO reads into an Image; save_image() writes an Image as
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
//   * Non-finite values in a file (NaN, +Inf, −Inf) are replaced by 0 on load, so they never
//     reach a pixel. Images larger than 2^32 values (16 GiB of floats) are refused.
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
// "… it is a directory", "… the file is empty", "… the file is truncated or corrupt
// (OpenImageIO: …)", "… it has 5 channels; footprint reads 1 to 4", "… the image has zero size";
// "cannot write 'b.exr': directory 'out' does not exist", "… unsupported extension '.bmp'
// (supported: …)". A failed load never returns an image. PNG files are checked for truncation
// and chunk checksum errors before they are decoded.
//
// Atomic saves: save_image writes a hidden temporary file in the target's directory
// (".<name>.tmp-<random>.<ext>") and renames it onto the target when it is complete. On any
// failure the temporary file is removed: the target is either fully replaced or left untouched,
// and no partial file is left behind.
//
// All functions are thread-safe for distinct files.
#pragma once

#include <filesystem>

#include "core/result.h"
#include "image/image.h"

namespace footprint {

enum class ColorEncoding { automatic, srgb, linear };

struct ImageLoadOptions {
    // automatic: integer-valued files are sRGB-encoded and decoded to linear unless their
    // metadata says linear; float files are linear. srgb / linear force the choice. Alpha is
    // never decoded.
    ColorEncoding encoding = ColorEncoding::automatic;
};

// Reads `file` (any format OpenImageIO reads) into a linear-light float Image with 1–4 channels.
Result<Image> load_image(const std::filesystem::path& file, const ImageLoadOptions& options = {});

struct ImageSaveOptions {
    // automatic: sRGB for .png .jpg .jpeg .tif .tiff, linear for .exr .hdr. srgb / linear force
    // the encoding for any format.
    ColorEncoding encoding = ColorEncoding::automatic;
    int bits = 8;           // 8 or 16 for PNG and TIFF; JPEG accepts only 8; ignored for EXR/HDR
    bool exr_half = false;  // EXR: write 16-bit half floats instead of 32-bit floats
};

// Writes `image` to `file`, the format chosen by the extension (see is_supported_image_extension).
// The target is replaced atomically; on failure nothing is left behind.
Status save_image(const Image& image, const std::filesystem::path& file,
                  const ImageSaveOptions& options = {});

// True if save_image can write `file`'s extension (case-insensitive): .png .jpg .jpeg .exr .hdr
// .tif .tiff. load_image reads these and any other format OpenImageIO supports.
bool is_supported_image_extension(const std::filesystem::path& file);

}  // namespace footprint
