#include "scene/scene_hash.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>
#include <type_traits>
#include <variant>
#include <vector>

namespace footprint {

namespace {

namespace fs = std::filesystem;

class Fnv1a {
  public:
    void bytes(const void* data, std::size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ p[i]) * 0x100000001b3ull;
    }
    template <class T>
    requires std::is_arithmetic_v<T>
    void add(T value) { bytes(&value, sizeof value); }
    void add(const std::string& s) {
        add(s.size());
        bytes(s.data(), s.size());
    }
    void add(Vec3d v) { add(v.x), add(v.y), add(v.z); }
    void add(Vec3 v) { add(v.x), add(v.y), add(v.z); }
    void add(Vec2d v) { add(v.x), add(v.y); }
    void file(const fs::path& path) {
        std::ifstream in(path, std::ios::binary);
        if (!in) {
            add(std::string("unreadable:") + path.string());
            return;
        }
        char buffer[1 << 16];
        std::uint64_t total = 0;
        while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
            bytes(buffer, static_cast<std::size_t>(in.gcount()));
            total += static_cast<std::uint64_t>(in.gcount());
        }
        add(total);
    }
    void image(const ImageSource& source) {
        if (source.image) {
            add(source.image->width), add(source.image->height), add(source.image->channels);
            bytes(source.image->pixels.data(), source.image->pixels.size() * sizeof(float));
        } else {
            file(source.file);
        }
    }
    std::uint64_t value() const { return hash_; }

  private:
    std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

void add_camera(Fnv1a& h, const CameraDesc& c) {
    h.add(c.position), h.add(c.look_at), h.add(c.up), h.add(c.fov_y_deg);
}

void add_material(Fnv1a& h, const MaterialDesc& m) {
    h.add(m.base_color);
    h.add(!m.base_color_map.empty());
    if (const auto& t = m.base_color_procedural) {  // (nothing otherwise: older hashes stand)
        h.add(std::string("procedural"));
        h.add(static_cast<int>(t->pattern)), h.add(t->scale), h.add(t->octaves);
        h.add(t->colors[0]), h.add(t->colors[1]);
    }
    if (!m.base_color_map.empty()) h.image(m.base_color_map);
    h.add(m.diffuse), h.add(m.specular), h.add(m.shininess), h.add(m.mirror);
    h.add(m.fresnel_f0), h.add(m.micro_roughness);
    h.add(m.environment_probe.has_value());
    if (const auto& p = m.environment_probe) h.add(p->center), h.add(p->size);
    h.add(static_cast<int>(m.highlight)), h.add(m.roughness);
    // Only where it is not the default, so that the footprint model's hashes stay as they were.
    if (m.model == MaterialDesc::Model::metallic_roughness) {
        h.add(1), h.add(m.metallic);
        h.add(!m.metallic_roughness_map.empty());
        if (!m.metallic_roughness_map.empty()) h.image(m.metallic_roughness_map);
    }
    h.add(static_cast<int>(m.bump.source));
    if (m.bump.source == BumpDesc::Source::procedural) {
        const ProceduralTexture& t = m.bump.procedural;
        h.add(static_cast<int>(t.pattern)), h.add(t.scale), h.add(t.octaves);
    } else if (m.bump.source != BumpDesc::Source::none) {
        h.image(m.bump.map);
    }
    h.add(m.bump.strength), h.add(static_cast<int>(m.bump.frame)), h.add(m.bump.main_direction);
    if (const std::optional<ParallaxOptions>& p = m.bump.parallax) {  // (older hashes stand)
        h.add(std::string("parallax")), h.add(p->depth), h.add(p->steps), h.add(p->max_shift);
    }
}

void add_mesh_files(Fnv1a& h, const fs::path& file) {
    h.file(file);
    std::error_code ec;
    const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    std::vector<fs::path> others;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        if (entry.is_regular_file(ec) && entry.path().filename() != file.filename()) {
            others.push_back(entry.path());
        }
    }
    std::sort(others.begin(), others.end());  // a fixed order, whatever the directory's
    for (const fs::path& other : others) h.file(other);
}

void add_shape(Fnv1a& h, const ShapeDesc& shape) {
    h.add(static_cast<int>(shape.index()));
    std::visit(
        [&](const auto& s) {
            using S = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<S, PlaneShape>) {
                h.add(s.center), h.add(s.normal), h.add(s.size), h.add(s.infinite),
                    h.add(s.uv_scale);
            } else if constexpr (std::is_same_v<S, SphereShape>) {
                h.add(s.center), h.add(s.radius);
            } else if constexpr (std::is_same_v<S, CylinderShape>) {
                h.add(s.center), h.add(s.axis), h.add(s.radius), h.add(s.height);
            } else if constexpr (std::is_same_v<S, ParaboloidShape>) {
                h.add(s.focus), h.add(s.axis), h.add(s.focal_length), h.add(s.radius);
            } else if constexpr (std::is_same_v<S, TorusShape>) {
                h.add(s.center), h.add(s.axis), h.add(s.major_radius), h.add(s.minor_radius);
            } else if constexpr (std::is_same_v<S, TerrainShape>) {
                h.add(s.center), h.add(s.size), h.add(s.subdivisions), h.add(s.roughness);
                h.add(s.height), h.add(s.seed);
            } else {
                add_mesh_files(h, s.file);
                h.add(s.transform.translate), h.add(s.transform.rotate_deg);
                h.add(s.transform.scale);
            }
        },
        shape);
}

void add_environment(Fnv1a& h, const EnvironmentDesc& e) {
    h.add(e.images.size());
    for (const ImageSource& image : e.images) h.image(image);
    h.add(static_cast<int>(e.layout)), h.add(e.rotation_deg), h.add(e.intensity);
    if (const std::optional<EnvProxy>& p = e.proxy) {  // (nothing otherwise: hashes stand)
        h.add(std::string("proxy")), h.add(static_cast<int>(p->shape));
        h.add(p->min), h.add(p->max), h.add(p->center), h.add(p->radius), h.add(p->capture);
    }
}

}  // namespace

std::uint64_t scene_content_hash(const SceneDesc& scene) {
    Fnv1a h;
    h.add(std::string("footprint scene v1"));
    h.add(scene.width), h.add(scene.height);
    add_camera(h, scene.camera);
    h.add(scene.camera_path.size());
    for (const CameraKeyframe& k : scene.camera_path) h.add(k.time), add_camera(h, k.camera);
    h.add(scene.environment.has_value());
    if (scene.environment) add_environment(h, *scene.environment);
    if (!scene.local_environments.empty()) {  // (nothing otherwise: hashes stand)
        h.add(std::string("local_environments")), h.add(scene.local_environments.size());
        for (const EnvironmentDesc& e : scene.local_environments) add_environment(h, e);
    }
    h.add(scene.background);
    h.add(scene.lights.size());
    for (const LightDesc& l : scene.lights) {
        h.add(static_cast<int>(l.type)), h.add(l.direction), h.add(l.position), h.add(l.color);
        h.add(l.shadows ? 1 : 0);
    }
    h.add(scene.objects.size());
    for (const ObjectDesc& o : scene.objects) {
        add_shape(h, o.shape);
        add_material(h, o.material);
    }
    return h.value();
}

std::string hash_hex(std::uint64_t hash) {
    char buffer[17];
    std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(hash));
    return buffer;
}

}  // namespace footprint
