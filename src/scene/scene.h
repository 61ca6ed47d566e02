// scene/scene.h — what a scene is: camera, environment, lights and objects with materials.
//
// Plain data, in world units, y up by convention (nothing depends on it). A scene comes from a
// JSON file (scene/scene_file.h, the keys are the same as the field names below) or is built in
// code (the built-in demos). Images a scene refers to are either files (resolved against the
// scene file's folder by the parser, loaded by the renderer) or images already in memory (demos
// generate theirs): ImageSource holds one or the other.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <footprint/bump/slope_map.h>
#include <footprint/envmap/env_layout.h>
#include <footprint/envmap/env_proxy.h>
#include <footprint/image/image.h>
#include <footprint/image/image_io.h>
#include <footprint/math/vec.h>
#include <footprint/math/vec3.h>
#include <footprint/texture/parallax.h>
#include <footprint/texture/procedural.h>

namespace footprint {

// An image given by file or in memory. `file` is absolute or relative to the working directory
// once a scene is parsed. `name` labels an in-memory image in messages.
struct ImageSource {
    std::filesystem::path file;
    std::shared_ptr<const Image> image;
    std::string name;

    bool empty() const { return file.empty() && !image; }
    std::string label() const { return image ? name : file.string(); }
};

struct CameraDesc {
    Vec3d position{0, 1, 5};
    Vec3d look_at{0, 0, 0};
    Vec3d up{0, 1, 0};
    double fov_y_deg = 40;  // vertical field of view, (0, 180)
};

// A camera keyframe of an animation (SceneDesc::camera_path): the camera at `time`.
struct CameraKeyframe {
    double time = 0;
    CameraDesc camera;
};

struct EnvironmentDesc {
    // 1 file (lat-long, sphere, cube cross/strip), 2 (paraboloid front, back) or 6 (cube faces
    // +X −X +Y −Y +Z −Z); in-memory images likewise (`images`, one per face).
    std::vector<ImageSource> images;
    EnvLayout layout = EnvLayout::latlong;
    // One file and no layout given: the layout is the file's (its aspect ratio or OpenEXR envmap
    // header, envmap/env_image_io.h), and a file that fits none is refused; `layout` is ignored.
    bool detect_layout = false;
    Vec3d rotation_deg{0, 0,
                       0};  // world → map: rotation_xyz_degrees (math/mat3.h), x then y then z
    float intensity = 1;    // multiplies every texel (linear)
    // A NaN or ±Inf texel in the files: refuse (the error names the file and the texel) or repair
    // (image/image_io.h: the mean of its finite neighbours), for maps known to hold a few.
    NonFinitePolicy non_finite = NonFinitePolicy::refuse;
    // A local map (envmap/env_proxy.h): reflections read it in the direction from its capture
    // point to where the reflected ray leaves this box or sphere; none: the map is at infinity.
    std::optional<EnvProxy> proxy;
};

enum class LightType { directional, point };

struct LightDesc {
    LightType type = LightType::directional;
    Vec3d direction{0, -1, 0};  // directional: the direction the light travels (towards the scene)
    Vec3d position{0, 5, 0};    // point
    Vec3 color{1, 1, 1};        // linear RGB; irradiance (directional) or intensity (point, /d²)
    bool shadows = true;        // whether objects between a surface and the light block it
};

enum class BumpFrame {
    natural,         // spec §6.1: n' = n + f_u s_u + f_v s_v (height derivatives per parameter)
    normalized,      // the natural frame's directions, normalised: T = (ŝ_u, ŝ_v)
    main_direction,  // spec §6.2: orthonormal (e1, e2) from `main_direction` m
};

struct BumpDesc {
    enum class Source { none, height_map, normal_map, procedural };
    Source source = Source::none;
    ImageSource map;  // a height map (channel 0) or a tangent-space normal map (OpenGL)
    // Source::procedural: the height field h = strength·v(p) of a solid pattern's value v
    // (texture/procedural.h: procedural_slopes()), in world units, band-limited by the footprint;
    // its slopes are in main_direction's orthonormal frame. Its colours are unused.
    ProceduralTexture procedural;
    float strength =
        1;  // height scale (height map, procedural: world height per unit) or slope factor
    BumpFrame frame = BumpFrame::main_direction;
    // m for frame = main_direction (world space); zero: the surface's own ∂p/∂v at each point
    Vec3d main_direction{0, 0, 0};
    // A height map's parallax-occlusion mapping (texture/parallax.h): the texture, bump and
    // roughness lookups at the (s, t) where the view ray meets the relief `depth` deep.
    std::optional<ParallaxOptions> parallax;
};

// The lectures' dynamic environment map: before a frame the renderer renders the scene into a cube
// map of `size`² texels per face from `center`, leaving out the objects that wear the material.
struct EnvironmentProbeDesc {
    Vec3d center{0, 0, 0};
    int size = 128;  // 4 … kMaxProbeSize
};
constexpr int kMaxProbeSize = 2048;

struct MaterialDesc {
    // The shading model (docs/scene-format.md#material-models):
    //   footprint           c ⊙ D + S + F·R with the weights below (diffuse, specular, mirror,
    //                       fresnel_f0, micro_roughness);
    //   metallic_roughness  glTF's: base_color, metallic and roughness (render/material_model.h),
    //                       the default of a glTF mesh (its file's materials).
    enum class Model { footprint, metallic_roughness };
    Model model = Model::footprint;
    Vec3 base_color{0.8f, 0.8f, 0.8f};  // linear RGB; multiplied by base_color_map where given
    ImageSource base_color_map;         // sRGB-decoded on load (colour)
    // A solid procedural texture instead of a map (texture/procedural.h), evaluated at the hit
    // point in world units and band-limited by the pixel's footprint; × base_color.
    std::optional<ProceduralTexture> base_color_procedural;
    float metallic = 0;  // metallic-roughness: 0 a dielectric, 1 a metal
    // metallic-roughness: glTF's metallicRoughnessTexture (G roughness, B metallic; data, not
    // decoded), × roughness and metallic. A glTF mesh's come from its file.
    ImageSource metallic_roughness_map;
    float diffuse = 1;     // Lambert weight
    float specular = 0;    // the lights' highlight weight
    float shininess = 50;  // Blinn-Phong exponent m
    // The lights' highlight: Blinn-Phong (shading/blinn_phong.h; rough in the rough modes) or a
    // microfacet BRDF (shading/microfacet.h) of roughness `roughness`, Fresnel `fresnel_f0`.
    enum class Highlight { blinn_phong, beckmann, ggx };
    Highlight highlight = Highlight::blinn_phong;
    // glTF's perceptual roughness r ∈ (0, 1] of the beckmann and ggx highlights: α = r². The
    // default α = 0.2 is a lobe as wide as the default shininess (Blinn-Phong ≈ Beckmann at
    // α² = 2/(m + 2)). Shapes the lights' highlight only, not the environment reflection — except
    // in the metallic-roughness model, where r ∈ [0, 1] roughens both.
    float roughness = 0.45f;
    float mirror = 0;      // environment reflection weight (× Fresnel)
    float fresnel_f0 = 1;  // Schlick's F0; 1 = a perfect mirror
    // A dynamic environment map: its mirror reflection reads a cube map of the scene rendered
    // from `center`, where the other objects appear, instead of the scene's environment.
    std::optional<EnvironmentProbeDesc> environment_probe;
    BumpDesc bump;
    float micro_roughness = 0;  // slope standard deviation below the bump map's resolution
    // What an invalid texel (NaN/Inf, n_z ≤ 0: an all-black map) of the material's normal maps
    // does: bump.normal_map and, on a mesh, the file's own normal textures. The default error
    // names the file and the texel; clamp (bump/slope_map.h) is for maps known to hold a few such
    // texels.
    InvalidNormalPolicy invalid_normals = InvalidNormalPolicy::error;
    // A NaN or ±Inf texel in base_color_map's or a height map's file: refuse or repair, as
    // EnvironmentDesc::non_finite. (A normal map's are invalid normals.)
    NonFinitePolicy non_finite = NonFinitePolicy::refuse;
};

struct PlaneShape {
    Vec3d center{0, 0, 0};
    Vec3d normal{0, 1, 0};
    Vec2d size{1, 1};  // extent along the plane's u and v axes (ignored if infinite)
    bool infinite = false;
    double uv_scale = 1;  // texture repeats per world unit
};

struct SphereShape {
    Vec3d center{0, 0, 0};
    double radius = 1;
};

struct CylinderShape {      // open tube, no caps
    Vec3d center{0, 0, 0};  // centre of the axis segment
    Vec3d axis{0, 1, 0};
    double radius = 1;
    double height = 2;
};

struct ParaboloidShape {  // a parabolic mirror: reflects rays from its focus parallel to its axis
    Vec3d focus{0, 0, 0};
    Vec3d axis{0, 0, 1};  // direction the mirror opens towards (from the vertex through the focus)
    double focal_length = 1;
    double radius = 1;  // aperture radius, measured perpendicular to the axis
};

struct TorusShape {
    Vec3d center{0, 0, 0};
    Vec3d axis{0, 1, 0};
    double major_radius = 1;
    double minor_radius = 0.25;
};

struct MeshTransform {
    Vec3d translate{0, 0, 0};
    Vec3d rotate_deg{0, 0, 0};  // x then y then z, as rotation_xyz_degrees
    Vec3d scale{1, 1, 1};
};

struct MeshShape {
    std::filesystem::path file;  // .obj, .gltf, .glb
    MeshTransform transform;
};

// A fractal height field (scene/terrain.h), rendered as a triangle mesh.
inline constexpr int kMaxTerrainSubdivisions = 11;  // 2049² samples, 8.4 M triangles
struct TerrainShape {
    Vec3d center{0, 0, 0};
    Vec2d size{10, 10};      // extent along x and z
    int subdivisions = 7;    // L: 2^L + 1 samples per side, 1 … kMaxTerrainSubdivisions
    double roughness = 0.7;  // H, the Hurst exponent, (0, 1]: small is jagged
    double height = 1;       // A: the displacement's standard deviation over the terrain's width
    std::uint32_t seed = 1;
};

using ShapeDesc = std::variant<PlaneShape, SphereShape, CylinderShape, ParaboloidShape, TorusShape,
                               MeshShape, TerrainShape>;

// Whether a shape is rendered as triangles (a mesh file, or a terrain's generated mesh) rather
// than intersected analytically (scene/shapes.h).
template <class S>
inline constexpr bool is_mesh_shape =
    std::is_same_v<S, MeshShape> || std::is_same_v<S, TerrainShape>;
inline bool renders_as_mesh(const ShapeDesc& shape) {
    return std::holds_alternative<MeshShape>(shape) || std::holds_alternative<TerrainShape>(shape);
}

struct ObjectDesc {
    std::string name;  // for messages ("objects[2]" if unnamed)
    ShapeDesc shape;
    MaterialDesc material;
};

struct SceneDesc {
    int width = 640, height = 360;
    CameraDesc camera;
    // Optional animation: keyframes in increasing time (≥ 2). Frame i of N is rendered at
    // time t0 + (t1 − t0)·i/(N − 1) over the path's [t0, t1] (camera_at).
    std::vector<CameraKeyframe> camera_path;
    std::optional<EnvironmentDesc> environment;  // none: black background, no reflections
    // Local maps, each with a proxy (envmap/env_proxy.h): a point inside one or more of their
    // proxies reads the innermost (the smallest) instead of `environment`, in its reflections,
    // its diffuse light and the background seen from it.
    std::vector<EnvironmentDesc> local_environments;
    Vec3 background{0, 0, 0};  // seen where rays escape and there is no environment
    std::vector<LightDesc> lights;
    std::vector<ObjectDesc> objects;
    std::filesystem::path source;  // the scene file (empty for built-in scenes)
};

// The camera at `time` on the scene's camera_path: position, look_at, up and fov interpolated
// linearly between the two keyframes around `time` (clamped to the path's ends); the scene's
// `camera` if it has no path.
CameraDesc camera_at(const SceneDesc& scene, double time);

// The camera of frame `frame` of `frame_count` (≥ 1) spread evenly over the path's time span;
// frame_count = 1 gives the first keyframe.
CameraDesc camera_for_frame(const SceneDesc& scene, int frame, int frame_count);

}  // namespace footprint
