// A renderer's first lookups through the installed footprint package: a filtered texture lookup,
// a filtered environment lookup, a texture-system lookup of a file by name, and a scene file
// rendered. Exits with 1 if a result is not what the maths says.
#include <footprint/footprint.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

namespace {

bool near(float value, float expected, float tolerance, const char* what) {
    const bool ok = std::fabs(value - expected) <= tolerance;
    std::printf("%-44s %.4f (expected %.4f ± %.4f) %s\n", what, value, expected, tolerance,
                ok ? "ok" : "WRONG");
    return ok;
}

}  // namespace

int main() {
    std::printf("footprint %s (headers %s)\n", footprint::version(), FOOTPRINT_VERSION_STRING);
    bool ok = std::strcmp(footprint::version(), FOOTPRINT_VERSION_STRING) == 0;

    // A texture: a black-and-white checkerboard of 8 × 8 squares, 256² texels.
    footprint::Image checker(256, 256, 1);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) checker.at(x, y, 0) = ((x / 32 + y / 32) % 2) ? 1.0f : 0.0f;
    const footprint::MipPyramid pyramid = footprint::MipPyramid::build(checker);
    footprint::LookupOptions options;  // footprint assembly
    float texel = 0;
    // A pixel that covers a little of one white square: the square's colour.
    footprint::TextureCoords inside{0.125f + 1 / 16.0f, 1 / 16.0f, 0.01f, 0, 0, 0.01f};
    footprint::texture_lookup(pyramid, inside, options, &texel);
    ok &= near(texel, 1.0f, 1e-3f, "texture: inside a white square");
    // A grazing pixel, 16 squares long and a tenth of one wide: half white.
    footprint::TextureCoords grazing{0.5f, 0.5f, 2.0f, 0, 0, 0.0125f};
    footprint::texture_lookup(pyramid, grazing, options, &texel);
    ok &= near(texel, 0.5f, 0.05f, "texture: a footprint across 16 squares");

    // An environment: a lat-long sky whose brightness is the direction's height y (1 at the
    // zenith, −1 at the nadir), 512 × 256.
    footprint::Image sky(512, 256, 3);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 512; ++x)
            for (int c = 0; c < 3; ++c)
                sky.at(x, y, c) = std::cos(3.14159265f * (static_cast<float>(y) + 0.5f) / 256);
    footprint::Result<footprint::EnvironmentMap> map = footprint::EnvironmentMap::from_latlong(sky);
    if (!map) {
        std::printf("environment: %s\n", map.error().message.c_str());
        return 1;
    }
    float colour[3] = {0, 0, 0};
    // A narrow ray a little above the horizon: y = sin 0.3.
    const footprint::Vec3 r{0, std::sin(0.3f), -std::cos(0.3f)};
    const footprint::Vec3 spread_x{0.001f, 0, 0}, spread_y{0, 0.001f, 0.0003f};
    footprint::environment_lookup(*map, r, spread_x, spread_y, footprint::EnvLookupOptions{},
                                  colour);
    ok &= near(colour[0], std::sin(0.3f), 2e-3f, "environment: 0.3 rad above the horizon");

    // The texture system: the checkerboard written as a file, looked up by name through the cache.
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / "footprint-consumer-checker.exr";
    if (footprint::Status saved = footprint::save_image(checker, file); !saved) {
        std::printf("texture system: %s\n", saved.error().message.c_str());
        return 1;
    }
    footprint::TextureSystemOptions ts_options;
    ts_options.max_memory_mb = 16;
    footprint::Result<std::unique_ptr<footprint::TextureSystem>> made =
        footprint::TextureSystem::create(ts_options);
    if (!made) {
        std::printf("texture system: %s\n", made.error().message.c_str());
        return 1;
    }
    std::unique_ptr<footprint::TextureSystem> ts = std::move(*made);
    float by_name = 0;
    footprint::Status looked_up = ts->texture(file.string(), grazing, options, {&by_name, 1});
    std::filesystem::remove(file);
    if (!looked_up) {
        std::printf("texture system: %s\n", looked_up.error().message.c_str());
        return 1;
    }
    ok &= near(by_name, texel, 0.0f, "texture system: the same grazing lookup");

    // A scene file rendered: a lit sphere in front of a black sky, parsed, prepared and rendered
    // as `footprint render` does (this is what links every module, glTF's reader included).
    const char* const scene_json = R"({
        "image": {"width": 32, "height": 18},
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
        "lights": [{"type": "directional", "direction": [0, -1, -1]}],
        "objects": [{"shape": "sphere", "radius": 0.8, "material": {"base_color": [0.8, 0.5, 0.2]}}]
    })";
    footprint::Result<footprint::SceneDesc> desc =
        footprint::parse_scene(scene_json, "consumer-scene.json");
    if (!desc) {
        std::printf("scene: %s\n", desc.error().message.c_str());
        return 1;
    }
    footprint::Result<footprint::RenderScene> scene = footprint::prepare_render_scene(*desc);
    if (!scene) {
        std::printf("scene: %s\n", scene.error().message.c_str());
        return 1;
    }
    const footprint::Image image = footprint::render(*scene, footprint::RenderOptions{});
    const float centre = image.at(16, 9, 0), corner = image.at(0, 0, 0);
    ok &= near(corner, 0.0f, 0.0f, "render: the black sky in a corner");
    ok &= near(centre > 0.01f ? 1.0f : 0.0f, 1.0f, 0.0f, "render: the lit sphere in the middle");

    std::printf("%s\n", ok ? "all results as expected" : "SOME RESULTS WRONG");
    return ok ? 0 : 1;
}
