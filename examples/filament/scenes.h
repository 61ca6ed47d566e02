// examples/filament/scenes.h — the built-in scenes of footprint-filament, as plain data: meshes,
// maps, camera and environment, before any Filament object exists.
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
    std::array<float, 3> base_color_factor{1, 1, 1};
    float metallic = 0;
    float roughness = 0.5f;  // authored perceptual roughness
    std::array<float, 2> uv_scale{1, 1};
};

struct CameraSetup {
    std::array<double, 3> eye{0, 0, 4}, target{0, 0, 0}, up{0, 1, 0};
    double fov_y_deg = 40;
    double near = 0.05, far = 1000;
};

struct BuiltinScene {
    std::string name;
    std::string title;
    Mesh mesh;
    SurfaceDesc surface;
    CameraSetup camera;
    MapSource environment;  // lat-long in footprint's orientation (docs/environment-maps.md)
};

const std::vector<std::string>& builtin_scene_names();

// The "sky" scene's environment: a lat-long of `width` × width/2 whose texel (s, t) holds
// 0.5 + 0.5·d for its direction d by docs/method.md's addressing, inverted here on its own:
// s = ½ + atan2(d_x, −d_z)/(2π), t = arccos(d_y)/π (+Y up, s = 0 at +Z, ¼ at −X).
Image make_direction_latlong(int width);

// What the "sky" scene must look like at width × height (top row first): for each pixel the
// colour 0.5 + 0.5·d of the camera ray's direction, or of its mirror reflection where it meets
// the plate; channel 3 is 1 (sky) or 2 (mirror) where the pixel and its 8 neighbours agree on
// which they see, 0 at the plate's edge. A pinhole camera as Filament's: vertical field of view,
// lookAt.
Image expected_direction_colours(const BuiltinScene& scene, int width, int height);

// One of builtin_scene_names(), its files looked up in `assets_dir` (the repository's assets/).
Result<BuiltinScene> make_builtin_scene(const std::string& name,
                                        const std::filesystem::path& assets_dir);

}  // namespace footprint::filament_example
