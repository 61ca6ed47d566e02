// scene/mesh.h — triangle meshes loaded from OBJ and glTF 2.0 files.
//
// load_mesh() reads a file into a MeshAsset: one TriangleMesh per glTF primitive or per OBJ
// material group, in world space (the MeshTransform and, for glTF, the node transforms applied),
// in double precision, with the material's colour and textures already decoded to Images.
//
// Formats
//   .obj   tinyobjloader, polygons triangulated. Positions, normals (vn) and texture coordinates
//          (vt) where every corner of the group has them. The faces are grouped by material (the
//          .mtl file next to the OBJ, as `mtllib` names it): Kd is the base colour (taken as linear
//          RGB; white when the material has a map_Kd and no or a black Kd), map_Kd the
//          base-colour texture (sRGB-decoded as image_io.h's automatic does),
//          `norm` a tangent-space normal texture (loaded linear). Paths are relative to the OBJ's
//          folder. OBJ has no tangents.
//   .gltf, .glb   tinygltf. Every primitive of mode TRIANGLES reachable from the default scene's
//          node hierarchy (scene 0 without `scene`; all root nodes without `scenes`), with the
//          node transforms applied; other modes (points, lines, strips, fans) are skipped.
//          Attributes POSITION, NORMAL, TEXCOORD_0 (float or normalised integers), TANGENT;
//          indices of any component type (or none: consecutive triangles). Material:
//          baseColorFactor (linear RGB), baseColorTexture (8-bit or 16-bit, sRGB-decoded),
//          normalTexture (values / 255 or / 65535, linear data, with its `scale`). Only
//          TEXCOORD_0 is read, whatever texCoord a texture names; samplers, KHR_texture_transform
//          and sparse accessors are not supported (sparse: an error).
//
// Conventions
//   * Transform: p' = T + R·(S·p) — scale, then rotation (rotation_xyz_degrees of rotate_deg,
//     math/mat3.h), then translation; for glTF the node's global matrix comes first (p' =
//     user · node · p). Normals go through the inverse transpose of the linear part and are
//     renormalised; tangents through the linear part and renormalised. A transform that mirrors
//     (negative determinant) reverses the triangles' winding and negates the tangent signs, so
//     the counter-clockwise side stays the front and n × tangent keeps its meaning.
//   * Texture coordinates: uv = (u, v) with v UP the image, as SurfaceHit (scene/surface.h);
//     images are looked up at (s, t) = (u, 1 − v). OBJ's vt is already v up: uv = vt. glTF's
//     texcoords (s, t) have (0, 0) at the image's top-left: uv = (s, 1 − t).
//   * Tangents (glTF only): xyz is the direction of ∂p/∂u, and w (±1) says that w·(n × xyz) is
//     the direction of ∂p/∂v (v up): the frame of an OpenGL-convention normal map (+Y up the
//     image), which glTF's normalTexture is.
//   * Normals, uvs and tangents are each either empty (absent) or one per position. Stored
//     normals and tangent directions are unit vectors, or zero where the file's were zero.
//   * Every value must be a finite number: a NaN, an infinity or (OBJ) a word where a number
//     belongs is refused, since a loader would otherwise read it as 0 and move the vertex.
//
// Errors (core/result.h) name the file: "cannot read 'a.obj': no such file", "… unsupported
// extension '.ply' (supported: .obj .gltf .glb)", "… parse error: …" (the loader's message),
// "… index 9 out of range (3 vertices) in …", "… line 4: 'v' value 1 is 'nan', not a finite
// number", "… accessor 2 (NORMAL of mesh 'hull'): element 5 holds the non-finite value nan",
// "… it has no triangles", "… cannot load texture 'wood.png': …", "… normalTexture of material
// 'visor' (texture 3): image 2 'visor_n.png': file not found (resolved to '…')", a transform with
// a zero or non-finite scale.
// Nothing is printed; warnings of the loaders are dropped.
//
// Thread-safe for distinct calls.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <footprint/core/result.h>
#include <footprint/image/image.h>
#include <footprint/math/vec.h>
#include <footprint/math/vec3.h>
#include <footprint/scene/scene.h>

namespace footprint {

struct MeshMaterial {
    std::string name;
    Vec3 base_color{1, 1, 1};  // linear RGB; multiplies base_color_texture where there is one
    // Linear-light colour (sRGB-decoded; alpha, where present, kept as stored). Null: none.
    std::shared_ptr<const Image> base_color_texture;
    // Tangent-space normal map, OpenGL convention, raw values in [0, 1] (not decoded: data).
    std::shared_ptr<const Image> normal_texture;
    float normal_scale = 1;  // glTF normalTexture.scale: scales the map's x and y
    // glTF's pbrMetallicRoughness (every glTF material has it; an OBJ material does not): metallic
    // and perceptual roughness factors, each × its channel of metallic_roughness_texture where
    // there is one (B metallic, G roughness; raw values in [0, 1], not decoded: data).
    bool metallic_roughness = false;
    float metallic = 1, roughness = 1;  // glTF's defaults
    std::shared_ptr<const Image> metallic_roughness_texture;

    bool has_base_color_texture() const { return base_color_texture != nullptr; }
    bool has_normal_texture() const { return normal_texture != nullptr; }
};

struct MeshTangent {
    Vec3d xyz;     // unit direction of ∂p/∂u (zero if the file's was degenerate)
    double w = 1;  // ±1: w·(n × xyz) is the direction of ∂p/∂v
};

struct TriangleMesh {
    std::string name;                   // the glTF mesh name or OBJ material name, for messages
    std::vector<Vec3d> positions;       // world space
    std::vector<Vec3d> normals;         // optional: empty or one per position, unit
    std::vector<Vec2d> uvs;             // optional: empty or one per position, v up
    std::vector<MeshTangent> tangents;  // optional: empty or one per position (glTF TANGENT)
    std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from the front
    MeshMaterial material;

    bool has_normals() const { return !normals.empty(); }
    bool has_uvs() const { return !uvs.empty(); }
    bool has_tangents() const { return !tangents.empty(); }
};

struct MeshAsset {
    std::vector<TriangleMesh> meshes;  // each with at least one triangle

    std::size_t triangle_count() const {
        std::size_t n = 0;
        for (const TriangleMesh& m : meshes) n += m.triangles.size();
        return n;
    }
};

// Reads an OBJ, glTF or GLB file (by extension, case-insensitive) and applies `transform`.
Result<MeshAsset> load_mesh(const std::filesystem::path& file, const MeshTransform& transform = {});

}  // namespace footprint
