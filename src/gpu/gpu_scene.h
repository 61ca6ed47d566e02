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
// The materials' colour and bump maps share units 0 … kMaterialUnits − 1: maps of one size, level
// count and wrap are the layers of one array texture, so that a scene may have any number of
// maps in up to kMaterialUnits different shapes.
constexpr int kMaterialUnits = 16;
constexpr int kEnvUnit = kMaterialUnits;  // a lat-long, sphere or paraboloid map (faces: layers)
constexpr int kCapsUnit = kEnvUnit + 1;
constexpr int kCubeUnit = kCapsUnit + 1;
constexpr int kVisibilityUnit = kCubeUnit + 1;  // the mesh pass's triangle ids (render.frag)
// The cube slots (CubeSlot below): units kSlotUnit … + 3.
constexpr int kSlotUnit = kVisibilityUnit + 1;
constexpr std::size_t kMaxCubeSlots = 4;  // environment.glsl's MAX_CUBE_SLOTS

// An array texture and the two samplers a frame binds with it: plain trilinear (every mode but
// hw-aniso) and anisotropic (hw-aniso).
struct MapTexture {
    Texture texture;
    Sampler trilinear, anisotropic;
    int width = 0, height = 0, levels = 0, layers = 0;  // level 0's size; the shaders' u_map_info
};

// Where a material's map lives: the unit of its array texture and its first layer (a colour map
// has one layer, a bump map's moments two).
struct MapRef {
    int unit = -1;  // −1: no map
    int layer = 0;
};

struct ObjectRecord {  // common.glsl's Object
    float origin[4], axis_u[4], axis_v[4], axis[4], params[4];
    int info[4];
};
struct MaterialRecord {  // common.glsl's Material
    float base_color[4], weights[4], bump[4], main_direction[4], roughness[4];
    int maps[4];
    float highlight[4], f0[4];
    int f0_map[4];
    float procedural[4];            // pattern + 1 (0: none), scale, octaves, unused
    float procedural_colors[2][4];  // the pattern's two colours (rgb)
    float procedural_bump[4];       // pattern + 1 (0: none), scale, octaves, strength
    float parallax[4];              // depth (0: none), steps, max_shift, unused
    int height_map[4];              // the parallax height map's unit and layer, unused
    int probe[4];                   // the environment probe's index in GpuScene::slots (−1: none)
};
struct LightRecord {                            // common.glsl's Light
    float direction[4], position[4], color[4];  // color[3]: 1 where it casts shadows
};
struct MeshVertexRecord {  // geometry.glsl's MeshVertex
    float position[4];     // relative to GpuMeshes::anchor
    float normal[4], uv[4], tangent[4];
};
struct MeshPartRecord {  // geometry.glsl's MeshPart
    int info[4];         // material record, has normals, has uvs, has tangents
};

// Every triangle of the scene's meshes, in one set of buffers: the vertices (the raster pass's
// vertex buffer and the shading pass's storage buffer alike), the triangles as indices (the
// element buffer) and as (i0, i1, i2, part) records, and the parts.
struct GpuMeshes {
    int triangle_count = 0;
    Vec3d anchor;  // the point the vertex positions are relative to (in float)
    Buffer vertices, indices, triangles, parts;
    Buffer bvh_nodes, bvh_triangles;  // the shadow rays' BVH (scene/triangle_bvh.h)
    VertexArray vertex_array;
};

// A cube map on a unit of its own (kSlotUnit + its index), read through its own rotation and
// proxy: a local map (converted to a cube map where it is another layout) or a probe.
struct CubeSlot {
    const RenderEnvironment* source = nullptr;
    Texture cube;
    float size = 0;  // texels along a face's edge
};

struct GpuScene {
    std::vector<MapTexture> material_maps;  // on units 0, 1, …
    std::vector<MaterialRecord> materials;
    std::vector<int> object_material;  // per scene object: its record, −1 for none (invalid shape)
    bool has_environment = false;
    EnvLayout layout = EnvLayout::latlong;
    MapTexture env_map;  // lat-long, sphere, paraboloid (layer 0 front, 1 back)
    MapTexture caps;     // lat-long: the polar caps (layer 0 +Y, 1 −Y)
    // env_map's per-level prefilter variance (level-0 texels², MipPyramid::prefilter_variance) and
    // whether it repeats in s and t: what EWA beyond the probe budget reads (environment.glsl).
    std::vector<float> env_prefilter;
    std::array<bool, 2> env_repeat{false, false};
    bool has_caps = false;
    Texture cube;
    Sampler cube_sampler;
    Buffer material_buffer;
    GpuMeshes meshes;
    // The cube maps besides the scene's: the local maps, innermost first (RenderScene::
    // local_environments(), so that the first whose proxy contains a point is its map), then the
    // probed materials' (RenderMaterial::probe) in the order the materials met them.
    std::vector<CubeSlot> slots;
    int local_count = 0;
    Sampler slot_sampler;
};

// Uploads every pyramid, material and mesh; an Error names the object whose maps need more array
// textures than there are units (gpu/gpu_renderer.h).
Result<GpuScene> upload_scene(const RenderScene& scene);

// The scene's objects and lights relative to the camera position (the shaders work in float
// around the camera; positions are subtracted here in double).
std::vector<ObjectRecord> object_records(const RenderScene& scene, const GpuScene& gpu,
                                         Vec3d camera_position);
std::vector<LightRecord> light_records(const SceneDesc& scene, Vec3d camera_position);

}  // namespace footprint::gpu
