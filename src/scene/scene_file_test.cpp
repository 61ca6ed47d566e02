#include "scene/scene_file.h"
#include "scene/scene_hash.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/test_temp_dir.h"
#include "image/image_io.h"
#include "render/render_scene.h"
#include "render/renderer.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// A fresh folder under the system temp directory, removed with everything in it.
using test::TempDir;

void write_file(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream out(file, std::ios::binary);
    out << text;
}

// The files the test scenes refer to (empty: the parser only checks that they exist).
void create_assets(const fs::path& dir) {
    for (const char* name : {"sky.hdr", "front.hdr", "back.hdr", "px.hdr", "nx.hdr", "py.hdr",
                             "ny.hdr", "pz.hdr", "nz.hdr", "bricks.png", "height.png", "normal.png",
                             "cow.obj", "helmet.gltf", "helmet.glb", "CAPS.OBJ"})
        write_file(dir / name, "");
}

std::string vec_text(Vec3d v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) +
           ")";
}
#define EXPECT_VEC3_EQ(actual, ex, ey, ez)                                               \
    do {                                                                                 \
        const auto v_ = (actual);                                                        \
        EXPECT_TRUE(v_.x == (ex) && v_.y == (ey) && v_.z == (ez))                        \
            << #actual << " = " << vec_text({double(v_.x), double(v_.y), double(v_.z)}); \
    } while (0)

// ---- A complete scene: every key, every shape.

constexpr const char* kCompleteScene = R"({
  "image": {"width": 320, "height": 200},
  "camera": {"position": [1, 2, 3], "look_at": [0, 0.5, 0], "up": [0, 0, 1], "fov_y_deg": 55.5},
  "environment": {"file": "sky.hdr", "layout": "sphere", "rotation_deg": [10, 20, 30],
                  "intensity": 0.5},
  "background": [0.25, 0.5, 0.75],
  "lights": [
    {"type": "directional", "direction": [1, -2, 0.5], "color": [2, 3, 4]},
    {"type": "point", "position": [4, 5, 6], "color": [10, 20, 30], "shadows": false},
    {}
  ],
  "objects": [
    {"name": "floor", "shape": "plane", "center": [0, -1, 0], "normal": [0, 2, 0],
     "size": [10, 20], "uv_scale": 0.25,
     "material": {"base_color": "bricks.png", "diffuse": 0.75, "specular": 0.125,
                  "shininess": 12, "mirror": 0.5, "fresnel_f0": 0.0625,
                  "bump": {"height_map": "height.png", "strength": 0.03125, "frame": "natural"},
                  "micro_roughness": 0.1875}},
    {"shape": "plane", "size": "infinite"},
    {"name": "ball", "shape": "sphere", "center": [1, 2, 3], "radius": 0.5,
     "material": {"base_color": [0.5, 0.25, 1], "highlight": "ggx", "roughness": 0.25,
                  "bump": {"normal_map": "normal.png", "strength": -2,
                           "main_direction": [1, 0, 0]}}},
    {"shape": "cylinder", "center": [4, 5, 6], "axis": [1, 0, 0], "radius": 0.75, "height": 3,
     "material": {"bump": {"normal_map": "normal.png", "frame": "normalized"}}},
    {"shape": "paraboloid", "focus": [7, 8, 9], "axis": [0, -1, 0], "focal_length": 1.5,
     "radius": 2.5},
    {"shape": "torus", "center": [-1, -2, -3], "axis": [0, 0, 1], "major_radius": 2,
     "minor_radius": 0.5},
    {"shape": "mesh", "file": "cow.obj",
     "transform": {"translate": [1, 2, 3], "rotate_deg": [0, 90, 45], "scale": 2}},
    {"shape": "mesh", "file": "helmet.gltf", "transform": {"scale": [1, 2, -3]}},
    {"shape": "mesh", "file": "helmet.glb"},
    {"shape": "mesh", "file": "CAPS.OBJ"}
  ]
})";

TEST(SceneFile, CompleteSceneParsesToTheExactValues) {
    TempDir dir;
    create_assets(dir.path());
    const fs::path file = dir.path() / "scene.json";
    write_file(file, kCompleteScene);
    const Result<SceneDesc> result = load_scene_file(file);
    ASSERT_TRUE(result.ok()) << result.error().message;
    const SceneDesc& s = *result;
    const fs::path d = dir.path().lexically_normal();

    EXPECT_EQ(s.source, file);
    EXPECT_EQ(s.width, 320);
    EXPECT_EQ(s.height, 200);
    EXPECT_VEC3_EQ(s.camera.position, 1, 2, 3);
    EXPECT_VEC3_EQ(s.camera.look_at, 0, 0.5, 0);
    EXPECT_VEC3_EQ(s.camera.up, 0, 0, 1);
    EXPECT_EQ(s.camera.fov_y_deg, 55.5);

    ASSERT_TRUE(s.environment.has_value());
    ASSERT_EQ(s.environment->images.size(), 1u);
    EXPECT_EQ(s.environment->images[0].file, d / "sky.hdr");
    EXPECT_FALSE(s.environment->images[0].image);
    EXPECT_EQ(s.environment->layout, EnvLayout::sphere);
    EXPECT_VEC3_EQ(s.environment->rotation_deg, 10, 20, 30);
    EXPECT_EQ(s.environment->intensity, 0.5f);
    EXPECT_VEC3_EQ(s.background, 0.25f, 0.5f, 0.75f);

    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_EQ(s.lights[0].type, LightType::directional);
    EXPECT_VEC3_EQ(s.lights[0].direction, 1, -2, 0.5);
    EXPECT_VEC3_EQ(s.lights[0].color, 2, 3, 4);
    EXPECT_EQ(s.lights[1].type, LightType::point);
    EXPECT_VEC3_EQ(s.lights[1].position, 4, 5, 6);
    EXPECT_VEC3_EQ(s.lights[1].color, 10, 20, 30);
    EXPECT_TRUE(s.lights[0].shadows);
    EXPECT_FALSE(s.lights[1].shadows);
    EXPECT_EQ(s.lights[2].type, LightType::directional);  // defaults
    EXPECT_VEC3_EQ(s.lights[2].direction, 0, -1, 0);
    EXPECT_VEC3_EQ(s.lights[2].color, 1, 1, 1);

    ASSERT_EQ(s.objects.size(), 10u);
    {
        const ObjectDesc& o = s.objects[0];
        EXPECT_EQ(o.name, "floor");
        const auto* plane = std::get_if<PlaneShape>(&o.shape);
        ASSERT_TRUE(plane);
        EXPECT_VEC3_EQ(plane->center, 0, -1, 0);
        EXPECT_VEC3_EQ(plane->normal, 0, 2, 0);  // as given, not normalised
        EXPECT_EQ(plane->size.x, 10);
        EXPECT_EQ(plane->size.y, 20);
        EXPECT_FALSE(plane->infinite);
        EXPECT_EQ(plane->uv_scale, 0.25);
        const MaterialDesc& m = o.material;
        EXPECT_EQ(m.base_color_map.file, d / "bricks.png");
        EXPECT_VEC3_EQ(m.base_color, 1, 1, 1);  // a texture is used as is
        EXPECT_EQ(m.diffuse, 0.75f);
        EXPECT_EQ(m.specular, 0.125f);
        EXPECT_EQ(m.shininess, 12.0f);
        EXPECT_EQ(m.highlight, MaterialDesc::Highlight::blinn_phong);
        EXPECT_EQ(m.mirror, 0.5f);
        EXPECT_EQ(m.fresnel_f0, 0.0625f);
        EXPECT_EQ(m.micro_roughness, 0.1875f);
        EXPECT_EQ(m.bump.source, BumpDesc::Source::height_map);
        EXPECT_EQ(m.bump.map.file, d / "height.png");
        EXPECT_EQ(m.bump.strength, 0.03125f);
        EXPECT_EQ(m.bump.frame, BumpFrame::natural);
    }
    {
        const ObjectDesc& o = s.objects[1];
        EXPECT_EQ(o.name, "");
        const auto* plane = std::get_if<PlaneShape>(&o.shape);
        ASSERT_TRUE(plane);
        EXPECT_TRUE(plane->infinite);
        EXPECT_VEC3_EQ(plane->normal, 0, 1, 0);
        EXPECT_EQ(plane->uv_scale, 1.0);
        // Default material.
        EXPECT_VEC3_EQ(o.material.base_color, 0.8f, 0.8f, 0.8f);
        EXPECT_TRUE(o.material.base_color_map.empty());
        EXPECT_EQ(o.material.diffuse, 1.0f);
        EXPECT_EQ(o.material.specular, 0.0f);
        EXPECT_EQ(o.material.shininess, 50.0f);
        EXPECT_EQ(o.material.highlight, MaterialDesc::Highlight::blinn_phong);
        EXPECT_EQ(o.material.roughness, 0.45f);
        EXPECT_EQ(o.material.mirror, 0.0f);
        EXPECT_EQ(o.material.fresnel_f0, 1.0f);
        EXPECT_EQ(o.material.micro_roughness, 0.0f);
        EXPECT_EQ(o.material.bump.source, BumpDesc::Source::none);
        EXPECT_TRUE(o.material.bump.map.empty());
    }
    {
        const ObjectDesc& o = s.objects[2];
        EXPECT_EQ(o.name, "ball");
        const auto* sphere = std::get_if<SphereShape>(&o.shape);
        ASSERT_TRUE(sphere);
        EXPECT_VEC3_EQ(sphere->center, 1, 2, 3);
        EXPECT_EQ(sphere->radius, 0.5);
        EXPECT_VEC3_EQ(o.material.base_color, 0.5f, 0.25f, 1.0f);
        EXPECT_TRUE(o.material.base_color_map.empty());
        EXPECT_EQ(o.material.highlight, MaterialDesc::Highlight::ggx);
        EXPECT_EQ(o.material.roughness, 0.25f);
        EXPECT_EQ(o.material.shininess, 50.0f);  // the default, unused by ggx
        const BumpDesc& b = o.material.bump;
        EXPECT_EQ(b.source, BumpDesc::Source::normal_map);
        EXPECT_EQ(b.map.file, d / "normal.png");
        EXPECT_EQ(b.strength, -2.0f);
        EXPECT_EQ(b.frame, BumpFrame::main_direction);
        EXPECT_VEC3_EQ(b.main_direction, 1, 0, 0);
    }
    {
        const auto* cylinder = std::get_if<CylinderShape>(&s.objects[3].shape);
        ASSERT_TRUE(cylinder);
        EXPECT_VEC3_EQ(cylinder->center, 4, 5, 6);
        EXPECT_VEC3_EQ(cylinder->axis, 1, 0, 0);
        EXPECT_EQ(cylinder->radius, 0.75);
        EXPECT_EQ(cylinder->height, 3.0);
        EXPECT_EQ(s.objects[3].material.bump.frame, BumpFrame::normalized);
        EXPECT_EQ(s.objects[3].material.bump.strength, 1.0f);
        EXPECT_VEC3_EQ(s.objects[3].material.bump.main_direction, 0, 0, 0);
    }
    {
        const auto* paraboloid = std::get_if<ParaboloidShape>(&s.objects[4].shape);
        ASSERT_TRUE(paraboloid);
        EXPECT_VEC3_EQ(paraboloid->focus, 7, 8, 9);
        EXPECT_VEC3_EQ(paraboloid->axis, 0, -1, 0);
        EXPECT_EQ(paraboloid->focal_length, 1.5);
        EXPECT_EQ(paraboloid->radius, 2.5);
    }
    {
        const auto* torus = std::get_if<TorusShape>(&s.objects[5].shape);
        ASSERT_TRUE(torus);
        EXPECT_VEC3_EQ(torus->center, -1, -2, -3);
        EXPECT_VEC3_EQ(torus->axis, 0, 0, 1);
        EXPECT_EQ(torus->major_radius, 2.0);
        EXPECT_EQ(torus->minor_radius, 0.5);
    }
    {
        const auto* mesh = std::get_if<MeshShape>(&s.objects[6].shape);
        ASSERT_TRUE(mesh);
        EXPECT_EQ(mesh->file, d / "cow.obj");
        EXPECT_VEC3_EQ(mesh->transform.translate, 1, 2, 3);
        EXPECT_VEC3_EQ(mesh->transform.rotate_deg, 0, 90, 45);
        EXPECT_VEC3_EQ(mesh->transform.scale, 2, 2, 2);
    }
    {
        const auto* mesh = std::get_if<MeshShape>(&s.objects[7].shape);
        ASSERT_TRUE(mesh);
        EXPECT_EQ(mesh->file, d / "helmet.gltf");
        EXPECT_VEC3_EQ(mesh->transform.translate, 0, 0, 0);
        EXPECT_VEC3_EQ(mesh->transform.rotate_deg, 0, 0, 0);
        EXPECT_VEC3_EQ(mesh->transform.scale, 1, 2, -3);
    }
    ASSERT_TRUE(std::holds_alternative<MeshShape>(s.objects[8].shape));
    EXPECT_EQ(std::get<MeshShape>(s.objects[8].shape).file, d / "helmet.glb");
    EXPECT_VEC3_EQ(std::get<MeshShape>(s.objects[8].shape).transform.scale, 1, 1, 1);
    ASSERT_TRUE(std::holds_alternative<MeshShape>(s.objects[9].shape));
    EXPECT_EQ(std::get<MeshShape>(s.objects[9].shape).file, d / "CAPS.OBJ");
    // A glTF mesh takes its file's metallic-roughness materials; everything else the footprint
    // model.
    using Model = MaterialDesc::Model;
    for (int i : {7, 8}) EXPECT_EQ(s.objects[i].material.model, Model::metallic_roughness) << i;
    for (int i : {0, 1, 2, 6, 9}) EXPECT_EQ(s.objects[i].material.model, Model::footprint) << i;
    EXPECT_EQ(s.objects[7].material.highlight, MaterialDesc::Highlight::ggx);
}

TEST(SceneFile, MetallicRoughnessMaterialsParse) {
    TempDir dir;
    create_assets(dir.path());
    write_file(dir.path() / "rm.png", "");
    write_file(dir.path() / "scene.json",
               R"({"camera": {"position": [0, 1, 5], "look_at": [0, 0, 0]},
        "objects": [
        {"shape": "sphere",
         "material": {"model": "metallic-roughness", "base_color": [1, 0.78, 0.34], "metallic": 1,
                      "roughness": 0, "highlight": "beckmann", "metallic_roughness": "rm.png"}},
        {"shape": "mesh", "file": "helmet.gltf", "material": {"model": "footprint", "mirror": 1}}]})");
    const Result<SceneDesc> s = load_scene_file(dir.path() / "scene.json");
    ASSERT_TRUE(s.ok()) << s.error().message;
    const MaterialDesc& m = s->objects[0].material;
    EXPECT_EQ(m.model, MaterialDesc::Model::metallic_roughness);
    EXPECT_EQ(m.metallic, 1.0f);
    EXPECT_EQ(m.roughness, 0.0f);
    EXPECT_EQ(m.highlight, MaterialDesc::Highlight::beckmann);
    EXPECT_EQ(m.metallic_roughness_map.file, dir.path() / "rm.png");
    EXPECT_EQ(s->objects[1].material.model, MaterialDesc::Model::footprint);
    EXPECT_EQ(s->objects[1].material.mirror, 1.0f);
}

TEST(SceneFile, TerrainParsesToTheExactValuesAndDefaults) {
    const Result<SceneDesc> result = parse_scene(R"({"camera": {}, "objects": [
        {"shape": "terrain", "center": [1, 2, 3], "size": [20, 10], "subdivisions": 9,
         "roughness": 0.5, "height": 2.5, "seed": 42},
        {"shape": "terrain"}]})",
                                                 "terrain.json");
    ASSERT_TRUE(result.ok()) << result.error().message;
    ASSERT_EQ(result->objects.size(), 2u);
    const auto& t = std::get<TerrainShape>(result->objects[0].shape);
    EXPECT_VEC3_EQ(t.center, 1, 2, 3);
    EXPECT_EQ(t.size.x, 20.0);
    EXPECT_EQ(t.size.y, 10.0);
    EXPECT_EQ(t.subdivisions, 9);
    EXPECT_EQ(t.roughness, 0.5);
    EXPECT_EQ(t.height, 2.5);
    EXPECT_EQ(t.seed, 42u);
    const auto& d = std::get<TerrainShape>(result->objects[1].shape);
    const TerrainShape defaults;
    EXPECT_EQ(d.size.x, defaults.size.x);
    EXPECT_EQ(d.subdivisions, defaults.subdivisions);
    EXPECT_EQ(d.roughness, defaults.roughness);
    EXPECT_EQ(d.height, defaults.height);
    EXPECT_EQ(d.seed, defaults.seed);
    EXPECT_TRUE(renders_as_mesh(result->objects[0].shape));
}

TEST(SceneFile, ProceduralBaseColoursParseToTheExactValues) {
    const Result<SceneDesc> result = parse_scene(R"({"camera": {}, "objects": [
        {"shape": "sphere", "material": {"base_color": {"procedural": "marble", "scale": 6,
            "octaves": 5, "colors": [[0.25, 0.5, 0.75], [1, 2, 3]]}}},
        {"shape": "sphere", "material": {"base_color": {"procedural": "checker"}}}]})",
                                                 "procedural.json");
    ASSERT_TRUE(result.ok()) << result.error().message;
    const auto& marble = result->objects[0].material.base_color_procedural;
    ASSERT_TRUE(marble.has_value());
    EXPECT_EQ(marble->pattern, ProceduralPattern::marble);
    EXPECT_EQ(marble->scale, 6.0);
    EXPECT_EQ(marble->octaves, 5);
    EXPECT_VEC3_EQ(marble->colors[0], 0.25f, 0.5f, 0.75f);
    EXPECT_VEC3_EQ(marble->colors[1], 1, 2, 3);
    EXPECT_VEC3_EQ(result->objects[0].material.base_color, 1, 1, 1);
    const auto& checker = result->objects[1].material.base_color_procedural;
    ASSERT_TRUE(checker.has_value());
    EXPECT_EQ(checker->pattern, ProceduralPattern::checker);
    const ProceduralTexture defaults;
    EXPECT_EQ(checker->scale, defaults.scale);
    EXPECT_EQ(checker->octaves, defaults.octaves);
}

TEST(SceneFile, ProceduralBumpsParseToTheExactValues) {
    const Result<SceneDesc> result = parse_scene(R"({"camera": {}, "objects": [
        {"shape": "sphere", "material": {"bump": {"procedural": "turbulence", "scale": 3,
            "octaves": 7, "strength": 0.02}}}]})",
                                                 "procedural_bump.json");
    ASSERT_TRUE(result.ok()) << result.error().message;
    const BumpDesc& bump = result->objects[0].material.bump;
    EXPECT_EQ(bump.source, BumpDesc::Source::procedural);
    EXPECT_EQ(bump.procedural.pattern, ProceduralPattern::turbulence);
    EXPECT_EQ(bump.procedural.scale, 3.0);
    EXPECT_EQ(bump.procedural.octaves, 7);
    EXPECT_EQ(bump.strength, 0.02f);
    EXPECT_EQ(bump.frame, BumpFrame::main_direction);
}

TEST(SceneFile, EnvironmentProxiesParseToTheExactValues) {
    const Result<SceneDesc> box = parse_scene(R"({"camera": {}, "environment": {"file": "sky.hdr",
        "proxy": {"box": {"min": [-4, 0, -5], "max": [4, 3, 3]}}}, "objects": []})",
                                              "box.json", {.check_files = false});
    ASSERT_TRUE(box.ok()) << box.error().message;
    const EnvProxy& b = *box->environment->proxy;
    EXPECT_EQ(b.shape, EnvProxy::Shape::box);
    EXPECT_VEC3_EQ(b.min, -4, 0, -5);
    EXPECT_VEC3_EQ(b.max, 4, 3, 3);
    EXPECT_VEC3_EQ(b.capture, 0, 1.5f, -1);  // the box's centre
    const Result<SceneDesc> sphere = parse_scene(R"({"camera": {}, "environment": {"file":
        "sky.hdr", "proxy": {"sphere": {"center": [1, 2, 3], "radius": 5}, "capture": [0, 1, 0]}},
        "objects": []})",
                                                 "sphere.json", {.check_files = false});
    ASSERT_TRUE(sphere.ok()) << sphere.error().message;
    const EnvProxy& s = *sphere->environment->proxy;
    EXPECT_EQ(s.shape, EnvProxy::Shape::sphere);
    EXPECT_VEC3_EQ(s.center, 1, 2, 3);
    EXPECT_EQ(s.radius, 5.0f);
    EXPECT_VEC3_EQ(s.capture, 0, 1, 0);
}

TEST(SceneFile, LocalEnvironmentsParseInTheirOrderWithTheirProxies) {
    const Result<SceneDesc> s = parse_scene(R"({"camera": {}, "environment": {"file": "sky.hdr"},
        "local_environments": [
          {"file": "room.hdr", "proxy": {"box": {"min": [-4, 0, -5], "max": [4, 3, 3]}}},
          {"file": "alcove.hdr", "layout": "latlong", "intensity": 2,
           "proxy": {"sphere": {"center": [1, 1, 1], "radius": 0.5}}}],
        "objects": []})",
                                            "locals.json", {.check_files = false});
    ASSERT_TRUE(s.ok()) << s.error().message;
    ASSERT_EQ(s->local_environments.size(), 2u);
    const EnvironmentDesc& room = s->local_environments[0];
    EXPECT_EQ(room.images[0].file.filename(), "room.hdr");
    EXPECT_EQ(room.proxy->shape, EnvProxy::Shape::box);
    EXPECT_VEC3_EQ(room.proxy->max, 4, 3, 3);
    const EnvironmentDesc& alcove = s->local_environments[1];
    EXPECT_EQ(alcove.images[0].file.filename(), "alcove.hdr");
    EXPECT_EQ(alcove.intensity, 2.0f);
    EXPECT_EQ(alcove.proxy->shape, EnvProxy::Shape::sphere);
    EXPECT_EQ(alcove.proxy->radius, 0.5f);
    // The scene's hash sees them (eval's caches are keyed by it).
    SceneDesc without = *s;
    without.local_environments.pop_back();
    EXPECT_NE(scene_content_hash(*s), scene_content_hash(without));
}

TEST(SceneFile, EnvironmentProbesParseToTheExactValues) {
    const Result<SceneDesc> s = parse_scene(R"({"camera": {}, "objects": [
        {"shape": "sphere", "material": {"mirror": 1,
         "environment_probe": {"center": [1, 2, 3], "size": 96, "layout": "cube"}}},
        {"shape": "sphere", "material": {"environment_probe": {}}},
        {"shape": "sphere"}]})",
                                            "probe.json", {.check_files = false});
    ASSERT_TRUE(s.ok()) << s.error().message;
    const auto& probe = s->objects[0].material.environment_probe;
    ASSERT_TRUE(probe);
    EXPECT_VEC3_EQ(probe->center, 1, 2, 3);
    EXPECT_EQ(probe->size, 96);
    ASSERT_TRUE(s->objects[1].material.environment_probe);  // the defaults
    EXPECT_VEC3_EQ(s->objects[1].material.environment_probe->center, 0, 0, 0);
    EXPECT_EQ(s->objects[1].material.environment_probe->size, 128);
    EXPECT_FALSE(s->objects[2].material.environment_probe);
}

TEST(SceneFile, MinimalSceneTakesTheDefaultsOfSceneDesc) {
    const Result<SceneDesc> result = parse_scene(
        R"({"camera": {}, "objects": [{"shape": "sphere"}, {"shape": "torus"}]})", "minimal.json");
    ASSERT_TRUE(result.ok()) << result.error().message;
    const SceneDesc& s = *result;
    const SceneDesc defaults;
    EXPECT_EQ(s.width, defaults.width);
    EXPECT_EQ(s.height, defaults.height);
    EXPECT_VEC3_EQ(s.camera.position, 0, 1, 5);
    EXPECT_VEC3_EQ(s.camera.look_at, 0, 0, 0);
    EXPECT_VEC3_EQ(s.camera.up, 0, 1, 0);
    EXPECT_EQ(s.camera.fov_y_deg, 40.0);
    EXPECT_FALSE(s.environment.has_value());
    EXPECT_VEC3_EQ(s.background, 0, 0, 0);
    EXPECT_TRUE(s.lights.empty());
    ASSERT_EQ(s.objects.size(), 2u);
    EXPECT_EQ(std::get<SphereShape>(s.objects[0].shape).radius, 1.0);
    EXPECT_EQ(std::get<TorusShape>(s.objects[1].shape).major_radius, 1.0);
    EXPECT_EQ(std::get<TorusShape>(s.objects[1].shape).minor_radius, 0.25);
    EXPECT_EQ(s.source, fs::path("minimal.json"));

    const Result<SceneDesc> empty = parse_scene(R"({"camera": {}, "objects": []})", "e.json");
    ASSERT_TRUE(empty.ok()) << empty.error().message;
    EXPECT_TRUE(empty->objects.empty());
}

TEST(SceneFile, EnvironmentLayoutDefaultsFollowTheFileCount) {
    TempDir dir;
    create_assets(dir.path());
    const fs::path file = dir.path() / "scene.json";
    auto parse_env = [&](const std::string& environment) {
        return parse_scene(R"({"camera": {}, "objects": [], "environment": )" + environment + "}",
                           file);
    };
    struct Case {
        std::string environment;
        EnvLayout layout;
        std::size_t files;
    };
    const std::string six = R"(["px.hdr", "nx.hdr", "py.hdr", "ny.hdr", "pz.hdr", "nz.hdr"])";
    const Case cases[] = {
        {R"({"file": "sky.hdr"})", EnvLayout::latlong, 1},
        {R"({"file": "sky.hdr", "layout": "cube"})", EnvLayout::cube, 1},
        {R"({"file": "sky.hdr", "layout": "paraboloid"})", EnvLayout::paraboloid, 1},
        {R"({"file": "sky.hdr", "layout": "latlong"})", EnvLayout::latlong, 1},
        {R"({"file": ["front.hdr", "back.hdr"]})", EnvLayout::paraboloid, 2},
        {R"({"file": ["front.hdr", "back.hdr"], "layout": "paraboloid"})", EnvLayout::paraboloid,
         2},
        {R"({"file": )" + six + "}", EnvLayout::cube, 6},
        {R"({"file": )" + six + R"(, "layout": "cube"})", EnvLayout::cube, 6},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.environment);
        const Result<SceneDesc> result = parse_env(c.environment);
        ASSERT_TRUE(result.ok()) << result.error().message;
        ASSERT_TRUE(result->environment.has_value());
        EXPECT_EQ(result->environment->layout, c.layout);
        ASSERT_EQ(result->environment->images.size(), c.files);
        EXPECT_VEC3_EQ(result->environment->rotation_deg, 0, 0, 0);
        EXPECT_EQ(result->environment->intensity, 1.0f);
    }
    // Faces in the order given (+X −X +Y −Y +Z −Z).
    const Result<SceneDesc> cube = parse_env(R"({"file": )" + six + "}");
    ASSERT_TRUE(cube.ok());
    EXPECT_EQ(cube->environment->images[0].file, (dir.path() / "px.hdr").lexically_normal());
    EXPECT_EQ(cube->environment->images[5].file, (dir.path() / "nz.hdr").lexically_normal());
}

TEST(SceneFile, RelativePathsResolveAgainstTheSceneFilesFolder) {
    TempDir dir;
    const fs::path root = dir.path().lexically_normal();
    write_file(root / "textures" / "bricks.png", "");
    write_file(root / "scenes" / "a" / "meshes" / "cow.obj", "");
    write_file(root / "scenes" / "a" / "sky.hdr", "");
    write_file(root / "elsewhere" / "n.png", "");
    const std::string absolute_normal = (root / "elsewhere" / "n.png").string();
    const fs::path file = root / "scenes" / "a" / "scene.json";
    write_file(file, R"({"camera": {}, "environment": {"file": "./sky.hdr"}, "objects": [
        {"shape": "plane", "material": {"base_color": "../../textures/bricks.png",
                                        "bump": {"normal_map": ")" +
                         absolute_normal + R"("}}},
        {"shape": "mesh", "file": "meshes/../meshes/cow.obj"}]})");
    const Result<SceneDesc> result = load_scene_file(file);
    ASSERT_TRUE(result.ok()) << result.error().message;
    EXPECT_EQ(result->environment->images[0].file, root / "scenes" / "a" / "sky.hdr");
    EXPECT_EQ(result->objects[0].material.base_color_map.file, root / "textures" / "bricks.png");
    EXPECT_EQ(result->objects[0].material.bump.map.file, root / "elsewhere" / "n.png");
    EXPECT_EQ(std::get<MeshShape>(result->objects[1].shape).file,
              root / "scenes" / "a" / "meshes" / "cow.obj");
}

TEST(SceneFile, RelativeSceneFileGivesPathsRelativeToTheWorkingDirectory) {
    const std::string text = R"({"camera": {}, "environment": {"file": "../env/sky.hdr"},
        "objects": [{"shape": "mesh", "file": "cow.obj"}]})";
    const SceneParseOptions no_checks{.check_files = false};
    const Result<SceneDesc> nested = parse_scene(text, "scenes/a/scene.json", no_checks);
    ASSERT_TRUE(nested.ok()) << nested.error().message;
    EXPECT_EQ(nested->environment->images[0].file, fs::path("scenes/env/sky.hdr"));
    EXPECT_EQ(std::get<MeshShape>(nested->objects[0].shape).file, fs::path("scenes/a/cow.obj"));

    const Result<SceneDesc> here = parse_scene(text, "scene.json", no_checks);
    ASSERT_TRUE(here.ok()) << here.error().message;
    EXPECT_EQ(here->environment->images[0].file, fs::path("../env/sky.hdr"));
    EXPECT_EQ(std::get<MeshShape>(here->objects[0].shape).file, fs::path("cow.obj"));
}

TEST(SceneFile, MissingFileMessageShowsTheNameAndTheResolvedPath) {
    TempDir dir;
    const fs::path file = dir.path() / "scene.json";
    write_file(file, R"({"camera": {}, "objects": [{"shape": "sphere",
        "material": {"bump": {"normal_map": "x.png"}}}]})");
    const Result<SceneDesc> result = load_scene_file(file);
    ASSERT_FALSE(result.ok());
    const fs::path resolved = fs::absolute(dir.path() / "x.png").lexically_normal();
    EXPECT_EQ(result.error().message, file.string() +
                                          ": objects[0].material.bump.normal_map: file 'x.png' "
                                          "not found (resolved to '" +
                                          resolved.string() + "')");
    // Without file checks the same scene is accepted.
    EXPECT_TRUE(load_scene_file(file, {.check_files = false}).ok());
}

TEST(SceneFile, MissingSceneFile) {
    TempDir dir;
    const fs::path file = dir.path() / "no_such_scene.json";
    const Result<SceneDesc> result = load_scene_file(file);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message.rfind(file.string() + ": ", 0), 0u) << result.error().message;
    EXPECT_NE(result.error().message.find("not found"), std::string::npos);

    const Result<SceneDesc> folder = load_scene_file(dir.path());
    ASSERT_FALSE(folder.ok());
    EXPECT_NE(folder.error().message.find("directory"), std::string::npos);
}

TEST(SceneFile, JsonSyntaxErrorGivesLineAndColumn) {
    TempDir dir;
    const fs::path file = dir.path() / "broken.json";
    write_file(file, "{\n  \"camera\": {},\n  \"objects\": [,]\n}\n");
    const Result<SceneDesc> result = load_scene_file(file);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(
        result.error().message.rfind(file.string() + ": line 3, column 15: invalid JSON: ", 0), 0u)
        << result.error().message;

    const Result<SceneDesc> eof = parse_scene("{\"camera\": {}", "eof.json");
    ASSERT_FALSE(eof.ok());
    EXPECT_NE(eof.error().message.find("eof.json: line 1, column 14: invalid JSON: "),
              std::string::npos)
        << eof.error().message;

    const Result<SceneDesc> empty = parse_scene("", "empty.json");
    ASSERT_FALSE(empty.ok());
    EXPECT_NE(empty.error().message.find("empty.json: line 1, column 1: invalid JSON"),
              std::string::npos)
        << empty.error().message;

    const Result<SceneDesc> trailing =
        parse_scene("{\"camera\": {}, \"objects\": []}\r\nx", "trailing.json");
    ASSERT_FALSE(trailing.ok());
    EXPECT_NE(trailing.error().message.find("trailing.json: line 2, column 1: invalid JSON"),
              std::string::npos)
        << trailing.error().message;
}

TEST(SceneFile, TopLevelMustBeAnObject) {
    const Result<SceneDesc> result = parse_scene("[1, 2]", "list.json");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message,
              "list.json: expected a JSON object at the top level, got an array of 2 elements");
}

TEST(SceneFile, DuplicateKeysAreErrors) {
    const Result<SceneDesc> top =
        parse_scene(R"({"camera": {}, "objects": [], "camera": {}})", "dup.json");
    ASSERT_FALSE(top.ok());
    EXPECT_EQ(top.error().message, "dup.json: camera: duplicate key");

    const Result<SceneDesc> nested = parse_scene(
        R"({"camera": {}, "objects": [{"shape": "sphere"},
            {"shape": "sphere", "material": {"mirror": [1, [2]], "diffuse": 1, "mirror": 0}}]})",
        "dup.json");
    ASSERT_FALSE(nested.ok());
    EXPECT_EQ(nested.error().message, "dup.json: objects[1].material.mirror: duplicate key");
}

TEST(SceneFile, NumbersThatOverflowAreRejectedWithTheirKey) {
    const Result<SceneDesc> fov =
        parse_scene(R"({"camera": {"fov_y_deg": 1e999}, "objects": []})", "big.json");
    ASSERT_FALSE(fov.ok());
    EXPECT_EQ(fov.error().message.rfind("big.json: camera.fov_y_deg: number out of range", 0), 0u)
        << fov.error().message;

    const Result<SceneDesc> element = parse_scene(
        R"({"camera": {}, "objects": [{"shape": "sphere"},
            {"shape": "sphere", "center": [0, -1e999, 0]}]})",
        "big.json");
    ASSERT_FALSE(element.ok());
    EXPECT_EQ(
        element.error().message.rfind("big.json: objects[1].center[1]: number out of range", 0), 0u)
        << element.error().message;
}

// ---- Every rule, one case each: a JSON merge patch (RFC 7386) applied to a valid scene, the key
// path the message must name right after the file name, and a part of the message.

constexpr const char* kBaseScene = R"({
  "camera": {"position": [0, 1, 5], "look_at": [0, 0, 0]},
  "environment": {"file": "sky.hdr"},
  "lights": [{"type": "directional", "direction": [0, -1, 0]},
             {"type": "point", "position": [0, 3, 0]}],
  "objects": [{"shape": "sphere", "material": {"bump": {"normal_map": "normal.png"}}},
              {"shape": "mesh", "file": "cow.obj"}]
})";

struct ErrorCase {
    const char* name;
    const char* patch;
    const char* key_path;  // "" for messages about the whole file
    const char* message;
};

// The first object is a valid sphere where a case's object is objects[1].
#define SPHERE R"({"shape": "sphere"})"

const ErrorCase kErrorCases[] = {
    // Unknown keys, with and without a suggestion.
    {"UnknownTopLevelKey", R"({"objcets": []})", "objcets",
     "unknown key (did you mean 'objects'?)"},
    {"UnknownMaterialKey", R"({"objects": [)" SPHERE R"(, {"shape": "sphere",
        "material": {"shinyness": 3}}]})",
     "objects[1].material.shinyness", "unknown key (did you mean 'shininess'?)"},
    {"UnknownCameraKey", R"({"camera": {"zoom": 2}})", "camera.zoom",
     "unknown key (expected one of: position, look_at, up, fov_y_deg)"},
    {"UnknownImageKey", R"({"image": {"widht": 2}})", "image.widht", "did you mean 'width'?"},
    {"UnknownEnvironmentKey", R"({"environment": {"rotation": [0, 0, 0]}})", "environment.rotation",
     "did you mean 'rotation_deg'?"},
    {"UnknownLightKey", R"({"lights": [{"type": "point", "colour": [1, 1, 1]}]})",
     "lights[0].colour", "did you mean 'color'?"},
    {"UnknownObjectKey", R"({"objects": [{"shape": "sphere", "radios": 1}]})", "objects[0].radios",
     "did you mean 'radius'?"},
    {"KeyOfAnotherShape", R"({"objects": [{"shape": "sphere", "normal": [0, 1, 0]}]})",
     "objects[0].normal",
     "not a key of shape 'sphere' (it takes: name, shape, material, center, "
     "radius)"},
    {"UnknownTransformKey", R"({"objects": [{"shape": "mesh", "file": "cow.obj",
        "transform": {"rotate": [0, 0, 0]}}]})",
     "objects[0].transform.rotate", "did you mean 'rotate_deg'?"},
    {"UnknownBumpKey", R"({"objects": [{"shape": "sphere", "material": {"bump": {
        "normal_map": "normal.png", "strenght": 1}}}]})",
     "objects[0].material.bump.strenght", "did you mean 'strength'?"},
    // Required keys and wrong types.
    {"CameraMissing", R"({"camera": null})", "camera", "required key is missing"},
    {"ObjectsMissing", R"({"objects": null})", "objects", "required key is missing"},
    {"ObjectsNotAnArray", R"({"objects": {}})", "objects", "expected an array, got an object"},
    {"ObjectNotAnObject", R"({"objects": [3]})", "objects[0]", "expected an object, got a number"},
    {"ShapeMissing", R"({"objects": [)" SPHERE R"(, {"radius": 1}]})", "objects[1].shape",
     "required key is missing"},
    {"ShapeNotAString", R"({"objects": [{"shape": 1}]})", "objects[0].shape",
     "expected a string, got a number"},
    {"ShapeUnknown", R"({"objects": [{"shape": "sphear"}]})", "objects[0].shape",
     "unknown shape 'sphear' (did you mean 'sphere'?)"},
    {"NameNotAString", R"({"objects": [{"shape": "sphere", "name": 7}]})", "objects[0].name",
     "expected a string, got a number"},
    {"CameraNotAnObject", R"({"camera": [0, 1, 2]})", "camera",
     "expected an object, got an array of 3 elements"},
    {"ImageNotAnObject", R"({"image": 640})", "image", "expected an object, got a number"},
    {"FovString", R"({"camera": {"fov_y_deg": "40"}})", "camera.fov_y_deg",
     "expected a number, got a string"},
    {"FovBoolean", R"({"camera": {"fov_y_deg": true}})", "camera.fov_y_deg",
     "expected a number, got a boolean"},
    {"FovArray", R"({"camera": {"fov_y_deg": [null]}})", "camera.fov_y_deg",
     "expected a number, got an array of 1 element"},
    {"PositionTooShort", R"({"camera": {"position": [0, 1]}})", "camera.position",
     "expected an array of 3 numbers, got an array of 2 elements"},
    {"PositionElementString", R"({"camera": {"position": [0, "1", 5]}})", "camera.position[1]",
     "expected a number, got a string"},
    {"LightsNotAnArray", R"({"lights": {"type": "point"}})", "lights",
     "expected an array, got an object"},
    {"BackgroundNotAColour", R"({"background": 0.5})", "background",
     "expected an array of 3 numbers [r, g, b], got a number"},
    // Image.
    {"WidthZero", R"({"image": {"width": 0}})", "image.width", "must be in 1..16384, got 0"},
    {"WidthTooLarge", R"({"image": {"width": 16385}})", "image.width",
     "must be in 1..16384, got 16385"},
    {"HeightNegative", R"({"image": {"height": -5}})", "image.height", "must be in 1..16384"},
    {"HeightNotAnInteger", R"({"image": {"height": 360.5}})", "image.height",
     "expected an integer, got 360.5"},
    {"WidthString", R"({"image": {"width": "640"}})", "image.width",
     "expected a number, got a string"},
    // Camera.
    {"FovZero", R"({"camera": {"fov_y_deg": 0}})", "camera.fov_y_deg", "must be in (0, 180)"},
    {"Fov180", R"({"camera": {"fov_y_deg": 180}})", "camera.fov_y_deg", "must be in (0, 180)"},
    {"FovNegative", R"({"camera": {"fov_y_deg": -10}})", "camera.fov_y_deg", "must be in (0, 180)"},
    {"LookAtEqualsPosition", R"({"camera": {"position": [1, 2, 3], "look_at": [1, 2, 3]}})",
     "camera.look_at", "equals camera.position"},
    {"UpParallelToView", R"({"camera": {"position": [0, 5, 0], "look_at": [0, 0, 0]}})",
     "camera.up", "parallel to the view direction"},
    {"UpAntiParallelToView", R"({"camera": {"position": [0, 0, 5], "up": [0, 0, 2]}})", "camera.up",
     "parallel"},
    {"UpZero", R"({"camera": {"up": [0, 0, 0]}})", "camera.up", "must be nonzero"},
    // Environment.
    {"EnvironmentFileMissing", R"({"environment": {"file": null, "intensity": 2}})",
     "environment.file", "required key is missing"},
    {"EnvironmentFileNotFound", R"({"environment": {"file": "nosuch.hdr"}})", "environment.file",
     "file 'nosuch.hdr' not found (resolved to '"},
    {"EnvironmentFileEmpty", R"({"environment": {"file": ""}})", "environment.file",
     "expected a file name, got an empty string"},
    {"EnvironmentThreeFiles", R"({"environment": {"file": ["px.hdr", "nx.hdr", "py.hdr"]}})",
     "environment.file", "expected a file name or an array of 2"},
    {"EnvironmentOneFileArray", R"({"environment": {"file": ["sky.hdr"]}})", "environment.file",
     "got an array of 1 element"},
    {"EnvironmentFileNumber", R"({"environment": {"file": 3}})", "environment.file",
     "got a number"},
    {"EnvironmentFaceNotFound", R"({"environment": {"file": ["px.hdr", "nx.hdr", "py.hdr",
        "ny.hdr", "missing.hdr", "nz.hdr"]}})",
     "environment.file[4]", "file 'missing.hdr' not found"},
    {"EnvironmentFaceNotAString", R"({"environment": {"file": ["front.hdr", 2]}})",
     "environment.file[1]", "expected a string, got a number"},
    {"LocalEnvironmentsNotAnArray", R"({"local_environments": {"file": "room.hdr"}})",
     "local_environments", "expected an array, got an object"},
    {"LocalEnvironmentNotAnObject", R"({"local_environments": ["room.hdr"]})",
     "local_environments[0]", "expected an object, got a string"},
    {"LocalEnvironmentWithoutProxy", R"({"local_environments": [{"file": "sky.hdr"}]})",
     "local_environments[0].proxy", "required key is missing"},
    {"LocalEnvironmentBadProxy", R"({"local_environments": [{"file": "sky.hdr",
        "proxy": {"sphere": {"center": [0, 0, 0], "radius": -1}}}]})",
     "local_environments[0].proxy.sphere.radius", "must be > 0"},
    {"LocalEnvironmentUnknownKey", R"({"local_environments": [{"file": "sky.hdr",
        "proxy": {"sphere": {"center": [0, 0, 0], "radius": 1}}, "rotation": [0, 0, 0]}]})",
     "local_environments[0].rotation", "did you mean 'rotation_deg'?"},
    {"ProbeLayoutLatlong",
     R"({"objects": [{"shape": "sphere", "material": {"environment_probe": {"layout": "latlong"}}}]})",
     "objects[0].material.environment_probe.layout", "a probe is a cube map, got 'latlong'"},
    {"ProbeSizeTooSmall",
     R"({"objects": [{"shape": "sphere", "material": {"environment_probe": {"size": 2}}}]})",
     "objects[0].material.environment_probe.size", "must be in 4..2048, got 2"},
    {"ProbeUnknownKey",
     R"({"objects": [{"shape": "sphere", "material": {"environment_probe": {"centre": [0, 0, 0]}}}]})",
     "objects[0].material.environment_probe.centre", "did you mean 'center'?"},
    {"ProxyBoxAndSphere", R"({"environment": {"proxy": {"box": {"min": [0, 0, 0],
        "max": [1, 1, 1]}, "sphere": {"center": [0, 0, 0], "radius": 1}}}})",
     "environment.proxy", "needs exactly one of box and sphere"},
    {"ProxyNeither", R"({"environment": {"proxy": {"capture": [0, 0, 0]}}})", "environment.proxy",
     "needs exactly one of box and sphere"},
    {"ProxyBoxInsideOut", R"({"environment": {"proxy": {"box": {"min": [0, 0, 0],
        "max": [1, -1, 1]}}}})",
     "environment.proxy.box.max", "must exceed min in x, y and z"},
    {"ProxyBoxNoMin", R"({"environment": {"proxy": {"box": {"max": [1, 1, 1]}}}})",
     "environment.proxy.box.min", "required key is missing"},
    {"ProxySphereRadiusZero", R"({"environment": {"proxy": {"sphere": {"center": [0, 0, 0],
        "radius": 0}}}})",
     "environment.proxy.sphere.radius", "must be > 0"},
    {"ProxyUnknownKey", R"({"environment": {"proxy": {"cylinder": {}}}})",
     "environment.proxy.cylinder", "unknown key"},
    {"LayoutUnknown", R"({"environment": {"layout": "cubemap"}})", "environment.layout",
     "unknown layout 'cubemap' (did you mean 'cube'?)"},
    {"LayoutNotForTwoFiles", R"({"environment": {"file": ["front.hdr", "back.hdr"],
        "layout": "cube"}})",
     "environment.layout", "'cube' does not take 2 files"},
    {"LayoutNotForSixFiles", R"({"environment": {"file": ["px.hdr", "nx.hdr", "py.hdr",
        "ny.hdr", "pz.hdr", "nz.hdr"], "layout": "latlong"}})",
     "environment.layout", "'latlong' does not take 6 files"},
    {"IntensityNegative", R"({"environment": {"intensity": -1}})", "environment.intensity",
     "must be >= 0, got -1"},
    {"IntensityTooLargeForFloat", R"({"environment": {"intensity": 1e300}})",
     "environment.intensity", "is too large"},
    {"RotationWrongType", R"({"environment": {"rotation_deg": 90}})", "environment.rotation_deg",
     "expected an array of 3 numbers, got a number"},
    // Background and lights.
    {"BackgroundNegative", R"({"background": [0, -0.5, 0]})", "background[1]",
     "must be >= 0, got -0.5"},
    {"BackgroundTooLarge", R"({"background": [1e39, 0, 0]})", "background[0]", "is too large"},
    {"LightTypeUnknown", R"({"lights": [{"type": "spot"}]})", "lights[0].type",
     "unknown light type 'spot' (expected one of: directional, point)"},
    {"DirectionalLightWithPosition", R"({"lights": [{"position": [0, 1, 0]}]})",
     "lights[0].position",
     "not a key of a directional light (it takes: type, direction, color, shadows)"},
    {"LightShadowsNotABoolean", R"({"lights": [{"shadows": 1}]})", "lights[0].shadows",
     "expected true or false, got a number"},
    {"PointLightWithDirection", R"({"lights": [{"type": "point"},
        {"type": "point", "direction": [0, 1, 0]}]})",
     "lights[1].direction", "not a key of a point light"},
    {"LightDirectionZero", R"({"lights": [{"direction": [0, 0, 0]}]})", "lights[0].direction",
     "must be nonzero"},
    {"LightColourNegative", R"({"lights": [{"type": "point"},
        {"type": "point", "color": [1, 1, -1]}]})",
     "lights[1].color[2]", "must be >= 0"},
    // Plane.
    {"PlaneNormalZero", R"({"objects": [{"shape": "plane", "normal": [0, 0, 0]}]})",
     "objects[0].normal", "must be nonzero"},
    {"PlaneSizeNegative", R"({"objects": [{"shape": "plane", "size": [2, -1]}]})",
     "objects[0].size[1]", "must be > 0, got -1"},
    {"PlaneSizeZero", R"({"objects": [{"shape": "plane", "size": [0, 1]}]})", "objects[0].size[0]",
     "must be > 0"},
    {"PlaneSizeWord", R"({"objects": [{"shape": "plane", "size": "infinity"}]})", "objects[0].size",
     "expected [width, height] or \"infinite\", got 'infinity'"},
    {"PlaneSizeThreeNumbers", R"({"objects": [{"shape": "plane", "size": [1, 2, 3]}]})",
     "objects[0].size", "got an array of 3 elements"},
    {"PlaneUvScaleZero", R"({"objects": [{"shape": "plane", "uv_scale": 0}]})",
     "objects[0].uv_scale", "must be > 0"},
    // Sphere, cylinder, paraboloid, torus.
    {"SphereRadiusZero", R"({"objects": [{"shape": "sphere", "radius": 0}]})", "objects[0].radius",
     "must be > 0, got 0"},
    {"SphereRadiusNegative", R"({"objects": [)" SPHERE R"(, {"shape": "sphere", "radius": -2}]})",
     "objects[1].radius", "must be > 0, got -2"},
    {"CylinderAxisZero", R"({"objects": [{"shape": "cylinder", "axis": [0, 0, 0]}]})",
     "objects[0].axis", "must be nonzero"},
    {"CylinderRadiusNegative", R"({"objects": [{"shape": "cylinder", "radius": -1}]})",
     "objects[0].radius", "must be > 0"},
    {"CylinderHeightZero", R"({"objects": [{"shape": "cylinder", "height": 0}]})",
     "objects[0].height", "must be > 0"},
    {"ParaboloidFocalLengthZero", R"({"objects": [{"shape": "paraboloid", "focal_length": 0}]})",
     "objects[0].focal_length", "must be > 0"},
    {"ParaboloidRadiusNegative", R"({"objects": [{"shape": "paraboloid", "radius": -1}]})",
     "objects[0].radius", "must be > 0"},
    {"ParaboloidAxisZero", R"({"objects": [{"shape": "paraboloid", "axis": [0, 0, 0]}]})",
     "objects[0].axis", "must be nonzero"},
    {"TorusMajorRadiusZero", R"({"objects": [{"shape": "torus", "major_radius": 0}]})",
     "objects[0].major_radius", "must be > 0"},
    {"TorusMinorRadiusNegative", R"({"objects": [{"shape": "torus", "minor_radius": -0.1}]})",
     "objects[0].minor_radius", "must be > 0"},
    {"TorusMinorNotBelowMajor", R"({"objects": [{"shape": "torus", "major_radius": 1,
        "minor_radius": 1}]})",
     "objects[0].minor_radius", "must be less than major_radius"},
    {"TorusAxisZero", R"({"objects": [{"shape": "torus", "axis": [0, 0, 0]}]})", "objects[0].axis",
     "must be nonzero"},
    // Terrain.
    {"TerrainSubdivisionsTooMany", R"({"objects": [{"shape": "terrain", "subdivisions": 12}]})",
     "objects[0].subdivisions", "must be in 1..11, got 12"},
    {"TerrainSubdivisionsFraction", R"({"objects": [{"shape": "terrain", "subdivisions": 2.5}]})",
     "objects[0].subdivisions", "expected an integer, got 2.5"},
    {"TerrainRoughnessZero", R"({"objects": [{"shape": "terrain", "roughness": 0}]})",
     "objects[0].roughness", "must be in (0, 1] (the Hurst exponent), got 0"},
    {"TerrainRoughnessAboveOne", R"({"objects": [{"shape": "terrain", "roughness": 1.5}]})",
     "objects[0].roughness", "must be in (0, 1]"},
    {"TerrainHeightNegative", R"({"objects": [{"shape": "terrain", "height": -1}]})",
     "objects[0].height", "must be >= 0, got -1"},
    {"TerrainSizeOneNumber", R"({"objects": [{"shape": "terrain", "size": [4]}]})",
     "objects[0].size", "expected [width, depth]"},
    {"TerrainSizeZero", R"({"objects": [{"shape": "terrain", "size": [4, 0]}]})",
     "objects[0].size[1]", "must be > 0"},
    {"TerrainSeedNegative", R"({"objects": [{"shape": "terrain", "seed": -1}]})", "objects[0].seed",
     "must be in 0..2147483647, got -1"},
    {"TerrainKeyOfAnotherShape", R"({"objects": [{"shape": "terrain", "radius": 1}]})",
     "objects[0].radius", "not a key of shape 'terrain'"},
    // Mesh.
    {"MeshFileMissing", R"({"objects": [{"shape": "mesh"}]})", "objects[0].file",
     "required key is missing"},
    {"MeshUnsupportedFormat", R"({"objects": [)" SPHERE R"(, {"shape": "mesh",
        "file": "cow.ply"}]})",
     "objects[1].file", "unsupported mesh format '.ply' (expected .obj, .gltf or .glb)"},
    {"MeshWithoutExtension", R"({"objects": [{"shape": "mesh", "file": "cow"}]})",
     "objects[0].file", "unsupported mesh format 'cow'"},
    {"MeshFileNotFound", R"({"objects": [{"shape": "mesh", "file": "horse.obj"}]})",
     "objects[0].file", "file 'horse.obj' not found (resolved to '"},
    {"MeshFileIsAFolder", R"({"objects": [{"shape": "mesh", "file": "folder.obj"}]})",
     "objects[0].file", "is a directory"},
    {"MeshScaleZero", R"({"objects": [{"shape": "mesh", "file": "cow.obj",
        "transform": {"scale": 0}}]})",
     "objects[0].transform.scale", "must be nonzero"},
    {"MeshScaleComponentZero", R"({"objects": [{"shape": "mesh", "file": "cow.obj",
        "transform": {"scale": [1, 0, 1]}}]})",
     "objects[0].transform.scale[1]", "must be nonzero"},
    {"MeshScaleString", R"({"objects": [{"shape": "mesh", "file": "cow.obj",
        "transform": {"scale": "2"}}]})",
     "objects[0].transform.scale", "expected a number or an array of 3 numbers, got a string"},
    {"MeshTranslateTooShort", R"({"objects": [{"shape": "mesh", "file": "cow.obj",
        "transform": {"translate": [1, 2]}}]})",
     "objects[0].transform.translate", "expected an array of 3 numbers"},
    // Material.
    {"MaterialNotAnObject", R"({"objects": [{"shape": "sphere", "material": "gold"}]})",
     "objects[0].material", "expected an object, got a string"},
    {"BaseColorNumber", R"({"objects": [{"shape": "sphere", "material": {"base_color": 1}}]})",
     "objects[0].material.base_color",
     "expected [r, g, b], a texture file name or {\"procedural\": ...}, got a number"},
    {"ProceduralUnknownPattern", R"({"objects": [{"shape": "sphere",
        "material": {"base_color": {"procedural": "marbel"}}}]})",
     "objects[0].material.base_color.procedural",
     "unknown pattern 'marbel' (did you mean 'marble'?)"},
    {"ProceduralMissingPattern", R"({"objects": [{"shape": "sphere",
        "material": {"base_color": {"scale": 2}}}]})",
     "objects[0].material.base_color.procedural", "required key is missing"},
    {"ProceduralScaleZero", R"({"objects": [{"shape": "sphere",
        "material": {"base_color": {"procedural": "noise", "scale": 0}}}]})",
     "objects[0].material.base_color.scale", "must be > 0"},
    {"ProceduralOctavesTooMany", R"({"objects": [{"shape": "sphere",
        "material": {"base_color": {"procedural": "noise", "octaves": 17}}}]})",
     "objects[0].material.base_color.octaves", "must be in 1..16, got 17"},
    {"ProceduralOneColour", R"({"objects": [{"shape": "sphere",
        "material": {"base_color": {"procedural": "checker", "colors": [[1, 0, 0]]}}}]})",
     "objects[0].material.base_color.colors", "expected two colours"},
    {"ProceduralUnknownKey", R"({"objects": [{"shape": "sphere",
        "material": {"base_color": {"procedural": "noise", "octave": 3}}}]})",
     "objects[0].material.base_color.octave", "unknown key"},
    {"ProceduralInMetallicRoughness", R"({"objects": [{"shape": "sphere",
        "material": {"model": "metallic-roughness", "base_color": {"procedural": "noise"}}}]})",
     "objects[0].material.base_color", "a procedural base colour is for the footprint model"},
    {"ParallaxWithNormalMap", R"({"objects": [{"shape": "sphere", "material": {"bump":
        {"normal_map": "normal.png", "parallax": {"depth": 0.1}}}}]})",
     "objects[0].material.bump.parallax", "needs a height_map"},
    {"ParallaxNoDepth", R"({"objects": [{"shape": "sphere", "material": {"bump":
        {"height_map": "height.png", "parallax": {"steps": 8}}}}]})",
     "objects[0].material.bump.parallax.depth", "required key is missing"},
    {"ParallaxStepsZero", R"({"objects": [{"shape": "sphere", "material": {"bump":
        {"height_map": "height.png", "parallax": {"depth": 0.1, "steps": 0}}}}]})",
     "objects[0].material.bump.parallax.steps", "must be in 1..256, got 0"},
    {"ProceduralBumpChecker", R"({"objects": [{"shape": "sphere",
        "material": {"bump": {"procedural": "checker"}}}]})",
     "objects[0].material.bump.procedural", "a checker is a sum of steps and has no slopes"},
    {"ProceduralBumpColors", R"({"objects": [{"shape": "sphere",
        "material": {"bump": {"procedural": "noise", "colors": [[0, 0, 0], [1, 1, 1]]}}}]})",
     "objects[0].material.bump.colors", "unknown key"},
    {"ProceduralBumpFrame", R"({"objects": [{"shape": "sphere",
        "material": {"bump": {"procedural": "noise", "frame": "natural"}}}]})",
     "objects[0].material.bump.frame", "unknown key"},
    {"ProceduralBumpInMetallicRoughness", R"({"objects": [{"shape": "sphere",
        "material": {"model": "metallic-roughness", "bump": {"procedural": "noise"}}}]})",
     "objects[0].material.bump", "a procedural bump is for the footprint model"},
    {"BaseColorNegative", R"({"objects": [{"shape": "sphere",
        "material": {"base_color": [-1, 0, 0]}}]})",
     "objects[0].material.base_color[0]", "must be >= 0"},
    {"BaseColorTextureNotFound", R"({"objects": [{"shape": "sphere",
        "material": {"base_color": "wood.png"}}]})",
     "objects[0].material.base_color", "file 'wood.png' not found (resolved to '"},
    {"DiffuseNegative", R"({"objects": [{"shape": "sphere", "material": {"diffuse": -0.1}}]})",
     "objects[0].material.diffuse", "must be >= 0"},
    {"SpecularNegative", R"({"objects": [{"shape": "sphere", "material": {"specular": -1}}]})",
     "objects[0].material.specular", "must be >= 0"},
    {"ShininessNegative", R"({"objects": [{"shape": "sphere", "material": {"shininess": -1}}]})",
     "objects[0].material.shininess", "must be >= 0"},
    {"MirrorNegative", R"({"objects": [{"shape": "sphere", "material": {"mirror": -1}}]})",
     "objects[0].material.mirror", "must be >= 0"},
    {"FresnelAboveOne", R"({"objects": [{"shape": "sphere", "material": {"fresnel_f0": 1.5}}]})",
     "objects[0].material.fresnel_f0", "must be in [0, 1], got 1.5"},
    {"FresnelNegative", R"({"objects": [{"shape": "sphere", "material": {"fresnel_f0": -0.5}}]})",
     "objects[0].material.fresnel_f0", "must be in [0, 1]"},
    {"HighlightUnknown",
     R"({"objects": [{"shape": "sphere", "material": {"highlight": "phong"}}]})",
     "objects[0].material.highlight",
     "unknown highlight 'phong' (expected one of: blinn-phong, beckmann, ggx)"},
    {"HighlightMisspelt", R"({"objects": [{"shape": "sphere", "material": {"highlight": "gxx"}}]})",
     "objects[0].material.highlight",
     "unknown highlight 'gxx' (did you mean 'ggx'? expected one of: blinn-phong, beckmann, ggx)"},
    {"HighlightUnderscore", R"({"objects": [{"shape": "sphere",
        "material": {"highlight": "blinn_phong"}}]})",
     "objects[0].material.highlight", "did you mean 'blinn-phong'?"},
    {"HighlightNotAString", R"({"objects": [{"shape": "sphere", "material": {"highlight": 1}}]})",
     "objects[0].material.highlight", "expected a string, got a number"},
    {"RoughnessZero", R"({"objects": [{"shape": "sphere",
        "material": {"highlight": "ggx", "roughness": 0}}]})",
     "objects[0].material.roughness", "must be in (0, 1], got 0"},
    {"RoughnessAboveOne", R"({"objects": [{"shape": "sphere",
        "material": {"highlight": "beckmann", "roughness": 1.5}}]})",
     "objects[0].material.roughness", "must be in (0, 1], got 1.5"},
    {"RoughnessString", R"({"objects": [{"shape": "sphere",
        "material": {"highlight": "ggx", "roughness": "0.3"}}]})",
     "objects[0].material.roughness", "expected a number, got a string"},
    {"RoughnessWithBlinnPhong", R"({"objects": [{"shape": "sphere",
        "material": {"roughness": 0.3}}]})",
     "objects[0].material.roughness",
     "is used only with \"highlight\": \"beckmann\" or \"ggx\" (blinn-phong, the default, "
     "takes shininess)"},
    {"ShininessWithGgx", R"({"objects": [{"shape": "sphere",
        "material": {"highlight": "ggx", "shininess": 80}}]})",
     "objects[0].material.shininess",
     "is the Blinn-Phong exponent: the ggx highlight takes roughness"},
    // Material models.
    {"ModelUnknown", R"({"objects": [{"shape": "sphere", "material": {"model": "pbr"}}]})",
     "objects[0].material.model", "unknown model 'pbr'"},
    {"MetallicInTheFootprintModel", R"({"objects": [{"shape": "sphere",
        "material": {"metallic": 1}}]})",
     "objects[0].material.metallic",
     "is a key of the metallic-roughness model: give \"model\": \"metallic-roughness\""},
    {"MirrorInTheMetallicRoughnessModel", R"({"objects": [{"shape": "sphere",
        "material": {"model": "metallic-roughness", "mirror": 1}}]})",
     "objects[0].material.mirror",
     "is a key of the footprint model; this material is metallic-roughness: it takes base_color, "
     "metallic and roughness, or give \"model\": \"footprint\""},
    {"DiffuseOnAGltfMesh", R"({"objects": [{"shape": "mesh", "file": "helmet.gltf",
        "material": {"diffuse": 0.5}}]})",
     "objects[0].material.diffuse",
     "this material is metallic-roughness (a glTF mesh's default: its file's materials)"},
    {"RoughnessOnAGltfMesh", R"({"objects": [{"shape": "mesh", "file": "helmet.glb",
        "material": {"roughness": 0.5}}]})",
     "objects[0].material.roughness", "comes from the glTF file's materials"},
    {"MetallicOutOfRange", R"({"objects": [{"shape": "sphere",
        "material": {"model": "metallic-roughness", "metallic": 1.5}}]})",
     "objects[0].material.metallic", "must be in [0, 1], got 1.5"},
    {"MetallicRoughnessBlinnPhong", R"({"objects": [{"shape": "sphere",
        "material": {"model": "metallic-roughness", "highlight": "blinn-phong"}}]})",
     "objects[0].material.highlight",
     "the metallic-roughness model's highlight is beckmann or ggx"},
    {"MicroRoughnessNegative", R"({"objects": [{"shape": "sphere",
        "material": {"micro_roughness": -0.01}}]})",
     "objects[0].material.micro_roughness", "must be >= 0"},
    {"DiffuseString", R"({"objects": [{"shape": "sphere", "material": {"diffuse": "1"}}]})",
     "objects[0].material.diffuse", "expected a number, got a string"},
    // Bump.
    {"BumpBothMaps", R"({"objects": [{"shape": "sphere", "material": {"bump": {
        "height_map": "height.png", "normal_map": "normal.png"}}}]})",
     "objects[0].material.bump", "has both height_map and normal_map"},
    {"BumpNoMap", R"({"objects": [{"shape": "sphere", "material": {"bump": {"strength": 1}}}]})",
     "objects[0].material.bump", "needs a height_map, a normal_map or a procedural"},
    {"BumpNormalMapNotFound", R"({"objects": [)" SPHERE R"(, {"shape": "sphere",
        "material": {"bump": {"normal_map": "x.png"}}}]})",
     "objects[1].material.bump.normal_map", "file 'x.png' not found (resolved to '"},
    {"BumpHeightMapNotFound", R"({"objects": [{"shape": "sphere",
        "material": {"bump": {"height_map": "h.png"}}}]})",
     "objects[0].material.bump.height_map", "file 'h.png' not found"},
    {"BumpMapNotAString", R"({"objects": [{"shape": "sphere",
        "material": {"bump": {"height_map": 1}}}]})",
     "objects[0].material.bump.height_map", "expected a string, got a number"},
    {"BumpFrameUnknown", R"({"objects": [{"shape": "sphere", "material": {"bump": {
        "normal_map": "normal.png", "frame": "normalised"}}}]})",
     "objects[0].material.bump.frame", "unknown frame 'normalised' (did you mean 'normalized'?)"},
    {"BumpMainDirectionWithOtherFrame", R"({"objects": [{"shape": "sphere", "material": {
        "bump": {"normal_map": "normal.png", "frame": "natural", "main_direction": [1, 0, 0]}}}]})",
     "objects[0].material.bump.main_direction", "is used only with frame \"main_direction\""},
    {"BumpStrengthString", R"({"objects": [{"shape": "sphere", "material": {"bump": {
        "normal_map": "normal.png", "strength": "big"}}}]})",
     "objects[0].material.bump.strength", "expected a number, got a string"},
    // Camera paths.
    {"CameraPathNotArray", R"({"camera_path": {"position": [0, 1, 5]}})", "camera_path",
     "expected an array"},
    {"CameraPathOneKeyframe", R"({"camera_path": [{"position": [0, 1, 5]}]})", "camera_path",
     "needs at least 2 keyframes"},
    {"CameraPathUnknownKey", R"({"camera_path": [{"position": [0, 1, 5]}, {"tim": 2}]})",
     "camera_path[1].tim", "did you mean 'time'?"},
    {"CameraPathTimesDecrease", R"({"camera_path": [{"time": 1}, {"time": 0.5}]})",
     "camera_path[1].time", "must be greater than the previous keyframe's"},
    {"CameraPathBadFov", R"({"camera_path": [{}, {"fov_y_deg": 190}]})", "camera_path[1].fov_y_deg",
     "must be in (0, 180)"},
};

#undef SPHERE

class SceneFileErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(SceneFileErrors, MessageNamesTheFileAndTheKey) {
    const ErrorCase& c = GetParam();
    TempDir dir;
    create_assets(dir.path());
    fs::create_directories(dir.path() / "folder.obj");
    json scene = json::parse(kBaseScene);
    scene.merge_patch(json::parse(c.patch));
    const fs::path file = dir.path() / "scene.json";
    write_file(file, scene.dump(2));
    const Result<SceneDesc> result = load_scene_file(file);
    ASSERT_FALSE(result.ok()) << scene.dump(2);
    const std::string& message = result.error().message;
    const std::string prefix =
        file.string() + ": " + (*c.key_path ? std::string(c.key_path) + ": " : "");
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message << "\nshould start with " << prefix;
    EXPECT_NE(message.find(c.message), std::string::npos)
        << message << "\nshould contain " << c.message;
}

INSTANTIATE_TEST_SUITE_P(SceneFile, SceneFileErrors, ::testing::ValuesIn(kErrorCases),
                         [](const ::testing::TestParamInfo<ErrorCase>& info) {
                             return std::string(info.param.name);
                         });

TEST(SceneFile, CameraPathKeyframesDefaultToTheCameraAndInterpolate) {
    TempDir dir;
    create_assets(dir.path());
    json scene = json::parse(kBaseScene);
    scene.merge_patch(json::parse(R"({"camera_path": [
        {"position": [0, 1, 5]},
        {"time": 3, "position": [4, 1, 5], "fov_y_deg": 60}]})"));
    const fs::path file = dir.path() / "scene.json";
    write_file(file, scene.dump(2));
    const Result<SceneDesc> result = load_scene_file(file);
    ASSERT_TRUE(result.ok()) << result.error().message;
    const SceneDesc& desc = *result;
    ASSERT_EQ(desc.camera_path.size(), 2u);
    EXPECT_EQ(desc.camera_path[0].time, 0);  // the index
    EXPECT_EQ(desc.camera_path[1].time, 3);
    EXPECT_EQ(desc.camera_path[0].camera.fov_y_deg, 40);  // the camera's (default) fov
    // Frame 1 of 4 lies at t = 1 of [0, 3]: a third of the way.
    const CameraDesc c = camera_for_frame(desc, 1, 4);
    EXPECT_NEAR(c.position.x, 4.0 / 3.0, 1e-12);
    EXPECT_NEAR(c.fov_y_deg, 40 + 20.0 / 3.0, 1e-12);
    EXPECT_EQ(camera_for_frame(desc, 3, 4).position.x, 4);
    EXPECT_EQ(camera_at(desc, -1).position.x, 0);  // clamped to the ends
    EXPECT_EQ(camera_at(desc, 9).position.x, 4);
}

TEST(SceneFile, TheErrorTablesBaseSceneIsValid) {
    TempDir dir;
    create_assets(dir.path());
    const Result<SceneDesc> result = parse_scene(kBaseScene, dir.path() / "scene.json");
    ASSERT_TRUE(result.ok()) << result.error().message;
}

// ---- The example scene in examples/scenes.

fs::path examples_dir() {
    if (const char* env = std::getenv("FOOTPRINT_EXAMPLES_DIR")) return env;
#ifdef FOOTPRINT_TEST_DATA_DIR
    return fs::path(FOOTPRINT_TEST_DATA_DIR) / ".." / ".." / "examples" / "scenes";
#else
    return "examples/scenes";  // run from the repository root
#endif
}

TEST(SceneFile, ShowcaseExampleParses) {
    const fs::path file = (examples_dir() / "showcase.json").lexically_normal();
    if (!fs::exists(file))
        GTEST_SKIP() << file << " not found (run from the repository root or set "
                     << "FOOTPRINT_EXAMPLES_DIR)";
    // Structure and values, whether or not the data it refers to is there.
    const Result<SceneDesc> structure = load_scene_file(file, {.check_files = false});
    ASSERT_TRUE(structure.ok()) << structure.error().message;
    EXPECT_TRUE(structure->environment.has_value());
    EXPECT_EQ(structure->lights.size(), 2u);
    EXPECT_EQ(structure->objects.size(), 7u);

    // Its files live in ../shared/data beside the repository.
    const fs::path shared = file.parent_path() / ".." / ".." / ".." / "shared" / "data";
    if (!fs::exists(shared))
        GTEST_SKIP() << "shared data not found at " << shared.lexically_normal()
                     << ": the example's files were not checked";
    const Result<SceneDesc> full = load_scene_file(file);
    ASSERT_TRUE(full.ok()) << full.error().message;
    EXPECT_TRUE(fs::exists(std::get<MeshShape>(full->objects[5].shape).file));
}

// ---- Invalid normal maps (material key "invalid_normals").

// A 4×3 normal map of flat normals (0.5, 0.5, 1) with `texel` set to `value`; all texels if the
// texel is (−1, −1).
Image normal_map_with(int x, int y, std::array<float, 3> value) {
    Image map(4, 3, 3);
    for (int ty = 0; ty < map.height; ++ty)
        for (int tx = 0; tx < map.width; ++tx) {
            const bool bad = (x < 0) || (tx == x && ty == y);
            const std::array<float, 3> c = bad ? value : std::array<float, 3>{0.5f, 0.5f, 1.0f};
            for (int k = 0; k < 3; ++k) map.at(tx, ty, k) = c[k];
        }
    return map;
}

// A scene of one plane bump-mapped with `normal_file`, the material's extra keys in `extra`.
std::string normal_map_scene(const std::string& normal_file, const std::string& extra) {
    return R"({"camera": {"position": [0, 1, 5], "look_at": [0, 0, 0]},
               "objects": [{"shape": "plane", "material": {"bump": {"normal_map": ")" +
           normal_file + "\"}" + extra + "}}]}";
}

struct BadNormalMap {
    const char* name;
    const char* file;
    int x, y;  // the first invalid texel, row-major from the top (x, y ≥ 0)
    bool whole_map;
    std::array<float, 3> value;
    const char* value_text;  // how the message prints the texel's value
};

const BadNormalMap kBadNormalMaps[] = {
    {"AllBlack", "black.png", 0, 0, true, {0, 0, 0}, "(0, 0, 0)"},
    {"ZBelowThePlane", "below.png", 2, 1, false, {0.8f, 0.5f, 0.2f}, "n_z ≤ 0"},
    {"OneTexelRgbZero", "hole.png", 3, 2, false, {0, 0, 0}, "(0, 0, 0)"},
    {"NanTexel", "nan.exr", 1, 2, false, {0.5f, std::nanf(""), 1}, "nan"},
};

TEST(SceneFileNormalMaps, InvalidTexelsAreErrorsNamingTheFileAndTheTexelUnlessClamped) {
    for (const BadNormalMap& bad : kBadNormalMaps) {
        SCOPED_TRACE(bad.name);
        TempDir dir;
        const Image map =
            normal_map_with(bad.whole_map ? -1 : bad.x, bad.whole_map ? -1 : bad.y, bad.value);
        ImageSaveOptions save;
        save.encoding = ColorEncoding::linear;  // the codes as they are: data, not colour
        ASSERT_TRUE(save_image(map, dir.path() / bad.file, save).ok());

        const fs::path file = dir.path() / "scene.json";
        write_file(file, normal_map_scene(bad.file, ""));
        const Result<SceneDesc> desc = load_scene_file(file);
        ASSERT_TRUE(desc.ok()) << desc.error().message;
        const Result<RenderScene> refused = prepare_render_scene(*desc);
        ASSERT_FALSE(refused.ok());
        const std::string& message = refused.error().message;
        const std::string texel =
            "texel (" + std::to_string(bad.x) + ", " + std::to_string(bad.y) + ")";
        EXPECT_EQ(message.rfind(file.string() + ": objects[0].material.bump.normal_map: ", 0), 0u)
            << message;
        EXPECT_NE(message.find(bad.file), std::string::npos) << message;
        EXPECT_NE(message.find(texel), std::string::npos) << message;
        EXPECT_NE(message.find(bad.value_text), std::string::npos) << message;
        EXPECT_NE(message.find("\"invalid_normals\": \"clamp\""), std::string::npos) << message;

        write_file(file, normal_map_scene(bad.file, R"(, "invalid_normals": "clamp")"));
        Result<SceneDesc> clamped = load_scene_file(file);
        ASSERT_TRUE(clamped.ok()) << clamped.error().message;
        EXPECT_EQ(clamped->objects[0].material.invalid_normals, InvalidNormalPolicy::clamp);
        clamped->width = 8;
        clamped->height = 6;
        const Result<RenderScene> scene = prepare_render_scene(*clamped);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        const Image image = render(*scene, RenderOptions{});
        ASSERT_EQ(image.pixel_count(), 48u);
        for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v));
    }
}

TEST(SceneFileNormalMaps, TheInvalidNormalsKeyIsChecked) {
    TempDir dir;
    create_assets(dir.path());
    struct Case {
        const char* material;
        const char* message;
    };
    const Case cases[] = {
        {R"({"bump": {"normal_map": "normal.png"}, "invalid_normals": "clmap"})",
         "unknown policy 'clmap' (did you mean 'clamp'?)"},
        {R"({"bump": {"normal_map": "normal.png"}, "invalid_normals": "skip"})",
         "unknown policy 'skip' (expected one of: error, clamp)"},
        {R"({"bump": {"normal_map": "normal.png"}, "invalid_normals": true})",
         "expected a string, got a boolean"},
        {R"({"bump": {"height_map": "height.png"}, "invalid_normals": "clamp"})",
         "applies to normal maps, not to bump.height_map"},
        {R"({"invalid_normals": "clamp"})", "applies to normal maps: give bump.normal_map"},
        {R"({"invalid_normal": "clamp"})", "unknown key (did you mean 'invalid_normals'?)"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.material);
        const std::string text = R"({"camera": {}, "objects": [{"shape": "sphere", "material": )" +
                                 std::string(c.material) + "}]}";
        const Result<SceneDesc> result = parse_scene(text, dir.path() / "s.json");
        ASSERT_FALSE(result.ok());
        const std::string& message = result.error().message;
        EXPECT_EQ(message.rfind((dir.path() / "s.json").string() + ": objects[0].material.", 0), 0u)
            << message;
        EXPECT_NE(message.find(c.message), std::string::npos) << message;
    }
    // A mesh's file may bring its own normal textures: the key needs no bump there; "error" is
    // the default.
    const Result<SceneDesc> mesh = parse_scene(
        R"({"camera": {}, "objects": [{"shape": "mesh", "file": "cow.obj",
            "material": {"invalid_normals": "clamp"}},
            {"shape": "sphere", "material": {"bump": {"normal_map": "normal.png"},
             "invalid_normals": "error"}}]})",
        dir.path() / "s.json");
    ASSERT_TRUE(mesh.ok()) << mesh.error().message;
    EXPECT_EQ(mesh->objects[0].material.invalid_normals, InvalidNormalPolicy::clamp);
    EXPECT_EQ(mesh->objects[1].material.invalid_normals, InvalidNormalPolicy::error);
}

// ---- NaN and infinite texels (environment and material key "non_finite").

// A scene (JSON) whose environment, base colour texture or height map is an image holding one NaN
// texel; `key` is the "non_finite" entry ("" or `, "non_finite": "repair"`) where it applies.
struct NonFiniteCase {
    const char* name;
    const char* scene;          // with %KEY% where the key goes
    const char* error_key;      // the key path the refusal starts with
    const char* hint_location;  // the key that takes "non_finite"
};

const NonFiniteCase kNonFiniteCases[] = {
    {"Environment", R"({"camera": {}, "objects": [], "environment": {"file": "bad.exr"%KEY%}})",
     "environment", "environment"},
    {"LocalEnvironment",
     R"({"camera": {}, "objects": [],
         "local_environments": [{"file": "bad.exr",
                                 "proxy": {"box": {"min": [-1, -1, -1], "max": [1, 1, 1]}}%KEY%}]})",
     "local_environments[0]", "local_environments[0]"},
    {"BaseColor",
     R"({"camera": {"position": [0, 1, 2], "look_at": [0, 0, 0]},
         "lights": [{"direction": [0, -1, 0]}],
         "objects": [{"shape": "plane", "size": "infinite",
                      "material": {"base_color": "bad.exr"%KEY%}}]})",
     "objects[0].material.base_color", "material"},
    {"HeightMap",
     R"({"camera": {"position": [0, 1, 2], "look_at": [0, 0, 0]},
         "lights": [{"direction": [0, -1, 0]}],
         "objects": [{"shape": "plane", "size": "infinite",
                      "material": {"bump": {"height_map": "bad.exr"}%KEY%}}]})",
     "objects[0].material.bump.height_map", "material"},
};

std::string with_key(std::string scene, const std::string& key) {
    return scene.replace(scene.find("%KEY%"), 5, key);
}

TEST(SceneFileNonFinite, NanTexelsAreRefusedNamingTheFileUnlessRepaired) {
    for (const NonFiniteCase& c : kNonFiniteCases) {
        SCOPED_TRACE(c.name);
        TempDir dir;
        Image bad(32, 16, 3, 0.5f);
        bad.at(5, 3, 1) = std::nanf("");
        ASSERT_TRUE(save_image(bad, dir.path() / "bad.exr").ok());
        const fs::path file = dir.path() / "scene.json";

        write_file(file, with_key(c.scene, ""));
        const Result<SceneDesc> desc = load_scene_file(file);
        ASSERT_TRUE(desc.ok()) << desc.error().message;
        const Result<RenderScene> refused = prepare_render_scene(*desc);
        ASSERT_FALSE(refused.ok());
        const std::string& message = refused.error().message;
        EXPECT_EQ(message.rfind(file.string() + ": " + c.error_key + ": ", 0), 0u) << message;
        EXPECT_NE(message.find("bad.exr"), std::string::npos) << message;
        EXPECT_NE(message.find("texel (5, 3) channel 1"), std::string::npos) << message;
        EXPECT_NE(
            message.find(std::string("the ") + c.hint_location + " key \"non_finite\": \"repair\""),
            std::string::npos)
            << message;

        write_file(file, with_key(c.scene, R"(, "non_finite": "repair")"));
        Result<SceneDesc> repaired = load_scene_file(file);
        ASSERT_TRUE(repaired.ok()) << repaired.error().message;
        repaired->width = 8;
        repaired->height = 6;
        const Result<RenderScene> scene = prepare_render_scene(*repaired);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        RenderStats stats;
        const Image image = render(*scene, RenderOptions{}, &stats);
        ASSERT_EQ(image.pixel_count(), 48u);
        for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v));
        EXPECT_EQ(stats.non_finite_samples, 0u);
    }
}

TEST(SceneFileNonFinite, TheNonFiniteKeyIsChecked) {
    TempDir dir;
    create_assets(dir.path());
    struct Case {
        const char* scene;  // the environment and the first object's material
        const char* key;    // where the message points
        const char* message;
    };
    const Case cases[] = {
        {R"("environment": {"file": "sky.hdr", "non_finite": "repiar"})", "environment.non_finite",
         "unknown policy 'repiar' (did you mean 'repair'?)"},
        {R"("environment": {"file": "sky.hdr", "non_finite": "ignore"})", "environment.non_finite",
         "unknown policy 'ignore' (expected one of: error, repair)"},
        {R"("environment": {"file": "sky.hdr", "non_finite": false})", "environment.non_finite",
         "expected a string, got a boolean"},
        {R"("environment": {"file": "sky.hdr", "nonfinite": "repair"})", "environment.nonfinite",
         "unknown key (did you mean 'non_finite'?)"},
        {R"("material": {"base_color": "bricks.png", "non_finite": "clamp"})",
         "objects[0].material.non_finite", "unknown policy 'clamp'"},
        {R"("material": {"non_finite": "repair"})", "objects[0].material.non_finite",
         "applies to the material's texture files: give base_color as a file or bump.height_map"},
        {R"("material": {"bump": {"normal_map": "normal.png"}, "non_finite": "repair"})",
         "objects[0].material.non_finite", "(for a normal map's NaN texels: invalid_normals)"},
    };
    const auto scene = [](const std::string& parts) {
        const bool material = parts.rfind(R"("material")", 0) == 0;
        return R"({"camera": {}, "objects": [{"shape": "sphere")" +
               (material ? ", " + parts + "}]" : std::string("}], ") + parts) + "}";
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.scene);
        const Result<SceneDesc> result = parse_scene(scene(c.scene), dir.path() / "s.json");
        ASSERT_FALSE(result.ok());
        const std::string& message = result.error().message;
        EXPECT_EQ(message.rfind((dir.path() / "s.json").string() + ": " + c.key + ": ", 0), 0u)
            << message;
        EXPECT_NE(message.find(c.message), std::string::npos) << message;
    }
    const Result<SceneDesc> valid =
        parse_scene(scene(R"("environment": {"file": "sky.hdr", "non_finite": "repair"})"),
                    dir.path() / "s.json");
    ASSERT_TRUE(valid.ok()) << valid.error().message;
    EXPECT_EQ(valid->environment->non_finite, NonFinitePolicy::repair);
    EXPECT_EQ(valid->objects[0].material.non_finite, NonFinitePolicy::refuse);
    const Result<SceneDesc> material = parse_scene(
        scene(R"("material": {"bump": {"height_map": "height.png"}, "non_finite": "error"})"),
        dir.path() / "s.json");
    ASSERT_TRUE(material.ok()) << material.error().message;
    EXPECT_EQ(material->objects[0].material.non_finite, NonFinitePolicy::refuse);
}

// ---- The layout of a single environment file (image_io helper).

// The environment of a scene whose environment is `environment` (JSON), the images in `dir`.
Result<RenderScene> scene_with_environment(const fs::path& dir, const std::string& environment) {
    const Result<SceneDesc> desc = parse_scene(
        R"({"camera": {}, "objects": [], "environment": )" + environment + "}", dir / "s.json");
    if (!desc) return desc.error();
    return prepare_render_scene(*desc);
}

TEST(SceneFile, SingleEnvironmentFileTakesTheLayoutOfItsAspectRatio) {
    TempDir dir;
    // A horizontal cross (4:3) and a 3x2 strip of faces 8 x 8, and a 2:1 lat-long.
    ASSERT_TRUE(save_image(Image(32, 24, 3, 0.5f), dir.path() / "cross.exr").ok());
    ASSERT_TRUE(save_image(Image(24, 16, 3, 0.5f), dir.path() / "strip.exr").ok());
    ASSERT_TRUE(save_image(Image(32, 16, 3, 0.5f), dir.path() / "sky.exr").ok());
    struct Case {
        const char* environment;
        EnvLayout layout;
    };
    for (const Case& c :
         {Case{R"({"file": "cross.exr"})", EnvLayout::cube},
          Case{R"({"file": "strip.exr"})", EnvLayout::cube},
          Case{R"({"file": "sky.exr"})", EnvLayout::latlong},
          Case{R"({"file": "cross.exr", "layout": "latlong"})", EnvLayout::latlong}}) {
        SCOPED_TRACE(c.environment);
        const Result<RenderScene> scene = scene_with_environment(dir.path(), c.environment);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        ASSERT_NE(scene->environment(), nullptr);
        EXPECT_EQ(scene->environment()->layout, c.layout);
    }
}

TEST(SceneFile, SingleEnvironmentFileOfNoLayoutIsRefusedUnlessTheLayoutIsGiven) {
    TempDir dir;
    const fs::path odd = dir.path() / "odd.exr";
    ASSERT_TRUE(save_image(Image(30, 12, 3, 0.5f), odd).ok());
    const Result<RenderScene> refused =
        scene_with_environment(dir.path(), R"({"file": "odd.exr"})");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(
        refused.error().message.find("environment: cannot tell the layout of '" +
                                     odd.lexically_normal().string() + "' from its size 30x12"),
        std::string::npos)
        << refused.error().message;
    const Result<RenderScene> given =
        scene_with_environment(dir.path(), R"({"file": "odd.exr", "layout": "latlong"})");
    ASSERT_TRUE(given.ok()) << given.error().message;
    EXPECT_EQ(given->environment()->layout, EnvLayout::latlong);
}

TEST(SceneFile, QuickstartExampleRendersFromTheRepositorysAssets) {
    const fs::path file = (examples_dir() / "quickstart.json").lexically_normal();
    if (!fs::exists(file))
        GTEST_SKIP() << file << " not found (run from the repository root or set "
                     << "FOOTPRINT_EXAMPLES_DIR)";
    // Its files are in assets/: it loads on a fresh clone, and its normal maps are valid.
    Result<SceneDesc> desc = load_scene_file(file);
    ASSERT_TRUE(desc.ok()) << desc.error().message;
    ASSERT_TRUE(desc->environment.has_value());
    EXPECT_EQ(desc->environment->images.at(0).file.parent_path().parent_path().filename(),
              "assets");
    desc->width = 16;
    desc->height = 9;
    const Result<RenderScene> scene = prepare_render_scene(*desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
}

// The three highlights side by side (examples/scenes/ggx_spheres.json), from assets/ alone.
TEST(SceneFile, GgxSpheresExampleLoadsFromTheRepositorysAssets) {
    const fs::path file = (examples_dir() / "ggx_spheres.json").lexically_normal();
    if (!fs::exists(file))
        GTEST_SKIP() << file << " not found (run from the repository root or set "
                     << "FOOTPRINT_EXAMPLES_DIR)";
    Result<SceneDesc> desc = load_scene_file(file);
    ASSERT_TRUE(desc.ok()) << desc.error().message;
    ASSERT_EQ(desc->objects.size(), 4u);
    EXPECT_EQ(desc->objects[1].material.highlight, MaterialDesc::Highlight::blinn_phong);
    EXPECT_EQ(desc->objects[2].material.highlight, MaterialDesc::Highlight::beckmann);
    EXPECT_EQ(desc->objects[3].material.highlight, MaterialDesc::Highlight::ggx);
    desc->width = 16;
    desc->height = 8;
    const Result<RenderScene> scene = prepare_render_scene(*desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
}

}  // namespace
}  // namespace footprint
