// envmap/env_image_io.h — environment maps from and to the image files people have: cube crosses,
// strips and face files, lat-long, sphere and dual-paraboloid images, and OpenEXR's own
// environment maps (ImfEnvmap), all brought into this library's conventions (env_layout.h).
//
// ---- The images of a map (EnvImages): level-0 images in OUR orientation (env_layout.h, spec §3):
//   cube        6 square faces +X −X +Y −Y +Z −Z, each drawn as env_layout.h's table says
//               (OpenGL face table, spec §3.1)
//   latlong     1 image, s = 0 at +Z, ¼ at −X, ½ at −Z, ¾ at +X; top row +Y (spec §3.4)
//   sphere      1 square image (spec §3.2)
//   paraboloid  2 square images, front (+Z hemisphere) then back (spec §3.3)
//
// ---- Cube arrangements in one image (N = face size; faces in the order above):
//   horizontal_cross 4N × 3N   exactly env_layout.h's unfolded drawing:
//                                    .  +Y  .   .
//                                   −X  +Z  +X  −Z
//                                    .  −Y  .   .
//   vertical_cross   3N × 4N         .  +Y  .          −Z below −Y is rotated by 180°, so that
//                                   −X  +Z  +X         its edges meet −Y's continuously (its
//                                    .  −Y  .          bottom edge, y = −1, is drawn on top).
//                                    .  −Z* .          All other faces are drawn unrotated.
//   strip_3x2        3N × 2N   +X −X +Y / −Y +Z −Z        (row-major, unrotated)
//   strip_2x3        2N × 3N   +X −X / +Y −Y / +Z −Z
//   column           N × 6N    +X −X +Y −Y +Z −Z top to bottom
//   row              6N × N    +X −X +Y −Y +Z −Z left to right
//   openexr_column   N × 6N    OpenEXR's cube (ImfEnvmap CubeMap): the same column order, but each
//                              face in OpenEXR's orientation, which is ours mirrored: the ±X and
//                              ±Z faces left–right, the ±Y faces top–bottom (derived from
//                              ImfEnvmap.cpp's CubeMap::direction and pixelPosition).
//   Empty cells of a cross are written black (alpha 1 where the image has alpha) and ignored on
//   load. automatic picks the arrangement from the aspect ratio: 4:3, 3:4, 3:2, 2:3, 1:6, 6:1.
//
// ---- OpenEXR environment maps (ImfEnvmap.h). A .exr file whose header holds the attribute
//   "envmap" (type envmap: 0 lat-long, 1 cube) is converted on load:
//   * lat-long: OpenEXR puts −Z at the left edge, +X at ¼, +Z in the middle, −X at ¾ (longitude
//     = −2π(u − ½) with direction (sin lon cos lat, sin lat, cos lon cos lat)): our s is OpenEXR's
//     u + ½, so the columns are rotated by half the width; rows are the same (top row +Y).
//   * cube: openexr_column above.
//   OpenEXR places its samples ON the borders (pixel i at u = i/(N−1); OpenImageIO reports
//   "oiio:sampleborder 1"), ours at texel centres ((i + ½)/N). The pixels are re-indexed, not
//   resampled, so sample directions move by at most ½ texel (0.09° for a 1024-wide lat-long,
//   0.11° for 256² cube faces) — nothing is blurred.
//
// ---- Layout detection (load_environment_images), unless EnvImageOptions::layout says otherwise:
//   6 files  → cube faces (+X −X +Y −Y +Z −Z);   2 files → paraboloid (front, back);
//   1 file   → the OpenEXR "envmap" attribute if present, else by aspect ratio
//              (env_layout_from_size): 2:1 lat-long (W within 1 % of 2H, at least ±1 pixel:
//              |W − 2H| ≤ max(1, H/50), integer division), 1:1 sphere, exactly 4:3 / 3:4 / 3:2 /
//              2:3 / 1:6 / 6:1 cube (arrangement as above). Any other size is refused unless the
//              layout is given.
//   A one-file paraboloid is the front and back side by side (2N × N, front left); since 2:1 means
//   lat-long by default, it must be asked for explicitly. An explicit lat-long accepts any size.
//   Texels that are NaN or ±Inf are refused, or repaired (EnvImageOptions::image.non_finite,
//   image_io.h); the error names the file and the texel in that file.
//
// ---- Errors: nothing is printed or thrown. Every failure is an Error naming the file in quotes
//   and the problem: "cannot read 'a.exr': no such file" (image_io.h), "cube map 'c.png' is
//   512x512, but a horizontal cross needs 4N x 3N pixels (faces N x N)", "cube face -Y ('ny.png')
//   is 64x64, but cube face +X ('px.png') is 128x128", "cannot tell the layout of 'x.png' from its
//   size 300x201 (lat-long 2:1 within 1 %, ...); give the layout", "sphere map 's.png' is 64x32,
//   not square".
//
// ---- Saving (save_environment_images): all files through save_images (image_io.h): every file
//   is written completely under a temporary name before any target is replaced, so a failed save
//   leaves nothing behind and no target changed. All target paths are checked (extension,
//   directory) before the first file is written.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <footprint/core/result.h>
#include <footprint/envmap/env_layout.h>
#include <footprint/envmap/environment_map.h>
#include <footprint/image/image.h>
#include <footprint/image/image_io.h>

namespace footprint {

enum class CubeArrangement {
    automatic,  // load: from the aspect ratio (and an OpenEXR header); save: horizontal cross
    horizontal_cross,
    vertical_cross,
    strip_3x2,
    strip_2x3,
    column,
    row,
    openexr_column,  // load only
};

// "hcross", "vcross", "3x2", "2x3", "column", "row", "openexr" (and "auto" for automatic).
const char* cube_arrangement_name(CubeArrangement arrangement);
std::optional<CubeArrangement> parse_cube_arrangement(std::string_view name);

// The level-0 images of an environment map in this library's conventions (see above).
struct EnvImages {
    EnvLayout layout = EnvLayout::latlong;
    std::vector<Image> faces;  // face_count(layout) images
};

struct EnvImageOptions {
    std::optional<EnvLayout> layout;                                // nullopt: detect (see above)
    CubeArrangement cube_arrangement = CubeArrangement::automatic;  // a one-file cube
    // Apply OpenEXR's conventions only when the file's header says it is an OpenEXR envmap (and
    // the layout agrees); false: never (the pixels are taken as drawn in our convention).
    bool honour_openexr_envmap = true;
    ImageLoadOptions image;  // colour decoding of integer files (image_io.h)
};

// Reads 1, 2 or 6 files into the images of one map (checked: sizes, aspect, channel counts).
Result<EnvImages> load_environment_images(const std::vector<std::filesystem::path>& files,
                                          const EnvImageOptions& options = {});
// load_environment_images, then the pyramids (EnvironmentMap::from_latlong / from_cube_faces /
// from_sphere / from_paraboloid).
Result<EnvironmentMap> load_environment(const std::vector<std::filesystem::path>& files,
                                        const EnvImageOptions& options = {});
// The pyramids of `images` (errors from EnvironmentMap's factories).
Result<EnvironmentMap> make_environment_map(const EnvImages& images);

struct EnvSaveOptions {
    // A cube written to one file: horizontal_cross (also for automatic), vertical_cross, strips,
    // column or row; openexr_column is refused. Six files get one face each.
    CubeArrangement cube_arrangement = CubeArrangement::automatic;
    ImageSaveOptions image;
};

// Writes a map: cube → 1 file (arrangement) or 6 (+X −X +Y −Y +Z −Z); paraboloid → 1 file (front
// and back side by side, front left) or 2 (front, back); lat-long and sphere → 1 file.
Status save_environment_images(const EnvImages& images,
                               const std::vector<std::filesystem::path>& files,
                               const EnvSaveOptions& options = {});

// ---- Pure helpers (no files).

// The layout a single image of this size stands for by its aspect ratio (the rule above), or
// nullopt if it fits none.
std::optional<EnvLayout> env_layout_from_size(int width, int height);

// The arrangement of a width × height cube image from its aspect ratio (never openexr_column), or
// nullopt if it is none of 4:3, 3:4, 3:2, 2:3, 1:6, 6:1.
std::optional<CubeArrangement> cube_arrangement_from_size(int width, int height);
// Grid size in faces (columns, rows) of an arrangement (automatic: {0, 0}).
std::array<int, 2> cube_arrangement_grid(CubeArrangement arrangement);
// Splits one image into the six faces in our orientation. `arrangement` automatic: from the
// aspect ratio. Error (naming `what`, e.g. the file) if the size does not fit the arrangement.
Result<std::array<Image, 6>> split_cube_image(const Image& image, CubeArrangement arrangement,
                                              const std::string& what = "the image");
// The inverse: six square faces of one size and channel count (our orientation) in one image;
// automatic means horizontal_cross. openexr_column writes OpenEXR's orientation.
Image assemble_cube_image(const std::array<Image, 6>& faces, CubeArrangement arrangement);
// OpenEXR lat-long pixels (ImfEnvmap LatLongMap) → ours, and back (columns rotated by W/2).
Image latlong_from_openexr(const Image& openexr);
Image latlong_to_openexr(const Image& ours);
// Paraboloid front | back side by side (2N × N) ↔ the two faces.
Result<std::array<Image, 2>> split_paraboloid_image(const Image& image,
                                                    const std::string& what = "the image");
Image assemble_paraboloid_image(const Image& front, const Image& back);

// The value of the "envmap" attribute of an OpenEXR file's (first) header: latlong, cube, or
// nullopt (not an EXR file, no such attribute, unreadable — load_image reports those).
std::optional<EnvLayout> read_openexr_envmap_attribute(const std::filesystem::path& file);

}  // namespace footprint
