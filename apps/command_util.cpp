#include "command_util.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <system_error>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "bump/slope_map.h"
#include "demo_scenes.h"
#include "image/image_io.h"
#include "plane_view.h"
#include "scene/scene_file.h"

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
    return output_location_problem(file);
}

std::optional<std::string> output_location_problem(const fs::path& file) {
    std::error_code ec;
    const fs::path dir = file.parent_path();
    if (!dir.empty() && !fs::is_directory(dir, ec))
        return "cannot write " + quoted(file) + ": directory " + quoted(dir) + " does not exist";
    if (fs::is_directory(file, ec)) return "cannot write " + quoted(file) + ": it is a directory";
    return std::nullopt;
}

std::string with_shared_data_hint(const std::string& message) {
    // scene/scene_file.h: "…: file 'F' not found (resolved to 'P')"
    const std::size_t resolved = message.find(" not found (resolved to '");
    if (resolved == std::string::npos ||
        message.find("/shared/data/", resolved) == std::string::npos)
        return message;
    return message +
           "; the file belongs to the shared data set, which this scene needs in ../shared/data "
           "beside the repository (examples/README.md)";
}

void warn(const std::string& message) {
    std::cerr << "footprint: warning: " << message << "\n";
}

RunOutputs::~RunOutputs() {
    if (kept_) return;
    std::error_code ignored;
    for (auto file = files_.rbegin(); file != files_.rend(); ++file) fs::remove(*file, ignored);
    // Deepest first; fs::remove leaves a directory that is not empty (another run's files).
    for (auto dir = directories_.rbegin(); dir != directories_.rend(); ++dir)
        fs::remove(*dir, ignored);
}

Status RunOutputs::create_directories(const fs::path& dir) {
    std::vector<fs::path> missing;  // dir and its missing parents, deepest first
    std::error_code ec;
    for (fs::path p = dir; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        missing.push_back(p);
        if (p == p.parent_path()) break;
    }
    fs::create_directories(dir, ec);
    if (!ec && !fs::is_directory(dir, ec)) ec = std::make_error_code(std::errc::not_a_directory);
    if (ec) return Error{"cannot create " + quoted(dir) + ": " + ec.message()};
    directories_.insert(directories_.end(), missing.rbegin(), missing.rend());
    return {};
}

Status RunOutputs::save(const std::vector<ImageToSave>& images, const ImageSaveOptions& options) {
    if (Status saved = save_images(images, options); !saved) return saved;
    for (const ImageToSave& item : images) files_.push_back(item.file);
    return {};
}

Status RunOutputs::save(const Image& image, const fs::path& file, const ImageSaveOptions& options) {
    return save({{&image, file}}, options);
}

Status RunOutputs::write(const fs::path& file, std::string_view bytes) {
    if (Status written = write_file_atomically(file, bytes); !written) return written;
    files_.push_back(file);
    return {};
}

namespace {

constexpr float kBackground = 0.18f;  // linear grey between the panels
constexpr float kStrip = 0.01f;       // near black under the labels: white text reads on it
constexpr int kMinFontSize = 8;       // smaller is not legible; longer labels are clipped

// The label font's size for panels `width` pixels wide: about 23 characters of DejaVu Sans
// across a panel at the largest size, smaller panels smaller text.
int label_font_size(int panel_width) {
    return std::clamp(panel_width / 23, 9, 14);
}

int strip_height(int font_size) {
    return font_size + font_size / 2 + 2;
}

// Why `font` cannot be used for labels, or nullopt.
std::optional<std::string> font_problem(const fs::path& font) {
    std::error_code ec;
    if (!fs::is_regular_file(font, ec))
        return "font " + quoted(font) + " not found (Debian package fonts-dejavu-core)";
    const OIIO::ROI size = OIIO::ImageBufAlgo::text_size("Ag", 12, font.string());
    if (!size.defined()) {
        std::string why = OIIO::geterror();
        if (why.empty()) why = "OpenImageIO cannot render text with it";
        return "font " + quoted(font) + ": " + why;
    }
    return std::nullopt;
}

// Draws `label` in white into `strip` of `sheet`, left-aligned, vertically centred, at the
// largest size up to `font_size` that fits the strip's width. A label that does not fit at the
// smallest size loses its last " | " fields (a demo's timing first) until it does, and is clipped
// to the strip if it still does not.
bool draw_label(OIIO::ImageBuf& sheet, const SheetRect& strip, std::string label, int font_size,
                const fs::path& font) {
    const int pad = std::max(2, font_size / 3);
    const auto fits = [&](const std::string& text, int size) {
        const OIIO::ROI extent = OIIO::ImageBufAlgo::text_size(text, size, font.string());
        return extent.defined() && extent.width() <= strip.width - 2 * pad;
    };
    int size = font_size;
    while (size > kMinFontSize && !fits(label, size)) --size;
    for (std::size_t bar; !fits(label, size) && (bar = label.rfind(" | ")) != std::string::npos;)
        label.erase(bar);
    // Drawn on a copy of the strip, then put back: OpenImageIO 2.4's render_text does not keep to
    // its clip region, so a long label would run into the next panel.
    const OIIO::ROI roi(strip.x, strip.x + strip.width, strip.y, strip.y + strip.height, 0, 1, 0,
                        sheet.nchannels());
    OIIO::ImageBuf text = OIIO::ImageBufAlgo::cut(sheet, roi);
    const std::vector<float> white(static_cast<std::size_t>(sheet.nchannels()), 1.0f);
    return OIIO::ImageBufAlgo::render_text(text, pad, strip.height / 2, label, size, font.string(),
                                           white, OIIO::ImageBufAlgo::TextAlignX::Left,
                                           OIIO::ImageBufAlgo::TextAlignY::Center) &&
           OIIO::ImageBufAlgo::paste(sheet, strip.x, strip.y, 0, 0, text);
}

void fill(Image& image, const SheetRect& r, float value) {
    for (int y = r.y; y < r.y + r.height; ++y)
        std::fill_n(image.at(r.x, y), static_cast<std::size_t>(r.width) * image.channels, value);
}

// Makes the alpha channel of 2- and 4-channel images 1 everywhere.
void make_opaque(Image& image) {
    if (image.channels != 2 && image.channels != 4) return;
    for (std::size_t p = 0; p < image.pixel_count(); ++p)
        image.pixels[p * image.channels + image.channels - 1] = 1.0f;
}

}  // namespace

ContactSheet contact_sheet(const std::vector<const Image*>& images,
                           const std::vector<std::string>& labels,
                           const ContactSheetOptions& options) {
    ContactSheet result;
    if (images.empty()) return result;
    const Image& first = *images.front();
    const int columns = std::max(1, options.columns), gap = std::max(0, options.gap);
    const int rows = (static_cast<int>(images.size()) + columns - 1) / columns;
    const int font_size = label_font_size(first.width);
    const int strip = labels.empty() ? 0 : strip_height(font_size);
    const int cell_height = first.height + strip;
    result.image = Image(columns * first.width + (columns + 1) * gap,
                         rows * cell_height + (rows + 1) * gap, first.channels, kBackground);
    Image& sheet = result.image;
    for (std::size_t i = 0; i < images.size(); ++i) {
        const int x0 = gap + static_cast<int>(i % columns) * (first.width + gap);
        const int y0 = gap + static_cast<int>(i / columns) * (cell_height + gap);
        result.panels.push_back({x0, y0, first.width, first.height});
        if (strip > 0) result.strips.push_back({x0, y0 + first.height, first.width, strip});
    }
    for (const SheetRect& r : result.strips) fill(sheet, r, kStrip);
    make_opaque(sheet);
    if (!labels.empty()) {
        if (const auto problem = font_problem(options.font)) {
            result.warning = "contact sheet labels not drawn: " + *problem;
        } else {
            OIIO::ImageBuf buffer(
                OIIO::ImageSpec(sheet.width, sheet.height, sheet.channels, OIIO::TypeDesc::FLOAT),
                sheet.pixels.data());
            for (std::size_t i = 0; i < result.strips.size() && i < labels.size(); ++i)
                if (!labels[i].empty() &&
                    !draw_label(buffer, result.strips[i], labels[i], font_size, options.font) &&
                    result.warning.empty())
                    result.warning =
                        "contact sheet label '" + labels[i] + "' not drawn: " + buffer.geterror();
        }
        make_opaque(sheet);
    }
    for (std::size_t i = 0; i < images.size(); ++i) {
        const SheetRect& r = result.panels[i];
        for (int y = 0; y < r.height; ++y)
            std::copy_n(images[i]->at(0, y), static_cast<std::size_t>(r.width) * sheet.channels,
                        sheet.at(r.x, r.y + y));
    }
    return result;
}

namespace {

std::string formatted(const char* pattern, double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, pattern, value);
    return buffer;
}

}  // namespace

std::string panel_label(const std::string& method, int spp, double rmse, double seconds) {
    std::string label = method + " | " + std::to_string(spp) + " spp";
    if (!std::isnan(rmse)) label += " | RMSE " + formatted("%.4g", rmse);
    if (std::isfinite(seconds))
        label += " | " + (seconds < 1 ? formatted("%.3g", seconds * 1e3) + " ms"
                                      : formatted("%.3g", seconds) + " s");
    return label;
}

bool is_float_image_file(const fs::path& file) {
    std::string ext = file.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".exr" || ext == ".hdr";
}

Result<NamedScene> resolve_scene(const std::string& name, std::optional<int> width) {
    const auto& demos = demo_scene_names();
    if (std::find(demos.begin(), demos.end(), name) != demos.end()) {
        DemoSceneOptions demo_options;
        if (width) {
            demo_options.width = *width;
            demo_options.height = plane_view_height(*width);
        }
        Result<DemoScene> demo = make_demo_scene(name, demo_options);
        if (!demo) return demo.error();
        return NamedScene{demo->name, demo->title, std::move(demo->scene)};
    }
    if (fs::path(name).extension() == ".json") {
        Result<SceneDesc> desc = load_scene_file(name);
        if (!desc) return Error{with_shared_data_hint(desc.error().message)};
        return NamedScene{fs::path(name).stem().string(), name, std::move(*desc)};
    }
    std::string valid;
    for (const std::string& n : demos) valid += (valid.empty() ? "" : ", ") + n;
    return Error{"unknown scene '" + name + "': not a built-in demo (" + valid +
                 ") nor a .json scene file"};
}

Result<Image> load_bump_slopes(const fs::path& input, bool height, bool clamp_invalid_normals) {
    ImageLoadOptions load;
    load.encoding = ColorEncoding::linear;  // a bump map's values are data, never sRGB
    if (!height) load.non_finite = NonFinitePolicy::keep;  // --invalid-normals decides
    Result<Image> map = load_image(input, load);
    if (!map) return map.error();
    Result<Image> slopes = [&] {
        if (height) {
            HeightMapOptions texels;
            texels.texel_size_u = 1.0f / static_cast<float>(map->width);
            texels.texel_size_v = 1.0f / static_cast<float>(map->height);
            return slopes_from_height_map(*map, texels);
        }
        NormalMapOptions normal;
        normal.invalid_normal_policy =
            clamp_invalid_normals ? InvalidNormalPolicy::clamp : InvalidNormalPolicy::error;
        return slopes_from_normal_map(*map, normal);
    }();
    if (!slopes)
        return Error{quoted(input) + " is not a " +
                     (height ? "height map" : "tangent-space normal map") + ": " +
                     slopes.error().message +
                     (height || clamp_invalid_normals
                          ? ""
                          : " (--invalid-normals clamp replaces such texels; --height reads a "
                            "height map)")};
    return slopes;
}

}  // namespace footprint
