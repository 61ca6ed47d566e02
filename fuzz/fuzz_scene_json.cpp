// fuzz/fuzz_scene_json.cpp — scene files (scene/scene_file.h), every key, then the scene prepared
// and rendered (render/render_scene.h, render/renderer.h) at 4 × 3 pixels.
//
// Feeds: the bytes as the JSON text of a scene file in the scratch folder, where these files lie
// (written once): env.hdr (8 × 4, a lat-long), face.hdr (4 × 4: a cube face, a sphere map, a
// paraboloid half), tex.png (4 × 4 RGB), height.png (4 × 4 grey), normal.png (4 × 4 normals) and
// mesh.obj (two triangles); the seed corpus and the dictionary (scene_json.dict) name them. A scene
// that parses is shrunk before it is prepared (4 × 3 pixels, probes of 4², terrains of at most
// 2³ + 1 samples a side) and rendered with one thread, one sample per pixel, in the filter mode
// that the text's length picks.
// Asserts: a scene that does not parse, or cannot be prepared, gets an error naming the scene file;
// one that does renders 4 × 3 RGB pixels that are all finite.
#include <cmath>
#include <cstdint>
#include <string>
#include <variant>

#include "fuzz_input.h"
#include "image/image_io.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "scene/scene_file.h"

namespace {

using namespace footprint;

Image ramp(int width, int height, int channels) {
    Image image(width, height, channels);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = static_cast<float>(i % 7) / 7.0f + 0.1f;
    return image;
}

void write_fixtures() {
    const auto dir = fuzz::scratch_dir();
    Image normals(4, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            normals.at(x, y, 0) = 0.5f + 0.1f * (x - 1.5f);
            normals.at(x, y, 1) = 0.5f;
            normals.at(x, y, 2) = 1.0f;
        }
    const ImageSaveOptions linear{ColorEncoding::linear};
    bool ok = save_image(ramp(8, 4, 3), dir / "env.hdr").ok() &&
              save_image(ramp(4, 4, 3), dir / "face.hdr").ok() &&
              save_image(ramp(4, 4, 3), dir / "tex.png").ok() &&
              save_image(ramp(4, 4, 1), dir / "height.png", linear).ok() &&
              save_image(normals, dir / "normal.png", linear).ok();
    ok = ok && write_file_atomically(dir / "mesh.obj",
                                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"
                                     "vt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n"
                                     "f 1/1/1 3/3/1 4/4/1\n")
                   .ok();
    fuzz::require(ok, "the fixture files are written");
}

// What a fuzzed scene may ask for that only costs time: the fuzzer looks for crashes, not for
// large renders.
void shrink(SceneDesc& scene) {
    scene.width = 4;
    scene.height = 3;
    for (ObjectDesc& object : scene.objects) {
        if (object.material.environment_probe) object.material.environment_probe->size = 4;
        if (auto* terrain = std::get_if<TerrainShape>(&object.shape))
            terrain->subdivisions = std::min(terrain->subdivisions, 3);
    }
}

void require_names_scene(const Error& error) {
    fuzz::require(error.message.find("scene.json") != std::string::npos,
                  "a scene error names the scene file");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const bool fixtures = (write_fixtures(), true);
    (void)fixtures;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    Result<SceneDesc> scene = parse_scene(text, fuzz::scratch_dir() / "scene.json");
    if (!scene.ok()) {
        require_names_scene(scene.error());
        return 0;
    }
    shrink(*scene);
    const Result<RenderScene> prepared = prepare_render_scene(*scene);
    if (!prepared.ok()) {
        require_names_scene(prepared.error());
        return 0;
    }
    RenderOptions options;
    const auto modes = all_filter_modes();
    options.filter = modes[size % modes.size()];
    options.threads = 1;
    if (!scene->camera_path.empty()) {
        options.frame_count = 3;
        options.frame = static_cast<int>(size % 3);
    }
    const Image image = render(*prepared, options);
    fuzz::require(image.width == 4 && image.height == 3 && image.channels == 3,
                  "the render has the scene's size");
    for (float v : image.pixels) fuzz::require(std::isfinite(v), "rendered pixels are finite");
    return 0;
}
