// examples/filament/gltf_scene.h — a glTF 2.0 file (.gltf, .glb) as footprint-filament's scene
// data (scenes.h), so that it goes through the same steps as the built-in scenes: each surface's
// maps built once for every material, each object's geometry, the camera.
//
// Geometry and materials are read by footprint's own glTF reader (scene/mesh.h, tinygltf): every
// TRIANGLES primitive of the default scene in world space, POSITION, NORMAL, TEXCOORD_0, and per
// material baseColorFactor × baseColorTexture (sRGB-decoded), normalTexture (its `scale` applied
// to the map), metallicFactor, roughnessFactor and metallicRoughnessTexture (G roughness, B
// metallic). A missing or unreadable texture file is an error naming it. Not read: occlusion,
// emissive, alphaMode (everything is opaque), doubleSided (nothing is culled), samplers (every
// map repeats), texture transforms, TEXCOORD_1, vertex colours, skins, morph targets, lights.
//
// The camera: the glTF's first perspective camera (the lowest index in `cameras` that a node of
// the default scene places), its node's world transform giving the eye, the view direction (−Z)
// and up (+Y), its yfov, znear and zfar (the output's size sets the aspect ratio). Without one
// (or with an orthographic one, which is not read), a view that frames the scene's bounding
// sphere from the front (+Z), a little above and to the right, with a 40° vertical field of view.
#pragma once

#include <filesystem>

#include <footprint/core/result.h>
#include "scenes.h"

namespace footprint::filament_example {

struct GltfScene {
    SceneSetup scene;  // its environment: the Venice sky of assets/ (--environment replaces it)
    bool has_camera = false;  // the glTF's camera, or else the framing view
    std::string note;         // why a camera in the file was not used, or empty
};

Result<GltfScene> load_gltf_scene(const std::filesystem::path& file,
                                  const std::filesystem::path& assets_dir);

}  // namespace footprint::filament_example
