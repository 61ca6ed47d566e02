#include "gpu/gpu_scene.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <variant>

#include "envmap/env_convert.h"
#include "envmap/env_image_io.h"
#include "scene/mesh.h"
#include "scene/shapes.h"
#include "scene/triangle_bvh.h"

namespace footprint::gpu {

namespace {

GLenum gl_wrap(WrapMode mode) {
    switch (mode) {
        case WrapMode::repeat:
            return GL_REPEAT;
        case WrapMode::clamp:
            return GL_CLAMP_TO_EDGE;
        case WrapMode::mirror:
            return GL_MIRRORED_REPEAT;
    }
    return GL_REPEAT;
}

Sampler make_sampler(GLenum wrap_s, GLenum wrap_t, float anisotropy) {
    GLuint name = 0;
    glCreateSamplers(1, &name);
    glSamplerParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glSamplerParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(name, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap_s));
    glSamplerParameteri(name, GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap_t));
    glSamplerParameteri(name, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    if (anisotropy > 1) glSamplerParameterf(name, GL_TEXTURE_MAX_ANISOTROPY, anisotropy);
    return Sampler(name);
}

float max_anisotropy() {
    GLfloat value = 1;
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &value);
    return value;
}

// The texels of one level of some pyramids, as RGBA layers one after the other: each image gives
// `layers` layers, channel c of its layer k being the image's channel 4k + c (alpha 1 where an
// RGB map has none).
std::vector<float> rgba_layers(const std::vector<Image>& images, int layers) {
    const std::size_t texels = images[0].pixel_count();
    std::vector<float> out(texels * 4 * images.size() * static_cast<std::size_t>(layers), 0.0f);
    float* o = out.data();
    for (const Image& image : images)
        for (int k = 0; k < layers; ++k)
            for (std::size_t i = 0; i < texels; ++i, o += 4) {
                o[3] = 1.0f;
                for (int c = 0; c < 4 && 4 * k + c < image.channels; ++c)
                    o[c] = image.pixels[i * static_cast<std::size_t>(image.channels) + 4 * k + c];
            }
    return out;
}

// A 2D array texture holding `pyramids` of one shape, each as `layers` layers of four channels;
// every level the pyramids' own.
MapTexture upload_maps(const std::vector<const MipPyramid*>& pyramids, int layers,
                       float anisotropy) {
    const MipPyramid& p = *pyramids[0];
    MapTexture map;
    map.width = p.width(0);
    map.height = p.height(0);
    map.levels = p.level_count();
    map.layers = layers * static_cast<int>(pyramids.size());
    map.texture = create_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(map.texture.get(), p.level_count(), GL_RGBA32F, p.width(0), p.height(0),
                       map.layers);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (int l = 0; l < p.level_count(); ++l) {
        std::vector<Image> images;
        for (const MipPyramid* q : pyramids) images.push_back(q->level_image(l));
        const std::vector<float> texels = rgba_layers(images, layers);
        glTextureSubImage3D(map.texture.get(), l, 0, 0, 0, p.width(l), p.height(l), map.layers,
                            GL_RGBA, GL_FLOAT, texels.data());
    }
    const GLenum s = gl_wrap(p.wrap_s()), t = gl_wrap(p.wrap_t());
    map.trilinear = make_sampler(s, t, 1);
    map.anisotropic = make_sampler(s, t, anisotropy);
    return map;
}

// The materials' maps, grouped by shape (size, levels, wrap, layers per map) into the array
// textures of units 0 … kMaterialUnits − 1.
class MapPool {
  public:
    // The place of `pyramid` as `layers` layers; none once the maps need more arrays than there
    // are units.
    // (The pool holds the pyramid until upload(): a tiled texture's is read whole for it.)
    std::optional<MapRef> add(std::shared_ptr<const MipPyramid> pyramid, int layers) {
        for (std::size_t g = 0; g < groups_.size(); ++g) {
            Group& group = groups_[g];
            for (std::size_t i = 0; i < group.maps.size(); ++i)
                if (group.maps[i] == pyramid.get()) return ref(g, i);
            if (same_shape(*group.maps[0], *pyramid) && group.layers == layers &&
                (static_cast<int>(group.maps.size()) + 1) * layers <= max_layers_) {
                group.maps.push_back(pyramid.get());
                held_.push_back(std::move(pyramid));
                return ref(g, group.maps.size() - 1);
            }
        }
        if (groups_.size() >= static_cast<std::size_t>(kMaterialUnits)) return std::nullopt;
        groups_.push_back({{pyramid.get()}, layers});
        held_.push_back(std::move(pyramid));
        return ref(groups_.size() - 1, 0);
    }

    std::vector<MapTexture> upload(float anisotropy) const {
        std::vector<MapTexture> maps;
        for (const Group& group : groups_)
            maps.push_back(upload_maps(group.maps, group.layers, anisotropy));
        return maps;
    }

  private:
    struct Group {
        std::vector<const MipPyramid*> maps;
        int layers;
    };
    std::vector<std::shared_ptr<const MipPyramid>> held_;

    static bool same_shape(const MipPyramid& a, const MipPyramid& b) {
        return a.width(0) == b.width(0) && a.height(0) == b.height(0) &&
               a.level_count() == b.level_count() && a.wrap_s() == b.wrap_s() &&
               a.wrap_t() == b.wrap_t();
    }
    MapRef ref(std::size_t group, std::size_t index) const {
        return {static_cast<int>(group), static_cast<int>(index) * groups_[group].layers};
    }

    std::vector<Group> groups_;
    int max_layers_ = [] {
        GLint value = 256;
        glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &value);
        return static_cast<int>(value);
    }();
};

Texture upload_cube(const EnvironmentMap& map) {
    const MipPyramid& face0 = map.face(0);
    Texture cube = create_texture(GL_TEXTURE_CUBE_MAP);
    glTextureStorage2D(cube.get(), face0.level_count(), GL_RGBA32F, face0.width(0),
                       face0.height(0));
    for (int f = 0; f < 6; ++f)
        for (int l = 0; l < face0.level_count(); ++l) {
            const std::vector<float> texels = rgba_layers({map.face(f).level_image(l)}, 1);
            glTextureSubImage3D(cube.get(), l, 0, 0, f, face0.width(l), face0.height(l), 1, GL_RGBA,
                                GL_FLOAT, texels.data());
        }
    return cube;
}

// A slot's map as a cube map: a probe's or a cube map's own levels, another layout resampled into
// a cube map of the same angular resolution (envmap/env_convert.h), filtered by its texels.
Status upload_slot(const RenderScene& scene, CubeSlot& slot) {
    Result<std::shared_ptr<const EnvironmentMap>> map =
        scene.textures().environment_map(slot.source->map);
    if (!map) return map.error();
    std::shared_ptr<const EnvironmentMap> cube = *map;
    if (cube->layout() != EnvLayout::cube) {
        Result<EnvImages> faces = convert_environment(*cube, EnvLayout::cube);
        if (!faces) return faces.error();
        Result<EnvironmentMap> converted = make_environment_map(*faces);
        if (!converted) return converted.error();
        cube = std::make_shared<EnvironmentMap>(std::move(*converted));
    }
    slot.cube = upload_cube(*cube);
    slot.size = static_cast<float>(cube->face(0).width(0));
    return {};
}

std::string object_name(const SceneDesc& scene, int i) {
    const std::string& name = scene.objects[static_cast<std::size_t>(i)].name;
    return "objects[" + std::to_string(i) + "]" + (name.empty() ? "" : " (" + name + ")");
}

Status upload_environment(const RenderScene& scene, GpuScene& gpu, float anisotropy) {
    Result<std::shared_ptr<const EnvironmentMap>> whole =
        scene.textures().environment_map(scene.environment()->map);
    if (!whole) return whole.error();
    const EnvironmentMap& map = **whole;
    gpu.has_environment = true;
    gpu.layout = map.layout();
    if (map.layout() == EnvLayout::cube) {
        gpu.cube = upload_cube(map);
        gpu.cube_sampler = make_sampler(GL_CLAMP_TO_EDGE, GL_CLAMP_TO_EDGE, 1);
        return {};
    }
    std::vector<const MipPyramid*> faces;
    for (int f = 0; f < map.face_count(); ++f) faces.push_back(&map.face(f));
    gpu.env_map = upload_maps(faces, 1, anisotropy);
    const MipPyramid& face = map.face(0);
    for (int l = 0; l < face.level_count(); ++l) {
        const Vec2 v = face.prefilter_variance(l);
        gpu.env_prefilter.push_back(std::max(v.x, v.y));
    }
    gpu.env_repeat = {face.wrap_s() == WrapMode::repeat, face.wrap_t() == WrapMode::repeat};
    if (map.polar_cap(0)) {
        gpu.caps = upload_maps({map.polar_cap(0), map.polar_cap(1)}, 1, 1);
        gpu.has_caps = true;
    }
    return {};
}

// A grey texture as the RGB one the shaders read (grey in every colour channel).
std::shared_ptr<const MipPyramid> grey_as_rgb(const MipPyramid& grey) {
    std::vector<Image> levels;
    for (int l = 0; l < grey.level_count(); ++l) {
        const Image level = grey.level_image(l);
        Image& rgb = levels.emplace_back(level.width, level.height, 3);
        for (std::size_t i = 0; i < level.pixel_count(); ++i)
            std::fill_n(&rgb.pixels[i * 3], 3, level.pixels[i * level.channels]);
    }
    MipPyramidOptions options;
    options.wrap_s = grey.wrap_s();
    options.wrap_t = grey.wrap_t();
    Result<MipPyramid> rgb = MipPyramid::from_levels(levels, options);
    return std::make_shared<const MipPyramid>(std::move(*rgb));
}

// footprint/highlight.glsl's FP_HIGHLIGHT_* codes.
float highlight_code(MaterialDesc::Highlight highlight) {
    switch (highlight) {
        case MaterialDesc::Highlight::blinn_phong:
            return 0;
        case MaterialDesc::Highlight::beckmann:
            return 1;
        case MaterialDesc::Highlight::ggx:
            return 2;
    }
    return 0;
}

float bump_frame_code(BumpFrame frame) {
    switch (frame) {
        case BumpFrame::natural:
            return 0;
        case BumpFrame::normalized:
            return 1;
        case BumpFrame::main_direction:
            return 2;
    }
    return 2;
}

// Material m's environment probe's cube slot (added at its first use), −1 for none.
Result<int> probe_slot(const RenderMaterial& m, std::vector<CubeSlot>& slots,
                       const std::string& name) {
    if (!m.probe) return -1;
    const auto it = std::find_if(slots.begin(), slots.end(),
                                 [&](const CubeSlot& slot) { return slot.source == m.probe; });
    if (it != slots.end()) return static_cast<int>(it - slots.begin());
    if (slots.size() == kMaxCubeSlots)
        return Error{name + ": environment_probe: the GPU path takes " +
                     std::to_string(kMaxCubeSlots) +
                     " cube maps per scene, local maps and probed objects together"};
    slots.push_back({m.probe, {}, 0});
    return static_cast<int>(slots.size()) - 1;
}

Result<MaterialRecord> material_record(const RenderMaterial& m, TextureSystem& textures,
                                       MapPool& pool, std::vector<CubeSlot>& slots,
                                       const std::string& name) {
    const MaterialDesc& d = m.desc;
    MaterialRecord r{};
    Result<int> probe = probe_slot(m, slots, name);
    if (!probe) return probe.error();
    r.probe[0] = *probe;
    auto place = [&](std::shared_ptr<const MipPyramid> pyramid, int layers) -> Result<MapRef> {
        if (std::optional<MapRef> ref = pool.add(std::move(pyramid), layers)) return *ref;
        return Error{name + ": the scene's maps come in more than " +
                     std::to_string(kMaterialUnits) +
                     " different sizes (or wrap modes); the GPU path takes that many"};
    };
    // A one-layer map (colour, F0, heights) as the texture system built its pyramid, a grey one
    // as RGB; `out` untouched where the material has none.
    auto place_map = [&](TextureHandle* map, bool grey, MapRef& out) -> Status {
        if (!map) return {};
        Result<std::shared_ptr<const MipPyramid>> pyramid = textures.pyramid(map);
        if (!pyramid) return Error{name + ": " + pyramid.error().message};
        if (grey) *pyramid = grey_as_rgb(**pyramid);
        Result<MapRef> ref = place(std::move(*pyramid), 1);
        if (!ref) return ref.error();
        out = *ref;
        return {};
    };
    MapRef color, bump, f0, heights;
    if (Status s = place_map(m.base_color_map, m.base_color_grey, color); !s) return s.error();
    if (Status s = place_map(m.f0_map, false, f0); !s) return s.error();
    if (Status s = place_map(m.height_map, false, heights); !s) return s.error();
    Vec2 offset;
    if (m.bump) {
        Result<std::shared_ptr<const BumpPyramid>> pyramid = textures.bump_pyramid(m.bump);
        if (!pyramid) return Error{name + ": " + pyramid.error().message};
        // A stored bump pyramid: the material's strength and micro-roughness (PSD: trace 0 is
        // none).
        if (m.bump_strength != 1 || m.bump_micro_roughness.trace() != 0)
            *pyramid = std::make_shared<const BumpPyramid>(
                (*pyramid)->scaled(m.bump_strength, m.bump_micro_roughness));
        const BumpPyramid& b = **pyramid;
        Result<MapRef> ref = place(std::shared_ptr<const MipPyramid>(*pyramid, &b.moments()), 2);
        if (!ref) return ref.error();
        bump = *ref;
        offset = b.slope_offset();
    }
    const Vec3d main = d.bump.main_direction;
    const float main_direction[4] = {static_cast<float>(main.x), static_cast<float>(main.y),
                                     static_cast<float>(main.z), offset.x};
    const float base[4] = {d.base_color.x, d.base_color.y, d.base_color.z,
                           m.frame_from_mesh_tangents ? 1.0f : 0.0f};
    const float weights[4] = {d.diffuse, d.specular, d.shininess, d.mirror};
    const float bump_info[4] = {0, 0, bump_frame_code(d.bump.frame), d.micro_roughness};
    const float roughness[4] = {m.micro_roughness.xx, m.micro_roughness.xy, m.micro_roughness.yy,
                                offset.y};
    const int maps[4] = {color.unit, color.layer, bump.unit, bump.layer};
    // A metallic-roughness material's α is its slope variance's (render/material_model.h).
    const float highlight[4] = {highlight_code(d.highlight), d.roughness * d.roughness,
                                m.metallic_roughness() ? 1.0f : 0.0f, 0};
    const float f0_info[4] = {m.f0[0], m.f0[1], m.f0[2], m.ambient_weight};
    const int f0_map[4] = {f0.unit, f0.layer, -1, -1};
    std::copy_n(base, 4, r.base_color);
    std::copy_n(weights, 4, r.weights);
    std::copy_n(bump_info, 4, r.bump);
    std::copy_n(main_direction, 4, r.main_direction);
    std::copy_n(roughness, 4, r.roughness);
    std::copy_n(maps, 4, r.maps);
    std::copy_n(highlight, 4, r.highlight);
    std::copy_n(f0_info, 4, r.f0);
    std::copy_n(f0_map, 4, r.f0_map);
    if (const std::optional<ProceduralTexture>& t = d.base_color_procedural) {
        r.procedural[0] = static_cast<float>(t->pattern) + 1;
        r.procedural[1] = static_cast<float>(t->scale);
        r.procedural[2] = static_cast<float>(t->octaves);
        for (int k = 0; k < 2; ++k) {
            r.procedural_colors[k][0] = t->colors[k].x;
            r.procedural_colors[k][1] = t->colors[k].y;
            r.procedural_colors[k][2] = t->colors[k].z;
        }
    }
    if (const std::optional<ParallaxOptions>& p = d.bump.parallax; p && m.height_map) {
        r.parallax[0] = p->depth;
        r.parallax[1] = static_cast<float>(p->steps);
        r.parallax[2] = p->max_shift;
        r.height_map[0] = heights.unit;
        r.height_map[1] = heights.layer;
    } else {
        r.height_map[0] = -1;
    }
    if (d.bump.source == BumpDesc::Source::procedural) {
        const ProceduralTexture& t = d.bump.procedural;
        r.procedural_bump[0] = static_cast<float>(t.pattern) + 1;
        r.procedural_bump[1] = static_cast<float>(t.scale);
        r.procedural_bump[2] = static_cast<float>(t.octaves);
        r.procedural_bump[3] = d.bump.strength;
    }
    return r;
}

Buffer storage_buffer(const void* data, std::size_t bytes) {
    Buffer buffer = create_buffer();
    // A zero-sized buffer cannot be bound: an empty list is a buffer of one zero record.
    std::vector<unsigned char> padded(std::max<std::size_t>(bytes, sizeof(MaterialRecord)), 0);
    if (bytes) std::memcpy(padded.data(), data, bytes);
    glNamedBufferStorage(buffer.get(), static_cast<GLsizeiptr>(padded.size()), padded.data(), 0);
    return buffer;
}

template <class T>
Buffer storage_buffer(const std::vector<T>& records) {
    return storage_buffer(records.data(), records.size() * sizeof(T));
}

void store(float* out, Vec3d v, float w = 0) {
    out[0] = static_cast<float>(v.x);
    out[1] = static_cast<float>(v.y);
    out[2] = static_cast<float>(v.z);
    out[3] = w;
}

// The centre of the bounding box of every mesh vertex (the origin without meshes).
Vec3d mesh_anchor(const RenderScene& scene) {
    const double inf = std::numeric_limits<double>::infinity();
    Vec3d lo{inf, inf, inf}, hi{-inf, -inf, -inf};
    for (int i = 0; i < static_cast<int>(scene.desc().objects.size()); ++i)
        for (const TriangleMesh& part : scene.mesh_parts(i))
            for (const Vec3d& p : part.positions) {
                lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
                hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
            }
    return lo.x <= hi.x ? 0.5 * (lo + hi) : Vec3d{0, 0, 0};
}

// The GPU's copy of one mesh part's vertices, relative to `anchor`.
void append_vertices(const TriangleMesh& part, Vec3d anchor,
                     std::vector<MeshVertexRecord>& vertices) {
    for (std::size_t v = 0; v < part.positions.size(); ++v) {
        MeshVertexRecord r{};
        store(r.position, part.positions[v] - anchor);
        if (part.has_normals()) store(r.normal, part.normals[v]);
        if (part.has_uvs()) store(r.uv, {part.uvs[v].x, part.uvs[v].y, 0});
        if (part.has_tangents())
            store(r.tangent, part.tangents[v].xyz, static_cast<float>(part.tangents[v].w));
        vertices.push_back(r);
    }
}

// Every part of every mesh into gpu.meshes (gpu_scene.h), its material appended to gpu.materials.
Status upload_meshes(const RenderScene& scene, MapPool& pool, GpuScene& gpu) {
    GpuMeshes& meshes = gpu.meshes;
    meshes.anchor = mesh_anchor(scene);
    std::vector<MeshVertexRecord> vertices;
    std::vector<std::uint32_t> indices;
    std::vector<std::array<std::uint32_t, 4>> triangles;
    std::vector<MeshPartRecord> parts;
    const SceneDesc& desc = scene.desc();
    for (int i = 0; i < static_cast<int>(desc.objects.size()); ++i) {
        const std::span<const TriangleMesh> object_parts = scene.mesh_parts(i);
        for (std::size_t k = 0; k < object_parts.size(); ++k) {
            const TriangleMesh& part = object_parts[k];
            Result<MaterialRecord> record = material_record(
                scene.mesh_part_material(i, static_cast<int>(k)), scene.textures(), pool, gpu.slots,
                object_name(desc, i) + " part '" + part.name + "'");
            if (!record) return record.error();
            const auto part_index = static_cast<std::uint32_t>(parts.size());
            parts.push_back({{static_cast<int>(gpu.materials.size()), part.has_normals() ? 1 : 0,
                              part.has_uvs() ? 1 : 0, part.has_tangents() ? 1 : 0}});
            gpu.materials.push_back(*record);
            const auto base = static_cast<std::uint32_t>(vertices.size());
            append_vertices(part, meshes.anchor, vertices);
            for (const auto& tri : part.triangles) {
                for (std::uint32_t v : tri) indices.push_back(base + v);
                triangles.push_back({base + tri[0], base + tri[1], base + tri[2], part_index});
            }
        }
    }
    meshes.triangle_count = static_cast<int>(triangles.size());
    std::vector<std::array<Vec3, 3>> corners;  // as the shader reads them
    corners.reserve(triangles.size());
    for (const auto& tri : triangles) {
        auto at = [&](std::uint32_t v) {
            const float* p = vertices[v].position;
            return Vec3{p[0], p[1], p[2]};
        };
        corners.push_back({at(tri[0]), at(tri[1]), at(tri[2])});
    }
    Result<TriangleBvh> bvh = build_triangle_bvh(corners);
    if (!bvh) return bvh.error();
    meshes.bvh_nodes = storage_buffer(bvh->nodes);
    meshes.bvh_triangles = storage_buffer(bvh->triangles);
    meshes.vertices = storage_buffer(vertices);
    meshes.indices = storage_buffer(indices);
    meshes.triangles = storage_buffer(triangles);
    meshes.parts = storage_buffer(parts);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    meshes.vertex_array = VertexArray(vao);
    glVertexArrayVertexBuffer(vao, 0, meshes.vertices.get(), 0, sizeof(MeshVertexRecord));
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayElementBuffer(vao, meshes.indices.get());
    return {};
}

}  // namespace

Result<GpuScene> upload_scene(const RenderScene& scene) {
    GpuScene gpu;
    MapPool pool;
    const float anisotropy = max_anisotropy();
    const SceneDesc& desc = scene.desc();
    if (scene.environment())
        if (Status s = upload_environment(scene, gpu, anisotropy); !s) return s.error();
    if (scene.local_environments().size() > kMaxCubeSlots)
        return Error{"local_environments: the GPU path takes " + std::to_string(kMaxCubeSlots) +
                     " local maps per scene, got " +
                     std::to_string(scene.local_environments().size())};
    for (const std::unique_ptr<RenderEnvironment>& local : scene.local_environments())
        gpu.slots.push_back({local.get(), {}, 0});
    gpu.local_count = static_cast<int>(gpu.slots.size());
    for (int i = 0; i < static_cast<int>(desc.objects.size()); ++i) {
        // Meshes are drawn by upload_meshes()'s buffers; an invalid shape never hits
        // (scene/shapes.h): both are left out of the analytic objects.
        const ShapeDesc& shape = desc.objects[static_cast<std::size_t>(i)].shape;
        if (renders_as_mesh(shape) || !evaluate_analytic(shape, {0.5, 0.5})) {
            gpu.object_material.push_back(-1);
            continue;
        }
        Result<MaterialRecord> record = material_record(
            *scene.analytic_material(i), scene.textures(), pool, gpu.slots, object_name(desc, i));
        if (!record) return record.error();
        gpu.object_material.push_back(static_cast<int>(gpu.materials.size()));
        gpu.materials.push_back(*record);
    }
    if (Status s = upload_meshes(scene, pool, gpu); !s) return s.error();
    for (CubeSlot& slot : gpu.slots)
        if (Status s = upload_slot(scene, slot); !s) return s.error();
    if (!gpu.slots.empty()) gpu.slot_sampler = make_sampler(GL_CLAMP_TO_EDGE, GL_CLAMP_TO_EDGE, 1);
    gpu.material_maps = pool.upload(anisotropy);
    gpu.material_buffer = storage_buffer(gpu.materials);
    if (std::string e = gl_error("uploading the scene"); !e.empty()) return Error{e};
    return gpu;
}

namespace {

void store_axes(ObjectRecord& r, const ShapeAxes& a) {
    store(r.axis_u, a.u);
    store(r.axis_v, a.v);
    store(r.axis, a.axis);
}

// One analytic shape as the shaders' Object (its type in info[0], as common.glsl's SHAPE_*).
ObjectRecord object_record(const ShapeDesc& shape, Vec3d eye) {
    ObjectRecord r{};
    struct Visitor {
        ObjectRecord& r;
        Vec3d eye;
        void operator()(const PlaneShape& s) const {
            r.info[0] = 0;
            store(r.origin, s.center - eye);
            store_axes(r, *shape_axes(s.normal));
            store(r.params, {s.size.x, s.size.y, s.uv_scale});
            r.info[2] = s.infinite ? 1 : 0;
        }
        void operator()(const SphereShape& s) const {
            r.info[0] = 1;
            store(r.origin, s.center - eye);
            // shapes.h: the sphere's polar axis is +y, its azimuth measured in (+x, −z).
            store_axes(r, ShapeAxes{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}});
            store(r.params, {s.radius, 0, 0});
        }
        void operator()(const CylinderShape& s) const {
            r.info[0] = 2;
            store(r.origin, s.center - eye);
            store_axes(r, *shape_axes(s.axis));
            store(r.params, {s.radius, s.height, 0});
        }
        void operator()(const ParaboloidShape& s) const {
            r.info[0] = 3;
            const ShapeAxes a = *shape_axes(s.axis);
            store(r.origin, s.focus - s.focal_length * a.axis - eye);  // the vertex
            store_axes(r, a);
            store(r.params, {s.focal_length, s.radius, 0});
        }
        void operator()(const TorusShape& s) const {
            r.info[0] = 4;
            store(r.origin, s.center - eye);
            store_axes(r, *shape_axes(s.axis));
            store(r.params, {s.major_radius, s.minor_radius, 0});
        }
        void operator()(const MeshShape&) const {}  // drawn from GpuMeshes
        void operator()(const TerrainShape&) const {}
    };
    std::visit(Visitor{r, eye}, shape);
    return r;
}

}  // namespace

std::vector<ObjectRecord> object_records(const RenderScene& scene, const GpuScene& gpu,
                                         Vec3d camera_position) {
    std::vector<ObjectRecord> records;
    const SceneDesc& desc = scene.desc();
    for (std::size_t i = 0; i < desc.objects.size(); ++i) {
        if (gpu.object_material[i] < 0) continue;
        ObjectRecord r = object_record(desc.objects[i].shape, camera_position);
        r.info[1] = gpu.object_material[i];
        records.push_back(r);
    }
    return records;
}

std::vector<LightRecord> light_records(const SceneDesc& scene, Vec3d camera_position) {
    std::vector<LightRecord> records;
    for (const LightDesc& light : scene.lights) {
        LightRecord r{};
        const bool point = light.type == LightType::point;
        store(r.direction, light.direction, point ? 1.0f : 0.0f);
        store(r.position, light.position - camera_position);
        store(r.color, vec3_cast<double>(light.color), light.shadows ? 1.0f : 0.0f);
        records.push_back(r);
    }
    return records;
}

}  // namespace footprint::gpu
