// image/image_input.h — opening an image file for reading with OpenImageIO, private to the modules
// that read files (image, bump, envmap, texsys). Every reader in footprint opens files here, so
// that a corrupt file meets the same checks wherever it is read.
//
// OpenImageIO's ImageInput::open() trusts more than footprint can: when the reader the extension
// names refuses a file, it hands the file to every other reader it has (DICOM, camera raw, FITS,
// …), and OpenEXR 3.1's C++ reader allocates whatever a corrupt header's attribute sizes claim
// (gigabytes, for a 2 KB file). open_image_input() opens with the extension's reader only, and
// checks a PNG's chunks, a JPEG's marker blocks and an OpenEXR's headers before that reader sees
// them, and every TIFF directory's tiles and colour space after (format_checks.h).
#pragma once

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <memory>
#include <string>

#include "core/result.h"
#include "image/image_io.h"

namespace footprint::detail {

// `file` opened by the OpenImageIO reader its extension names, its first subimage current, its
// texels to be read as stored: unassociated (straight) alpha is not multiplied into the colour, as
// OpenImageIO's TIFF and PNG readers otherwise do. The error is
// "cannot read '<file>': <cause>": no such file, a directory, an empty file, no reader for the
// extension, a corrupt PNG chunk or JPEG marker block, a corrupt OpenEXR header (OpenEXR's words,
// or footprint's), a file too short for what its header claims, the reader's refusal
// (OpenImageIO's words), or, in any subimage or MIP level (a TIFF directory), tiles far larger
// than their image or CMYK OpenImageIO cannot convert safely.
Result<std::unique_ptr<OIIO::ImageInput>> open_image_input(const std::filesystem::path& file);

// Whether load_image with ColorEncoding::automatic decodes a file whose header is `spec` from sRGB
// (is_srgb_encoded(), image_io.h, on a file already open).
bool automatic_decodes_srgb(const OIIO::ImageSpec& spec);
// Whether load_image with `encoding` decodes a file whose header is `spec` from sRGB.
bool decodes_srgb(ColorEncoding encoding, const OIIO::ImageSpec& spec);

// "cannot read '<file>': <cause>", the error every reader gives.
Error read_error(const std::filesystem::path& file, const std::string& cause);

// OpenImageIO's message (often several lines) as one line: its lines joined with "; ", "" when
// it has none.
std::string one_line(const std::string& message);

}  // namespace footprint::detail
