#include "scene/scene_file.h"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <climits>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/suggest.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using Keys = std::vector<std::string_view>;

// Thrown inside the parser, turned into an Error by parse_scene (never escapes this file).
struct Failure {
    std::string message;
};
// A key given twice in one object (thrown by KeyTracker while nlohmann parses).
struct DuplicateKey {
    std::string path;
};

std::string quoted(const std::string& s) {
    return "'" + s + "'";
}

std::string member(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
}
std::string element(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i) + "]";
}

std::string format_number(double v) {
    std::ostringstream out;
    out.precision(10);
    out << v;
    return out.str();
}

// "a string", "an array of 2 elements", … for "expected X, got <this>".
std::string describe(const json& j) {
    switch (j.type()) {
        case json::value_t::null:
            return "null";
        case json::value_t::object:
            return "an object";
        case json::value_t::array:
            return "an array of " + std::to_string(j.size()) +
                   (j.size() == 1 ? " element" : " elements");
        case json::value_t::string:
            return "a string";
        case json::value_t::boolean:
            return "a boolean";
        case json::value_t::number_integer:
        case json::value_t::number_unsigned:
        case json::value_t::number_float:
            return "a number";
        default:
            return std::string("a ") + j.type_name();
    }
}

std::string join_names(Keys names, const char* last_separator) {
    std::string out;
    std::size_t i = 0;
    for (std::string_view name : names) {
        if (i > 0) out += (i + 1 == names.size()) ? last_separator : ", ";
        out += name;
        ++i;
    }
    return out;
}

// " (did you mean 'x'?)" for the closest candidate (core/suggest.h), otherwise
// " (expected one of: a, b, c)".
std::string suggest(std::string_view word, Keys candidates) {
    if (const auto best = closest_name(word, candidates))
        return " (did you mean " + quoted(std::string(*best)) + "?)";
    return " (expected one of: " + join_names(candidates, ", ") + ")";
}

bool contains(Keys keys, std::string_view key) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
}

std::string lowercase(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// The key path of the value being parsed, tracked through nlohmann's parser callback: rejects
// duplicate keys (nlohmann would silently keep the last) and names the key of a number that
// overflows.
class KeyTracker {
  public:
    // Always true (nothing is filtered out); throws DuplicateKey on a duplicate key.
    bool event(json::parse_event_t event, const json& parsed) {
        switch (event) {
            case json::parse_event_t::object_start:
                frames_.push_back({false, 0, {}, {}});
                break;
            case json::parse_event_t::array_start:
                frames_.push_back({true, 0, {}, {}});
                break;
            case json::parse_event_t::key: {
                Frame& top = frames_.back();
                top.key = parsed.get<std::string>();
                if (!top.keys.insert(top.key).second) throw DuplicateKey{path()};
                break;
            }
            case json::parse_event_t::object_end:
            case json::parse_event_t::array_end:
                frames_.pop_back();
                element_done();
                break;
            case json::parse_event_t::value:
                element_done();
                break;
        }
        return true;
    }
    // The path of the value being read ("" at the top level).
    std::string path() const {
        std::string out;
        for (const Frame& f : frames_) out = f.array ? element(out, f.index) : member(out, f.key);
        return out;
    }

  private:
    struct Frame {
        bool array;
        std::size_t index;
        std::string key;
        std::set<std::string> keys;
    };
    void element_done() {
        if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    }
    std::vector<Frame> frames_;
};

// "line L, column C" of the 0-based byte offset `pos` (clamped to the text).
std::string line_column(std::string_view text, std::size_t pos) {
    pos = std::min(pos, text.size());
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(
                                     text.begin(), text.begin() + static_cast<long>(pos), '\n'));
    const std::size_t newline = pos == 0 ? std::string_view::npos : text.rfind('\n', pos - 1);
    const std::size_t column = newline == std::string_view::npos ? pos + 1 : pos - newline;
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann's message without its "[json.exception.…] parse error at line L, column C: " prefix.
std::string parse_error_reason(const std::string& what) {
    std::size_t start = what.find("] ");
    start = start == std::string::npos ? 0 : start + 2;
    const std::size_t column = what.find("column", start);
    if (column != std::string::npos) {
        const std::size_t colon = what.find(": ", column);
        if (colon != std::string::npos) return what.substr(colon + 2);
    }
    return what.substr(start);
}

class SceneParser {
  public:
    SceneParser(const fs::path& file, const SceneParseOptions& options)
        : file_(file), base_dir_(file.parent_path()), options_(options) {}

    SceneDesc parse(const json& root) {
        if (!root.is_object())
            fail("", "expected a JSON object at the top level, got " + describe(root));
        check_keys(root, "",
                   {"image", "camera", "camera_path", "environment", "local_environments",
                    "background", "lights", "objects"});
        SceneDesc scene;
        scene.source = file_;
        if (const json* image = find(root, "image")) parse_image(*image, "image", scene);
        parse_camera(require(root, "", "camera"), "camera", scene.camera);
        if (const json* path = find(root, "camera_path"))
            scene.camera_path = parse_camera_path(*path, "camera_path", scene.camera);
        if (const json* env = find(root, "environment"))
            scene.environment = parse_environment(*env, "environment");
        if (const json* locals = find(root, "local_environments")) {
            expect_array(*locals, "local_environments");
            for (std::size_t i = 0; i < locals->size(); ++i) {
                const std::string path = element("local_environments", i);
                const json& local = (*locals)[i];
                expect_object(local, path);
                require(local, path, "proxy");
                scene.local_environments.push_back(parse_environment(local, path));
            }
        }
        if (const json* background = find(root, "background"))
            scene.background = color(*background, "background");
        if (const json* lights = find(root, "lights")) {
            expect_array(*lights, "lights");
            for (std::size_t i = 0; i < lights->size(); ++i)
                scene.lights.push_back(parse_light((*lights)[i], element("lights", i)));
        }
        const json& objects = require(root, "", "objects");
        expect_array(objects, "objects");
        for (std::size_t i = 0; i < objects.size(); ++i)
            scene.objects.push_back(parse_object(objects[i], element("objects", i)));
        return scene;
    }

  private:
    [[noreturn]] void fail(const std::string& path, const std::string& what) const {
        throw Failure{file_.string() + ": " + (path.empty() ? "" : path + ": ") + what};
    }

    // ---- Structure.

    static const json* find(const json& object, std::string_view key) {
        const auto it = object.find(std::string(key));
        return it == object.end() ? nullptr : &*it;
    }
    const json& require(const json& object, const std::string& path, std::string_view key) const {
        const json* value = find(object, key);
        if (!value) fail(member(path, key), "required key is missing");
        return *value;
    }
    void expect_object(const json& j, const std::string& path) const {
        if (!j.is_object()) fail(path, "expected an object, got " + describe(j));
    }
    void expect_array(const json& j, const std::string& path) const {
        if (!j.is_array()) fail(path, "expected an array, got " + describe(j));
    }
    // `j` must be an object whose keys are all in `keys`.
    void check_keys(const json& j, const std::string& path, Keys keys) const {
        expect_object(j, path);
        for (const auto& item : j.items())
            if (!contains(keys, item.key()))
                fail(member(path, item.key()), "unknown key" + suggest(item.key(), keys));
    }

    // ---- Values.

    std::string string(const json& j, const std::string& path) const {
        if (!j.is_string()) fail(path, "expected a string, got " + describe(j));
        return j.get<std::string>();
    }
    bool boolean(const json& j, const std::string& path) const {
        if (!j.is_boolean()) fail(path, "expected true or false, got " + describe(j));
        return j.get<bool>();
    }
    double number(const json& j, const std::string& path) const {
        if (!j.is_number()) fail(path, "expected a number, got " + describe(j));
        const double v = j.get<double>();
        if (!std::isfinite(v)) fail(path, "must be finite");
        return v;
    }
    double positive(const json& j, const std::string& path) const {
        const double v = number(j, path);
        if (!(v > 0)) fail(path, "must be > 0, got " + format_number(v));
        return v;
    }
    static float narrow(double v) { return static_cast<float>(v); }
    // A float field: finite in float too.
    float single(const json& j, const std::string& path) const {
        const double v = number(j, path);
        if (std::abs(v) > FLT_MAX) fail(path, "is too large (" + format_number(v) + ")");
        return narrow(v);
    }
    float non_negative(const json& j, const std::string& path) const {
        const float v = single(j, path);
        if (!(v >= 0)) fail(path, "must be >= 0, got " + format_number(v));
        return v;
    }
    int integer(const json& j, const std::string& path, int lo, int hi) const {
        const double v = number(j, path);
        if (v != std::floor(v)) fail(path, "expected an integer, got " + format_number(v));
        if (v < lo || v > hi)
            fail(path, "must be in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " +
                           format_number(v));
        return static_cast<int>(v);
    }
    Vec3d vec3(const json& j, const std::string& path) const {
        if (!j.is_array() || j.size() != 3)
            fail(path, "expected an array of 3 numbers, got " + describe(j));
        return {number(j[0], element(path, 0)), number(j[1], element(path, 1)),
                number(j[2], element(path, 2))};
    }
    Vec3d nonzero_vec3(const json& j, const std::string& path) const {
        const Vec3d v = vec3(j, path);
        if (v.x == 0 && v.y == 0 && v.z == 0) fail(path, "must be nonzero");
        return v;
    }
    Vec3 color(const json& j, const std::string& path) const {
        if (!j.is_array() || j.size() != 3)
            fail(path, "expected an array of 3 numbers [r, g, b], got " + describe(j));
        return {non_negative(j[0], element(path, 0)), non_negative(j[1], element(path, 1)),
                non_negative(j[2], element(path, 2))};
    }
    // A file name, resolved against the scene file's folder, checked for existence.
    fs::path file(const json& j, const std::string& path) const {
        const std::string name = string(j, path);
        if (name.empty()) fail(path, "expected a file name, got an empty string");
        const fs::path given(name);
        const fs::path resolved =
            (given.is_absolute() ? given : base_dir_ / given).lexically_normal();
        if (options_.check_files) {
            std::error_code error;
            const fs::file_status status = fs::status(resolved, error);
            fs::path absolute = fs::absolute(resolved, error);
            if (error) absolute = resolved;
            const std::string where = " (resolved to " + quoted(absolute.string()) + ")";
            if (!fs::exists(status)) fail(path, "file " + quoted(name) + " not found" + where);
            if (fs::is_directory(status))
                fail(path, "file " + quoted(name) + " is a directory" + where);
        }
        return resolved;
    }
    ImageSource image_file(const json& j, const std::string& path) const {
        ImageSource source;
        source.file = file(j, path);
        return source;
    }

    // ---- Sections.

    void parse_image(const json& j, const std::string& path, SceneDesc& scene) const {
        check_keys(j, path, {"width", "height"});
        if (const json* w = find(j, "width"))
            scene.width = integer(*w, member(path, "width"), 1, 16384);
        if (const json* h = find(j, "height"))
            scene.height = integer(*h, member(path, "height"), 1, 16384);
    }

    // Keyframes [{time, position, look_at, up, fov_y_deg}, …]: each key defaults to the scene's
    // camera, `time` to the keyframe's index; times must increase.
    std::vector<CameraKeyframe> parse_camera_path(const json& j, const std::string& path,
                                                  const CameraDesc& base) const {
        expect_array(j, path);
        if (j.size() < 2) fail(path, "needs at least 2 keyframes, got " + std::to_string(j.size()));
        std::vector<CameraKeyframe> keys;
        for (std::size_t i = 0; i < j.size(); ++i) {
            const std::string key_path = element(path, i);
            expect_object(j[i], key_path);
            CameraKeyframe key;
            key.time = static_cast<double>(i);
            key.camera = base;
            json camera = j[i];
            if (const json* t = find(j[i], "time")) {
                key.time = number(*t, member(key_path, "time"));
                camera.erase("time");
            }
            parse_camera(camera, key_path, key.camera, true);
            if (!keys.empty() && !(key.time > keys.back().time)) {
                fail(member(key_path, "time"), "must be greater than the previous keyframe's (" +
                                                   format_number(keys.back().time) + "), got " +
                                                   format_number(key.time));
            }
            keys.push_back(key);
        }
        return keys;
    }

    void parse_camera(const json& j, const std::string& path, CameraDesc& camera,
                      bool keyframe = false) const {
        if (keyframe) {
            check_keys(j, path, {"position", "look_at", "up", "fov_y_deg", "time"});
        } else {
            check_keys(j, path, {"position", "look_at", "up", "fov_y_deg"});
        }
        if (const json* v = find(j, "position"))
            camera.position = vec3(*v, member(path, "position"));
        if (const json* v = find(j, "look_at")) camera.look_at = vec3(*v, member(path, "look_at"));
        if (const json* v = find(j, "up")) camera.up = nonzero_vec3(*v, member(path, "up"));
        if (const json* v = find(j, "fov_y_deg")) {
            camera.fov_y_deg = number(*v, member(path, "fov_y_deg"));
            if (!(camera.fov_y_deg > 0 && camera.fov_y_deg < 180))
                fail(member(path, "fov_y_deg"),
                     "must be in (0, 180) degrees, got " + format_number(camera.fov_y_deg));
        }
        const Vec3d& p = camera.position;
        const Vec3d& a = camera.look_at;
        if (p.x == a.x && p.y == a.y && p.z == a.z)
            fail(member(path, "look_at"), "equals camera.position (no view direction)");
        Vec3d view = normalize(a * 0.5 - p * 0.5);  // halved: no overflow
        if (view.x == 0 && view.y == 0 && view.z == 0) view = normalize(a - p);
        if (length(cross(normalize(camera.up), view)) < 1e-6)
            fail(member(path, "up"), "is parallel to the view direction (look_at - position)");
    }

    EnvironmentDesc parse_environment(const json& j, const std::string& path) const {
        check_keys(j, path, {"file", "layout", "rotation_deg", "intensity", "non_finite", "proxy"});
        EnvironmentDesc env;
        const std::string file_path = member(path, "file");
        const json& files = require(j, path, "file");
        if (files.is_string()) {
            env.images.push_back(image_file(files, file_path));
        } else if (files.is_array() && (files.size() == 2 || files.size() == 6)) {
            for (std::size_t i = 0; i < files.size(); ++i)
                env.images.push_back(image_file(files[i], element(file_path, i)));
        } else {
            fail(file_path,
                 "expected a file name or an array of 2 (paraboloid front, back) or 6 (cube faces "
                 "+X -X +Y -Y +Z -Z) file names, got " +
                     describe(files));
        }
        const std::size_t n = env.images.size();
        env.layout = n == 1 ? EnvLayout::latlong : n == 2 ? EnvLayout::paraboloid : EnvLayout::cube;
        env.detect_layout = n == 1 && !find(j, "layout");
        if (const json* layout = find(j, "layout")) {
            const std::string layout_path = member(path, "layout");
            const std::string name = string(*layout, layout_path);
            const std::optional<EnvLayout> parsed = parse_env_layout(name);
            if (!parsed)
                fail(layout_path, "unknown layout " + quoted(name) +
                                      suggest(name, {"latlong", "cube", "sphere", "paraboloid"}));
            const bool fits = n == 1   ? true
                              : n == 2 ? *parsed == EnvLayout::paraboloid
                                       : *parsed == EnvLayout::cube;
            if (!fits)
                fail(layout_path, quoted(name) + " does not take " + std::to_string(n) +
                                      " files (2: paraboloid, 6: cube)");
            env.layout = *parsed;
        }
        if (const json* v = find(j, "rotation_deg"))
            env.rotation_deg = vec3(*v, member(path, "rotation_deg"));
        if (const json* v = find(j, "intensity"))
            env.intensity = non_negative(*v, member(path, "intensity"));
        if (const json* v = find(j, "non_finite"))
            env.non_finite = parse_non_finite(*v, member(path, "non_finite"));
        if (const json* v = find(j, "proxy")) env.proxy = parse_proxy(*v, member(path, "proxy"));
        return env;
    }

    // {"box": {"min": [x, y, z], "max": [x, y, z]}} or {"sphere": {"center": [x, y, z], "radius":
    // R}}, and "capture": [x, y, z] (default: the box's or the sphere's centre).
    EnvProxy parse_proxy(const json& j, const std::string& path) const {
        check_keys(j, path, {"box", "sphere", "capture"});
        const json* box = find(j, "box");
        const json* sphere = find(j, "sphere");
        if ((box != nullptr) == (sphere != nullptr))
            fail(path, "needs exactly one of box and sphere");
        auto point = [&](const json& v, const std::string& at) {
            const Vec3d d = vec3(v, at);
            return Vec3{static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z)};
        };
        EnvProxy proxy;
        if (box) {
            const std::string box_path = member(path, "box");
            check_keys(*box, box_path, {"min", "max"});
            proxy.shape = EnvProxy::Shape::box;
            proxy.min = point(require(*box, box_path, "min"), member(box_path, "min"));
            proxy.max = point(require(*box, box_path, "max"), member(box_path, "max"));
            if (!(proxy.min.x < proxy.max.x && proxy.min.y < proxy.max.y &&
                  proxy.min.z < proxy.max.z))
                fail(member(box_path, "max"), "must exceed min in x, y and z");
            proxy.capture = 0.5f * (proxy.min + proxy.max);
        } else {
            const std::string sphere_path = member(path, "sphere");
            check_keys(*sphere, sphere_path, {"center", "radius"});
            proxy.shape = EnvProxy::Shape::sphere;
            proxy.center =
                point(require(*sphere, sphere_path, "center"), member(sphere_path, "center"));
            proxy.radius = static_cast<float>(
                positive(require(*sphere, sphere_path, "radius"), member(sphere_path, "radius")));
            proxy.capture = proxy.center;
        }
        if (const json* v = find(j, "capture")) proxy.capture = point(*v, member(path, "capture"));
        return proxy;
    }

    LightDesc parse_light(const json& j, const std::string& path) const {
        expect_object(j, path);
        LightDesc light;
        if (const json* type = find(j, "type")) {
            const std::string name = string(*type, member(path, "type"));
            if (name == "directional") {
                light.type = LightType::directional;
            } else if (name == "point") {
                light.type = LightType::point;
            } else {
                fail(member(path, "type"), "unknown light type " + quoted(name) +
                                               suggest(name, {"directional", "point"}));
            }
        }
        const bool directional = light.type == LightType::directional;
        for (const auto& item : j.items()) {
            const std::string& key = item.key();
            if (key == (directional ? "position" : "direction"))
                fail(member(path, key),
                     std::string("not a key of a ") + (directional ? "directional" : "point") +
                         " light (it takes: type, " + (directional ? "direction" : "position") +
                         ", color, shadows)");
        }
        check_keys(j, path, {"type", "direction", "position", "color", "shadows"});
        if (const json* v = find(j, "direction"))
            light.direction = nonzero_vec3(*v, member(path, "direction"));
        if (const json* v = find(j, "position"))
            light.position = vec3(*v, member(path, "position"));
        if (const json* v = find(j, "color")) light.color = color(*v, member(path, "color"));
        if (const json* v = find(j, "shadows"))
            light.shadows = boolean(*v, member(path, "shadows"));
        return light;
    }

    ObjectDesc parse_object(const json& j, const std::string& path) const {
        expect_object(j, path);
        ObjectDesc object;
        if (const json* name = find(j, "name")) object.name = string(*name, member(path, "name"));
        const std::string shape_path = member(path, "shape");
        const std::string shape = string(require(j, path, "shape"), shape_path);
        static const Keys shapes = {"plane", "sphere",  "cylinder", "paraboloid",
                                    "torus", "terrain", "mesh"};
        if (!contains(shapes, shape))
            fail(shape_path, "unknown shape " + quoted(shape) + suggest(shape, shapes));
        check_object_keys(j, path, shape);
        // A glTF file's materials are metallic-roughness: its meshes take that model unless the
        // scene's material names another.
        const json* file_key = shape == "mesh" ? find(j, "file") : nullptr;
        const std::string extension =
            file_key && file_key->is_string()
                ? lowercase(fs::path(file_key->get<std::string>()).extension().string())
                : "";
        const MeshFileKind kind = shape != "mesh"                               ? MeshFileKind::none
                                  : extension == ".gltf" || extension == ".glb" ? MeshFileKind::gltf
                                                                                : MeshFileKind::obj;
        if (kind == MeshFileKind::gltf) {
            object.material.model = MaterialDesc::Model::metallic_roughness;
            object.material.highlight = MaterialDesc::Highlight::ggx;
        }
        if (const json* material = find(j, "material"))
            object.material = parse_material(*material, member(path, "material"), kind);

        auto get = [&](std::string_view key) { return find(j, key); };
        auto at = [&](std::string_view key) { return member(path, key); };
        if (shape == "plane") {
            PlaneShape s;
            if (const json* v = get("center")) s.center = vec3(*v, at("center"));
            if (const json* v = get("normal")) s.normal = nonzero_vec3(*v, at("normal"));
            if (const json* v = get("size")) {
                if (v->is_string() && v->get<std::string>() == "infinite") {
                    s.infinite = true;
                } else if (v->is_array() && v->size() == 2) {
                    s.size = {positive((*v)[0], element(at("size"), 0)),
                              positive((*v)[1], element(at("size"), 1))};
                } else {
                    fail(at("size"),
                         "expected [width, height] or \"infinite\", got " +
                             (v->is_string() ? quoted(v->get<std::string>()) : describe(*v)));
                }
            }
            if (const json* v = get("uv_scale")) s.uv_scale = positive(*v, at("uv_scale"));
            object.shape = s;
        } else if (shape == "sphere") {
            SphereShape s;
            if (const json* v = get("center")) s.center = vec3(*v, at("center"));
            if (const json* v = get("radius")) s.radius = positive(*v, at("radius"));
            object.shape = s;
        } else if (shape == "cylinder") {
            CylinderShape s;
            if (const json* v = get("center")) s.center = vec3(*v, at("center"));
            if (const json* v = get("axis")) s.axis = nonzero_vec3(*v, at("axis"));
            if (const json* v = get("radius")) s.radius = positive(*v, at("radius"));
            if (const json* v = get("height")) s.height = positive(*v, at("height"));
            object.shape = s;
        } else if (shape == "paraboloid") {
            ParaboloidShape s;
            if (const json* v = get("focus")) s.focus = vec3(*v, at("focus"));
            if (const json* v = get("axis")) s.axis = nonzero_vec3(*v, at("axis"));
            if (const json* v = get("focal_length"))
                s.focal_length = positive(*v, at("focal_length"));
            if (const json* v = get("radius")) s.radius = positive(*v, at("radius"));
            object.shape = s;
        } else if (shape == "torus") {
            TorusShape s;
            if (const json* v = get("center")) s.center = vec3(*v, at("center"));
            if (const json* v = get("axis")) s.axis = nonzero_vec3(*v, at("axis"));
            if (const json* v = get("major_radius"))
                s.major_radius = positive(*v, at("major_radius"));
            if (const json* v = get("minor_radius"))
                s.minor_radius = positive(*v, at("minor_radius"));
            if (!(s.minor_radius < s.major_radius))
                fail(at("minor_radius"), "must be less than major_radius (" +
                                             format_number(s.minor_radius) +
                                             " >= " + format_number(s.major_radius) + ")");
            object.shape = s;
        } else if (shape == "terrain") {
            object.shape = parse_terrain(j, path);
        } else {  // mesh
            MeshShape s;
            const std::string file_path = at("file");
            const json& file_value = require(j, path, "file");
            const std::string name = string(file_value, file_path);
            const std::string extension = lowercase(fs::path(name).extension().string());
            if (extension != ".obj" && extension != ".gltf" && extension != ".glb")
                fail(file_path, "unsupported mesh format " +
                                    quoted(extension.empty() ? name : extension) +
                                    " (expected .obj, .gltf or .glb)");
            s.file = file(file_value, file_path);
            if (const json* v = get("transform"))
                s.transform = parse_transform(*v, at("transform"));
            object.shape = s;
        }
        return object;
    }

    // The object's keys: name, shape, material and those of its shape.
    void check_object_keys(const json& j, const std::string& path, const std::string& shape) const {
        struct ShapeKeys {
            std::string_view shape;
            Keys keys;
        };
        static const ShapeKeys table[] = {
            {"plane", {"name", "shape", "material", "center", "normal", "size", "uv_scale"}},
            {"sphere", {"name", "shape", "material", "center", "radius"}},
            {"cylinder", {"name", "shape", "material", "center", "axis", "radius", "height"}},
            {"paraboloid",
             {"name", "shape", "material", "focus", "axis", "focal_length", "radius"}},
            {"torus",
             {"name", "shape", "material", "center", "axis", "major_radius", "minor_radius"}},
            {"terrain",
             {"name", "shape", "material", "center", "size", "subdivisions", "roughness", "height",
              "seed"}},
            {"mesh", {"name", "shape", "material", "file", "transform"}},
        };
        const ShapeKeys* own = nullptr;
        for (const ShapeKeys& entry : table)
            if (entry.shape == shape) own = &entry;
        for (const auto& item : j.items()) {
            const std::string& key = item.key();
            if (contains(own->keys, key)) continue;
            for (const ShapeKeys& other : table)
                if (contains(other.keys, key))
                    fail(member(path, key), "not a key of shape " + quoted(shape) +
                                                " (it takes: " + join_names(own->keys, ", ") + ")");
            fail(member(path, key), "unknown key" + suggest(key, own->keys));
        }
    }

    TerrainShape parse_terrain(const json& j, const std::string& path) const {
        auto at = [&](std::string_view key) { return member(path, key); };
        TerrainShape s;
        if (const json* v = find(j, "center")) s.center = vec3(*v, at("center"));
        if (const json* v = find(j, "size")) {
            if (!v->is_array() || v->size() != 2)
                fail(at("size"), "expected [width, depth], got " + describe(*v));
            s.size = {positive((*v)[0], element(at("size"), 0)),
                      positive((*v)[1], element(at("size"), 1))};
        }
        if (const json* v = find(j, "subdivisions"))
            s.subdivisions = integer(*v, at("subdivisions"), 1, kMaxTerrainSubdivisions);
        if (const json* v = find(j, "roughness")) {
            s.roughness = number(*v, at("roughness"));
            if (!(s.roughness > 0 && s.roughness <= 1))
                fail(at("roughness"),
                     "must be in (0, 1] (the Hurst exponent), got " + format_number(s.roughness));
        }
        if (const json* v = find(j, "height")) {
            s.height = number(*v, at("height"));
            if (!(s.height >= 0))
                fail(at("height"), "must be >= 0, got " + format_number(s.height));
        }
        if (const json* v = find(j, "seed"))
            s.seed = static_cast<std::uint32_t>(integer(*v, at("seed"), 0, INT_MAX));
        return s;
    }

    MeshTransform parse_transform(const json& j, const std::string& path) const {
        check_keys(j, path, {"translate", "rotate_deg", "scale"});
        MeshTransform t;
        if (const json* v = find(j, "translate")) t.translate = vec3(*v, member(path, "translate"));
        if (const json* v = find(j, "rotate_deg"))
            t.rotate_deg = vec3(*v, member(path, "rotate_deg"));
        if (const json* v = find(j, "scale")) {
            const std::string scale_path = member(path, "scale");
            if (v->is_number()) {
                const double s = number(*v, scale_path);
                if (s == 0) fail(scale_path, "must be nonzero");
                t.scale = {s, s, s};
            } else if (v->is_array() && v->size() == 3) {
                t.scale = vec3(*v, scale_path);
                for (std::size_t i = 0; i < 3; ++i)
                    if ((*v)[i].get<double>() == 0) fail(element(scale_path, i), "must be nonzero");
            } else {
                fail(scale_path, "expected a number or an array of 3 numbers, got " + describe(*v));
            }
        }
        return t;
    }

    // What a material's object is: a mesh's file may bring normal textures (both kinds) and, a
    // glTF's, metallic-roughness materials.
    enum class MeshFileKind { none, obj, gltf };

    MaterialDesc parse_material(const json& j, const std::string& path, MeshFileKind mesh) const {
        check_keys(j, path,
                   {"model", "base_color", "diffuse", "specular", "shininess", "highlight",
                    "roughness", "metallic", "metallic_roughness", "mirror", "fresnel_f0", "bump",
                    "micro_roughness", "invalid_normals", "non_finite", "environment_probe"});
        MaterialDesc m;
        auto at = [&](std::string_view key) { return member(path, key); };
        if (mesh == MeshFileKind::gltf) m.model = MaterialDesc::Model::metallic_roughness;
        if (const json* v = find(j, "model")) m.model = parse_model(*v, at("model"));
        const bool pbr = m.model == MaterialDesc::Model::metallic_roughness;
        if (pbr) m.highlight = MaterialDesc::Highlight::ggx;
        check_model_keys(j, path, m.model, mesh);
        if (const json* v = find(j, "base_color")) {
            if (v->is_string()) {
                m.base_color_map = image_file(*v, at("base_color"));
                m.base_color = {1, 1, 1};  // the texture as is
            } else if (v->is_array()) {
                m.base_color = color(*v, at("base_color"));
            } else if (v->is_object()) {
                if (pbr)
                    fail(at("base_color"),
                         "a procedural base colour is for the footprint model: its F0 and "
                         "diffuse colour would need the pattern texel by texel");
                m.base_color_procedural = parse_procedural(*v, at("base_color"));
                m.base_color = {1, 1, 1};  // the pattern's colours as they are
            } else {
                fail(at("base_color"),
                     "expected [r, g, b], a texture file name or {\"procedural\": ...}, got " +
                         describe(*v));
            }
        }
        if (const json* v = find(j, "diffuse")) m.diffuse = non_negative(*v, at("diffuse"));
        if (const json* v = find(j, "specular")) m.specular = non_negative(*v, at("specular"));
        if (const json* v = find(j, "shininess")) m.shininess = non_negative(*v, at("shininess"));
        if (const json* v = find(j, "highlight"))
            m.highlight = parse_highlight(*v, at("highlight"));
        if (pbr && m.highlight == MaterialDesc::Highlight::blinn_phong)
            fail(at("highlight"), "the metallic-roughness model's highlight is beckmann or ggx");
        if (const json* v = find(j, "roughness")) {
            // glTF's range is [0, 1]; the footprint model's microfacet highlight has no mirror.
            const double r = number(*v, at("roughness"));
            if (!((pbr ? r >= 0 : r > 0) && r <= 1))
                fail(at("roughness"), std::string("must be in ") + (pbr ? "[0, 1]" : "(0, 1]") +
                                          ", got " + format_number(r));
            m.roughness = narrow(r);
        }
        if (const json* v = find(j, "metallic")) {
            m.metallic = single(*v, at("metallic"));
            if (!(m.metallic >= 0 && m.metallic <= 1))
                fail(at("metallic"), "must be in [0, 1], got " + format_number(m.metallic));
        }
        if (const json* v = find(j, "metallic_roughness"))
            m.metallic_roughness_map = image_file(*v, at("metallic_roughness"));
        // Each highlight takes its own width: shininess (Blinn-Phong) or roughness (microfacet).
        const bool microfacet = m.highlight != MaterialDesc::Highlight::blinn_phong;
        if (!microfacet && find(j, "roughness"))
            fail(at("roughness"),
                 "is used only with \"highlight\": \"beckmann\" or \"ggx\" (blinn-phong, "
                 "the default, takes shininess)");
        if (microfacet && find(j, "shininess"))
            fail(at("shininess"), "is the Blinn-Phong exponent: the " +
                                      std::string(highlight_name(m.highlight)) +
                                      " highlight takes roughness");
        if (const json* v = find(j, "mirror")) m.mirror = non_negative(*v, at("mirror"));
        if (const json* v = find(j, "fresnel_f0")) {
            m.fresnel_f0 = single(*v, at("fresnel_f0"));
            if (!(m.fresnel_f0 >= 0 && m.fresnel_f0 <= 1))
                fail(at("fresnel_f0"), "must be in [0, 1], got " + format_number(m.fresnel_f0));
        }
        if (const json* v = find(j, "micro_roughness"))
            m.micro_roughness = non_negative(*v, at("micro_roughness"));
        if (const json* v = find(j, "environment_probe"))
            m.environment_probe = parse_probe(*v, at("environment_probe"));
        if (const json* v = find(j, "bump")) {
            m.bump = parse_bump(*v, at("bump"));
            if (pbr && m.bump.source == BumpDesc::Source::procedural)
                fail(at("bump"),
                     "a procedural bump is for the footprint model: the metallic-roughness "
                     "model's roughness lives in a map of slope moments");
        }
        if (const json* v = find(j, "invalid_normals"))
            m.invalid_normals = parse_invalid_normals(*v, at("invalid_normals"), m.bump,
                                                      mesh != MeshFileKind::none);
        if (const json* v = find(j, "non_finite")) {
            m.non_finite = parse_non_finite(*v, at("non_finite"));
            if (m.base_color_map.empty() && m.bump.source != BumpDesc::Source::height_map)
                fail(at("non_finite"),
                     "applies to the material's texture files: give base_color as a file or "
                     "bump.height_map (for a normal map's NaN texels: invalid_normals)");
        }
        return m;
    }

    // {"center": [x, y, z], "size": N, "layout": "cube"}: the only layout is the cube, whose faces
    // the renderer renders as six square views.
    EnvironmentProbeDesc parse_probe(const json& j, const std::string& path) const {
        expect_object(j, path);
        check_keys(j, path, {"center", "size", "layout"});
        EnvironmentProbeDesc probe;
        if (const json* v = find(j, "center")) probe.center = vec3(*v, member(path, "center"));
        if (const json* v = find(j, "size"))
            probe.size = integer(*v, member(path, "size"), 4, kMaxProbeSize);
        if (const json* v = find(j, "layout")) {
            const std::string name = string(*v, member(path, "layout"));
            if (name != "cube")
                fail(member(path, "layout"),
                     "a probe is a cube map, got " + quoted(name) + suggest(name, {"cube"}));
        }
        return probe;
    }

    // {"procedural": "noise" | "turbulence" | "marble" | "checker", "scale": S, "octaves": N,
    //  "colors": [[r, g, b], [r, g, b]]} (texture/procedural.h).
    ProceduralTexture parse_procedural(const json& j, const std::string& path) const {
        check_keys(j, path, {"procedural", "scale", "octaves", "colors"});
        ProceduralTexture t;
        const std::string pattern_path = member(path, "procedural");
        const std::string pattern = string(require(j, path, "procedural"), pattern_path);
        static const Keys patterns = {"noise", "turbulence", "marble", "checker"};
        if (!contains(patterns, pattern))
            fail(pattern_path, "unknown pattern " + quoted(pattern) + suggest(pattern, patterns));
        t.pattern = pattern == "noise"        ? ProceduralPattern::noise
                    : pattern == "turbulence" ? ProceduralPattern::turbulence
                    : pattern == "marble"     ? ProceduralPattern::marble
                                              : ProceduralPattern::checker;
        if (const json* v = find(j, "scale")) t.scale = positive(*v, member(path, "scale"));
        if (const json* v = find(j, "octaves"))
            t.octaves = integer(*v, member(path, "octaves"), 1, kMaxProceduralOctaves);
        if (const json* v = find(j, "colors")) {
            const std::string colors_path = member(path, "colors");
            if (!v->is_array() || v->size() != 2)
                fail(colors_path,
                     "expected two colours [[r, g, b], [r, g, b]], got " + describe(*v));
            t.colors = {color((*v)[0], element(colors_path, 0)),
                        color((*v)[1], element(colors_path, 1))};
        }
        return t;
    }

    // "footprint" or "metallic-roughness" (scene.h's MaterialDesc::Model).
    MaterialDesc::Model parse_model(const json& j, const std::string& path) const {
        const std::string name = string(j, path);
        if (name == "footprint") return MaterialDesc::Model::footprint;
        if (name == "metallic-roughness") return MaterialDesc::Model::metallic_roughness;
        fail(path,
             "unknown model " + quoted(name) + suggest(name, {"footprint", "metallic-roughness"}));
    }

    // Each model takes its own keys; a key of the other model says which one it belongs to. A glTF
    // mesh's metallic and roughness come from its file.
    void check_model_keys(const json& j, const std::string& path, MaterialDesc::Model model,
                          MeshFileKind mesh) const {
        static const Keys footprint_only = {"diffuse", "specular",   "shininess",
                                            "mirror",  "fresnel_f0", "micro_roughness"};
        const bool pbr = model == MaterialDesc::Model::metallic_roughness;
        const std::string why = mesh == MeshFileKind::gltf && !find(j, "model")
                                    ? " (a glTF mesh's default: its file's materials)"
                                    : "";
        for (const auto& item : j.items()) {
            const std::string& key = item.key();
            if (pbr && contains(footprint_only, key))
                fail(member(path, key),
                     "is a key of the footprint model; this material is metallic-roughness" + why +
                         ": it takes base_color, metallic and roughness, or give \"model\": " +
                         "\"footprint\"");
            const bool pbr_only = key == "metallic" || key == "metallic_roughness";
            if (!pbr && pbr_only)
                fail(member(path, key),
                     "is a key of the metallic-roughness model: give "
                     "\"model\": \"metallic-roughness\"");
            if (pbr && mesh == MeshFileKind::gltf && (pbr_only || key == "roughness"))
                fail(member(path, key),
                     "comes from the glTF file's materials (base_color "
                     "multiplies the file's colours; metallic and roughness "
                     "are the file's)");
        }
    }

    static constexpr std::string_view kHighlightNames[] = {"blinn-phong", "beckmann", "ggx"};
    static std::string_view highlight_name(MaterialDesc::Highlight h) {
        return kHighlightNames[static_cast<int>(h)];
    }

    // "blinn-phong" (the default), "beckmann" or "ggx" (scene.h's MaterialDesc::Highlight).
    MaterialDesc::Highlight parse_highlight(const json& j, const std::string& path) const {
        const std::string name = string(j, path);
        for (const MaterialDesc::Highlight h :
             {MaterialDesc::Highlight::blinn_phong, MaterialDesc::Highlight::beckmann,
              MaterialDesc::Highlight::ggx})
            if (name == highlight_name(h)) return h;
        const Keys names(std::begin(kHighlightNames), std::end(kHighlightNames));
        const std::optional<std::string_view> best = closest_name(name, names);
        fail(path, "unknown highlight " + quoted(name) + " (" +
                       (best ? "did you mean " + quoted(std::string(*best)) + "? " : "") +
                       "expected one of: " + join_names(names, ", ") + ")");
    }

    // "error" (the default: a NaN or infinite texel stops the render, named) or "repair"
    // (image/image_io.h's NonFinitePolicy::repair).
    NonFinitePolicy parse_non_finite(const json& j, const std::string& path) const {
        const std::string name = string(j, path);
        if (name == "repair") return NonFinitePolicy::repair;
        if (name != "error")
            fail(path, "unknown policy " + quoted(name) + suggest(name, {"error", "repair"}));
        return NonFinitePolicy::refuse;
    }

    // "error" (the default: an invalid normal map texel stops the render, named) or "clamp"
    // (bump/slope_map.h's InvalidNormalPolicy); only where the material has a normal map.
    InvalidNormalPolicy parse_invalid_normals(const json& j, const std::string& path,
                                              const BumpDesc& bump, bool mesh) const {
        const std::string name = string(j, path);
        InvalidNormalPolicy policy = InvalidNormalPolicy::error;
        if (name == "clamp") {
            policy = InvalidNormalPolicy::clamp;
        } else if (name != "error") {
            fail(path, "unknown policy " + quoted(name) + suggest(name, {"error", "clamp"}));
        }
        if (bump.source == BumpDesc::Source::height_map)
            fail(path, "applies to normal maps, not to bump.height_map");
        if (bump.source == BumpDesc::Source::none && !mesh)
            fail(path,
                 "applies to normal maps: give bump.normal_map (or use a mesh whose file "
                 "has normal textures)");
        return policy;
    }

    BumpDesc parse_bump(const json& j, const std::string& path) const {
        if (find(j, "procedural")) return parse_procedural_bump(j, path);
        check_keys(j, path,
                   {"height_map", "normal_map", "strength", "frame", "main_direction", "parallax"});
        BumpDesc bump;
        const json* height = find(j, "height_map");
        const json* normal = find(j, "normal_map");
        if (height && normal) fail(path, "has both height_map and normal_map (give exactly one)");
        if (!height && !normal) fail(path, "needs a height_map, a normal_map or a procedural");
        if (height) {
            bump.source = BumpDesc::Source::height_map;
            bump.map = image_file(*height, member(path, "height_map"));
        } else {
            bump.source = BumpDesc::Source::normal_map;
            bump.map = image_file(*normal, member(path, "normal_map"));
        }
        if (const json* v = find(j, "strength"))
            bump.strength = single(*v, member(path, "strength"));
        if (const json* v = find(j, "frame")) {
            const std::string frame_path = member(path, "frame");
            const std::string name = string(*v, frame_path);
            if (name == "natural") {
                bump.frame = BumpFrame::natural;
            } else if (name == "normalized") {
                bump.frame = BumpFrame::normalized;
            } else if (name == "main_direction") {
                bump.frame = BumpFrame::main_direction;
            } else {
                fail(frame_path, "unknown frame " + quoted(name) +
                                     suggest(name, {"natural", "normalized", "main_direction"}));
            }
        }
        if (const json* v = find(j, "main_direction")) {
            const std::string direction_path = member(path, "main_direction");
            if (bump.frame != BumpFrame::main_direction)
                fail(direction_path, "is used only with frame \"main_direction\"");
            bump.main_direction = vec3(*v, direction_path);  // zero: the surface's ∂p/∂v
        }
        if (const json* v = find(j, "parallax")) {
            const std::string parallax_path = member(path, "parallax");
            if (bump.source != BumpDesc::Source::height_map)
                fail(parallax_path, "needs a height_map (a normal map has no heights to march)");
            bump.parallax = parse_parallax(*v, parallax_path);
        }
        return bump;
    }

    // {"depth": D, "steps": N} (texture/parallax.h).
    ParallaxOptions parse_parallax(const json& j, const std::string& path) const {
        check_keys(j, path, {"depth", "steps"});
        ParallaxOptions parallax;
        parallax.depth =
            static_cast<float>(positive(require(j, path, "depth"), member(path, "depth")));
        if (const json* v = find(j, "steps"))
            parallax.steps = integer(*v, member(path, "steps"), 1, kMaxParallaxSteps);
        return parallax;
    }

    // {"procedural": "noise" | "turbulence" | "marble", "scale": S, "octaves": N, "strength": A}:
    // the pattern's value as a height field of A world units; its slopes are the height's gradient.
    BumpDesc parse_procedural_bump(const json& j, const std::string& path) const {
        check_keys(j, path, {"procedural", "scale", "octaves", "strength"});
        json pattern = j;
        pattern.erase("strength");
        BumpDesc bump;
        bump.source = BumpDesc::Source::procedural;
        bump.procedural = parse_procedural(pattern, path);
        if (bump.procedural.pattern == ProceduralPattern::checker)
            fail(member(path, "procedural"),
                 "a checker is a sum of steps and has no slopes: give noise, turbulence or marble");
        if (const json* v = find(j, "strength"))
            bump.strength = single(*v, member(path, "strength"));
        bump.frame = BumpFrame::main_direction;  // any orthonormal frame: the gradient is 3-D
        return bump;
    }

    fs::path file_;
    fs::path base_dir_;
    SceneParseOptions options_;
};

}  // namespace

Result<SceneDesc> parse_scene(std::string_view json_text, const fs::path& file,
                              const SceneParseOptions& options) {
    KeyTracker tracker;
    try {
        const json root = json::parse(json_text.begin(), json_text.end(),
                                      [&tracker](int, json::parse_event_t event, json& parsed) {
                                          return tracker.event(event, parsed);
                                      });
        return SceneParser(file, options).parse(root);
    } catch (const Failure& failure) {
        return Error{failure.message};
    } catch (const DuplicateKey& duplicate) {
        return Error{file.string() + ": " + duplicate.path + ": duplicate key"};
    } catch (const json::parse_error& e) {
        const std::size_t pos = e.byte > 0 ? e.byte - 1 : 0;
        return Error{file.string() + ": " + line_column(json_text, pos) +
                     ": invalid JSON: " + parse_error_reason(e.what())};
    } catch (const json::out_of_range& e) {  // a number that overflows a double (1e999)
        const std::string path = tracker.path();
        return Error{file.string() + ": " + (path.empty() ? "" : path + ": ") +
                     "number out of range (" + parse_error_reason(e.what()) + ")"};
    } catch (const json::exception& e) {
        return Error{file.string() + ": invalid JSON: " + parse_error_reason(e.what())};
    }
}

Result<SceneDesc> load_scene_file(const fs::path& file, const SceneParseOptions& options) {
    std::error_code error;
    const fs::file_status status = fs::status(file, error);
    if (!fs::exists(status)) return Error{file.string() + ": scene file not found"};
    if (fs::is_directory(status))
        return Error{file.string() + ": is a directory, not a scene file"};
    std::ifstream in(file, std::ios::binary);
    if (!in) return Error{file.string() + ": cannot open the scene file"};
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) return Error{file.string() + ": cannot read the scene file"};
    return parse_scene(text, file, options);
}

}  // namespace footprint
