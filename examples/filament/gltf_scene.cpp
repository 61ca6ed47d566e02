// examples/filament/gltf_scene.cpp — a glTF file as footprint-filament's scene data (gltf_scene.h).
#include "gltf_scene.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <numbers>
#include <optional>

#include "scene/mesh.h"

namespace footprint::filament_example {
namespace fs = std::filesystem;
namespace {

using Json = nlohmann::json;
using Mat4 = std::array<double, 16>;  // column-major, as glTF's node.matrix

constexpr double kFramingFovDeg = 40;    // the framing view's vertical field of view
constexpr double kFramingMargin = 1.05;  // the view is this much wider than the scene's box

Mat4 identity() {
    return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
}

Mat4 multiply(const Mat4& a, const Mat4& b) {
    Mat4 out{};
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            for (int k = 0; k < 4; ++k) out[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
    return out;
}

std::array<double, 3> transform(const Mat4& m, std::array<double, 3> v, double w) {
    std::array<double, 3> out{};
    for (int r = 0; r < 3; ++r)
        out[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * w;
    return out;
}

std::array<double, 3> normalized(std::array<double, 3> v) {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return l > 0 ? std::array<double, 3>{v[0] / l, v[1] / l, v[2] / l} : v;
}

double number(const Json& j, double fallback) {
    return j.is_number() ? j.get<double>() : fallback;
}

// A node's local matrix: `matrix`, or T·R·S.
Mat4 local_matrix(const Json& node) {
    if (node.contains("matrix") && node["matrix"].is_array() && node["matrix"].size() == 16) {
        Mat4 m{};
        for (int i = 0; i < 16; ++i) m[i] = number(node["matrix"][i], i % 5 == 0 ? 1 : 0);
        return m;
    }
    auto vec = [&node](const char* key, std::array<double, 4> fallback, std::size_t n) {
        if (node.contains(key) && node[key].is_array() && node[key].size() == n)
            for (std::size_t i = 0; i < n; ++i) fallback[i] = number(node[key][i], fallback[i]);
        return fallback;
    };
    const auto t = vec("translation", {0, 0, 0, 0}, 3);
    const auto q = vec("rotation", {0, 0, 0, 1}, 4);  // x, y, z, w
    const auto s = vec("scale", {1, 1, 1, 0}, 3);
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    // The rotation matrix of a unit quaternion, columns.
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)},
                            {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)},
                            {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)}};
    Mat4 m = identity();
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) m[c * 4 + k] = r[c][k] * s[c];
    for (int k = 0; k < 3; ++k) m[12 + k] = t[k];
    return m;
}

// The file's JSON: the whole .gltf, or a .glb's first chunk. Empty when it cannot be read (the
// mesh reader has parsed the file already and named any fault).
Json read_gltf_json(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::string text = bytes;
    if (bytes.size() >= 20 && bytes.compare(0, 4, "glTF") == 0) {
        std::uint32_t length = 0, type = 0;
        std::memcpy(&length, bytes.data() + 12, 4);
        std::memcpy(&type, bytes.data() + 16, 4);
        if (type != 0x4E4F534Au || bytes.size() - 20 < length) return Json();  // "JSON"
        text = bytes.substr(20, length);
    }
    return Json::parse(text, nullptr, false);
}

// The default scene's root nodes, as scene/mesh.h picks them.
std::vector<int> root_nodes(const Json& gltf) {
    std::vector<int> roots;
    const Json& nodes = gltf.contains("nodes") ? gltf["nodes"] : Json::array();
    if (gltf.contains("scenes") && gltf["scenes"].is_array() && !gltf["scenes"].empty()) {
        std::size_t s = 0;
        if (gltf.contains("scene") && gltf["scene"].is_number_integer() &&
            gltf["scene"].get<long>() >= 0 &&
            static_cast<std::size_t>(gltf["scene"].get<long>()) < gltf["scenes"].size())
            s = gltf["scene"].get<std::size_t>();
        const Json& scene = gltf["scenes"][s];
        if (scene.contains("nodes") && scene["nodes"].is_array())
            for (const Json& n : scene["nodes"])
                if (n.is_number_integer()) roots.push_back(n.get<int>());
        return roots;
    }
    std::vector<bool> child(nodes.size(), false);
    for (const Json& node : nodes)
        if (node.contains("children") && node["children"].is_array())
            for (const Json& c : node["children"])
                if (c.is_number_integer() && c.get<long>() >= 0 &&
                    static_cast<std::size_t>(c.get<long>()) < child.size())
                    child[c.get<std::size_t>()] = true;
    for (std::size_t i = 0; i < nodes.size(); ++i)
        if (!child[i]) roots.push_back(static_cast<int>(i));
    return roots;
}

struct FoundCamera {
    std::optional<CameraSetup> camera;
    std::string note;
};

// The first perspective camera placed by the default scene (gltf_scene.h).
FoundCamera find_camera(const fs::path& file) {
    const Json gltf = read_gltf_json(file);
    FoundCamera found;
    if (!gltf.is_object() || !gltf.contains("cameras") || !gltf["cameras"].is_array()) return found;
    const Json& nodes =
        gltf.contains("nodes") && gltf["nodes"].is_array() ? gltf["nodes"] : Json::array();
    // Each camera's first placement: camera index → world matrix.
    std::vector<std::optional<Mat4>> placed(gltf["cameras"].size());
    std::vector<int> visiting;
    std::function<void(int, const Mat4&)> visit = [&](int index, const Mat4& parent) {
        if (index < 0 || static_cast<std::size_t>(index) >= nodes.size() ||
            std::find(visiting.begin(), visiting.end(), index) != visiting.end() ||
            visiting.size() > 64)
            return;
        const Json& node = nodes[index];
        const Mat4 world = multiply(parent, local_matrix(node));
        if (node.contains("camera") && node["camera"].is_number_integer()) {
            const long c = node["camera"].get<long>();
            if (c >= 0 && static_cast<std::size_t>(c) < placed.size() && !placed[c])
                placed[c] = world;
        }
        visiting.push_back(index);
        if (node.contains("children") && node["children"].is_array())
            for (const Json& child : node["children"])
                if (child.is_number_integer()) visit(child.get<int>(), world);
        visiting.pop_back();
    };
    for (int root : root_nodes(gltf)) visit(root, identity());
    for (std::size_t c = 0; c < placed.size(); ++c) {
        if (!placed[c]) continue;
        const Json& camera = gltf["cameras"][c];
        const std::string type = camera.value("type", std::string());
        if (type != "perspective" || !camera.contains("perspective")) {
            found.note = "camera " + std::to_string(c) + " is " +
                         (type.empty() ? std::string("of no type") : "'" + type + "'") +
                         ", not perspective: the view frames the scene instead";
            return found;
        }
        const Json& p = camera["perspective"];
        const Mat4& m = *placed[c];
        CameraSetup setup;
        const auto eye = transform(m, {0, 0, 0}, 1);
        const auto forward = normalized(transform(m, {0, 0, -1}, 0));
        const auto up = normalized(transform(m, {0, 1, 0}, 0));
        setup.eye = eye;
        setup.target = {eye[0] + forward[0], eye[1] + forward[1], eye[2] + forward[2]};
        setup.up = up;
        const double yfov = number(p.value("yfov", Json()), 0);
        if (!(yfov > 0 && yfov < std::numbers::pi)) {
            found.note = "camera " + std::to_string(c) +
                         " has no valid yfov: the view frames the scene instead";
            return found;
        }
        setup.fov_y_deg = yfov * 180 / std::numbers::pi;
        setup.near = std::max(1e-6, number(p.value("znear", Json()), 0.05));
        // An infinite projection (no zfar): a far plane far enough for any scene seen through it.
        setup.far = number(p.value("zfar", Json()), setup.near * 1e6);
        if (!(setup.far > setup.near)) setup.far = setup.near * 1e6;
        found.camera = setup;
        return found;
    }
    return found;
}

// A view of every object from the front (+Z), a little above and right, aimed at the bounding
// box's centre and as close as keeps the box's eight corners inside the vertical field of view and
// inside a square one (whatever the output's aspect ratio), with a margin.
CameraSetup framing_camera(const std::vector<SceneObject>& objects) {
    std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const SceneObject& object : objects)
        for (const auto& p : object.mesh.positions)
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], double(p[k]));
                hi[k] = std::max(hi[k], double(p[k]));
            }
    std::array<double, 3> centre{};
    double radius = 0;
    for (int k = 0; k < 3; ++k) {
        centre[k] = (lo[k] + hi[k]) / 2;
        radius += (hi[k] - lo[k]) * (hi[k] - lo[k]) / 4;
    }
    radius = std::max(std::sqrt(radius), 1e-6);
    // The view's basis: back (from the centre to the eye), right, up.
    const auto back = normalized({0.3, 0.4, 1});
    const auto right = normalized({back[2], 0, -back[0]});  // (0, 1, 0) × back
    const std::array<double, 3> up{back[1] * right[2] - back[2] * right[1],
                                   back[2] * right[0] - back[0] * right[2],
                                   back[0] * right[1] - back[1] * right[0]};
    const double tan_half = std::tan(kFramingFovDeg * std::numbers::pi / 360) / kFramingMargin;
    double distance = 0;
    for (int corner = 0; corner < 8; ++corner) {
        std::array<double, 3> d{};
        for (int k = 0; k < 3; ++k) d[k] = ((corner >> k) & 1 ? hi[k] : lo[k]) - centre[k];
        auto along = [&d](const std::array<double, 3>& axis) {
            return d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2];
        };
        // The corner at depth `along(back)` towards the eye must satisfy |offset| ≤
        // (distance − depth)·tan_half on both axes.
        distance = std::max(distance, along(back) + std::abs(along(up)) / tan_half);
        distance = std::max(distance, along(back) + std::abs(along(right)) / tan_half);
    }
    distance = std::max(distance, radius * 0.01);
    CameraSetup camera;
    camera.fov_y_deg = kFramingFovDeg;
    camera.target = centre;
    for (int k = 0; k < 3; ++k) camera.eye[k] = centre[k] + distance * back[k];
    camera.near = std::max(distance - radius * 1.5, distance * 0.01);
    camera.far = distance + radius * 1.5;
    return camera;
}

// Vertex normals from the triangles (area-weighted) where the file has none.
std::vector<std::array<float, 3>> face_normals(const TriangleMesh& mesh) {
    std::vector<Vec3d> sum(mesh.positions.size());
    for (const auto& t : mesh.triangles) {
        const Vec3d n = cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                              mesh.positions[t[2]] - mesh.positions[t[0]]);
        for (std::uint32_t i : t) sum[i] = sum[i] + n;
    }
    std::vector<std::array<float, 3>> out(sum.size(), {0, 0, 1});
    for (std::size_t i = 0; i < sum.size(); ++i) {
        const double l = std::sqrt(dot(sum[i], sum[i]));
        if (l > 0) out[i] = {float(sum[i].x / l), float(sum[i].y / l), float(sum[i].z / l)};
    }
    return out;
}

MapSource image_map(const std::shared_ptr<const Image>& image, std::string label) {
    MapSource map;
    if (!image) return map;
    map.image = *image;
    map.label = std::move(label);
    return map;
}

// glTF's normalTexture.scale: the map's x and y scaled, then renormalised, written back as a map.
Image scaled_normal_map(const Image& map, float scale) {
    Image out = map;
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            float* p = out.at(x, y);
            const double n[3] = {(2.0 * p[0] - 1) * scale, (2.0 * p[1] - 1) * scale,
                                 2.0 * p[std::min(2, map.channels - 1)] - 1};
            const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int c = 0; c < std::min(3, map.channels); ++c)
                p[c] = static_cast<float>(l > 0 ? 0.5 + 0.5 * n[c] / l : (c == 2 ? 1.0 : 0.5));
        }
    }
    return out;
}

SurfaceDesc surface_of(const MeshMaterial& m, const std::string& where) {
    SurfaceDesc surface;
    surface.base_color = image_map(m.base_color_texture, where + " baseColorTexture");
    if (m.normal_texture) {
        surface.normal = image_map(m.normal_texture, where + " normalTexture");
        if (m.normal_scale != 1)
            surface.normal.image = scaled_normal_map(*m.normal_texture, m.normal_scale);
    }
    surface.metallic_roughness =
        image_map(m.metallic_roughness_texture, where + " metallicRoughnessTexture");
    surface.base_color_factor = {static_cast<float>(m.base_color.x),
                                 static_cast<float>(m.base_color.y),
                                 static_cast<float>(m.base_color.z)};
    surface.metallic = m.metallic_roughness ? m.metallic : 0.0f;
    surface.roughness = m.metallic_roughness ? m.roughness : 0.5f;
    return surface;
}

}  // namespace

Result<GltfScene> load_gltf_scene(const fs::path& file, const fs::path& assets_dir) {
    Result<fs::path> sky = asset_file(assets_dir, "envmaps/venice_sunset_1k.hdr");
    if (!sky) return sky.error();
    Result<MeshAsset> asset = load_mesh(file);
    if (!asset) return asset.error();

    GltfScene out;
    SceneSetup& scene = out.scene;
    scene.name = file.stem().string();
    scene.title = "glTF " + file.string();
    scene.environment = file_map(*sky);
    // One surface per distinct material (the reader shares a material's decoded images).
    struct Key {
        const Image *base, *normal, *mr;
        std::string name;
        bool operator==(const Key&) const = default;
    };
    std::vector<Key> keys;
    for (const TriangleMesh& m : asset->meshes) {
        const MeshMaterial& mat = m.material;
        const Key key{mat.base_color_texture.get(), mat.normal_texture.get(),
                      mat.metallic_roughness_texture.get(), mat.name};
        std::size_t index = 0;
        while (
            index < keys.size() &&
            !(keys[index] == key &&
              scene.surfaces[index].base_color_factor ==
                  std::array<float, 3>{float(mat.base_color.x), float(mat.base_color.y),
                                       float(mat.base_color.z)} &&
              scene.surfaces[index].metallic == (mat.metallic_roughness ? mat.metallic : 0.0f) &&
              scene.surfaces[index].roughness == (mat.metallic_roughness ? mat.roughness : 0.5f)))
            ++index;
        if (index == keys.size()) {
            keys.push_back(key);
            scene.surfaces.push_back(
                surface_of(mat, "'" + file.string() + "' material '" + mat.name + "'"));
        }
        SceneObject object;
        object.surface = index;
        Mesh& mesh = object.mesh;
        for (const Vec3d& p : m.positions)
            mesh.positions.push_back({float(p.x), float(p.y), float(p.z)});
        if (m.has_normals()) {
            for (const Vec3d& n : m.normals)
                mesh.normals.push_back({float(n.x), float(n.y), float(n.z)});
        } else {
            mesh.normals = face_normals(m);
        }
        // scene/mesh.h's uv has v up; the materials read (s, t) with t = 0 on the image's top row.
        if (m.has_uvs())
            for (const Vec2d& uv : m.uvs) mesh.uvs.push_back({float(uv.x), float(1 - uv.y)});
        mesh.triangles = m.triangles;
        scene.objects.push_back(std::move(object));
    }

    FoundCamera found = find_camera(file);
    out.note = found.note;
    out.has_camera = found.camera.has_value();
    scene.camera = found.camera ? *found.camera : framing_camera(scene.objects);
    return out;
}

}  // namespace footprint::filament_example
