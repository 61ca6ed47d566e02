// render/render_scene.h — a scene made ready to render: images loaded and filtered into pyramids,
// meshes loaded into an Embree BVH, and one intersection query over all objects.
//
// prepare_render_scene() turns a SceneDesc (scene/scene.h, from a file or built in code) into a
// RenderScene, whose maps all live in one TextureSystem (texture_system.h) that every lookup of
// the renderer and the GPU path's uploads go through:
//   * base-colour maps → textures of the texture system: a file by its name (its stored MIP
//     levels used as stored and read tile by tile, or its pyramid built, sRGB files decoded to
//     linear; repeating in s and t unless the file says otherwise), an image in memory or a file
//     whose non-finite texels are repaired registered by add_image(); grey maps are read as grey
//     RGB, an alpha channel is ignored;
//   * bump maps → slope maps b in slope_map.h's convention (height maps: b = −strength·∇h per unit
//     of (u, v), one map period = 1; normal maps: b = strength·(n_x, n_y)/n_z) → bump + roughness
//     pyramids (bump/bump_pyramid.h) with the material's micro-roughness σ as K_0 = σ² I,
//     registered by add_bump() (materials with the same map, strength and σ share one); a bump
//     pyramid file (`footprint maketx --bump`, in either key) is read as stored, tile by tile, its
//     slopes × strength with σ² I added at each lookup;
//   * the environment → an EnvironmentMap (envmap/), scaled by its intensity and registered by
//     add_environment(), with its rotation A; an environment pyramid file (`footprint maketx
//     --env`) of RGB at intensity 1 is read as stored, tile by tile;
//   * meshes → triangles (scene/mesh.h) in one MeshAccel. Each part of a mesh file keeps its own
//     colours: the scene material's base_color multiplies the file's (glTF baseColorFactor, OBJ
//     Kd), the file's texture (glTF baseColorTexture, OBJ map_Kd) is used unless the scene gives
//     base_color as a file, and a glTF normalTexture becomes the bump (a normal map of strength
//     normalTexture.scale, in the frame of the mesh's tangents, or of ∂p/∂v without them)
//     unless the scene gives one;
//   * metallic-roughness materials (glTF's, and the scene's with that model) → a diffuse-colour
//     and an F0 map made texel by texel, and the roughness as slope variance in the bump
//     pyramid's K_0 (render/material_model.h).
// Errors name the file (and the scene's key where the scene has one). Everything is immutable
// afterwards: rendering threads share one RenderScene.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <footprint/core/result.h>
#include <footprint/envmap/irradiance.h>
#include <footprint/math/mat3.h>
#include <footprint/scene/scene.h>
#include <footprint/scene/surface.h>
#include <footprint/texture_system.h>

namespace footprint {

class MeshAccel;
struct TriangleMesh;

// A material with its maps in the scene's texture system.
struct RenderEnvironment;

struct RenderMaterial {
    MaterialDesc desc;
    TextureHandle* base_color_map = nullptr;  // linear; null: desc.base_color only
    bool base_color_grey = false;             // the map has 1 or 2 channels: grey (and alpha)
    BumpHandle* bump = nullptr;               // slopes b (see above); null: flat
    // Applied by each bump lookup (BumpLookupOptions): a bump pyramid file's slopes are stored at
    // strength 1 without micro-roughness; the maps built here have both already (1 and none).
    float bump_strength = 1;
    Sym2 bump_micro_roughness;
    Sym2 micro_roughness;  // σ² I: the slope covariance when there is no bump map
    bool frame_from_mesh_tangents = false;  // a glTF normal texture on a part with tangents
    // Schlick's F0 of the highlight and the mirror, per channel: f0 × f0_map where there is one
    // (the metallic-roughness model's 0.04 (1 − m) + c m; the footprint model's fresnel_f0). The
    // map is a textured metallic-roughness material's, and holds in its fourth channel the slope
    // variance σ² per texel below the bump map's resolution (render/material_model.h), for the
    // modes that read it apart from the slope moments (which hold it in K_0): the highlight's α
    // where K_b is left out, the sampled slopes of the reference and stochastic modes, toksvig and
    // specular-aa. Without a map the variance is micro_roughness.
    std::array<float, 3> f0{1, 1, 1};
    TextureHandle* f0_map = nullptr;
    // A parallax-mapped material's height map (channel 0, data), for the march
    // (texture/parallax.h).
    TextureHandle* height_map = nullptr;
    // The environment's diffuse weight (its mean radiance × c): the footprint model's `diffuse`;
    // 1 in the metallic-roughness model, whose lights' Lambert weight (desc.diffuse) is 1/π.
    float ambient_weight = 1;
    // An environment_probe material's cube map (rendered by prepare_render_scene()), which its
    // mirror reflects instead of the scene's environment; null for the others.
    const RenderEnvironment* probe = nullptr;

    bool metallic_roughness() const {
        return desc.model == MaterialDesc::Model::metallic_roughness;
    }
    // Slopes below the maps' resolution: micro-roughness, constant or per texel (f0_map).
    bool has_micro_slopes() const { return desc.micro_roughness > 0 || f0_map; }
};

struct RenderEnvironment {
    EnvironmentHandle* map = nullptr;  // in the scene's texture system, × intensity
    EnvLayout layout = EnvLayout::latlong;
    Vec2 texel_scale;  // the map's, for compute_env_footprint()
    Mat3 rotation;     // A: world → map
    float intensity = 1;
    IrradianceSH irradiance;  // the map's radiance × intensity, nine coefficients (diffuse light)
    std::optional<EnvProxy> proxy;  // a local map's (scene.h's EnvironmentDesc::proxy)
};

// One hit with the material it shows.
struct SceneHit {
    SurfaceHit surface;
    const RenderMaterial* material = nullptr;
    // A normal-mapped mesh part with tangents (glTF TANGENT): the interpolated tangent (unit,
    // world) and the bitangent's sign, bitangent = tangent_sign·(n × tangent) (v up). The
    // renderer then builds the normal map's frame from them, as the map was baked.
    std::optional<Vec3d> tangent;
    double tangent_sign = 1;
};

class RenderScene {
  public:
    RenderScene();
    ~RenderScene();
    RenderScene(RenderScene&&) noexcept;
    RenderScene& operator=(RenderScene&&) noexcept;

    const SceneDesc& desc() const { return desc_; }
    const RenderEnvironment* environment() const { return environment_.get(); }
    // The map that a point p sees: the innermost local map whose proxy contains p, else the
    // scene's environment (null where there is none).
    const RenderEnvironment* environment_at(Vec3 p) const;
    // The local maps, innermost first (by their proxies' volume): the order environment_at()
    // tries them in.
    std::span<const std::unique_ptr<RenderEnvironment>> local_environments() const {
        return local_environments_;
    }
    // The texture system holding the scene's maps (thread-safe, as all its calls are).
    TextureSystem& textures() const { return *textures_; }
    // After rendering: the texture errors met since the last call — a stored file's tile that
    // could not be read (a file truncated or changed on disk), whose texels rendered black — as
    // one Error naming the file, or success. A caller that writes images checks it first.
    Status take_texture_errors() const;

    // The material of analytic object `object` (an index into desc().objects); nullptr for a mesh.
    const RenderMaterial* analytic_material(int object) const {
        const int m = object_material_[static_cast<std::size_t>(object)];
        return m < 0 ? nullptr : &materials_[static_cast<std::size_t>(m)];
    }
    // The parts of mesh object `object` (scene/mesh.h, in world space), each with its material;
    // no parts for an analytic object.
    std::span<const TriangleMesh> mesh_parts(int object) const;
    const RenderMaterial& mesh_part_material(int object, int part) const {
        const auto i = static_cast<std::size_t>(object);
        return materials_[static_cast<std::size_t>(
            mesh_part_material_[i][static_cast<std::size_t>(part)])];
    }

    // The nearest hit along the ray with t in (t_min, t_max), over all objects. Thread-safe.
    std::optional<SceneHit> intersect(const Ray& ray, double t_min, double t_max) const;
    // Whether any object is hit with t in (t_min, t_max): a shadow ray. Thread-safe.
    bool occluded(const Ray& ray, double t_min, double t_max) const;

    // The unit normals of a bumped material's slopes (× its strength) as a texture of the scene's
    // texture system, for the `toksvig` peer mode: made at the first call for that bump map, then
    // shared; null if the bump map cannot be read whole. Thread-safe.
    TextureHandle* toksvig_normals(const RenderMaterial& material) const;

  private:
    friend Result<RenderScene> prepare_render_scene(const SceneDesc& desc,
                                                    std::shared_ptr<TextureSystem> textures);

    SceneDesc desc_;
    std::shared_ptr<TextureSystem> textures_;
    std::unique_ptr<RenderEnvironment> environment_;
    std::vector<std::unique_ptr<RenderEnvironment>> local_environments_;  // innermost first
    std::vector<std::unique_ptr<RenderEnvironment>> probes_;              // RenderMaterial::probe's
    std::vector<RenderMaterial> materials_;             // one per object, then one per mesh part
    std::vector<int> object_material_;                  // analytic objects: index into materials_
    std::vector<std::vector<int>> mesh_part_material_;  // [object][part] for mesh objects
    std::vector<std::vector<TriangleMesh>> meshes_;     // [object] (empty for analytic objects)
    struct MeshPart {
        int object, part;
    };
    std::vector<MeshPart> accel_parts_;  // MeshAccel's mesh index → (object, part)
    std::unique_ptr<MeshAccel> mesh_accel_;
    struct ToksvigMaps;
    std::unique_ptr<ToksvigMaps> toksvig_;
};

// `textures`: the texture system to hold the scene's maps (shared with other scenes, or made with
// the cache size a caller wants); null: one with TextureSystemOptions' defaults.
Result<RenderScene> prepare_render_scene(const SceneDesc& desc,
                                         std::shared_ptr<TextureSystem> textures = nullptr);

}  // namespace footprint
