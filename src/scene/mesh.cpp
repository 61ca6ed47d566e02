// scene/mesh.cpp — OBJ (tinyobjloader) and glTF 2.0 (tinygltf) loading into TriangleMesh.
#include "scene/mesh.h"

#include <tiny_gltf.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>

#include "image/color.h"
#include "image/image_io.h"
#include "math/mat3.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

std::string quoted(const fs::path& file) {
    return "'" + file.string() + "'";
}

Error file_error(const fs::path& file, const std::string& cause) {
    return Error{"cannot read " + quoted(file) + ": " + cause};
}

// Drops trailing newlines and joins lines of a loader's message.
std::string tidy(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}

// ---------------------------------------------------------------------------------------------
// Affine transforms (double precision)

struct Affine {
    double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Vec3d t{0, 0, 0};

    Vec3d linear(Vec3d v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    Vec3d point(Vec3d p) const { return linear(p) + t; }
    double determinant() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    // The inverse transpose up to a positive factor: cofactor matrix × sign(det). Normals are
    // renormalised afterwards, so the factor 1/|det| is not needed (and no division by a tiny
    // determinant happens).
    Affine normal_matrix() const {
        Affine c;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                c.m[i][j] = m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1];
            }
        const double s = determinant() < 0 ? -1.0 : 1.0;
        for (auto& row : c.m)
            for (double& x : row) x *= s;
        c.t = {};
        return c;
    }
};

Affine operator*(const Affine& a, const Affine& b) {
    Affine r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
    r.t = a.linear(b.t) + a.t;
    return r;
}

Affine user_affine(const MeshTransform& transform) {
    const Mat3 rot = rotation_xyz_degrees(static_cast<float>(transform.rotate_deg.x),
                                          static_cast<float>(transform.rotate_deg.y),
                                          static_cast<float>(transform.rotate_deg.z));
    const double s[3] = {transform.scale.x, transform.scale.y, transform.scale.z};
    Affine a;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a.m[i][j] = static_cast<double>(rot.m[i][j]) * s[j];
    a.t = transform.translate;
    return a;
}

// Transforms a mesh built in file space into world space and validates it.
Status finish_mesh(TriangleMesh& mesh, const Affine& xf, const fs::path& file) {
    const std::size_t n = mesh.positions.size();
    for (const auto& tri : mesh.triangles)
        for (std::uint32_t i : tri)
            if (i >= n)
                return file_error(file, "index " + std::to_string(i) + " out of range (" +
                                            std::to_string(n) + " vertices) in '" + mesh.name +
                                            "'");
    for (Vec3d& p : mesh.positions) {
        if (!is_finite(p))
            return file_error(file, "non-finite vertex position in '" + mesh.name + "'");
        p = xf.point(p);
        if (!is_finite(p))
            return file_error(
                file, "vertex position overflows after the transform in '" + mesh.name + "'");
    }
    const Affine nm = xf.normal_matrix();
    for (Vec3d& nrm : mesh.normals) nrm = normalize(nm.linear(nrm));
    const bool mirror = xf.determinant() < 0;
    for (MeshTangent& tg : mesh.tangents) {
        tg.xyz = normalize(xf.linear(tg.xyz));
        const double w = tg.w < 0 ? -1.0 : 1.0;
        tg.w = mirror ? -w : w;
    }
    for (Vec2d& uv : mesh.uvs)
        if (!is_finite(uv)) uv = {0, 0};
    if (mirror)
        for (auto& tri : mesh.triangles) std::swap(tri[1], tri[2]);
    return {};
}

Status check_transform(const MeshTransform& t, const fs::path& file) {
    const Vec3d s = t.scale;
    if (!is_finite(s) || s.x == 0 || s.y == 0 || s.z == 0)
        return Error{"cannot load mesh " + quoted(file) +
                     ": the transform's scale must be finite and nonzero"};
    if (!is_finite(t.translate) || !is_finite(t.rotate_deg))
        return Error{"cannot load mesh " + quoted(file) + ": the transform is not finite"};
    return {};
}

// ---------------------------------------------------------------------------------------------
// OBJ

Result<std::shared_ptr<const Image>> load_texture(const fs::path& mesh_file,
                                                  const std::string& name, ColorEncoding enc) {
    const fs::path path = mesh_file.parent_path() / name;
    ImageLoadOptions options;
    options.encoding = enc;
    Result<Image> img = load_image(path, options);
    if (!img)
        return file_error(mesh_file, "cannot load texture '" + name + "': " + img.error().message);
    return std::shared_ptr<const Image>(std::make_shared<Image>(std::move(img).value()));
}

// A value as a message shows it: its shortest round-trip form (1.5, not 1.500000).
std::string number(double value) {
    char text[32];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, value);
    return ec == std::errc() ? std::string(text, end) : std::to_string(value);
}

// Whether `field` is a finite number as OBJ writes one (an optional sign, decimal or exponent).
bool finite_number(std::string_view field) {
    if (field.starts_with('+')) field.remove_prefix(1);
    double value = 0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
    return error == std::errc{} && end == field.data() + field.size() && std::isfinite(value);
}

// tinyobjloader reads a value it cannot parse ("nan", "inf", "1e999", a typo) as 0, which would
// silently move a vertex to the origin: every value of the v, vn and vt lines must be a finite
// number.
Status check_obj_values(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return file_error(file, "cannot open it");
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        std::string_view rest = line;
        std::string_view keyword;
        for (int field = 0;; ++field) {
            const std::size_t begin = rest.find_first_not_of(" \t\r");
            if (begin == std::string_view::npos || rest[begin] == '#') break;
            rest.remove_prefix(begin);
            const std::string_view value = rest.substr(0, rest.find_first_of(" \t\r"));
            rest.remove_prefix(value.size());
            if (field == 0) {
                keyword = value;
                if (keyword != "v" && keyword != "vn" && keyword != "vt") break;
            } else if (!finite_number(value)) {
                return file_error(file, "line " + std::to_string(number) + ": '" +
                                            std::string(keyword) + "' value " +
                                            std::to_string(field) + " is '" + std::string(value) +
                                            "', not a finite number");
            }
        }
    }
    if (in.bad()) return file_error(file, "read error");
    return {};
}

Result<MeshAsset> load_obj(const fs::path& file, const Affine& xf) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(file.string(), config))
        return file_error(file, "parse error: " + tidy(reader.Error()));
    if (Status s = check_obj_values(file); !s) return s.error();
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const auto& materials = reader.GetMaterials();
    const std::size_t nv = attrib.vertices.size() / 3;
    const std::size_t nn = attrib.normals.size() / 3;
    const std::size_t nt = attrib.texcoords.size() / 2;

    // Corners grouped by material id (−1: no material), in file order.
    std::map<int, std::vector<tinyobj::index_t>> groups;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const tinyobj::mesh_t& m = shape.mesh;
        std::size_t offset = 0;
        for (std::size_t f = 0; f < m.num_face_vertices.size(); ++f) {
            const std::size_t count = m.num_face_vertices[f];
            if (offset + count > m.indices.size()) break;
            int mat = f < m.material_ids.size() ? m.material_ids[f] : -1;
            if (mat < 0 || static_cast<std::size_t>(mat) >= materials.size()) mat = -1;
            // Triangulation leaves triangles; fan anything larger just in case.
            for (std::size_t k = 1; k + 1 < count; ++k) {
                auto& g = groups[mat];
                g.push_back(m.indices[offset]);
                g.push_back(m.indices[offset + k]);
                g.push_back(m.indices[offset + k + 1]);
            }
            offset += count;
        }
    }

    MeshAsset asset;
    for (auto& [mat, corners] : groups) {
        TriangleMesh mesh;
        mesh.name = mat >= 0 ? materials[mat].name : file.filename().string();
        bool with_normals = nn > 0, with_uvs = nt > 0;
        for (const tinyobj::index_t& c : corners) {
            if (c.vertex_index < 0 || static_cast<std::size_t>(c.vertex_index) >= nv)
                return file_error(file, "index " + std::to_string(c.vertex_index + 1) +
                                            " out of range (" + std::to_string(nv) + " vertices)");
            if (c.normal_index < 0 || static_cast<std::size_t>(c.normal_index) >= nn)
                with_normals = false;
            if (c.texcoord_index < 0 || static_cast<std::size_t>(c.texcoord_index) >= nt)
                with_uvs = false;
        }
        // One vertex per distinct (position, normal, texcoord) triple used.
        struct Key {
            int v, n, t;
            bool operator==(const Key&) const = default;
        };
        struct KeyHash {
            std::size_t operator()(const Key& k) const {
                return std::hash<long long>()((static_cast<long long>(k.v) * 73856093) ^
                                              (static_cast<long long>(k.n) * 19349663) ^
                                              (static_cast<long long>(k.t) * 83492791));
            }
        };
        std::unordered_map<Key, std::uint32_t, KeyHash> vertex_of;
        std::vector<std::uint32_t> index;
        index.reserve(corners.size());
        for (const tinyobj::index_t& c : corners) {
            const Key key{c.vertex_index, with_normals ? c.normal_index : -1,
                          with_uvs ? c.texcoord_index : -1};
            auto [it, inserted] =
                vertex_of.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
            if (inserted) {
                const float* p = &attrib.vertices[3 * static_cast<std::size_t>(key.v)];
                mesh.positions.push_back({p[0], p[1], p[2]});
                if (with_normals) {
                    const float* q = &attrib.normals[3 * static_cast<std::size_t>(key.n)];
                    mesh.normals.push_back(normalize(Vec3d{q[0], q[1], q[2]}));
                }
                if (with_uvs) {
                    const float* q = &attrib.texcoords[2 * static_cast<std::size_t>(key.t)];
                    mesh.uvs.push_back({q[0], q[1]});  // vt is v up already
                }
            }
            index.push_back(it->second);
        }
        for (std::size_t i = 0; i + 2 < index.size(); i += 3)
            mesh.triangles.push_back({index[i], index[i + 1], index[i + 2]});
        if (mat >= 0) {
            const tinyobj::material_t& m = materials[mat];
            mesh.material.name = m.name;
            mesh.material.base_color = {m.diffuse[0], m.diffuse[1], m.diffuse[2]};
            // tinyobjloader reports a missing Kd as black: with a map_Kd, let the map show.
            if (!m.diffuse_texname.empty() && m.diffuse[0] == 0 && m.diffuse[1] == 0 &&
                m.diffuse[2] == 0)
                mesh.material.base_color = {1, 1, 1};
            if (!m.diffuse_texname.empty()) {
                auto tex = load_texture(file, m.diffuse_texname, ColorEncoding::automatic);
                if (!tex) return tex.error();
                mesh.material.base_color_texture = std::move(tex).value();
            }
            if (!m.normal_texname.empty()) {
                auto tex = load_texture(file, m.normal_texname, ColorEncoding::linear);
                if (!tex) return tex.error();
                mesh.material.normal_texture = std::move(tex).value();
            }
        }
        if (Status s = finish_mesh(mesh, xf, file); !s) return s.error();
        if (!mesh.triangles.empty()) asset.meshes.push_back(std::move(mesh));
    }
    return asset;
}

// ---------------------------------------------------------------------------------------------
// glTF

struct GltfReader {
    const tinygltf::Model& model;
    const fs::path& file;
    std::string error;  // first error; empty while all is well
    std::map<int, std::shared_ptr<const Image>> color_images, data_images;

    bool fail(const std::string& message) {
        if (error.empty()) error = message;
        return false;
    }

    // Calls fn(element index, const double* components) for each element of an accessor, with
    // normalised integers mapped to [0, 1] / [−1, 1] and others converted as they are. A NaN or
    // infinite float is an error: no attribute has a meaning for it. `role` names the accessor's
    // use in messages ("NORMAL of mesh 'hull'").
    template <class Fn>
    bool read_accessor(int index, int components, const std::string& role, Fn&& fn) {
        if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
            return fail("accessor " + std::to_string(index) + " does not exist");
        const tinygltf::Accessor& acc = model.accessors[index];
        const std::string what = "accessor " + std::to_string(index) + " (" + role + ")";
        if (acc.sparse.isSparse) return fail(what + ": sparse accessors are not supported");
        const int ncomp = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(acc.type));
        if (ncomp != components)
            return fail(what + " has " + std::to_string(ncomp) + " components, expected " +
                        std::to_string(components));
        const int csize =
            tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(acc.componentType));
        if (csize <= 0) return fail(what + " has an unknown component type");
        if (acc.count == 0) return true;
        if (acc.bufferView < 0 ||
            static_cast<std::size_t>(acc.bufferView) >= model.bufferViews.size())
            return fail(what + " has no buffer view");
        const tinygltf::BufferView& view = model.bufferViews[acc.bufferView];
        if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
            return fail(what + ": buffer view without a buffer");
        const std::vector<unsigned char>& data = model.buffers[view.buffer].data;
        const std::size_t elem = static_cast<std::size_t>(csize) * ncomp;
        const std::size_t stride = view.byteStride ? view.byteStride : elem;
        const std::size_t begin = view.byteOffset + acc.byteOffset;
        const std::size_t end = begin + stride * (acc.count - 1) + elem;
        if (end > view.byteOffset + view.byteLength || end > data.size() || end < begin)
            return fail(what + " reads past the end of its buffer");
        double values[4];
        for (std::size_t i = 0; i < acc.count; ++i) {
            const unsigned char* p = data.data() + begin + i * stride;
            for (int c = 0; c < ncomp; ++c) {
                values[c] = component(p + c * csize, acc);
                if (!std::isfinite(values[c]))
                    return fail(what + ": element " + std::to_string(i) + " holds the non-finite " +
                                "value " +
                                (std::isnan(values[c]) ? "nan"
                                 : values[c] > 0       ? "inf"
                                                       : "-inf"));
            }
            fn(i, values);
        }
        return true;
    }

    static double component(const unsigned char* p, const tinygltf::Accessor& acc) {
        auto get = [p](auto v) {
            std::memcpy(&v, p, sizeof v);  // little-endian host assumed, as glTF is
            return v;
        };
        const bool norm = acc.normalized;
        switch (acc.componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT:
                return get(float{});
            case TINYGLTF_COMPONENT_TYPE_DOUBLE:
                return get(double{});
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
                const double v = get(std::uint8_t{});
                return norm ? v / 255.0 : v;
            }
            case TINYGLTF_COMPONENT_TYPE_BYTE: {
                const double v = get(std::int8_t{});
                return norm ? std::max(v / 127.0, -1.0) : v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                const double v = get(std::uint16_t{});
                return norm ? v / 65535.0 : v;
            }
            case TINYGLTF_COMPONENT_TYPE_SHORT: {
                const double v = get(std::int16_t{});
                return norm ? std::max(v / 32767.0, -1.0) : v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
                return get(std::uint32_t{});
            case TINYGLTF_COMPONENT_TYPE_INT:
                return get(std::int32_t{});
            default:
                return 0;
        }
    }

    // The file an external image URI names: its %XX escapes decoded, relative to the glTF's folder.
    fs::path image_file(const std::string& uri) const {
        std::string path;
        for (std::size_t i = 0; i < uri.size(); ++i) {
            if (uri[i] == '%' && i + 2 < uri.size() &&
                std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
                std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
                path += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
                i += 2;
            } else {
                path += uri[i];
            }
        }
        return (file.parent_path() / path).lexically_normal();
    }

    // The decoded image behind texture `texture`, as linear colour (srgb) or raw data. `use` names
    // the material slot in messages ("normalTexture of material 'visor'").
    bool texture(int texture, bool srgb, const std::string& use,
                 std::shared_ptr<const Image>& out) {
        if (texture < 0) return true;
        const std::string what = use + " (texture " + std::to_string(texture) + ")";
        if (static_cast<std::size_t>(texture) >= model.textures.size())
            return fail(what + " does not exist");
        const int source = model.textures[texture].source;
        if (source < 0 || static_cast<std::size_t>(source) >= model.images.size())
            return fail(what + " has no image");
        auto& cache = srgb ? color_images : data_images;
        if (auto it = cache.find(source); it != cache.end()) {
            out = it->second;
            return true;
        }
        const tinygltf::Image& src = model.images[source];
        const bool external = !src.uri.empty() && src.uri.rfind("data:", 0) != 0;
        const std::string label = what + ": image " + std::to_string(source) +
                                  (external && src.uri.size() <= 200 ? " '" + src.uri + "'" : "");
        const int w = src.width, h = src.height, c = src.component;
        const int bytes = src.bits == 16 ? 2 : 1;
        if (w <= 0 || h <= 0 || c < 1 || c > 4 || (src.bits != 8 && src.bits != 16)) {
            // tinygltf only warns about an image file it cannot find and leaves it empty.
            std::error_code ec;
            if (external && !fs::is_regular_file(image_file(src.uri), ec))
                return fail(label + ": file not found (resolved to '" +
                            image_file(src.uri).string() + "')");
            return fail(label + " was not decoded (" + std::to_string(w) + "×" + std::to_string(h) +
                        ", " + std::to_string(c) + " channels, " + std::to_string(src.bits) +
                        " bits)");
        }
        auto img = std::make_shared<Image>(w, h, c);
        if (src.image.size() < img->pixels.size() * bytes)
            return fail(label + " holds fewer bytes than its size needs");
        const double scale = bytes == 2 ? 1.0 / 65535.0 : 1.0 / 255.0;
        const bool has_alpha = c == 2 || c == 4;
        for (std::size_t i = 0; i < img->pixels.size(); ++i) {
            unsigned v = src.image[i * bytes];
            if (bytes == 2) v |= static_cast<unsigned>(src.image[i * bytes + 1]) << 8;
            float x = static_cast<float>(v * scale);
            const bool alpha = has_alpha && static_cast<int>(i % c) == c - 1;
            if (srgb && !alpha) x = srgb_to_linear(x);
            img->pixels[i] = x;
        }
        out = img;
        cache.emplace(source, out);
        return true;
    }

    bool material(int index, MeshMaterial& out) {
        out.metallic_roughness = true;
        if (index < 0) return true;  // glTF's default material: white, metallic 1, roughness 1
        if (static_cast<std::size_t>(index) >= model.materials.size())
            return fail("material " + std::to_string(index) + " does not exist");
        const tinygltf::Material& m = model.materials[index];
        out.name = m.name;
        const auto& f = m.pbrMetallicRoughness.baseColorFactor;
        if (f.size() >= 3)
            out.base_color = {static_cast<float>(f[0]), static_cast<float>(f[1]),
                              static_cast<float>(f[2])};
        out.normal_scale = static_cast<float>(m.normalTexture.scale);
        const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
        out.metallic = static_cast<float>(pbr.metallicFactor);
        out.roughness = static_cast<float>(pbr.roughnessFactor);
        for (const auto& [key, value] : {std::pair{"metallicFactor", pbr.metallicFactor},
                                         std::pair{"roughnessFactor", pbr.roughnessFactor}})
            if (!(value >= 0 && value <= 1))
                return fail(std::string(key) + " of material " +
                            (m.name.empty() ? std::to_string(index) : "'" + m.name + "'") + " is " +
                            number(value) + "; glTF allows [0, 1]");
        const std::string of_material =
            " of material " + (m.name.empty() ? std::to_string(index) : "'" + m.name + "'");
        return texture(m.pbrMetallicRoughness.baseColorTexture.index, true,
                       "baseColorTexture" + of_material, out.base_color_texture) &&
               texture(m.normalTexture.index, false, "normalTexture" + of_material,
                       out.normal_texture) &&
               texture(pbr.metallicRoughnessTexture.index, false,
                       "metallicRoughnessTexture" + of_material, out.metallic_roughness_texture);
    }

    bool primitive(const tinygltf::Mesh& gmesh, const tinygltf::Primitive& prim, const Affine& xf,
                   MeshAsset& asset) {
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) return true;
        TriangleMesh mesh;
        mesh.name = gmesh.name;
        auto attr = [&](const char* name) {
            auto it = prim.attributes.find(name);
            return it == prim.attributes.end() ? -1 : it->second;
        };
        const std::string of_mesh = " of mesh '" + gmesh.name + "'";
        const int pos = attr("POSITION");
        if (pos < 0) return true;  // nothing to draw
        if (!read_accessor(pos, 3, "POSITION" + of_mesh, [&](std::size_t, const double* v) {
                mesh.positions.push_back({v[0], v[1], v[2]});
            }))
            return false;
        const std::size_t n = mesh.positions.size();
        auto count_ok = [&](std::size_t got, const char* what) {
            return got == n || fail(std::string(what) + " count differs from POSITION's in mesh '" +
                                    gmesh.name + "'");
        };
        if (const int a = attr("NORMAL"); a >= 0) {
            if (!read_accessor(a, 3, "NORMAL" + of_mesh,
                               [&](std::size_t, const double* v) {
                                   mesh.normals.push_back(normalize(Vec3d{v[0], v[1], v[2]}));
                               }) ||
                !count_ok(mesh.normals.size(), "NORMAL"))
                return false;
        }
        if (const int a = attr("TEXCOORD_0"); a >= 0) {
            if (!read_accessor(
                    a, 2, "TEXCOORD_0" + of_mesh,
                    [&](std::size_t, const double* v) {
                        mesh.uvs.push_back({v[0], 1.0 - v[1]});  // glTF t grows down; v grows up
                    }) ||
                !count_ok(mesh.uvs.size(), "TEXCOORD_0"))
                return false;
        }
        if (const int a = attr("TANGENT"); a >= 0) {
            if (!read_accessor(
                    a, 4, "TANGENT" + of_mesh,
                    [&](std::size_t, const double* v) {
                        mesh.tangents.push_back({normalize(Vec3d{v[0], v[1], v[2]}), v[3]});
                    }) ||
                !count_ok(mesh.tangents.size(), "TANGENT"))
                return false;
        }
        std::vector<std::uint32_t> index;
        if (prim.indices >= 0) {
            bool integral = true;
            if (!read_accessor(prim.indices, 1, "indices" + of_mesh,
                               [&](std::size_t, const double* v) {
                                   if (!(v[0] >= 0 && v[0] <= 4294967295.0)) integral = false;
                                   index.push_back(integral ? static_cast<std::uint32_t>(v[0]) : 0);
                               }))
                return false;
            if (!integral) return fail("invalid index in mesh '" + gmesh.name + "'");
        } else {
            for (std::size_t i = 0; i < n; ++i) index.push_back(static_cast<std::uint32_t>(i));
        }
        for (std::size_t i = 0; i + 2 < index.size(); i += 3)
            mesh.triangles.push_back({index[i], index[i + 1], index[i + 2]});
        if (mesh.triangles.empty()) return true;
        if (!material(prim.material, mesh.material)) return false;
        if (Status s = finish_mesh(mesh, xf, file); !s) {
            error = s.error().message;
            return false;
        }
        asset.meshes.push_back(std::move(mesh));
        return true;
    }

    static Affine node_local(const tinygltf::Node& node) {
        Affine a;
        if (node.matrix.size() == 16) {
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) a.m[r][c] = node.matrix[c * 4 + r];
            a.t = {node.matrix[12], node.matrix[13], node.matrix[14]};
            return a;
        }
        if (node.rotation.size() == 4) {
            const double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2],
                         w = node.rotation[3];
            const double n = std::sqrt(x * x + y * y + z * z + w * w);
            if (n > 0) {
                const double qx = x / n, qy = y / n, qz = z / n, qw = w / n;
                a.m[0][0] = 1 - 2 * (qy * qy + qz * qz);
                a.m[0][1] = 2 * (qx * qy - qz * qw);
                a.m[0][2] = 2 * (qx * qz + qy * qw);
                a.m[1][0] = 2 * (qx * qy + qz * qw);
                a.m[1][1] = 1 - 2 * (qx * qx + qz * qz);
                a.m[1][2] = 2 * (qy * qz - qx * qw);
                a.m[2][0] = 2 * (qx * qz - qy * qw);
                a.m[2][1] = 2 * (qy * qz + qx * qw);
                a.m[2][2] = 1 - 2 * (qx * qx + qy * qy);
            }
        }
        if (node.scale.size() == 3)
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) a.m[r][c] *= node.scale[c];
        if (node.translation.size() == 3)
            a.t = {node.translation[0], node.translation[1], node.translation[2]};
        return a;
    }

    bool node(int index, const Affine& parent, MeshAsset& asset, int depth) {
        if (index < 0 || static_cast<std::size_t>(index) >= model.nodes.size())
            return fail("node " + std::to_string(index) + " does not exist");
        if (depth > 256) return fail("the node hierarchy is too deep or has a cycle");
        const tinygltf::Node& nd = model.nodes[index];
        const Affine xf = parent * node_local(nd);
        if (nd.mesh >= 0) {
            if (static_cast<std::size_t>(nd.mesh) >= model.meshes.size())
                return fail("mesh " + std::to_string(nd.mesh) + " does not exist");
            const tinygltf::Mesh& m = model.meshes[nd.mesh];
            for (const tinygltf::Primitive& p : m.primitives)
                if (!primitive(m, p, xf, asset)) return false;
        }
        for (int child : nd.children)
            if (!node(child, xf, asset, depth + 1)) return false;
        return true;
    }
};

Result<MeshAsset> load_gltf(const fs::path& file, const Affine& xf, bool binary) {
    tinygltf::TinyGLTF loader;
    loader.SetPreserveImageChannels(true);
    tinygltf::Model model;
    std::string err, warn;
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, file.string())
                           : loader.LoadASCIIFromFile(&model, &err, &warn, file.string());
    if (!ok) return file_error(file, "parse error: " + tidy(err.empty() ? warn : err));
    GltfReader reader{model, file, {}, {}, {}};
    MeshAsset asset;
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        const int s = model.defaultScene >= 0 &&
                              static_cast<std::size_t>(model.defaultScene) < model.scenes.size()
                          ? model.defaultScene
                          : 0;
        roots = model.scenes[s].nodes;
    } else {
        std::vector<bool> child(model.nodes.size(), false);
        for (const tinygltf::Node& nd : model.nodes)
            for (int c : nd.children)
                if (c >= 0 && static_cast<std::size_t>(c) < child.size()) child[c] = true;
        for (std::size_t i = 0; i < model.nodes.size(); ++i)
            if (!child[i]) roots.push_back(static_cast<int>(i));
    }
    for (int r : roots)
        if (!reader.node(r, xf, asset, 0)) break;
    if (!reader.error.empty()) {
        if (reader.error.rfind("cannot read ", 0) == 0) return Error{reader.error};
        return file_error(file, reader.error);
    }
    return asset;
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

}  // namespace

Result<MeshAsset> load_mesh(const fs::path& file, const MeshTransform& transform) {
    std::error_code ec;
    const fs::file_status st = fs::status(file, ec);
    if (!fs::exists(st)) return file_error(file, "no such file");
    if (fs::is_directory(st)) return file_error(file, "it is a directory");
    if (Status s = check_transform(transform, file); !s) return s.error();
    const std::string ext = lower(file.extension().string());
    const Affine xf = user_affine(transform);
    if (ext != ".obj" && ext != ".gltf" && ext != ".glb")
        return file_error(file, "unsupported extension '" + ext + "' (supported: .obj .gltf .glb)");
    Result<MeshAsset> asset =
        ext == ".obj" ? load_obj(file, xf) : load_gltf(file, xf, ext == ".glb");
    if (asset && asset->meshes.empty()) return file_error(file, "it has no triangles");
    return asset;
}

}  // namespace footprint
