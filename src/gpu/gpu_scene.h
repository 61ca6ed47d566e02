// gpu/gpu_scene.h — (private to gpu) a RenderScene on the GPU: its pyramids as textures, level by
// level, and its objects, materials and lights as the shader storage buffers of
// gpu/shaders/common.glsl (records laid out as its std430 structs).
#pragma once

#include <array>
#include <vector>

#include "core/result.h"
#include "envmap/env_layout.h"
#include "gpu/gl_objects.h"
#include "render/render_scene.h"

namespace footprint::gpu {

// The texture units of the shaders' samplers: u_maps[i] on unit i (gpu/shaders/filtering.glsl).
constexpr int kMaxMaps = 8;  // colour and bump maps each (gpu/shaders/shading.glsl)
constexpr int kColorUnit = 0;
constexpr int kBumpUnit = kColorUnit + kMaxMaps;
constexpr int kLatlongUnit = kBumpUnit + kMaxMaps;
constexpr int kCapsUnit = kLatlongUnit + 1;
constexpr int kCubeUnit = kCapsUnit + 1;

// A 2D map and the two samplers a frame binds with it: plain trilinear (every mode but hw-aniso)
// and anisotropic (hw-aniso).
struct MapTexture {
    Texture texture;
    Sampler trilinear, anisotropic;
    int width = 0, height = 0, levels = 0, layers = 0;  // level 0's size; the shaders' u_map_info
};

struct ObjectRecord {  // common.glsl's Object
    float origin[4], axis_u[4], axis_v[4], axis[4], params[4];
    int info[4];
};
struct MaterialRecord {  // common.glsl's Material
    float base_color[4], weights[4], bump[4], main_direction[4], roughness[4];
};
struct LightRecord {  // common.glsl's Light
    float direction[4], position[4], color[4];
};

struct GpuScene {
    std::vector<MapTexture> color_maps, bump_maps;
    std::vector<MaterialRecord> materials;
    std::vector<int> object_material;  // per scene object: its record, −1 for none (invalid shape)
    bool has_environment = false;
    EnvLayout layout = EnvLayout::latlong;
    MapTexture latlong, caps;  // lat-long: the map and its polar caps (layer 0 +Y, 1 −Y)
    bool has_caps = false;
    Texture cube;
    Sampler cube_sampler;
    Buffer material_buffer, gaussian_spacing_buffer;
};

// Uploads every pyramid and material; an Error names an object, map or layout the GPU path does
// not take yet (gpu/gpu_renderer.h).
Result<GpuScene> upload_scene(const RenderScene& scene);

// The scene's objects and lights relative to the camera position (the shaders work in float
// around the camera; positions are subtracted here in double).
std::vector<ObjectRecord> object_records(const RenderScene& scene, const GpuScene& gpu,
                                         Vec3d camera_position);
std::vector<LightRecord> light_records(const SceneDesc& scene, Vec3d camera_position);

}  // namespace footprint::gpu
