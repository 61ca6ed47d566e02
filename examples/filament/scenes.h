// examples/filament/scenes.h — footprint-filament's scenes as plain data: meshes, surfaces (maps
// and factors), camera and environment, before any Filament object exists. The built-in scenes
// below; a glTF file's (gltf_scene.h) are the same data.
//
//   plate   a bumpy mirror plate (demo bump_plate: metal-plate normal map, zebra-stripe sky)
//   floor   a grazing textured floor (demo secret_writing: the "secret writing" texture on an
//           almost infinite plane seen from 0.5 units above it)
//   mirror  a curved mirror (demo cylinder: a mirror cylinder in the Venice sky)
//   sky     the orientation check: a flat mirror under a sky whose colour is its direction,
//           0.5 + 0.5·d (footprint's lat-long convention, docs/method.md), so that every pixel of
//           the sky and of its reflection has a known colour (expected_direction_colours())
//
// The maps come from footprint's demo assets (apps/demo_assets.h, generated in code) and from the
// repository's assets/ (CC0, assets/LICENSES), so every scene renders from a fresh clone.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <footprint/core/result.h>
#include <footprint/image/image.h>

namespace footprint::filament_example {

struct Mesh {
    std::vector<std::array<float, 3>> positions;
    std::vector<std::array<float, 3>> normals;
    std::vector<std::array<float, 2>> uvs;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

// A map: a file, or an image made in code (then `file` is empty and `label` names it).
struct MapSource {
    std::filesystem::path file;
    Image image;
    std::string label;
    bool empty() const { return file.empty() && image.empty(); }
};

// glTF's metallic-roughness inputs, as the lit materials take them.
struct SurfaceDesc {
    MapSource base_color;  // sRGB colour; empty: white
    MapSource normal;      // tangent-space normal map, OpenGL convention; empty: flat
    // glTF's metallicRoughnessTexture (data, not decoded): G roughness, B metallic, each × its
    // factor below; empty: the factors alone.
    MapSource metallic_roughness;
    std::array<float, 3> base_color_factor{1, 1, 1};
    float metallic = 0;
    float roughness = 0.5f;  // authored perceptual roughness
    std::array<float, 2> uv_scale{1, 1};
};

// One mesh and the index of its surface in SceneSetup::surfaces.
struct SceneObject {
    Mesh mesh;
    std::size_t surface = 0;
};

struct CameraSetup {
    std::array<double, 3> eye{0, 0, 4}, target{0, 0, 0}, up{0, 1, 0};
    double fov_y_deg = 40;
    double near = 0.05, far = 1000;
};

struct SceneSetup {
    std::string name;  // the built-in scene's, or the glTF file's stem: tables and file names
    std::string title;
    std::vector<SurfaceDesc> surfaces;  // each one's maps are built once, whatever uses it
    std::vector<SceneObject> objects;   // at least one
    CameraSetup camera;
    MapSource environment;  // lat-long in footprint's orientation (docs/environment-maps.md)
};

const std::vector<std::string>& builtin_scene_names();

// `relative` in the repository's assets/ folder `assets_dir`; an error naming the path when it is
// not there.
Result<std::filesystem::path> asset_file(const std::filesystem::path& assets_dir,
                                         const std::filesystem::path& relative);

// A map read from a file.
MapSource file_map(const std::filesystem::path& path);

// The "sky" scene's environment: a lat-long of `width` × width/2 whose texel (s, t) holds
// 0.5 + 0.5·d for its direction d by docs/method.md's addressing, inverted here on its own:
// s = ½ + atan2(d_x, −d_z)/(2π), t = arccos(d_y)/π (+Y up, s = 0 at +Z, ¼ at −X).
Image make_direction_latlong(int width);

// What the "sky" scene must look like at width × height (top row first): for each pixel the
// colour 0.5 + 0.5·d of the camera ray's direction, or of its mirror reflection where it meets
// the plate; channel 3 is 1 (sky) or 2 (mirror) where the pixel and its 8 neighbours agree on
// which they see, 0 at the plate's edge. A pinhole camera as Filament's: vertical field of view,
// lookAt.
Image expected_direction_colours(const SceneSetup& scene, int width, int height);

// One of builtin_scene_names(), its files looked up in `assets_dir` (the repository's assets/).
Result<SceneSetup> make_builtin_scene(const std::string& name,
                                      const std::filesystem::path& assets_dir);

}  // namespace footprint::filament_example
