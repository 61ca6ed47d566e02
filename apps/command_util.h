// apps/command_util.h — what every `footprint` command does the same way: one-line errors and
// checking an output path before any work is done.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.h"
#include "image/image.h"
#include "image/image_io.h"
#include "scene/scene.h"

namespace footprint {

// Prints "footprint: <message>" to stderr; returns 1 (the exit status of a failed command).
int fail(const std::string& message);

// 'path', quoted for messages.
std::string quoted(const std::filesystem::path& path);

// Why `file` cannot be written as an image (no file name, unsupported extension, missing
// directory, a directory), or nullopt if it can.
std::optional<std::string> output_file_problem(const std::filesystem::path& file);
// The same for where `file` is, whatever it holds: a missing directory, a directory.
std::optional<std::string> output_location_problem(const std::filesystem::path& file);

// The slopes of a bump map file at strength 1, read as `footprint maketx --bump` and `footprint
// bake bump` read it (data, never sRGB): a tangent-space normal map's b = (n_x, n_y)/n_z, invalid
// normals refused unless clamp_invalid_normals; or with `height` a height map's b = −∇h per unit
// of (u, v). The error names the file and what it is not.
Result<Image> load_bump_slopes(const std::filesystem::path& input, bool height,
                               bool clamp_invalid_normals);

// Whether an output file holds linear radiance as rendered (.exr, .hdr) rather than sRGB-encoded
// integers (exposure applies to those only).
bool is_float_image_file(const std::filesystem::path& file);

// `message` of a scene file that did not load; where the missing file is one of the optional shared
// data set (../shared/data beside the repository, which a clone lacks), it says so.
std::string with_shared_data_hint(const std::string& message);

// Prints "footprint: warning: <message>" to stderr (the command goes on).
void warn(const std::string& message);

// The files and directories one run of a command writes, removed again unless the run completes:
// a command that fails part way (a full disk, an unwritable file) leaves nothing of its own run
// behind (a file of an earlier run that it had already replaced goes too). Each file is written
// completely or not at all (save_images, write_file_atomically); the directories the run created
// are removed with its files when nothing else is in them.
class RunOutputs {
  public:
    RunOutputs() = default;
    RunOutputs(const RunOutputs&) = delete;
    RunOutputs& operator=(const RunOutputs&) = delete;
    ~RunOutputs();  // unless keep() was called: removes the files, then the directories created

    // Creates `dir` and its missing parents: "cannot create 'out/a': Not a directory".
    Status create_directories(const std::filesystem::path& dir);
    // save_images (image_io.h): all the images or none; the message names the file at fault.
    Status save(const std::vector<ImageToSave>& images, const ImageSaveOptions& options = {});
    Status save(const Image& image, const std::filesystem::path& file,
                const ImageSaveOptions& options = {});
    Status write(const std::filesystem::path& file, std::string_view bytes);
    // The run completed: what it wrote stays.
    void keep() { kept_ = true; }

  private:
    std::vector<std::filesystem::path> files_, directories_;  // in the order they were made
    bool kept_ = false;
};

// The font of contact-sheet labels (Debian package fonts-dejavu-core).
inline constexpr const char* kLabelFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

struct ContactSheetOptions {
    int columns = 3;
    int gap = 4;  // pixels between the panels and around them
    // A TrueType file. If it cannot be read the sheet keeps its label strips, blank, and
    // ContactSheet::warning says why.
    std::filesystem::path font = kLabelFont;
};

// A rectangle of a sheet in pixels: columns x … x + width − 1, rows y … y + height − 1.
struct SheetRect {
    int x = 0, y = 0, width = 0, height = 0;
};

struct ContactSheet {
    Image image;
    std::vector<SheetRect> panels;  // where each image was copied, unchanged
    std::vector<SheetRect> strips;  // the label strip under each panel (none without labels)
    std::string warning;            // empty, or one line saying why no label was drawn
};

// All images (same size and channels) in a grid, `options.columns` wide, row-major, `gap` pixels
// apart on a dark grey background (opaque where the images have alpha). With labels (one per
// image) each panel gets a near-black strip under it holding its label in white, shrunk to fit
// the panel's width down to a legible minimum and clipped beyond it; the panels themselves are
// the images' pixels, untouched.
ContactSheet contact_sheet(const std::vector<const Image*>& images,
                           const std::vector<std::string>& labels,
                           const ContactSheetOptions& options = {});

// A panel's label, in ASCII (OpenImageIO 2.4 draws bytes, not UTF-8):
// "fa-rough | 1 spp | RMSE 0.2703 | 31 ms"; without the RMSE part when `rmse` is NaN (the
// reference itself).
std::string panel_label(const std::string& method, int spp, double rmse, double seconds);

// A scene named on the command line: a built-in demo scene by name (apps/demo_scenes.h), `width`
// pixels wide and plane_view_height(width) high where a width is given (else its own size), or a
// scene file (.json, its own size). The error names an unknown name with the valid ones.
struct NamedScene {
    std::string name, title;
    SceneDesc desc;
};
Result<NamedScene> resolve_scene(const std::string& name, std::optional<int> width = std::nullopt);

}  // namespace footprint
