// examples/filament/scenes.cpp — the built-in scenes (scenes.h), after footprint's demo scenes
// (apps/demo_scenes.cpp) with the same cameras.
#include "scenes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "demo_assets.h"

namespace footprint::filament_example {
namespace {

// A w × d rectangle in the xz-plane centred at the origin, facing +y; u runs along +x, v along +z
// (v = 0 at the far edge, the image's top row, as footprint's planes).
Mesh make_plane(double width, double depth, double uv_units) {
    Mesh mesh;
    const float hw = static_cast<float>(width / 2), hd = static_cast<float>(depth / 2);
    const float u = static_cast<float>(width / uv_units), v = static_cast<float>(depth / uv_units);
    mesh.positions = {{-hw, 0, -hd}, {hw, 0, -hd}, {hw, 0, hd}, {-hw, 0, hd}};
    mesh.normals.assign(4, {0, 1, 0});
    mesh.uvs = {{0, 0}, {u, 0}, {u, v}, {0, v}};
    mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
    return mesh;
}

// An open cylinder about +y, radius r, height h, centred at the origin; `segments` quads around.
// u goes once around, v from the top (0) to the bottom (1).
Mesh make_cylinder(double radius, double height, int segments) {
    Mesh mesh;
    for (int i = 0; i <= segments; ++i) {
        const double phi = 2 * std::numbers::pi * i / segments;
        const float x = static_cast<float>(std::sin(phi)), z = static_cast<float>(std::cos(phi));
        for (int j = 0; j < 2; ++j) {
            const float y = static_cast<float>((j == 0 ? 0.5 : -0.5) * height);
            mesh.positions.push_back(
                {static_cast<float>(radius) * x, y, static_cast<float>(radius) * z});
            mesh.normals.push_back({x, 0, z});
            mesh.uvs.push_back({static_cast<float>(i) / segments, static_cast<float>(j)});
        }
    }
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(segments); ++i) {
        const std::uint32_t a = 2 * i, b = a + 1, c = a + 2, d = a + 3;
        mesh.triangles.push_back({a, b, c});
        mesh.triangles.push_back({c, b, d});
    }
    return mesh;
}

MapSource generated(Image image, std::string label) {
    MapSource map;
    map.image = std::move(image);
    map.label = std::move(label);
    return map;
}

}  // namespace

MapSource file_map(const std::filesystem::path& path) {
    MapSource map;
    map.file = path;
    map.label = path.string();
    return map;
}

Result<std::filesystem::path> asset_file(const std::filesystem::path& assets_dir,
                                         const std::filesystem::path& relative) {
    std::filesystem::path path = assets_dir / relative;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        return Error{"missing asset '" + path.string() + "' (the repository's assets/ folder)"};
    return path;
}

const std::vector<std::string>& builtin_scene_names() {
    static const std::vector<std::string> names{"plate", "floor", "mirror", "sky"};
    return names;
}

Result<SceneSetup> make_builtin_scene(const std::string& name,
                                      const std::filesystem::path& assets_dir) {
    SceneSetup scene;
    scene.name = name;
    Mesh mesh;
    SurfaceDesc surface;
    if (name == "plate") {
        Result<std::filesystem::path> normals =
            asset_file(assets_dir, "normals/polyhaven_metal_plate_02_nor_gl_1k.jpg");
        if (!normals) return normals.error();
        scene.title = "bumpy mirror plate reflecting a zebra-stripe sky";
        mesh = make_plane(3, 3, 1.5);  // the 1K map twice across the plate
        surface.normal = file_map(*normals);
        surface.base_color_factor = {0.9f, 0.9f, 0.9f};
        surface.metallic = 1;
        surface.roughness = 0.08f;
        scene.camera.eye = {0, 1.6, 3.2};
        scene.camera.target = {0, 0, -0.2};
        scene.environment = generated(make_zebra_latlong(1024), "generated zebra");
    } else if (name == "floor") {
        Result<std::filesystem::path> sky = asset_file(assets_dir, "envmaps/venice_sunset_1k.hdr");
        if (!sky) return sky.error();
        scene.title = "grazing floor with the secret-writing texture";
        mesh = make_plane(400, 400, 5);  // uv_scale 0.2 of the demo: one tile per 5 units
        surface.base_color = generated(make_secret_writing_texture(1024), "secret writing");
        surface.roughness = 0.6f;
        scene.camera.eye = {0, 0.5, 0};
        scene.camera.target = {0, 0, 5};
        scene.environment = file_map(*sky);
    } else if (name == "mirror") {
        Result<std::filesystem::path> sky = asset_file(assets_dir, "envmaps/venice_sunset_1k.hdr");
        if (!sky) return sky.error();
        scene.title = "curved mirror: a mirror cylinder";
        mesh = make_cylinder(0.75, 2.6, 256);
        surface.base_color_factor = {0.9f, 0.9f, 0.9f};
        surface.metallic = 1;
        surface.roughness = 0.05f;
        scene.camera.eye = {0, 0.35, 3.2};
        scene.camera.target = {0, 0, 0};
        scene.environment = file_map(*sky);
    } else if (name == "sky") {
        scene.title = "orientation check: a flat mirror under a sky coloured by direction";
        mesh = make_plane(2, 2, 2);
        surface.metallic = 1;
        surface.roughness = 0;  // Filament clamps it to its smallest (0.045)
        scene.camera.eye = {0.3, 0.8, 2.2};
        scene.camera.target = {0, 0.25, 0};
        scene.camera.fov_y_deg = 70;
        scene.environment = generated(make_direction_latlong(512), "direction colours");
    } else {
        std::string list;
        for (const std::string& n : builtin_scene_names()) list += (list.empty() ? "" : ", ") + n;
        return Error{"unknown scene '" + name + "' (a .gltf/.glb file or one of " + list + ")"};
    }
    scene.surfaces.push_back(std::move(surface));
    scene.objects.push_back({std::move(mesh), 0});
    return scene;
}

Image make_direction_latlong(int width) {
    const int height = width / 2;
    Image image(width, height, 3);
    for (int y = 0; y < height; ++y) {
        const double theta = std::numbers::pi * (y + 0.5) / height;
        for (int x = 0; x < width; ++x) {
            const double phi = 2 * std::numbers::pi * ((x + 0.5) / width - 0.5);
            // s − ½ = atan2(d_x, −d_z)/(2π) and t = θ/π, solved for d.
            const double d[3] = {std::sin(theta) * std::sin(phi), std::cos(theta),
                                 -std::sin(theta) * std::cos(phi)};
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = static_cast<float>(0.5 + 0.5 * d[c]);
        }
    }
    return image;
}

Image expected_direction_colours(const SceneSetup& scene, int width, int height) {
    using V = std::array<double, 3>;
    auto sub = [](V a, V b) { return V{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
    auto cross = [](V a, V b) {
        return V{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    };
    auto normalize = [](V a) {
        const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        return V{a[0] / l, a[1] / l, a[2] / l};
    };
    const CameraSetup& c = scene.camera;
    const V forward = normalize(sub(c.target, c.eye));
    const V right = normalize(cross(forward, c.up));
    const V up = cross(right, forward);
    const double tan_half = std::tan(c.fov_y_deg * std::numbers::pi / 360);
    const double aspect = static_cast<double>(width) / height;
    // The plate: y = 0, |x|, |z| within the mesh's half extent.
    double half = 0;
    for (const auto& p : scene.objects.front().mesh.positions)
        half = std::max(half, std::abs(double(p[0])));
    std::vector<int> hits(static_cast<std::size_t>(width) * height);
    Image image(width, height, 4);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double nx = (2 * (x + 0.5) / width - 1) * tan_half * aspect;
            const double ny = (1 - 2 * (y + 0.5) / height) * tan_half;
            V d = normalize(V{forward[0] + nx * right[0] + ny * up[0],
                              forward[1] + nx * right[1] + ny * up[1],
                              forward[2] + nx * right[2] + ny * up[2]});
            bool hit = false;
            if (d[1] < 0) {
                const double t = -c.eye[1] / d[1];
                const double px = c.eye[0] + t * d[0], pz = c.eye[2] + t * d[2];
                hit = std::abs(px) <= half && std::abs(pz) <= half;
            }
            if (hit) d[1] = -d[1];  // the mirror's reflection about +Y
            hits[static_cast<std::size_t>(y) * width + x] = hit ? 1 : 0;
            for (int k = 0; k < 3; ++k) image.at(x, y, k) = static_cast<float>(0.5 + 0.5 * d[k]);
        }
    }
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            bool same = true;
            const int h = hits[static_cast<std::size_t>(y) * width + x];
            for (int j = -1; j <= 1; ++j) {
                for (int i = -1; i <= 1; ++i) {
                    const int xx = std::clamp(x + i, 0, width - 1);
                    const int yy = std::clamp(y + j, 0, height - 1);
                    same = same && hits[static_cast<std::size_t>(yy) * width + xx] == h;
                }
            }
            image.at(x, y, 3) = same ? (h ? 2.0f : 1.0f) : 0.0f;
        }
    }
    return image;
}

}  // namespace footprint::filament_example
