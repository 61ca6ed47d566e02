#include "demo_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <system_error>

#include "demo_assets.h"
#include "image/image_io.h"

namespace footprint {

namespace {

namespace fs = std::filesystem;

std::shared_ptr<const Image> shared(Image image) {
    return std::make_shared<const Image>(std::move(image));
}

ImageSource generated(Image image, const std::string& name) {
    return ImageSource{{}, shared(std::move(image)), name};
}

// The file `relative` of the data folder, else of the assets folder, else nullopt.
std::optional<fs::path> data_file(const DemoSceneOptions& options, const std::string& relative) {
    for (const fs::path& dir : {options.data_dir, options.assets_dir}) {
        if (dir.empty()) continue;
        const fs::path file = dir / relative;
        std::error_code ec;
        if (fs::is_regular_file(file, ec)) return file;
    }
    return std::nullopt;
}

// A real HDR environment from the data folder, or the generated daylight sky.
EnvironmentDesc daylight_environment(const DemoSceneOptions& options, std::string& assets) {
    EnvironmentDesc env;
    env.layout = EnvLayout::latlong;
    if (auto file = data_file(options, "envmaps/venice_sunset_1k.hdr")) {
        env.images.push_back(ImageSource{*file, nullptr, ""});
        assets += "environment " + file->filename().string();
    } else {
        env.images.push_back(generated(make_sky_gradient_latlong(512), "generated sky"));
        assets += "environment generated (sky gradient)";
    }
    return env;
}

EnvironmentDesc generated_environment(Image image, const std::string& name) {
    EnvironmentDesc env;
    env.layout = EnvLayout::latlong;
    env.images.push_back(generated(std::move(image), name));
    return env;
}

// The brick normal map from the data folder at `normal_strength`, or generated waves as a height
// map at `height_strength`; `assets` says which.
BumpDesc brick_bump(const DemoSceneOptions& options, float normal_strength, float height_strength,
                    std::string& assets) {
    BumpDesc bump;
    if (auto file = data_file(options, "normals/ambientCG_Bricks102_1K_NormalGL.jpg")) {
        bump.source = BumpDesc::Source::normal_map;
        bump.map = ImageSource{*file, nullptr, ""};
        bump.strength = normal_strength;
        assets += ", normal map " + file->filename().string();
    } else {
        bump.source = BumpDesc::Source::height_map;
        bump.map = generated(make_water_height_map(512), "generated waves");
        bump.strength = height_strength;
        assets += ", bumps generated (waves)";
    }
    return bump;
}

SceneDesc base_scene(const DemoSceneOptions& options) {
    SceneDesc scene;
    scene.width = options.width;
    scene.height = options.height;
    return scene;
}

// A short camera move for temporal-stability measurements (footprint eval, render --frames):
// the camera and its target both move by `offset` (a dolly or a truck), or only the target (a pan).
void add_camera_move(SceneDesc& scene, Vec3d position_offset, Vec3d target_offset) {
    CameraDesc end = scene.camera;
    end.position = end.position + position_offset;
    end.look_at = end.look_at + target_offset;
    scene.camera_path = {{0, scene.camera}, {1, end}};
}

MaterialDesc mirror(float f0) {
    MaterialDesc m;
    m.diffuse = 0;
    m.mirror = 1;
    m.fresnel_f0 = f0;
    return m;
}

DemoScene cylinder(const DemoSceneOptions& options) {
    DemoScene demo{"cylinder", "mirror cylinder: curvature in one direction only", "", {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    scene.camera = {{0, 0.35, 3.2}, {0, 0, 0}, {0, 1, 0}, 40};
    scene.environment = daylight_environment(options, demo.assets);
    CylinderShape shape;
    shape.radius = 0.75;
    shape.height = 2.6;
    scene.objects.push_back({"cylinder", shape, mirror(0.9f)});
    add_camera_move(scene, {0.15, 0, 0}, {0.15, 0, 0});
    return demo;
}

DemoScene parabolic_mirror(const DemoSceneOptions& options) {
    DemoScene demo{"parabolic_mirror",
                   "parabolic mirror seen from its focus: the footprint vanishes (uniform image)",
                   "",
                   {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    // The mirror opens towards +z with its focus at the origin; the eye sits at the focus looking
    // into it, so every reflected ray leaves parallel to +z.
    scene.camera = {{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 80};
    scene.environment = daylight_environment(options, demo.assets);
    ParaboloidShape shape;
    shape.focal_length = 0.5;
    shape.radius = 2.0;
    scene.objects.push_back({"mirror", shape, mirror(0.9f)});
    add_camera_move(scene, {0, 0, 0}, {0.1, 0, 0});  // the eye stays at the focus
    return demo;
}

DemoScene water(const DemoSceneOptions& options) {
    DemoScene demo{"water",
                   "wavy water at a grazing angle reflecting a night sky with a moon",
                   "environment generated (night sky), waves generated",
                   {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    const Vec3 moon = night_sky_moon_direction();
    const Vec3d eye{0, 0.35, 0};
    // Looking towards the moon's azimuth, horizon just above the middle: the moon (18° up) near
    // the top, its glitter path on the water below.
    scene.camera = {eye, eye + Vec3d{moon.x, 0.02, moon.z}, {0, 1, 0}, 45};
    scene.environment = generated_environment(make_night_sky_latlong(2048), "generated night sky");
    PlaneShape plane;
    plane.infinite = true;
    plane.uv_scale = 0.5;
    MaterialDesc m = mirror(0.02f);
    m.diffuse = 0.02f;
    m.base_color = {0.05f, 0.12f, 0.15f};
    m.bump.source = BumpDesc::Source::height_map;
    m.bump.map = generated(make_water_height_map(512), "generated water waves");
    m.bump.strength = 0.012f;
    m.micro_roughness = 0.02f;
    scene.objects.push_back({"water", plane, m});
    add_camera_move(scene, {moon.x * 0.5, 0, moon.z * 0.5}, {moon.x * 0.5, 0, moon.z * 0.5});
    return demo;
}

DemoScene bump_plate(const DemoSceneOptions& options) {
    DemoScene demo{"bump_plate",
                   "bump-mapped plate reflecting a zebra-stripe environment",
                   "environment generated (zebra)",
                   {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    scene.camera = {{0, 1.6, 3.2}, {0, 0, -0.2}, {0, 1, 0}, 40};
    scene.environment = generated_environment(make_zebra_latlong(1024), "generated zebra");
    PlaneShape plate;
    plate.size = {3, 3};
    plate.uv_scale = 1.0 / 3.0;  // the map once across the plate
    MaterialDesc m = mirror(0.9f);
    m.diffuse = 0.02f;
    m.bump = brick_bump(options, 0.3f, 0.01f, demo.assets);
    scene.objects.push_back({"plate", plate, m});
    add_camera_move(scene, {0.2, 0, 0}, {0.2, 0, 0});
    return demo;
}

DemoScene secret_writing(const DemoSceneOptions& options) {
    DemoScene demo{"secret_writing",
                   "\"secret writing\" on a plane at a grazing angle",
                   "texture generated, ",
                   {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    scene.camera = {{0, 0.5, 0}, {0, 0, 5}, {0, 1, 0}, 40};
    scene.environment = daylight_environment(options, demo.assets);
    scene.lights.push_back({LightType::directional, {0.3, -1, 0.6}, {}, {0.8f, 0.8f, 0.8f}});
    PlaneShape plane;
    plane.infinite = true;
    plane.uv_scale = 0.2;
    MaterialDesc m;
    m.base_color = {1, 1, 1};
    m.base_color_map = generated(make_secret_writing_texture(1024), "generated secret writing");
    scene.objects.push_back({"plane", plane, m});
    add_camera_move(scene, {0, 0, 0.5}, {0, 0, 0.5});
    return demo;
}

DemoScene brushed_sphere(const DemoSceneOptions& options) {
    DemoScene demo{
        "brushed_sphere", "brushed-metal sphere: anisotropic roughness", "grooves generated, ", {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    scene.camera = {{0, 1.25, 3.4}, {0, 1, 0}, {0, 1, 0}, 40};
    scene.environment = daylight_environment(options, demo.assets);
    scene.lights.push_back({LightType::directional, {-0.6, -0.5, -0.6}, {}, {2, 1.9f, 1.7f}});
    SphereShape sphere;
    sphere.center = {0, 1, 0};
    sphere.radius = 1;
    MaterialDesc m = mirror(0.75f);
    m.base_color = {0.9f, 0.75f, 0.5f};
    m.diffuse = 0.05f;
    m.specular = 1;
    m.shininess = 400;
    m.micro_roughness = 0.02f;
    m.bump.source = BumpDesc::Source::height_map;
    m.bump.map = generated(make_brushed_metal_height_map(512), "generated brushed metal");
    m.bump.strength = 0.004f;
    scene.objects.push_back({"sphere", sphere, m});
    add_camera_move(scene, {0.3, 0, 0}, {0, 0, 0});
    return demo;
}

DemoScene terrain(const DemoSceneOptions& options) {
    DemoScene demo{"terrain",
                   "fractal terrain with a topographic map's contour lines, and a lake",
                   "terrain and its texture generated, ",
                   {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    scene.camera = {{0, 3, 16}, {0, 0.5, 0}, {0, 1, 0}, 45};
    scene.environment = daylight_environment(options, demo.assets);
    scene.environment->rotation_deg = {0, 180, 0};  // the sun behind the camera, out of the lake
    scene.lights.push_back({LightType::directional, {-0.5, -0.6, -0.4}, {}, {0.8f, 0.75f, 0.65f}});
    TerrainShape land;
    land.size = {60, 60};
    land.subdivisions = 9;
    land.roughness = 0.85;
    land.height = 5;
    land.seed = 11;
    MaterialDesc ground;
    ground.specular = 0.05f;
    ground.base_color_map =
        generated(make_topographic_texture(land, 0.25, 2048), "generated topographic map");
    scene.objects.push_back({"land", land, ground});
    PlaneShape lake;
    lake.center = {0, -0.5, 0};
    lake.size = {60, 60};
    MaterialDesc water = mirror(0.02f);
    water.diffuse = 0.05f;
    water.base_color = {0.05f, 0.1f, 0.12f};
    water.micro_roughness = 0.01f;
    scene.objects.push_back({"lake", lake, water});
    add_camera_move(scene, {0.3, 0, 0}, {0.3, 0, 0});
    return demo;
}

DemoScene procedural(const DemoSceneOptions& options) {
    DemoScene demo{"procedural",
                   "solid procedural textures, band-limited by the footprint: a marble floor at a "
                   "grazing angle, a checker and a turbulence sphere",
                   "textures procedural, ",
                   {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    scene.camera = {{0, 0.6, 4}, {0, 0.35, -2}, {0, 1, 0}, 45};
    scene.environment = daylight_environment(options, demo.assets);
    scene.environment->rotation_deg = {0, 150, 0};  // the sun out of view
    scene.lights.push_back({LightType::directional, {-0.4, -1, -0.3}, {}, {1.2f, 1.15f, 1.0f}});
    PlaneShape floor;
    floor.infinite = true;
    MaterialDesc marble;
    marble.base_color = {1, 1, 1};
    marble.base_color_procedural = ProceduralTexture{
        ProceduralPattern::marble, 6, 6, {Vec3{0.16f, 0.15f, 0.14f}, Vec3{0.85f, 0.83f, 0.78f}}};
    marble.specular = 0.3f;
    scene.objects.push_back({"marble floor", floor, marble});
    SphereShape left{{-0.8, 0.5, -1.2}, 0.5}, right{{0.7, 0.5, -2.2}, 0.5};
    MaterialDesc checker;
    checker.base_color = {1, 1, 1};
    checker.base_color_procedural = ProceduralTexture{
        ProceduralPattern::checker, 8, 1, {Vec3{0.1f, 0.1f, 0.12f}, Vec3{0.9f, 0.85f, 0.6f}}};
    scene.objects.push_back({"checker sphere", left, checker});
    MaterialDesc turbulence;
    turbulence.base_color = {1, 1, 1};
    turbulence.base_color_procedural = ProceduralTexture{
        ProceduralPattern::turbulence, 4, 6, {Vec3{0.05f, 0.15f, 0.4f}, Vec3{0.9f, 0.95f, 1.0f}}};
    scene.objects.push_back({"turbulence sphere", right, turbulence});
    add_camera_move(scene, {0, 0, -0.3}, {0, 0, -0.3});
    return demo;
}

DemoScene procedural_bump(const DemoSceneOptions& options) {
    DemoScene demo{
        "procedural_bump",
        "procedural bumps: a sea of noise waves to the horizon reflecting the sky, and a "
        "chrome sphere hammered with turbulence",
        "bumps procedural, ",
        {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    scene.camera = {{0, 0.8, 4}, {0, 0.4, -4}, {0, 1, 0}, 45};
    scene.environment = daylight_environment(options, demo.assets);
    scene.environment->rotation_deg = {0, 200, 0};  // the sun ahead, low: a glitter path
    PlaneShape sea;
    sea.infinite = true;
    MaterialDesc waves = mirror(0.02f);
    waves.diffuse = 0.05f;
    waves.base_color = {0.05f, 0.1f, 0.12f};
    waves.bump.source = BumpDesc::Source::procedural;
    waves.bump.procedural = ProceduralTexture{ProceduralPattern::noise, 1.5, 8};
    waves.bump.strength = 0.4f;
    scene.objects.push_back({"sea", sea, waves});
    MaterialDesc hammered = mirror(0.9f);
    hammered.diffuse = 0;
    hammered.bump.source = BumpDesc::Source::procedural;
    hammered.bump.procedural = ProceduralTexture{ProceduralPattern::turbulence, 6, 5};
    hammered.bump.strength = 0.03f;
    scene.objects.push_back({"hammered sphere", SphereShape{{0.6, 0.7, -1.2}, 0.5}, hammered});
    add_camera_move(scene, {0, 0, -0.3}, {0, 0, -0.3});
    return demo;
}

// The local-map demo's world: a box room (tiled floor, coloured walls, a window onto the sky and
// a ceiling light, HDR) with a booth in its far right corner, open at the front and on the left,
// lined with teal cloth and lit by a warm strip under its roof.
struct RoomWorld {
    EnvProxy room, booth;
    RoomWorld() {
        room.min = {-4, 0, -5}, room.max = {4, 3, 3};
        room.capture = {0, 1.5f, -1};
        booth.min = {1.6f, 0, -4.8f}, booth.max = {3.8f, 2, -3};
        booth.capture = {2.7f, 1, -3.9f};
    }

    Vec3 room_wall(Vec3 q) const {
        const float eps = 1e-3f;
        if (q.y < room.min.y + eps) {  // floor: 0.5 m tiles
            const bool dark = (int(std::floor(2 * q.x)) + int(std::floor(2 * q.z))) & 1;
            return dark ? Vec3{0.15f, 0.12f, 0.1f} : Vec3{0.7f, 0.65f, 0.55f};
        }
        if (q.y > room.max.y - eps)  // ceiling, with a light panel
            return std::abs(q.x) < 1 && std::abs(q.z) < 0.6f ? Vec3{8, 8, 7}
                                                             : Vec3{0.8f, 0.8f, 0.8f};
        if (q.z < room.min.z + eps)  // the far wall, with a window onto the sky
            return std::abs(q.x - 0.5f) < 1.2f && q.y > 0.9f && q.y < 2.3f
                       ? Vec3{3, 4, 6}
                       : Vec3{0.6f, 0.55f, 0.3f};
        if (q.x < room.min.x + eps) return {0.6f, 0.15f, 0.1f};
        if (q.x > room.max.x + -eps) return {0.1f, 0.25f, 0.6f};
        return {0.85f, 0.85f, 0.8f};
    }

    // The booth's back (z = min), right (x = max) and roof (y = max) from inside: cloth with gold
    // stripes, and the light strip.
    Vec3 booth_wall(Vec3 q, int axis) const {
        if (axis == 1)
            return std::abs(q.x - booth.capture.x) < 0.8f && std::abs(q.z - booth.capture.z) < 0.2f
                       ? Vec3{3, 2.4f, 1.4f}
                       : Vec3{0.08f, 0.3f, 0.3f};
        const float along = axis == 2 ? q.x : q.z;
        const bool stripe = std::abs(along * 4 - std::round(along * 4)) < 0.06f;
        return stripe ? Vec3{0.8f, 0.6f, 0.2f} : Vec3{0.05f, 0.35f, 0.35f};
    }

    // What a ray from o (inside the room) along the unit direction w meets first.
    Vec3 seen(Vec3 o, Vec3 w) const {
        const std::optional<ProxyStep> step = proxy_step(room, o, w);
        if (!step) return {0, 0, 0};
        const Vec3 q_room = step->direction + room.capture;
        float nearest = length(q_room - o);
        Vec3 colour = room_wall(q_room);
        const float walls[3] = {booth.max.x, booth.max.y, booth.min.z};  // right, roof, back
        for (int axis = 0; axis < 3; ++axis) {
            const float d = (&w.x)[axis];
            if (d == 0) continue;
            const float t = (walls[axis] - (&o.x)[axis]) / d;
            const Vec3 q = o + t * w;
            bool inside = t > 1e-4f && t < nearest;
            for (int k = 0; k < 3; ++k)
                if (k != axis)
                    inside =
                        inside && (&q.x)[k] >= (&booth.min.x)[k] && (&q.x)[k] <= (&booth.max.x)[k];
            if (inside) nearest = t, colour = booth_wall(q, axis);
        }
        return colour;
    }

    // The world from `from` along the directions of face f's texel (x, y) of a `layout` map of
    // width × height: the mean of n × n.
    Image capture(Vec3 from, EnvLayout layout, int face, int width, int height, int n) const {
        Image image(width, height, 3);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                Vec3 sum{0, 0, 0};
                for (int j = 0; j < n; ++j)
                    for (int i = 0; i < n; ++i) {
                        const float s = (x + (i + 0.5f) / n) / width;
                        const float t = (y + (j + 0.5f) / n) / height;
                        sum = sum + seen(from, normalize(env_direction(layout, face, s, t)));
                    }
                sum = sum / static_cast<float>(n * n);
                image.at(x, y, 0) = sum.x, image.at(x, y, 1) = sum.y, image.at(x, y, 2) = sum.z;
            }
        return image;
    }
};

// The booth's back, side and roof as planes of cloth, which the booth's map lights.
void add_booth_walls(const EnvProxy& b, SceneDesc& scene) {
    MaterialDesc cloth;
    cloth.diffuse = 1;
    cloth.base_color = {0.15f, 0.6f, 0.6f};
    const Vec3d centre{(b.min.x + b.max.x) / 2, (b.min.y + b.max.y) / 2, (b.min.z + b.max.z) / 2};
    const Vec3d size{b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z};
    auto wall = [&](Vec3d center, Vec3d normal, Vec2d extent) {
        PlaneShape plane;
        plane.center = center, plane.normal = normal, plane.size = extent;
        return plane;
    };
    scene.objects.push_back(
        {"booth back", wall({centre.x, centre.y, b.min.z}, {0, 0, 1}, {size.x, size.y}), cloth});
    scene.objects.push_back(
        {"booth side", wall({b.max.x, centre.y, centre.z}, {-1, 0, 0}, {size.z, size.y}), cloth});
    scene.objects.push_back(
        {"booth roof", wall({centre.x, b.max.y, centre.z}, {0, -1, 0}, {size.x, size.z}), cloth});
}

DemoScene local_environment(const DemoSceneOptions& options) {
    DemoScene demo{"local_environment",
                   "local environment maps with box proxies, one nested in the other: a chrome "
                   "sphere and a polished floor reflect the room's walls where their reflected "
                   "rays meet them, and a sphere in the booth the booth's",
                   "environments generated (a room, a booth in it), ",
                   {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    const RoomWorld world;
    scene.camera = {{-1.5, 1.6, 2.2}, {0.8, 0.8, -2.5}, {0, 1, 0}, 60};
    scene.environment = generated_environment(
        world.capture(world.room.capture, EnvLayout::latlong, 0, 1024, 512, 2), "generated room");
    scene.environment->proxy = world.room;
    EnvironmentDesc booth;  // a cube map: the GPU reads it as it is
    booth.layout = EnvLayout::cube;
    for (int face = 0; face < 6; ++face)
        booth.images.push_back(
            generated(world.capture(world.booth.capture, EnvLayout::cube, face, 256, 256, 4),
                      "generated booth face " + std::to_string(face)));
    booth.proxy = world.booth;
    scene.local_environments.push_back(std::move(booth));
    MaterialDesc chrome = mirror(0.9f);
    scene.objects.push_back({"chrome sphere", SphereShape{{-0.3, 0.7, -2.2}, 0.7}, chrome});
    scene.objects.push_back(
        {"chrome sphere in the booth", SphereShape{{2.65, 0.7, -3.95}, 0.7}, chrome});
    PlaneShape floor;
    floor.center = {-0.5, 0.005, -1.2};  // a polished slab on the tiled floor
    floor.size = {3, 2.5};
    MaterialDesc polished = mirror(0.08f);
    polished.diffuse = 0.5f;
    polished.base_color = {0.35f, 0.3f, 0.25f};
    scene.objects.push_back({"polished floor", floor, polished});
    add_booth_walls(world.booth, scene);
    add_camera_move(scene, {0.3, 0, 0}, {0.3, 0, 0});
    return demo;
}

// Bricks (4 × 8 per tile, offset rows): a height map — 1 on the bricks, bevelled down to 0 in the
// mortar — and the matching colours, `size` texels square.
std::pair<Image, Image> brick_maps(int size) {
    Image heights(size, size, 1), colours(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float v = 8.0f * (y + 0.5f) / size;  // rows
            const int row = static_cast<int>(v);
            const float u = 4.0f * (x + 0.5f) / size + (row % 2 ? 0.5f : 0.0f);
            const float fu = u - std::floor(u), fv = v - std::floor(v);
            // Distance to the brick's edge in brick heights (a brick is 2 rows' worth wide).
            const float edge = std::min({2 * fu, 2 * (1 - fu), fv, 1 - fv});
            const float h = std::clamp((edge - 0.06f) / 0.1f, 0.0f, 1.0f);
            heights.at(x, y, 0) = h;
            const float shade = 0.85f + 0.15f * std::sin(37.0f * row + 11.0f * std::floor(u));
            const Vec3 brick{0.55f * shade, 0.22f * shade, 0.12f * shade},
                mortar{0.5f, 0.48f, 0.45f};
            const Vec3 c = h > 0 ? brick : mortar;
            colours.at(x, y, 0) = c.x, colours.at(x, y, 1) = c.y, colours.at(x, y, 2) = c.z;
        }
    return {std::move(heights), std::move(colours)};
}

// The generated bricks as a material: their colours, and their heights as a bump map of `relief`
// (the relief's depth over one map period, one unit of (u, v); none at 0) in the natural frame.
MaterialDesc brick_material(float specular, float relief) {
    auto [heights, colours] = brick_maps(512);
    MaterialDesc bricks;
    bricks.base_color_map = generated(std::move(colours), "generated bricks");
    bricks.specular = specular;
    if (relief > 0) {
        bricks.bump.source = BumpDesc::Source::height_map;
        bricks.bump.map = generated(std::move(heights), "generated brick heights");
        bricks.bump.strength = relief;
        bricks.bump.frame = BumpFrame::natural;
    }
    return bricks;
}

DemoScene parallax(const DemoSceneOptions& options) {
    DemoScene demo{"parallax",
                   "parallax-occlusion mapping: a brick wall and pavement whose bricks stand out "
                   "of the flat geometry, the view ray marched through their height map",
                   "bricks generated, ",
                   {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    scene.camera = {{-1.2, 1.1, 2.6}, {0.6, 0.6, -1}, {0, 1, 0}, 50};
    scene.environment = daylight_environment(options, demo.assets);
    scene.environment->rotation_deg = {0, 120, 0};
    scene.lights.push_back({LightType::directional, {0.6, -0.5, -0.6}, {}, {1.5f, 1.4f, 1.2f}});
    MaterialDesc bricks = brick_material(0.1f, 0.04f);
    bricks.base_color = {1, 1, 1};
    bricks.bump.parallax = ParallaxOptions{0.04f, 24};
    PlaneShape pavement;
    pavement.size = {4, 4};
    pavement.uv_scale = 0.5;
    scene.objects.push_back({"brick pavement", pavement, bricks});
    PlaneShape wall;
    wall.center = {0, 1, -2};
    wall.normal = {0, 0, 1};
    wall.size = {4, 2};
    wall.uv_scale = 0.5;
    scene.objects.push_back({"brick wall", wall, bricks});
    add_camera_move(scene, {0.3, 0, 0}, {0.3, 0, 0});
    return demo;
}

DemoScene shadows(const DemoSceneOptions& options) {
    DemoScene demo{"shadows",
                   "shadow rays: a low sun casts the shadows of a sphere, a torus and fractal "
                   "mounds (a mesh) across a brick pavement; a lamp without shadows fills them",
                   "bricks and mounds generated, ",
                   {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    scene.camera = {{0.4, 1.5, 4.2}, {-0.2, 0.3, -1}, {0, 1, 0}, 45};
    scene.environment = daylight_environment(options, demo.assets);
    scene.environment->rotation_deg = {0, 60, 0};
    scene.lights.push_back({LightType::directional, {-0.6, -0.4, 0.7}, {}, {3.2f, 3.0f, 2.6f}});
    LightDesc lamp{LightType::point, {}, {-1.5, 1.4, 1.8}, {0.5f, 0.55f, 0.7f}};
    lamp.shadows = false;
    scene.lights.push_back(lamp);
    const MaterialDesc pavement = brick_material(0.15f, 0.02f);
    PlaneShape ground;
    ground.size = {10, 10};
    ground.center = {0, 0, -2};
    ground.uv_scale = 0.5;
    scene.objects.push_back({"pavement", ground, pavement});
    MaterialDesc glossy = mirror(0.04f);
    glossy.base_color = {0.7f, 0.15f, 0.1f};
    glossy.diffuse = 0.8f;
    glossy.specular = 0.5f;
    glossy.shininess = 80;
    scene.objects.push_back({"sphere", SphereShape{{0.9, 0.55, -1.2}, 0.55}, glossy});
    MaterialDesc gold = mirror(0.8f);
    gold.base_color = {0.9f, 0.7f, 0.35f};
    gold.diffuse = 0.1f;
    scene.objects.push_back(
        {"torus", TorusShape{{-0.3, 0.55, -2.2}, {0.3, 0.2, 1}, 0.5, 0.15}, gold});
    TerrainShape mounds;  // the ground cuts its lower half away: hills breaking the pavement
    mounds.center = {-1.6, -0.1, -1.0};
    mounds.size = {2.4, 2.4};
    mounds.subdivisions = 6;
    mounds.roughness = 0.8;
    mounds.height = 0.5;
    mounds.seed = 5;
    MaterialDesc stone;
    stone.base_color = {0.22f, 0.21f, 0.19f};
    stone.specular = 0.05f;
    scene.objects.push_back({"mounds", mounds, stone});
    add_camera_move(scene, {0.3, 0, 0}, {0.2, 0, 0});
    return demo;
}

DemoScene environment_probe(const DemoSceneOptions& options) {
    DemoScene demo{"environment_probe",
                   "a dynamic environment map: a chrome sphere reflects its neighbours and the "
                   "pavement from a cube map rendered at its centre, filtered by its footprint",
                   "bricks generated, ",
                   {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    scene.camera = {{0, 1.4, 5.2}, {0, 0.6, 0}, {0, 1, 0}, 40};
    scene.environment = daylight_environment(options, demo.assets);
    scene.environment->rotation_deg = {0, 60, 0};
    scene.lights.push_back({LightType::directional, {-0.6, -0.7, -0.4}, {}, {2, 1.9f, 1.7f}});
    const MaterialDesc pavement = brick_material(0.1f, 0);
    PlaneShape ground;
    ground.size = {10, 10};
    ground.uv_scale = 0.5;
    scene.objects.push_back({"pavement", ground, pavement});
    MaterialDesc chrome = mirror(0.9f);
    chrome.environment_probe = EnvironmentProbeDesc{{0, 0.6, 0}, 256};
    scene.objects.push_back({"chrome sphere", SphereShape{{0, 0.6, 0}, 0.6}, chrome});
    MaterialDesc red;
    red.base_color = {0.75f, 0.1f, 0.06f};
    red.specular = 0.4f;
    scene.objects.push_back({"red sphere", SphereShape{{2.1, 0.45, 0.4}, 0.45}, red});
    MaterialDesc green = red;
    green.base_color = {0.1f, 0.55f, 0.15f};
    scene.objects.push_back(
        {"green torus", TorusShape{{-2.0, 0.5, 0.3}, {0.5, 0.3, 1}, 0.4, 0.14}, green});
    MaterialDesc blue = red;
    blue.base_color = {0.1f, 0.2f, 0.7f};
    scene.objects.push_back({"blue sphere", SphereShape{{-0.7, 0.3, 2.0}, 0.3}, blue});
    add_camera_move(scene, {0.3, 0, 0}, {0, 0, 0});
    return demo;
}

DemoScene irradiance(const DemoSceneOptions& options) {
    DemoScene demo{"irradiance",
                   "matte surfaces lit by the environment alone: its irradiance by the normal, "
                   "averaged over a bump map's slopes where the footprint filters them away",
                   "",
                   {}};
    SceneDesc& scene = demo.scene = base_scene(options);
    scene.camera = {{0, 1.2, 4.5}, {0, 0.3, -3}, {0, 1, 0}, 45};
    scene.environment = daylight_environment(options, demo.assets);
    scene.environment->rotation_deg = {0, 100, 0};  // the low sun from the right
    MaterialDesc matte;
    matte.base_color = {0.5f, 0.5f, 0.5f};
    matte.specular = 0;
    scene.objects.push_back({"matte sphere", SphereShape{{-0.9, 0.6, -1.5}, 0.6}, matte});
    PlaneShape floor;
    floor.size = {12, 40};
    floor.center = {0, 0, -12};
    floor.uv_scale = 0.5;
    MaterialDesc bricks = matte;
    bricks.base_color = {0.45f, 0.3f, 0.22f};
    bricks.bump = brick_bump(options, 1, 0.03f, demo.assets);
    scene.objects.push_back({"bumpy floor", floor, bricks});
    add_camera_move(scene, {0.3, 0, 0}, {0.3, 0, 0});
    return demo;
}

}  // namespace

fs::path DemoSceneOptions::default_demo_data_dir() {
    if (const char* env = std::getenv("FOOTPRINT_DATA"); env && *env) {
        // A folder that is not there is most likely a typo: the scenes then fall back to the
        // repository's assets, which the user should hear about (once a run).
        std::error_code ec;
        if (!fs::is_directory(env, ec)) {
            static std::once_flag warned;
            std::call_once(warned, [&] {
                std::fprintf(stderr,
                             "footprint: warning: FOOTPRINT_DATA '%s' is not a folder; the demo "
                             "scenes use the repository's assets\n",
                             env);
            });
        }
        return env;
    }
    return FOOTPRINT_DEFAULT_DATA_DIR;
}

fs::path DemoSceneOptions::default_demo_assets_dir() {
    return FOOTPRINT_ASSETS_DIR;
}

const std::vector<std::string>& demo_scene_names() {
    static const std::vector<std::string> names = {
        "cylinder",          "parabolic_mirror", "water",      "bump_plate",       "secret_writing",
        "brushed_sphere",    "terrain",          "procedural", "procedural_bump",  "irradiance",
        "local_environment", "parallax",         "shadows",    "environment_probe"};
    return names;
}

Result<DemoScene> make_demo_scene(const std::string& name, const DemoSceneOptions& options) {
    if (name == "cylinder") return cylinder(options);
    if (name == "parabolic_mirror") return parabolic_mirror(options);
    if (name == "water") return water(options);
    if (name == "bump_plate") return bump_plate(options);
    if (name == "secret_writing") return secret_writing(options);
    if (name == "brushed_sphere") return brushed_sphere(options);
    if (name == "terrain") return terrain(options);
    if (name == "procedural") return procedural(options);
    if (name == "procedural_bump") return procedural_bump(options);
    if (name == "irradiance") return irradiance(options);
    if (name == "local_environment") return local_environment(options);
    if (name == "parallax") return parallax(options);
    if (name == "shadows") return shadows(options);
    if (name == "environment_probe") return environment_probe(options);
    std::string valid;
    for (const std::string& n : demo_scene_names()) valid += (valid.empty() ? "" : ", ") + n;
    return Error{"unknown demo scene '" + name + "' (valid: " + valid + ")"};
}

}  // namespace footprint
