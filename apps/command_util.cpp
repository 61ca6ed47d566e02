#include "command_util.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <random>
#include <system_error>

#include "image/image_io.h"

namespace footprint {

namespace fs = std::filesystem;

int fail(const std::string& message) {
    std::cerr << "footprint: " << message << "\n";
    return 1;
}

std::string quoted(const fs::path& p) {
    return "'" + p.string() + "'";
}

// Fails if `file` cannot be written (before any work is done).
std::optional<std::string> output_file_problem(const fs::path& file) {
    if (file.empty() || file.filename().empty())
        return "cannot write " + quoted(file) + ": not a file name";
    if (!is_supported_image_extension(file))
        return "cannot write " + quoted(file) + ": unsupported extension '" +
               file.extension().string() + "' (supported: .png .jpg .jpeg .exr .hdr .tif .tiff)";
    std::error_code ec;
    const fs::path dir = file.parent_path();
    if (!dir.empty() && !fs::is_directory(dir, ec))
        return "cannot write " + quoted(file) + ": directory " + quoted(dir) + " does not exist";
    if (fs::is_directory(file, ec)) return "cannot write " + quoted(file) + ": it is a directory";
    return std::nullopt;
}

// Writes `text` to `file` through a temporary file in the same directory and a rename.
Status write_text_atomically(const std::filesystem::path& file, const std::string& text) {
    std::random_device random;
    const std::filesystem::path dir = file.parent_path();
    std::string temp_name = file.filename().string();
    temp_name.insert(temp_name.begin(), '.');
    temp_name += ".tmp-";
    temp_name += std::to_string(random());
    const std::filesystem::path temp = dir / temp_name;
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        out << text;
        out.flush();
        if (!out) {
            std::error_code ignored;
            std::filesystem::remove(temp, ignored);
            return Error{"cannot write " + quoted(file) + ": write failed"};
        }
    }
    std::error_code ec;
    std::filesystem::rename(temp, file, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
        return Error{"cannot write " + quoted(file) + ": " + ec.message()};
    }
    return {};
}

// All images (same size and channels) in a grid, `columns` wide, row-major, `gap` pixels apart.
Image contact_sheet(const std::vector<const Image*>& images, int columns, int gap) {
    const Image& first = *images.front();
    const int rows = (static_cast<int>(images.size()) + columns - 1) / columns;
    Image sheet(columns * first.width + (columns + 1) * gap, rows * first.height + (rows + 1) * gap,
                first.channels, 0.18f);
    if (first.channels == 2 || first.channels == 4)  // opaque background
        for (std::size_t p = 0; p < sheet.pixel_count(); ++p)
            sheet.pixels[p * sheet.channels + sheet.channels - 1] = 1.0f;
    for (std::size_t i = 0; i < images.size(); ++i) {
        const int x0 = gap + static_cast<int>(i % columns) * (first.width + gap);
        const int y0 = gap + static_cast<int>(i / columns) * (first.height + gap);
        for (int y = 0; y < first.height; ++y)
            std::copy_n(images[i]->at(0, y), static_cast<std::size_t>(first.width) * first.channels,
                        sheet.at(x0, y0 + y));
    }
    return sheet;
}

}  // namespace footprint
