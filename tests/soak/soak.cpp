// footprint-soak: many random scenes rendered in every mode, as a long-running renderer would.
//
//   footprint-soak [SCENES] [--seed N] [--threads N]      (make soak SOAK_SCENES=N)
//
// Each scene is written as scene-file JSON by a generator that follows docs/scene-format.md (every
// shape; colours, texture files and procedural textures; height, normal and procedural bumps,
// parallax; both material models and the highlight models; every environment layout and file
// arrangement, rotated, with proxies and nested local maps; probes; lights with and without
// shadows; camera paths) over a few small asset files written at the start, parsed by parse_scene,
// prepared and rendered at a small size in every filter mode. It fails (exit 1, naming the scene
// and the mode) when a generated scene is refused (the generator and the grammar disagree), when
// a pixel is not finite, or when the resident memory at the end exceeds that after the first 100
// scenes by more than 10 % (a leak, or a cache that is not bounded). It prints a JSON summary.
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "core/test_temp_dir.h"
#include "image/image_io.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "scene/scene_file.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace footprint {
namespace {

// The resident set (VmRSS) in MiB.
double resident_mib() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
    return 0;
}

// The asset files scenes refer to: a colour map, height and normal maps, a metallic-roughness
// map, an OBJ mesh, and an environment in every layout and file arrangement.
struct Assets {
    test::TempDir dir;

    std::string path(const char* name) const { return (dir / name).string(); }
};

Image smooth_noise(int width, int height, int channels, unsigned seed, float lo, float hi) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> phase(0, 6.3f);
    Image image(width, height, channels);
    for (int c = 0; c < channels; ++c) {
        const float a = phase(rng), b = phase(rng);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                image.at(x, y)[c] = lo + (hi - lo) * (0.5f + 0.25f * std::sin(a + 0.4f * x) +
                                                      0.25f * std::cos(b + 0.7f * y));
    }
    return image;
}

bool write_assets(const Assets& a) {
    Image normals(32, 32, 3);  // tangent-space normals with n_z > 0, encoded as (n + 1) / 2
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const float sx = 0.4f * std::sin(0.5f * x), sy = 0.4f * std::cos(0.3f * y);
            const float inv = 1 / std::sqrt(sx * sx + sy * sy + 1);
            float* p = normals.at(x, y);
            p[0] = 0.5f + 0.5f * sx * inv, p[1] = 0.5f + 0.5f * sy * inv, p[2] = 0.5f + 0.5f * inv;
        }
    const struct {
        const char* name;
        Image image;
    } files[] = {
        {"color.png", smooth_noise(64, 64, 3, 1, 0.05f, 0.95f)},
        {"height.exr", smooth_noise(32, 32, 1, 2, 0, 1)},
        {"normal.png", normals},
        {"mr.png", smooth_noise(16, 16, 3, 3, 0.1f, 0.9f)},
        {"latlong.exr", smooth_noise(64, 32, 3, 4, 0, 4)},
        {"cross.exr", smooth_noise(64, 48, 3, 5, 0, 2)},  // a horizontal cross, 4 × 3 faces
        {"sphere.exr", smooth_noise(32, 32, 3, 6, 0, 2)},
        {"front.exr", smooth_noise(32, 32, 3, 7, 0, 2)},
        {"back.exr", smooth_noise(32, 32, 3, 8, 0, 2)},
    };
    for (const auto& f : files)
        if (Status s = save_image(f.image, a.dir / f.name); !s) {
            std::cerr << "footprint-soak: " << s.error().message << "\n";
            return false;
        }
    for (int face = 0; face < 6; ++face) {
        const std::string name = "face" + std::to_string(face) + ".exr";
        if (!save_image(smooth_noise(16, 16, 3, 10 + face, 0, 2), a.dir / name)) return false;
    }
    std::ofstream obj(a.dir / "mesh.obj");  // a tetrahedron with texture coordinates
    obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
           "f 1/1 3/3 2/2\nf 1/1 2/2 4/3\nf 1/1 4/3 3/2\nf 2/1 3/2 4/3\n";
    return static_cast<bool>(obj.flush());
}

// Random scene JSON following docs/scene-format.md.
class SceneGenerator {
  public:
    SceneGenerator(const Assets& assets, unsigned seed) : assets_(assets), rng_(seed) {}

    json scene() {
        json s;
        s["image"] = {{"width", integer(12, 32)}, {"height", integer(8, 24)}};
        s["camera"] = camera();
        if (chance(0.2)) s["camera_path"] = json::array({camera(), camera()});
        if (chance(0.85)) s["environment"] = environment();
        if (chance(0.15)) {
            s["local_environments"] = json::array();
            for (int i = integer(1, 2); i > 0; --i) {
                json local = environment();
                local["proxy"] = proxy(1.5 * i);
                s["local_environments"].push_back(local);
            }
        }
        s["background"] = vec(0, 1);
        s["lights"] = json::array();
        for (int i = integer(0, 3); i > 0; --i) s["lights"].push_back(light());
        s["objects"] = json::array();
        for (int i = integer(1, 4); i > 0; --i) s["objects"].push_back(object());
        return s;
    }

  private:
    bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
    double number(double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(rng_);
    }
    int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
    json vec(double lo, double hi) { return {number(lo, hi), number(lo, hi), number(lo, hi)}; }
    template <class T>
    T pick(std::initializer_list<T> options) {
        return options.begin()[integer(0, static_cast<int>(options.size()) - 1)];
    }
    std::string file(const char* name) { return assets_.path(name); }

    json camera() {
        const double angle = number(0, 6.28), distance = number(2.5, 7);
        return {
            {"position", {distance * std::cos(angle), number(0.3, 3), distance * std::sin(angle)}},
            {"look_at", vec(-0.5, 0.5)},
            {"fov_y_deg", number(15, 100)}};
    }

    json environment() {
        json e;
        switch (integer(0, 5)) {
            case 0:
                e["file"] = file("latlong.exr"), e["layout"] = "latlong";
                break;
            case 1:
                e["file"] = file("cross.exr");
                break;  // the layout detected from the file
            case 2:
                e["file"] = file("sphere.exr"), e["layout"] = "sphere";
                break;
            case 3:
                e["file"] = {file("front.exr"), file("back.exr")}, e["layout"] = "paraboloid";
                break;
            case 4:
                e["file"] = json::array();
                for (int f = 0; f < 6; ++f)
                    e["file"].push_back(file(("face" + std::to_string(f) + ".exr").c_str()));
                e["layout"] = "cube";
                break;
            default:
                e["file"] = file("latlong.exr");
                break;
        }
        if (chance(0.5)) e["rotation_deg"] = vec(-180, 180);
        if (chance(0.5)) e["intensity"] = number(0, 2);
        if (chance(0.2)) e["proxy"] = proxy(4);
        return e;
    }

    json proxy(double size) {
        json p;
        if (chance(0.5))
            p["box"] = {{"min", {-size, -0.5, -size}}, {"max", {size, size, size}}};
        else
            p["sphere"] = {{"center", vec(-0.2, 0.2)}, {"radius", size}};
        if (chance(0.3)) p["capture"] = vec(-0.3, 0.3);
        return p;
    }

    json light() {
        json l;
        if (chance(0.5)) {
            l["type"] = "directional";
            l["direction"] = {number(-1, 1), number(-1, -0.1), number(-1, 1)};
        } else {
            l["type"] = "point";
            l["position"] = vec(-3, 3);
        }
        l["color"] = vec(0, 3);
        if (chance(0.3)) l["shadows"] = false;
        return l;
    }

    json object() {
        json o;
        o["name"] = "object";
        switch (integer(0, 6)) {
            case 0:
                o["shape"] = "plane";
                o["normal"] = {number(-0.3, 0.3), 1, number(-0.3, 0.3)};
                if (chance(0.5))
                    o["size"] = "infinite";
                else
                    o["size"] = {number(0.5, 6), number(0.5, 6)};
                o["uv_scale"] = number(0.2, 8);
                break;
            case 1:
                o["shape"] = "sphere", o["center"] = vec(-1, 1), o["radius"] = number(0.1, 1.5);
                break;
            case 2:
                o["shape"] = "cylinder", o["axis"] = vec(-1, 1), o["radius"] = number(0.1, 1);
                o["height"] = number(0.1, 3);
                break;
            case 3:
                o["shape"] = "paraboloid", o["focus"] = vec(-1, 1), o["axis"] = {0, 0.5, 1};
                o["focal_length"] = number(0.2, 2), o["radius"] = number(0.2, 1.5);
                break;
            case 4:
                o["shape"] = "torus", o["center"] = vec(-1, 1),
                o["major_radius"] = number(0.5, 1.5);
                o["minor_radius"] = number(0.05, 0.45);
                break;
            case 5:
                o["shape"] = "terrain", o["size"] = {number(2, 10), number(2, 10)};
                o["subdivisions"] = integer(1, 4), o["roughness"] = number(0.1, 1);
                o["height"] = number(0, 1), o["seed"] = integer(0, 100);
                break;
            default:
                o["shape"] = "mesh", o["file"] = file("mesh.obj");
                o["transform"] = {{"translate", vec(-1, 1)},
                                  {"rotate_deg", vec(-90, 90)},
                                  {"scale", number(0.3, 2)}};
                break;
        }
        o["material"] = material(o["shape"] != "mesh" && o["shape"] != "terrain");
        return o;
    }

    json material(bool analytic) {
        json m;
        const bool metal_rough = chance(0.15);
        if (metal_rough) {
            m["model"] = "metallic-roughness";
            m["metallic"] = number(0, 1), m["roughness"] = number(0, 1);
            if (chance(0.3)) m["highlight"] = pick({"ggx", "beckmann"});
            if (chance(0.4)) m["metallic_roughness"] = file("mr.png");
        } else {
            m["diffuse"] = number(0, 1), m["mirror"] = number(0, 1);
            m["fresnel_f0"] = number(0, 1);
            if (chance(0.5)) {
                m["highlight"] = pick({"blinn-phong", "beckmann", "ggx"});
                m["specular"] = number(0, 1);
                if (m["highlight"] == "blinn-phong")
                    m["shininess"] = number(1, 500);
                else
                    m["roughness"] = number(0.05, 1);
            }
        }
        if (const double c = number(0, 1); c < 0.3) {
            m["base_color"] = file("color.png");
        } else if (c < 0.45 && !metal_rough) {
            m["base_color"] = {{"procedural", pick({"noise", "turbulence", "marble", "checker"})},
                               {"scale", number(0.5, 20)},
                               {"colors", {vec(0, 1), vec(0, 1)}}};
        } else {
            m["base_color"] = vec(0, 1);
        }
        if (chance(0.5)) m["bump"] = bump(!metal_rough);
        if (!metal_rough && chance(0.3)) m["micro_roughness"] = number(0, 0.3);
        if (analytic && !metal_rough && chance(0.05))
            m["environment_probe"] = {{"center", vec(-0.5, 0.5)}, {"size", integer(4, 12)}};
        return m;
    }

    json bump(bool procedural) {
        json b;
        switch (integer(0, procedural ? 2 : 1)) {
            case 0:
                b["height_map"] = file("height.exr");
                if (chance(0.3))
                    b["parallax"] = {{"depth", number(0.01, 0.2)}, {"steps", integer(1, 24)}};
                break;
            case 1:
                b["normal_map"] = file("normal.png");
                break;
            default:  // footprint model only; a checker has no slopes
                b["procedural"] = pick({"noise", "turbulence", "marble"});
                b["scale"] = number(0.5, 20), b["octaves"] = integer(1, 6);
                break;
        }
        b["strength"] = number(-2, 2);
        if (b.contains("procedural")) return b;  // its frame is fixed (main_direction)
        b["frame"] = pick({"natural", "normalized", "main_direction"});
        if (b["frame"] == "main_direction" && chance(0.5)) b["main_direction"] = vec(-1, 1);
        return b;
    }

    const Assets& assets_;
    std::mt19937 rng_;
};

struct Totals {
    long scenes = 0, renders = 0, pixels = 0;
    double rss_after_100 = 0, rss_end = 0;
};

// Prepares and renders one scene in every mode; false after a message naming what failed.
bool soak_one(const json& text, int index, int threads, Totals& totals) {
    const std::string name = "scene" + std::to_string(index) + ".json";
    Result<SceneDesc> desc = parse_scene(text.dump(), name);
    if (!desc) {
        std::cerr << "footprint-soak: the generator wrote a scene the parser refuses: "
                  << desc.error().message << "\n"
                  << text.dump(2) << "\n";
        return false;
    }
    Result<RenderScene> scene = prepare_render_scene(*desc);
    if (!scene) {
        std::cerr << "footprint-soak: " << scene.error().message << "\n" << text.dump(2) << "\n";
        return false;
    }
    for (FilterMode mode : all_filter_modes()) {
        RenderOptions options;
        options.filter = mode;
        options.spp = mode == FilterMode::reference ? 4 : 1;
        options.threads = threads;
        const Image image = render(*scene, options);
        for (float v : image.pixels) {
            if (!std::isfinite(v)) {
                std::cerr << "footprint-soak: " << name << " in " << filter_mode_name(mode)
                          << ": a pixel is not finite\n"
                          << text.dump(2) << "\n";
                return false;
            }
        }
        ++totals.renders;
        totals.pixels += static_cast<long>(image.width) * image.height;
    }
    return true;
}

int run(int scene_count, unsigned seed, int threads) {
    Assets assets;
    if (!write_assets(assets)) return 1;
    SceneGenerator generator(assets, seed);
    Totals totals;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < scene_count; ++i) {
        if (!soak_one(generator.scene(), i, threads, totals)) return 1;
        ++totals.scenes;
        if (i + 1 == 100) totals.rss_after_100 = resident_mib();
        if ((i + 1) % 1000 == 0) std::cerr << "footprint-soak: " << i + 1 << " scenes\n";
    }
    totals.rss_end = resident_mib();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double growth = totals.rss_after_100 > 0 ? totals.rss_end / totals.rss_after_100 - 1 : 0;
    std::cout << json{{"scenes", totals.scenes},
                      {"renders", totals.renders},
                      {"pixels", totals.pixels},
                      {"seconds", seconds},
                      {"threads", threads},
                      {"rss_after_100_mib", totals.rss_after_100},
                      {"rss_end_mib", totals.rss_end},
                      {"rss_growth", growth}}
                     .dump()
              << "\n";
    if (growth > 0.10) {
        std::cerr << "footprint-soak: resident memory grew by " << 100 * growth
                  << " % after the first 100 scenes (at most 10 %)\n";
        return 1;
    }
    return 0;
}

}  // namespace
}  // namespace footprint

int main(int argc, char** argv) {
    int scenes = 10000, threads = 2;
    unsigned seed = 1;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--seed" && i + 1 < argc)
            seed = static_cast<unsigned>(std::atoi(argv[++i]));
        else if (arg == "--threads" && i + 1 < argc)
            threads = std::atoi(argv[++i]);
        else if (arg[0] != '-' && std::atoi(arg.c_str()) > 0)
            scenes = std::atoi(arg.c_str());
        else {
            std::cerr << "usage: footprint-soak [SCENES] [--seed N] [--threads N]\n";
            return 2;
        }
    }
    return footprint::run(scenes, seed, threads);
}
