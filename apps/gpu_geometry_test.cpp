// The GPU path's geometry against the CPU renderer: the torus, triangle meshes (OBJ with a
// texture and a normal map, glTF with tangents), meshes and analytic shapes in front of each
// other, and scenes with many maps (gpu/gpu_renderer.h, docs/gpu.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/test_shared_data.h"
#include "core/test_temp_dir.h"
#include "demo_assets.h"
#include "gpu/gpu_renderer.h"
#include "gpu/gpu_test_device.h"
#include "gpu_test_support.h"
#include "image/image_io.h"
#include "render/renderer.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

using test::cpu_counterpart;
using test::gpu_cpu_tolerance;
using test::rmse;
using test::TempDir;

// The tolerances are apps/gpu_test_support.h's: a mesh adds no term of its own inside objects,
// since its hit is the ray's intersection with the triangle the rasteriser found, in float around
// the camera as every GPU hit. Where a pixel centre lies within rounding of a triangle's edge, the
// rasteriser (fixed point) and Embree (float, on the CPU) may pick the triangles on either side: at
// a silhouette that pixel shows another object. Interiors (render/renderer.h's interior_mask()) are
// held to the tolerance, whole images to twice it.
constexpr double kSilhouetteFactor = 2;

// Every mode but hw-aniso on the GPU against its CPU counterpart, each rendered twice alike.
void expect_gpu_matches_cpu(const SceneDesc& desc, const char* what) {
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene) << scene.error().message;
    const Image mask = interior_mask(*scene);
    Result<GpuRenderer> gpu = GpuRenderer::create(*scene);
    ASSERT_TRUE(gpu) << gpu.error().message;
    for (GpuFilter f :
         {GpuFilter::point, GpuFilter::trilinear, GpuFilter::fa, GpuFilter::fa_rough}) {
        GpuRenderOptions gpu_options;
        gpu_options.filter = f;
        Result<Image> image = gpu->render(gpu_options);
        ASSERT_TRUE(image) << image.error().message;
        // Deterministic with meshes too: the raster pass's depth test picks one triangle.
        Result<Image> again = gpu->render(gpu_options);
        ASSERT_TRUE(again) << again.error().message;
        EXPECT_EQ(image->pixels, again->pixels) << what << " " << gpu_filter_name(f);
        RenderOptions options;
        options.filter = *cpu_counterpart(f);
        const Image cpu = render(*scene, options);
        const double whole = rmse(*image, cpu), interior = rmse(*image, cpu, &mask);
        std::printf("%-18s %-9s GPU vs CPU RMSE %.2e, interior %.2e\n", what, gpu_filter_name(f),
                    whole, interior);
        EXPECT_LT(interior, gpu_cpu_tolerance(f)) << what << " " << gpu_filter_name(f);
        EXPECT_LT(whole, kSilhouetteFactor * gpu_cpu_tolerance(f))
            << what << " " << gpu_filter_name(f);
    }
}

EnvironmentDesc zebra_sky() {
    EnvironmentDesc env;
    env.layout = EnvLayout::latlong;
    env.images.push_back({{}, std::make_shared<Image>(make_zebra_latlong(256)), "zebra"});
    return env;
}

// A checkerboard of n × n squares of 4 × 4 texels, in linear light.
Image checker(int n, float dark) {
    Image image(4 * n, 4 * n, 3);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c)
                image.at(x, y, c) = ((x / 4 + y / 4) % 2 == 0) ? 0.9f - 0.2f * c : dark;
    return image;
}

SceneDesc base_scene() {
    SceneDesc desc;
    desc.width = 128;
    desc.height = 72;
    desc.camera = {{0.3, 1.4, 3.2}, {0, 0.4, 0}, {0, 1, 0}, 45};
    desc.environment = zebra_sky();
    LightDesc sun;
    sun.direction = {-0.4, -1, -0.3};
    sun.color = {1.5f, 1.4f, 1.2f};
    desc.lights.push_back(sun);
    return desc;
}

MaterialDesc checker_mirror(float mirror) {
    MaterialDesc m;
    m.base_color_map = {{}, std::make_shared<Image>(checker(8, 0.1f)), "checker"};
    m.diffuse = 1 - mirror;
    m.specular = 0.3f;
    m.shininess = 40;
    m.mirror = mirror;
    m.fresnel_f0 = 0.6f;
    return m;
}

TEST(GpuGeometry, TheTorusMatchesTheCpu) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    SceneDesc desc = base_scene();
    ObjectDesc ring;
    TorusShape torus;
    torus.center = {0, 0.4, 0};
    torus.axis = {0.2, 1, 0.3};
    torus.major_radius = 0.7;
    torus.minor_radius = 0.25;
    ring.shape = torus;
    ring.material = checker_mirror(0.5f);
    ring.material.bump.source = BumpDesc::Source::height_map;
    ring.material.bump.map = {{}, std::make_shared<Image>(make_water_height_map(64)), "waves"};
    ring.material.bump.strength = 0.01f;
    desc.objects.push_back(ring);
    // A sphere through the hole: the torus in front of it and behind it.
    ObjectDesc ball;
    ball.shape = SphereShape{{0, 0.4, 0}, 0.5};
    ball.material = checker_mirror(0.8f);
    desc.objects.push_back(ball);
    expect_gpu_matches_cpu(desc, "torus");
}

// A UV sphere as an OBJ file: shared vertices with normals and texture coordinates (the seam
// duplicated), its material's colour map (map_Kd) and normal map (norm) beside it.
void write_uv_sphere(const TempDir& dir, int rings, int segments, double radius) {
    std::ofstream obj(dir / "ball.obj");
    obj << "mtllib ball.mtl\n";
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const double theta = M_PI * i / rings, phi = 2 * M_PI * j / segments;
            const double x = std::sin(theta) * std::cos(phi), y = std::cos(theta),
                         z = -std::sin(theta) * std::sin(phi);
            obj << "v " << radius * x << ' ' << radius * y << ' ' << radius * z << '\n'
                << "vn " << x << ' ' << y << ' ' << z << '\n'
                << "vt " << static_cast<double>(j) / segments << ' '
                << 1 - static_cast<double>(i) / rings << '\n';
        }
    obj << "usemtl painted\n";
    auto index = [&](int i, int j) { return i * (segments + 1) + j + 1; };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const int a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1),
                      d = index(i, j + 1);
            obj << "f " << a << '/' << a << '/' << a << ' ' << b << '/' << b << '/' << b << ' ' << c
                << '/' << c << '/' << c << '\n'
                << "f " << a << '/' << a << '/' << a << ' ' << c << '/' << c << '/' << c << ' ' << d
                << '/' << d << '/' << d << '\n';
        }
    std::ofstream(dir / "ball.mtl")
        << "newmtl painted\nKd 1 1 1\nmap_Kd paint.png\nnorm bumps.png\n";
    ASSERT_TRUE(save_image(checker(16, 0.2f), dir / "paint.png").ok());
    // Bumps: n = (−∂h/∂x, −∂h/∂y, 1)/|…| of h = sin·sin, stored as n/2 + ½.
    Image bumps(64, 64, 3);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const double u = 2 * M_PI * x / 64, v = 2 * M_PI * y / 64;
            const double hx = 0.4 * std::cos(4 * u) * std::sin(3 * v),
                         hy = 0.3 * std::sin(4 * u) * std::cos(3 * v);
            const double len = std::sqrt(hx * hx + hy * hy + 1);
            bumps.at(x, y, 0) = static_cast<float>(0.5 - 0.5 * hx / len);
            bumps.at(x, y, 1) = static_cast<float>(0.5 - 0.5 * hy / len);
            bumps.at(x, y, 2) = static_cast<float>(0.5 + 0.5 / len);
        }
    ImageSaveOptions raw;
    raw.encoding = ColorEncoding::linear;
    ASSERT_TRUE(save_image(bumps, dir / "bumps.png", raw).ok());
}

TEST(GpuGeometry, AnObjMeshWithTexturesMatchesTheCpuInFrontOfAndBehindAnalyticShapes) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    TempDir dir;
    write_uv_sphere(dir, 24, 48, 0.6);
    SceneDesc desc = base_scene();
    ObjectDesc ball;
    MeshShape mesh;
    mesh.file = dir / "ball.obj";
    mesh.transform.translate = {-0.3, 0.6, 0};
    ball.shape = mesh;
    ball.material.diffuse = 0.6f;
    ball.material.specular = 0.4f;
    ball.material.shininess = 60;
    ball.material.mirror = 0.4f;
    ball.material.fresnel_f0 = 0.5f;
    desc.objects.push_back(ball);
    // An analytic sphere half inside the mesh, and a floor the mesh stands on.
    ObjectDesc other;
    other.shape = SphereShape{{0.35, 0.5, 0.1}, 0.4};
    other.material = checker_mirror(0.7f);
    desc.objects.push_back(other);
    ObjectDesc floor;
    PlaneShape plane;
    plane.size = {6, 6};
    floor.shape = plane;
    floor.material = checker_mirror(0.2f);
    desc.objects.push_back(floor);
    expect_gpu_matches_cpu(desc, "OBJ mesh");
}

// glTF normal textures in the frame of the mesh's tangents (render/bump_frame.h), six parts with
// their own colour and normal maps: the FlightHelmet of the shared data set.
TEST(GpuGeometry, AGltfMeshWithTangentFramesMatchesTheCpu) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    const fs::path file = test::shared_data_dir() / "meshes/FlightHelmet/FlightHelmet.gltf";
    if (!fs::exists(file)) GTEST_SKIP() << test::missing_shared_data(file);
    SceneDesc desc = base_scene();
    desc.camera = {{0.25, 0.45, 0.55}, {0, 0.3, 0}, {0, 1, 0}, 40};
    ObjectDesc helmet;
    MeshShape mesh;
    mesh.file = file;
    helmet.shape = mesh;
    helmet.material.mirror = 0.3f;
    helmet.material.fresnel_f0 = 0.2f;
    desc.objects.push_back(helmet);
    expect_gpu_matches_cpu(desc, "glTF FlightHelmet");
}

// The same helmet shaded by its file's metallic-roughness materials (render/material_model.h):
// diffuse-colour and F0 maps made texel by texel, the roughness texture in the bump pyramid's K_0.
TEST(GpuGeometry, AGltfMeshWithItsMetallicRoughnessMaterialsMatchesTheCpu) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    const fs::path file = test::shared_data_dir() / "meshes/FlightHelmet/FlightHelmet.gltf";
    if (!fs::exists(file)) GTEST_SKIP() << test::missing_shared_data(file);
    SceneDesc desc = base_scene();
    desc.camera = {{0.25, 0.45, 0.55}, {0, 0.3, 0}, {0, 1, 0}, 40};
    ObjectDesc helmet;
    MeshShape mesh;
    mesh.file = file;
    helmet.shape = mesh;
    helmet.material.model = MaterialDesc::Model::metallic_roughness;
    helmet.material.highlight = MaterialDesc::Highlight::ggx;
    desc.objects.push_back(helmet);
    expect_gpu_matches_cpu(desc, "glTF metal-rough");
}

// A metallic-roughness sphere with a colour map, a metallic-roughness map (stripes of metal and
// rough dielectric) and a bump map: the F0 map, per-channel Fresnel and per-texel roughness.
TEST(GpuGeometry, MetallicRoughnessMapsMatchTheCpu) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    SceneDesc desc = base_scene();
    auto stripes = std::make_shared<Image>(32, 32, 3);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const bool metal = (x / 4) % 2 == 0;
            stripes->at(x, y, 1) = metal ? 0.3f : 0.8f;  // roughness
            stripes->at(x, y, 2) = metal ? 1.0f : 0.0f;  // metallic
        }
    ObjectDesc ball;
    ball.shape = SphereShape{{0, 0.4, 0}, 0.6};
    MaterialDesc& m = ball.material;
    m.model = MaterialDesc::Model::metallic_roughness;
    m.highlight = MaterialDesc::Highlight::ggx;
    m.base_color_map = {{}, std::make_shared<Image>(checker(8, 0.1f)), "checker"};
    m.metallic_roughness_map = {{}, stripes, "stripes"};
    m.bump.source = BumpDesc::Source::height_map;
    m.bump.map = {{}, std::make_shared<Image>(make_water_height_map(64)), "waves"};
    m.bump.strength = 0.01f;
    desc.objects.push_back(ball);
    expect_gpu_matches_cpu(desc, "metal-rough maps");
}

// More maps than units: maps of one size share an array texture (gpu/gpu_scene.h), so twelve
// colour and twelve bump maps in three sizes take six units.
TEST(GpuGeometry, ManyMapsOfAFewSizesMatchTheCpu) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    SceneDesc desc = base_scene();
    desc.camera = {{0, 3.5, 3.5}, {0, 0, 0}, {0, 1, 0}, 45};
    for (int i = 0; i < 12; ++i) {
        ObjectDesc tile;
        PlaneShape plane;
        plane.center = {-1.5 + (i % 4), 0, -1.0 + (i / 4)};
        plane.size = {0.9, 0.9};
        tile.shape = plane;
        tile.material = checker_mirror(0.3f);
        tile.material.base_color_map.image =
            std::make_shared<Image>(checker(4 << (i % 3), 0.05f * static_cast<float>(i)));
        tile.material.bump.source = BumpDesc::Source::height_map;
        tile.material.bump.map = {
            {}, std::make_shared<Image>(make_water_height_map(32 << (i % 3))), "waves"};
        tile.material.bump.strength = 0.002f * static_cast<float>(i + 1);
        desc.objects.push_back(tile);
    }
    expect_gpu_matches_cpu(desc, "12 + 12 maps");
}

TEST(GpuGeometry, MoreMapShapesThanUnitsAreRefusedNamingTheObject) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    SceneDesc desc = base_scene();
    for (int i = 0; i < 17; ++i) {
        ObjectDesc tile;
        PlaneShape plane;
        plane.center = {static_cast<double>(i), 0, 0};
        tile.shape = plane;
        tile.name = "tile " + std::to_string(i);
        tile.material.base_color_map = {{}, std::make_shared<Image>(checker(2 + i, 0)), "c"};
        desc.objects.push_back(tile);
    }
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene) << scene.error().message;
    Result<GpuRenderer> gpu = GpuRenderer::create(*scene);
    ASSERT_FALSE(gpu);
    EXPECT_EQ(gpu.error().message,
              "objects[16] (tile 16): the scene's maps come in more than 16 different sizes (or "
              "wrap modes); the GPU path takes that many");
}

}  // namespace
}  // namespace footprint
