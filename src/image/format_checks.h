// image/format_checks.h — the checks of an image file's own structure that run before
// OpenImageIO's reader sees it (private to the image module; open_image_input() runs them).
//
// Each answers why the file is refused, or nothing. They guard against what OpenImageIO 2.4.7 and
// OpenEXR 3.1, Debian 12's, would do with a corrupt file: allocate what a header claims, or read
// and write past their buffers (each check names the upstream fix it stands in for).
#pragma once

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <filesystem>
#include <istream>
#include <optional>
#include <string>
#include <string_view>

namespace footprint::detail {

// A PNG's chunks (`in` just after its signature): truncated, a critical chunk corrupt, or Exif
// (an eXIf chunk, a "Raw profile type exif" text) OpenImageIO's decoder would read past.
std::optional<std::string> png_problem(std::istream& in);

// A JPEG's marker blocks up to its first scan (`in` just after its SOI): an Exif, XMP, ICC or IPTC
// block cut short, an IPTC block longer than its APP13 block, or an Exif block OpenImageIO's
// decoder would read past; or scans too short for the blocks of the texels a Huffman-coded frame
// claims.
std::optional<std::string> jpeg_problem(std::istream& in);

// The OpenEXR file `file`, also open as `in` (which the checks move about in): what OpenEXR's
// core library reports of its headers, a header its C++ reader (OpenImageIO's) reads otherwise,
// tiles tile_problem() refuses, a file too short for the chunks and texels it claims, or a chunk
// missing from its place or with a corrupt leader.
std::optional<std::string> exr_problem(const std::filesystem::path& file, std::istream& in);

// Tiles of `tile_width` × `tile_height` texels for an image of `width` × `height`: larger than the
// image and than 1024².
std::optional<std::string> tile_problem(std::uint64_t tile_width, std::uint64_t tile_height,
                                        std::uint64_t width, std::uint64_t height);

// "the file is truncated: its header claims W x H texels, more than its N bytes can hold": why
// each check that bounds a file's size refuses it. `counted` names the bytes counted where they
// are not the whole file's ("bytes of scans").
std::string claims_more_texels_than_bytes(std::uint64_t width, std::uint64_t height,
                                          std::uint64_t bytes, std::string_view counted = "bytes");

// A TIFF directory, as OpenImageIO describes it, that OpenImageIO 2.4 overruns its buffers
// reading: CMYK it converts to RGB, in tiles or of fewer than 8 bits a sample.
std::optional<std::string> tiff_cmyk_problem(const OIIO::ImageSpec& spec);

}  // namespace footprint::detail
