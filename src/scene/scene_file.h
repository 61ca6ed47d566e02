// scene/scene_file.h — JSON scene files → SceneDesc (scene/scene.h).
//
// The format is documented key by key, with a complete example, in the README ("Scene files");
// examples/scenes/showcase.json uses every key. In short:
//
//   {
//     "image":       {"width": 640, "height": 360},                       // optional
//     "camera":      {"position": [x,y,z], "look_at": [x,y,z], "up": [x,y,z], "fov_y_deg": 40},
//     "environment": {"file": "sky.hdr" | ["front", "back"] | ["+x","-x","+y","-y","+z","-z"],
//                     "layout": "latlong" | "cube" | "sphere" | "paraboloid",
//                     "rotation_deg": [x,y,z], "intensity": 1,
//                     "non_finite": "error" | "repair"},                       // optional
//     "background":  [r,g,b],                                              // optional
//     "lights":      [{"type": "directional", "direction": [x,y,z], "color": [r,g,b]},
//                     {"type": "point", "position": [x,y,z], "color": [r,g,b]}],
//     "objects":     [{"name": "floor", "shape": "plane", <the shape's keys>, "material": {...}}]
//   }
//
// Shape keys sit beside "shape" in the object: plane {center, normal, size ([w,h] or "infinite"),
// uv_scale}, sphere {center, radius}, cylinder {center, axis, radius, height}, paraboloid {focus,
// axis, focal_length, radius}, torus {center, axis, major_radius, minor_radius}, mesh {file
// (.obj .gltf .glb), transform {translate, rotate_deg, scale (number or [x,y,z])}}. A material is
// {base_color ([r,g,b] or a texture file), diffuse, specular, highlight ("blinn-phong" |
// "beckmann" | "ggx"), shininess (blinn-phong), roughness (beckmann, ggx), mirror, fresnel_f0,
// micro_roughness, bump {height_map | normal_map (exactly one), strength, frame (natural |
// normalized | main_direction), main_direction}, invalid_normals ("error" | "clamp": what an
// invalid texel of the material's normal maps does, scene.h), non_finite ("error" | "repair": what
// a NaN or infinite texel of its base_color file or height map does)}. "camera" and "objects" are
// required (objects may be an empty array), and "shape" in every object; every other key
// defaults to scene.h.
//
// Validation is strict and stops at the first problem: unknown keys (with a did-you-mean),
// duplicate keys, wrong types, out-of-range or non-finite values, geometry that cannot be set up
// (a zero axis, look_at = position, up parallel to the view direction), unsupported mesh formats
// and files that do not exist. Every message starts with the scene file's path and the key path
// in dotted form with [i] indices, e.g.
//   scenes/a.json: objects[1].material.shinyness: unknown key (did you mean 'shininess'?)
//   scenes/a.json: objects[0].material.bump.normal_map: file 'n.png' not found (resolved to
//       '/home/me/scenes/n.png')
//   scenes/a.json: line 12, column 5: invalid JSON: syntax error while parsing object - …
//
// File names in a scene are relative to the scene file's folder (or absolute). The parsed scene
// holds them resolved and lexically normalised (ImageSource::file, MeshShape::file): relative to
// the working directory if the scene file's path was, absolute otherwise. Images and meshes are
// not read here (the renderer loads them), only checked for existence.
#pragma once

#include <filesystem>
#include <string_view>

#include <footprint/core/result.h>
#include <footprint/scene/scene.h>

namespace footprint {

struct SceneParseOptions {
    // Whether a file key must name an existing file. Off: the scene is validated and its paths
    // resolved without touching the file system (checking a scene meant for another machine).
    bool check_files = true;
};

// Reads and parses the scene file `file`. SceneDesc::source is `file`.
Result<SceneDesc> load_scene_file(const std::filesystem::path& file,
                                  const SceneParseOptions& options = {});

// Parses scene JSON text as if read from `file`: messages name `file`, and relative file names
// resolve against file.parent_path(). `file` itself is not read (it need not exist).
Result<SceneDesc> parse_scene(std::string_view json_text, const std::filesystem::path& file,
                              const SceneParseOptions& options = {});

}  // namespace footprint
