// apps/command_util.h — what every `footprint` command does the same way: one-line errors and
// checking an output path before any work is done.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "image/image.h"

namespace footprint {

// Prints "footprint: <message>" to stderr; returns 1 (the exit status of a failed command).
int fail(const std::string& message);

// 'path', quoted for messages.
std::string quoted(const std::filesystem::path& path);

// Why `file` cannot be written as an image (no file name, unsupported extension, missing
// directory, a directory), or nullopt if it can.
std::optional<std::string> output_file_problem(const std::filesystem::path& file);

// Writes `text` to `file` through a temporary file in the same directory and a rename: the file is
// either completely written or left untouched.
Status write_text_atomically(const std::filesystem::path& file, const std::string& text);

// All images (same size and channels) in a grid, `columns` wide, row-major, `gap` pixels apart on
// a dark grey background (opaque where the images have alpha).
Image contact_sheet(const std::vector<const Image*>& images, int columns, int gap);

}  // namespace footprint
