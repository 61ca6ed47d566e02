#include "merge_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "command_util.h"
#include "image/image_io.h"

namespace footprint {

namespace {

struct Tile {
    std::filesystem::path file;
    ImageBand band;
    Image image;
    int end() const { return band.y + image.height; }
};

std::string rows(int begin, int end) {
    return "rows " + std::to_string(begin) + " to " + std::to_string(end - 1);
}

// The bands sorted by their first row, or what keeps them from being one image's rows.
Result<std::vector<Tile>> load_tiles(const std::vector<std::filesystem::path>& files) {
    std::vector<Tile> tiles;
    for (const std::filesystem::path& file : files) {
        Result<ImageBand> band = load_image_band(file);
        if (!band) return band.error();
        Result<Image> image = load_image(file, {.encoding = ColorEncoding::linear});
        if (!image) return image.error();
        tiles.push_back({file, *band, std::move(*image)});
    }
    std::sort(tiles.begin(), tiles.end(),
              [](const Tile& a, const Tile& b) { return a.band.y < b.band.y; });
    const Tile& first = tiles.front();
    int next = 0;  // the first row no tile has covered yet
    for (const Tile& tile : tiles) {
        if (tile.band.full_width != first.band.full_width ||
            tile.band.full_height != first.band.full_height || tile.image.channels != 3)
            return Error{quoted(tile.file) + " is a band of a " +
                         std::to_string(tile.band.full_width) + "x" +
                         std::to_string(tile.band.full_height) + " image with " +
                         std::to_string(tile.image.channels) + " channels, " + quoted(first.file) +
                         " of a " + std::to_string(first.band.full_width) + "x" +
                         std::to_string(first.band.full_height) + " RGB image"};
        if (tile.band.y > next) return Error{rows(next, tile.band.y) + " are in no tile"};
        if (tile.band.y < next)
            return Error{quoted(tile.file) + " (" + rows(tile.band.y, tile.end()) +
                         ") overlaps the tile before it, which ends at row " +
                         std::to_string(next - 1)};
        next = tile.end();
    }
    if (next < first.band.full_height)
        return Error{rows(next, first.band.full_height) + " are in no tile"};
    return tiles;
}

}  // namespace

int run_merge_command(const MergeCommandOptions& options) {
    if (options.tiles.empty()) return fail("merge: no tiles given");
    if (!std::isfinite(options.exposure)) return fail("--exposure: must be finite");
    if (const auto problem = output_file_problem(options.output)) return fail(*problem);
    Result<std::vector<Tile>> tiles = load_tiles(options.tiles);
    if (!tiles) return fail("merge: " + tiles.error().message);
    const ImageBand& full = tiles->front().band;
    Image image(full.full_width, full.full_height, 3);
    for (const Tile& tile : *tiles)
        std::copy(
            tile.image.pixels.begin(), tile.image.pixels.end(),
            image.pixels.begin() + static_cast<std::ptrdiff_t>(tile.band.y) * full.full_width * 3);
    if (!is_float_image_file(options.output) && options.exposure != 0) {
        const float scale = std::exp2(options.exposure);
        for (float& v : image.pixels) v *= scale;
    }
    if (Status saved = save_image(image, options.output); !saved)
        return fail(saved.error().message);
    if (!options.quiet)
        std::fprintf(stderr, "footprint: wrote %s (%dx%d, %zu tiles)\n",
                     options.output.string().c_str(), image.width, image.height, tiles->size());
    return 0;
}

}  // namespace footprint
