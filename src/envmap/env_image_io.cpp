#include "envmap/env_image_io.h"

#include <openexr.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <system_error>

namespace footprint {

namespace {

namespace fs = std::filesystem;

constexpr const char* kFaceNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

std::string quoted(const fs::path& p) {
    return "'" + p.string() + "'";
}

std::string size_text(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

// How a face is drawn in its cell. All are involutions, so one mapping serves split and assemble.
enum class CellTransform { identity, rotate180, mirror_x, mirror_y };

struct Cell {
    int column = 0, row = 0;
    CellTransform transform = CellTransform::identity;
};

// Where each face (+X −X +Y −Y +Z −Z) sits in an arrangement (see env_image_io.h).
std::array<Cell, 6> cells_of(CubeArrangement arrangement) {
    using T = CellTransform;
    switch (arrangement) {
        case CubeArrangement::automatic:
        case CubeArrangement::horizontal_cross:
            return {{{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}}};
        case CubeArrangement::vertical_cross:
            return {{{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {1, 3, T::rotate180}}};
        case CubeArrangement::strip_3x2:
            return {{{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}}};
        case CubeArrangement::strip_2x3:
            return {{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0, 2}, {1, 2}}};
        case CubeArrangement::column:
            return {{{0, 0}, {0, 1}, {0, 2}, {0, 3}, {0, 4}, {0, 5}}};
        case CubeArrangement::row:
            return {{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}}};
        case CubeArrangement::openexr_column:
            // ImfEnvmap.cpp, CubeMap::direction + pixelPosition: OpenEXR's faces are ours mirrored.
            return {{{0, 0, T::mirror_x},
                     {0, 1, T::mirror_x},
                     {0, 2, T::mirror_y},
                     {0, 3, T::mirror_y},
                     {0, 4, T::mirror_x},
                     {0, 5, T::mirror_x}}};
    }
    return {};
}

// The pixel of the cell (relative to its corner) that shows face pixel (x, y), face size n.
std::array<int, 2> cell_pixel(CellTransform transform, int n, int x, int y) {
    switch (transform) {
        case CellTransform::identity:
            return {x, y};
        case CellTransform::rotate180:
            return {n - 1 - x, n - 1 - y};
        case CellTransform::mirror_x:
            return {n - 1 - x, y};
        case CellTransform::mirror_y:
            return {x, n - 1 - y};
    }
    return {x, y};
}

const char* arrangement_description(CubeArrangement arrangement) {
    switch (arrangement) {
        case CubeArrangement::automatic:
            return "cube map";
        case CubeArrangement::horizontal_cross:
            return "a horizontal cross needs 4N x 3N pixels";
        case CubeArrangement::vertical_cross:
            return "a vertical cross needs 3N x 4N pixels";
        case CubeArrangement::strip_3x2:
            return "a 3x2 strip needs 3N x 2N pixels";
        case CubeArrangement::strip_2x3:
            return "a 2x3 strip needs 2N x 3N pixels";
        case CubeArrangement::column:
            return "a column of faces needs N x 6N pixels";
        case CubeArrangement::row:
            return "a row of faces needs 6N x N pixels";
        case CubeArrangement::openexr_column:
            return "an OpenEXR cube map needs N x 6N pixels";
    }
    return "";
}

// Face pixel (x, y) ↔ pixel (x0, y0) + cell_pixel(transform, n, x, y) of the arranged image:
// copy_face writes a face into its cell, extract_face reads it back.
void copy_face(const Image& face, Image& image, int x0, int y0, CellTransform transform) {
    const int n = face.width;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const auto p = cell_pixel(transform, n, x, y);
            std::copy_n(face.at(x, y), face.channels, image.at(x0 + p[0], y0 + p[1]));
        }
}
void extract_face(const Image& image, int x0, int y0, CellTransform transform, Image& face) {
    const int n = face.width;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const auto p = cell_pixel(transform, n, x, y);
            std::copy_n(image.at(x0 + p[0], y0 + p[1]), image.channels, face.at(x, y));
        }
}

// Black, opaque where the image has alpha (2 or 4 channels): the empty cells of a cross.
Image opaque_black(int width, int height, int channels) {
    Image image(width, height, channels, 0.0f);
    if (channels == 2 || channels == 4)
        for (std::size_t p = 0; p < image.pixel_count(); ++p)
            image.pixels[p * channels + channels - 1] = 1.0f;
    return image;
}

}  // namespace

std::optional<EnvLayout> env_layout_from_size(int width, int height) {
    if (width <= 0 || height <= 0) return std::nullopt;
    // Lat-long maps resized by hand are often a pixel or so off 2:1; no other layout is near it.
    if (std::abs(width - 2 * height) <= std::max(1, height / 50)) return EnvLayout::latlong;
    if (width == height) return EnvLayout::sphere;
    if (cube_arrangement_from_size(width, height)) return EnvLayout::cube;
    return std::nullopt;
}

namespace {

Status check_square(const Image& image, const std::string& what) {
    if (image.width != image.height)
        return Error{what + " is " + size_text(image) + ", not square"};
    return {};
}

// Fails if `file` cannot be a save_image target (before anything is written).
Status check_output_file(const fs::path& file) {
    if (file.empty() || file.filename().empty())
        return Error{"cannot write " + quoted(file) + ": not a file name"};
    if (!is_supported_image_extension(file))
        return Error{"cannot write " + quoted(file) + ": unsupported extension '" +
                     file.extension().string() +
                     "' (supported: .png .jpg .jpeg .exr .hdr .tif .tiff)"};
    std::error_code ec;
    const fs::path dir = file.parent_path();
    if (!dir.empty() && !fs::is_directory(dir, ec))
        return Error{"cannot write " + quoted(file) + ": directory " + quoted(dir) +
                     " does not exist"};
    if (fs::is_directory(file, ec))
        return Error{"cannot write " + quoted(file) + ": it is a directory"};
    return {};
}

}  // namespace

const char* cube_arrangement_name(CubeArrangement arrangement) {
    switch (arrangement) {
        case CubeArrangement::automatic:
            return "auto";
        case CubeArrangement::horizontal_cross:
            return "hcross";
        case CubeArrangement::vertical_cross:
            return "vcross";
        case CubeArrangement::strip_3x2:
            return "3x2";
        case CubeArrangement::strip_2x3:
            return "2x3";
        case CubeArrangement::column:
            return "column";
        case CubeArrangement::row:
            return "row";
        case CubeArrangement::openexr_column:
            return "openexr";
    }
    return "?";
}

std::optional<CubeArrangement> parse_cube_arrangement(std::string_view name) {
    for (CubeArrangement a :
         {CubeArrangement::automatic, CubeArrangement::horizontal_cross,
          CubeArrangement::vertical_cross, CubeArrangement::strip_3x2, CubeArrangement::strip_2x3,
          CubeArrangement::column, CubeArrangement::row, CubeArrangement::openexr_column})
        if (name == cube_arrangement_name(a)) return a;
    return std::nullopt;
}

std::optional<CubeArrangement> cube_arrangement_from_size(int width, int height) {
    if (width <= 0 || height <= 0) return std::nullopt;
    if (3 * width == 4 * height) return CubeArrangement::horizontal_cross;
    if (4 * width == 3 * height) return CubeArrangement::vertical_cross;
    if (2 * width == 3 * height) return CubeArrangement::strip_3x2;
    if (3 * width == 2 * height) return CubeArrangement::strip_2x3;
    if (6 * width == height) return CubeArrangement::column;
    if (width == 6 * height) return CubeArrangement::row;
    return std::nullopt;
}

std::array<int, 2> cube_arrangement_grid(CubeArrangement arrangement) {
    switch (arrangement) {
        case CubeArrangement::automatic:
            return {0, 0};
        case CubeArrangement::horizontal_cross:
            return {4, 3};
        case CubeArrangement::vertical_cross:
            return {3, 4};
        case CubeArrangement::strip_3x2:
            return {3, 2};
        case CubeArrangement::strip_2x3:
            return {2, 3};
        case CubeArrangement::column:
        case CubeArrangement::openexr_column:
            return {1, 6};
        case CubeArrangement::row:
            return {6, 1};
    }
    return {0, 0};
}

Result<std::array<Image, 6>> split_cube_image(const Image& image, CubeArrangement arrangement,
                                              const std::string& what) {
    if (image.empty() || image.width < 1 || image.height < 1) return Error{what + " is empty"};
    if (arrangement == CubeArrangement::automatic) {
        const std::optional<CubeArrangement> detected =
            cube_arrangement_from_size(image.width, image.height);
        if (!detected)
            return Error{what + " is " + size_text(image) +
                         ", which is no cube-map arrangement (4:3, 3:4, 3:2, 2:3, 1:6 or 6:1)"};
        arrangement = *detected;
    }
    const auto grid = cube_arrangement_grid(arrangement);
    const int n = image.width / grid[0];
    if (n < 1 || image.width != grid[0] * n || image.height != grid[1] * n)
        return Error{what + " is " + size_text(image) + ", but " +
                     arrangement_description(arrangement) + " (faces N x N)"};
    const std::array<Cell, 6> cells = cells_of(arrangement);
    std::array<Image, 6> faces;
    for (int f = 0; f < 6; ++f) {
        faces[f] = Image(n, n, image.channels);
        extract_face(image, cells[f].column * n, cells[f].row * n, cells[f].transform, faces[f]);
    }
    return faces;
}

Image assemble_cube_image(const std::array<Image, 6>& faces, CubeArrangement arrangement) {
    if (arrangement == CubeArrangement::automatic) arrangement = CubeArrangement::horizontal_cross;
    const int n = faces[0].width;
    const auto grid = cube_arrangement_grid(arrangement);
    Image image = opaque_black(grid[0] * n, grid[1] * n, faces[0].channels);
    const std::array<Cell, 6> cells = cells_of(arrangement);
    for (int f = 0; f < 6; ++f)
        copy_face(faces[f], image, cells[f].column * n, cells[f].row * n, cells[f].transform);
    return image;
}

Image latlong_from_openexr(const Image& openexr) {
    // Our s = OpenEXR's u + ½ (env_image_io.h): our column x shows OpenEXR column x − W/2.
    Image ours(openexr.width, openexr.height, openexr.channels);
    const int w = openexr.width, half = w / 2;
    for (int y = 0; y < openexr.height; ++y)
        for (int x = 0; x < w; ++x)
            std::copy_n(openexr.at((x + w - half) % w, y), openexr.channels, ours.at(x, y));
    return ours;
}

Image latlong_to_openexr(const Image& ours) {
    Image openexr(ours.width, ours.height, ours.channels);
    const int w = ours.width, half = w / 2;
    for (int y = 0; y < ours.height; ++y)
        for (int x = 0; x < w; ++x)
            std::copy_n(ours.at((x + half) % w, y), ours.channels, openexr.at(x, y));
    return openexr;
}

Result<std::array<Image, 2>> split_paraboloid_image(const Image& image, const std::string& what) {
    const int n = image.height;
    if (image.empty() || n < 1 || image.width != 2 * n)
        return Error{what + " is " + size_text(image) +
                     ", but a paraboloid map in one file needs 2N x N pixels (front | back)"};
    std::array<Image, 2> faces{Image(n, n, image.channels), Image(n, n, image.channels)};
    for (int f = 0; f < 2; ++f) extract_face(image, f * n, 0, CellTransform::identity, faces[f]);
    return faces;
}

Image assemble_paraboloid_image(const Image& front, const Image& back) {
    const int n = front.width;
    Image image(2 * n, n, front.channels);
    copy_face(front, image, 0, 0, CellTransform::identity);
    copy_face(back, image, n, 0, CellTransform::identity);
    return image;
}

std::optional<EnvLayout> read_openexr_envmap_attribute(const fs::path& file) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    // Silent: a file that is not OpenEXR has no such attribute, and load_image has reported
    // whatever makes an OpenEXR unreadable.
    init.error_handler_fn = [](exr_const_context_t, exr_result_t, const char*) {};
    exr_context_t context = nullptr;
    std::optional<EnvLayout> layout;
    if (exr_start_read(&context, file.c_str(), &init) == EXR_ERR_SUCCESS) {
        exr_envmap_t envmap{};
        if (exr_attr_get_envmap(context, 0, "envmap", &envmap) == EXR_ERR_SUCCESS) {
            if (envmap == EXR_ENVMAP_LATLONG) layout = EnvLayout::latlong;
            if (envmap == EXR_ENVMAP_CUBE) layout = EnvLayout::cube;
        }
        exr_finish(&context);
    }
    return layout;
}

Result<EnvImages> load_environment_images(const std::vector<fs::path>& files,
                                          const EnvImageOptions& options) {
    if (files.empty()) return Error{"no environment-map file given"};
    if (files.size() != 1 && files.size() != 2 && files.size() != 6)
        return Error{
            "an environment map is 1 file, 2 (paraboloid front, back) or 6 (cube faces "
            "+X -X +Y -Y +Z -Z), not " +
            std::to_string(files.size())};
    std::vector<Image> images;
    for (const fs::path& file : files) {
        Result<Image> image = load_image(file, options.image);
        if (!image) return image.error();
        images.push_back(std::move(*image));
    }
    EnvImages result;

    if (files.size() == 6 || files.size() == 2) {
        const EnvLayout implied = files.size() == 6 ? EnvLayout::cube : EnvLayout::paraboloid;
        if (options.layout && *options.layout != implied)
            return Error{std::to_string(files.size()) + " files make a " +
                         env_layout_name(implied) + " map, not a " +
                         env_layout_name(*options.layout) + " map (" + quoted(files[0]) + ", ...)"};
        const char* const paraboloid_names[2] = {"front", "back"};
        auto face_name = [&](std::size_t i) {
            return std::string(implied == EnvLayout::cube ? "cube face " : "paraboloid ") +
                   (implied == EnvLayout::cube ? kFaceNames[i] : paraboloid_names[i]) + " (" +
                   quoted(files[i]) + ")";
        };
        for (std::size_t i = 0; i < images.size(); ++i) {
            if (Status s = check_square(images[i], face_name(i)); !s) return s.error();
            if (images[i].width != images[0].width)
                return Error{face_name(i) + " is " + size_text(images[i]) + ", but " +
                             face_name(0) + " is " + size_text(images[0])};
            if (images[i].channels != images[0].channels)
                return Error{face_name(i) + " has " + std::to_string(images[i].channels) +
                             " channels, but " + face_name(0) + " has " +
                             std::to_string(images[0].channels)};
        }
        result.layout = implied;
        result.faces = std::move(images);
        return result;
    }

    // One file.
    const fs::path& file = files[0];
    Image& image = images[0];
    const std::optional<EnvLayout> exr_envmap =
        options.honour_openexr_envmap ? read_openexr_envmap_attribute(file) : std::nullopt;
    std::optional<EnvLayout> layout = options.layout ? options.layout : exr_envmap;
    if (!layout) layout = env_layout_from_size(image.width, image.height);
    if (!layout)
        return Error{"cannot tell the layout of " + quoted(file) + " from its size " +
                     size_text(image) +
                     " (lat-long 2:1 within 1 %, sphere 1:1, cube 4:3 3:4 3:2 2:3 1:6 6:1); give "
                     "the layout"};
    const bool openexr = exr_envmap && exr_envmap == layout;
    result.layout = *layout;
    switch (*layout) {
        case EnvLayout::latlong:
            result.faces.push_back(openexr ? latlong_from_openexr(image) : std::move(image));
            break;
        case EnvLayout::sphere:
            if (Status s = check_square(image, "sphere map " + quoted(file)); !s) return s.error();
            result.faces.push_back(std::move(image));
            break;
        case EnvLayout::paraboloid: {
            Result<std::array<Image, 2>> faces =
                split_paraboloid_image(image, "paraboloid map " + quoted(file));
            if (!faces) return faces.error();
            for (Image& face : *faces) result.faces.push_back(std::move(face));
            break;
        }
        case EnvLayout::cube: {
            CubeArrangement arrangement = options.cube_arrangement;
            if (arrangement == CubeArrangement::automatic && openexr)
                arrangement = CubeArrangement::openexr_column;
            Result<std::array<Image, 6>> faces =
                split_cube_image(image, arrangement, "cube map " + quoted(file));
            if (!faces) return faces.error();
            for (Image& face : *faces) result.faces.push_back(std::move(face));
            break;
        }
    }
    return result;
}

Result<EnvironmentMap> make_environment_map(const EnvImages& images) {
    const int expected = face_count(images.layout);
    if (static_cast<int>(images.faces.size()) != expected)
        return Error{std::string("a ") + env_layout_name(images.layout) + " map needs " +
                     std::to_string(expected) + " images, not " +
                     std::to_string(images.faces.size())};
    switch (images.layout) {
        case EnvLayout::latlong:
            return EnvironmentMap::from_latlong(images.faces[0]);
        case EnvLayout::sphere:
            return EnvironmentMap::from_sphere(images.faces[0]);
        case EnvLayout::paraboloid:
            return EnvironmentMap::from_paraboloid(images.faces[0], images.faces[1]);
        case EnvLayout::cube: {
            std::array<Image, 6> faces;
            std::copy(images.faces.begin(), images.faces.end(), faces.begin());
            return EnvironmentMap::from_cube_faces(faces);
        }
    }
    return Error{"unknown environment-map layout"};
}

Result<EnvironmentMap> load_environment(const std::vector<fs::path>& files,
                                        const EnvImageOptions& options) {
    Result<EnvImages> images = load_environment_images(files, options);
    if (!images) return images.error();
    Result<EnvironmentMap> map = make_environment_map(*images);
    if (!map) return Error{"cannot use " + quoted(files[0]) + ": " + map.error().message};
    return map;
}

Status save_environment_images(const EnvImages& images, const std::vector<fs::path>& files,
                               const EnvSaveOptions& options) {
    const std::size_t count = images.faces.size();
    if (count != static_cast<std::size_t>(face_count(images.layout)))
        return Error{std::string("cannot save a ") + env_layout_name(images.layout) + " map of " +
                     std::to_string(count) + " images"};
    for (const Image& face : images.faces)
        if (face.empty() || face.width != images.faces[0].width ||
            face.height != images.faces[0].height || face.channels != images.faces[0].channels)
            return Error{std::string("cannot save a ") + env_layout_name(images.layout) +
                         " map whose images differ in size or channels"};
    const bool one_file = files.size() == 1;
    if (!one_file && files.size() != count) {
        const std::string choices = count == 6   ? "1 file (a cross or strip) or 6 (one per face)"
                                    : count == 2 ? "1 file (front | back) or 2 (front, back)"
                                                 : "1 file";
        return Error{std::string("a ") + env_layout_name(images.layout) + " map is written to " +
                     choices + ", not " + std::to_string(files.size())};
    }
    if (images.layout == EnvLayout::cube && one_file &&
        options.cube_arrangement == CubeArrangement::openexr_column)
        return Error{"cannot write " + quoted(files[0]) +
                     ": the OpenEXR cube arrangement is for reading only"};
    for (const fs::path& file : files)
        if (Status s = check_output_file(file); !s) return s;

    if (!one_file || count == 1) {
        std::vector<ImageToSave> all;
        for (std::size_t i = 0; i < files.size(); ++i) all.push_back({&images.faces[i], files[i]});
        return save_images(all, options.image);
    }
    if (images.layout == EnvLayout::cube) {
        std::array<Image, 6> faces;
        std::copy(images.faces.begin(), images.faces.end(), faces.begin());
        return save_image(assemble_cube_image(faces, options.cube_arrangement), files[0],
                          options.image);
    }
    return save_image(assemble_paraboloid_image(images.faces[0], images.faces[1]), files[0],
                      options.image);
}

}  // namespace footprint
