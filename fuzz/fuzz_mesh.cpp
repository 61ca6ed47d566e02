// fuzz/fuzz_mesh.cpp — mesh files through load_mesh (scene/mesh.h): OBJ, glTF (.gltf JSON) and
// binary glTF (.glb), with the materials' textures they name.
//
// Feeds: the bytes after the first as a file whose extension the first byte picks (.obj .gltf
// .glb), loaded with a transform that the first byte's upper bits pick (identity, or a rotation,
// a scale and a translation). Relative file names in it (an OBJ's mtllib, a glTF's buffers and
// images) resolve to the scratch folder, where nothing else lies, or to data: URIs.
// Asserts: a load fails with a message naming the file, or gives meshes that each have at least
// one triangle, whose indices all name a vertex, whose normals, uvs and tangents are absent or one
// per vertex, and whose positions are finite (and normals finite, unit or zero).
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "fuzz_input.h"
#include "scene/mesh.h"

namespace {

using namespace footprint;

bool finite(const Vec3d& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void require_sound(const TriangleMesh& mesh) {
    const std::size_t n = mesh.positions.size();
    fuzz::require(!mesh.triangles.empty(), "a mesh has at least one triangle");
    for (const auto& triangle : mesh.triangles)
        for (std::uint32_t i : triangle) fuzz::require(i < n, "indices name a vertex");
    fuzz::require(mesh.normals.empty() || mesh.normals.size() == n, "one normal per vertex");
    fuzz::require(mesh.uvs.empty() || mesh.uvs.size() == n, "one uv per vertex");
    fuzz::require(mesh.tangents.empty() || mesh.tangents.size() == n, "one tangent per vertex");
    for (const Vec3d& p : mesh.positions) fuzz::require(finite(p), "positions are finite");
    for (const Vec3d& normal : mesh.normals) {
        fuzz::require(finite(normal), "normals are finite");
        const double length2 = dot(normal, normal);
        fuzz::require(length2 == 0 || std::abs(length2 - 1) < 1e-6, "normals are unit or zero");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    static constexpr std::array kExtensions{".obj", ".gltf", ".glb"};
    const std::uint8_t choice = data[0];
    const std::filesystem::path file =
        fuzz::write_scratch(std::string("mesh") + kExtensions[choice % kExtensions.size()],
                            std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));
    MeshTransform transform;
    if (choice & 0x80) {
        transform.translate = {1, -2, 3};
        transform.rotate_deg = {30, 45, -60};
        transform.scale = {2, 0.5, -1};
    }
    const Result<MeshAsset> asset = load_mesh(file, transform);
    if (!asset.ok()) {
        fuzz::require(asset.error().message.find(file.filename().string()) != std::string::npos,
                      "a load error names the file");
        return 0;
    }
    for (const TriangleMesh& mesh : asset->meshes) require_sound(mesh);
    return 0;
}
