#include "gpu/gpu_scene.h"

#include <algorithm>
#include <cstring>
#include <variant>

#include "scene/shapes.h"
#include "texture/footprint_assembly.h"

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

// The texels of one level of `layers` pyramids (or of one pyramid's channels split into layers of
// four), as RGBA layers one after the other: channel c of layer k is the pyramid's channel 4k + c
// (alpha 1 where an RGB map has none).
std::vector<float> rgba_layers(const std::vector<Image>& images, int layers) {
    const Image& first = images[0];
    const std::size_t texels = first.pixel_count();
    std::vector<float> out(texels * 4 * static_cast<std::size_t>(layers), 0.0f);
    for (int k = 0; k < layers; ++k) {
        const Image& image = images.size() == 1 ? first : images[static_cast<std::size_t>(k)];
        const int base = images.size() == 1 ? 4 * k : 0;
        for (std::size_t i = 0; i < texels; ++i) {
            float* o = &out[(static_cast<std::size_t>(k) * texels + i) * 4];
            o[3] = 1.0f;
            for (int c = 0; c < 4 && base + c < image.channels; ++c)
                o[c] = image.pixels[i * static_cast<std::size_t>(image.channels) + base + c];
        }
    }
    return out;
}

// A 2D array texture holding `pyramids` (one per layer), or one pyramid's channels in `layers`
// layers of four; every level the pyramid's own.
MapTexture upload_maps(const std::vector<const MipPyramid*>& pyramids, int layers,
                       float anisotropy) {
    const MipPyramid& p = *pyramids[0];
    MapTexture map;
    map.width = p.width(0);
    map.height = p.height(0);
    map.levels = p.level_count();
    map.layers = layers;
    map.texture = create_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(map.texture.get(), p.level_count(), GL_RGBA32F, p.width(0), p.height(0),
                       layers);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (int l = 0; l < p.level_count(); ++l) {
        std::vector<Image> images;
        for (const MipPyramid* q : pyramids) images.push_back(q->level_image(l));
        const std::vector<float> texels = rgba_layers(images, layers);
        glTextureSubImage3D(map.texture.get(), l, 0, 0, 0, p.width(l), p.height(l), layers, GL_RGBA,
                            GL_FLOAT, texels.data());
    }
    const GLenum s = gl_wrap(p.wrap_s()), t = gl_wrap(p.wrap_t());
    map.trilinear = make_sampler(s, t, 1);
    map.anisotropic = make_sampler(s, t, anisotropy);
    return map;
}

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

std::string object_name(const SceneDesc& scene, int i) {
    const std::string& name = scene.objects[static_cast<std::size_t>(i)].name;
    return "objects[" + std::to_string(i) + "]" + (name.empty() ? "" : " (" + name + ")");
}

Status upload_environment(const RenderEnvironment& env, GpuScene& gpu, float anisotropy) {
    const EnvironmentMap& map = env.map;
    gpu.has_environment = true;
    gpu.layout = map.layout();
    if (map.layout() == EnvLayout::latlong) {
        gpu.latlong = upload_maps({&map.face(0)}, 1, anisotropy);
        if (map.polar_cap(0)) {
            gpu.caps = upload_maps({map.polar_cap(0), map.polar_cap(1)}, 2, 1);
            gpu.has_caps = true;
        }
        return {};
    }
    if (map.layout() == EnvLayout::cube) {
        gpu.cube = upload_cube(map);
        gpu.cube_sampler = make_sampler(GL_CLAMP_TO_EDGE, GL_CLAMP_TO_EDGE, 1);
        return {};
    }
    return Error{std::string("environment: the ") + env_layout_name(map.layout()) +
                 " layout is not on the GPU yet (cube and latlong are; `footprint env` converts)"};
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

Result<MaterialRecord> material_record(const RenderMaterial& m, GpuScene& gpu,
                                       const std::string& name, float anisotropy) {
    const MaterialDesc& d = m.desc;
    MaterialRecord r{};
    float color_index = -1, bump_index = -1;
    if (m.base_color_map) {
        if (gpu.color_maps.size() >= static_cast<std::size_t>(kMaxMaps))
            return Error{name + ": more than " + std::to_string(kMaxMaps) +
                         " base colour maps in one scene are not on the GPU yet"};
        color_index = static_cast<float>(gpu.color_maps.size());
        gpu.color_maps.push_back(upload_maps({m.base_color_map.get()}, 1, anisotropy));
    }
    Vec2 offset;
    if (m.bump) {
        if (gpu.bump_maps.size() >= static_cast<std::size_t>(kMaxMaps))
            return Error{name + ": more than " + std::to_string(kMaxMaps) +
                         " bump maps in one scene are not on the GPU yet"};
        bump_index = static_cast<float>(gpu.bump_maps.size());
        gpu.bump_maps.push_back(upload_maps({&m.bump->moments()}, 2, anisotropy));
        offset = m.bump->slope_offset();
    }
    const Vec3d main = d.bump.main_direction;
    const float main_direction[4] = {static_cast<float>(main.x), static_cast<float>(main.y),
                                     static_cast<float>(main.z), offset.x};
    const float base[4] = {d.base_color.x, d.base_color.y, d.base_color.z, color_index};
    const float weights[4] = {d.diffuse, d.specular, d.shininess, d.mirror};
    const float bump[4] = {d.fresnel_f0, bump_index, bump_frame_code(d.bump.frame),
                           d.micro_roughness};
    const float roughness[4] = {m.micro_roughness.xx, m.micro_roughness.xy, m.micro_roughness.yy,
                                offset.y};
    std::copy_n(base, 4, r.base_color);
    std::copy_n(weights, 4, r.weights);
    std::copy_n(bump, 4, r.bump);
    std::copy_n(main_direction, 4, r.main_direction);
    std::copy_n(roughness, 4, r.roughness);
    return r;
}

// What the GPU path does not draw yet, as an Error naming the object.
Status check_shape(const SceneDesc& scene, int i) {
    const ShapeDesc& shape = scene.objects[static_cast<std::size_t>(i)].shape;
    if (std::holds_alternative<MeshShape>(shape))
        return Error{object_name(scene, i) + ": triangle meshes are not on the GPU yet"};
    if (std::holds_alternative<TorusShape>(shape))
        return Error{object_name(scene, i) + ": the torus is not on the GPU yet"};
    return {};
}

Buffer storage_buffer(const void* data, std::size_t bytes) {
    Buffer buffer = create_buffer();
    // A zero-sized buffer cannot be bound: an empty list is a buffer of one zero record.
    std::vector<unsigned char> padded(std::max<std::size_t>(bytes, sizeof(MaterialRecord)), 0);
    if (bytes) std::memcpy(padded.data(), data, bytes);
    glNamedBufferStorage(buffer.get(), static_cast<GLsizeiptr>(padded.size()), padded.data(), 0);
    return buffer;
}

}  // namespace

Result<GpuScene> upload_scene(const RenderScene& scene) {
    GpuScene gpu;
    const float anisotropy = max_anisotropy();
    const SceneDesc& desc = scene.desc();
    if (const RenderEnvironment* env = scene.environment())
        if (Status s = upload_environment(*env, gpu, anisotropy); !s) return s.error();
    for (int i = 0; i < static_cast<int>(desc.objects.size()); ++i) {
        if (Status s = check_shape(desc, i); !s) return s.error();
        // An invalid shape never hits (scene/shapes.h): it is left out.
        if (!evaluate_analytic(desc.objects[static_cast<std::size_t>(i)].shape, {0.5, 0.5})) {
            gpu.object_material.push_back(-1);
            continue;
        }
        Result<MaterialRecord> record =
            material_record(*scene.analytic_material(i), gpu, object_name(desc, i), anisotropy);
        if (!record) return record.error();
        gpu.object_material.push_back(static_cast<int>(gpu.materials.size()));
        gpu.materials.push_back(*record);
    }
    gpu.material_buffer =
        storage_buffer(gpu.materials.data(), gpu.materials.size() * sizeof(MaterialRecord));
    std::vector<float> spacing(kMaxProbeCount + 1);
    for (int n = 0; n <= kMaxProbeCount; ++n)
        spacing[static_cast<std::size_t>(n)] = gaussian_spacing_factor(n);
    gpu.gaussian_spacing_buffer = storage_buffer(spacing.data(), spacing.size() * sizeof(float));
    if (std::string e = gl_error("uploading the scene"); !e.empty()) return Error{e};
    return gpu;
}

namespace {

void store(float* out, Vec3d v, float w = 0) {
    out[0] = static_cast<float>(v.x);
    out[1] = static_cast<float>(v.y);
    out[2] = static_cast<float>(v.z);
    out[3] = w;
}

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
        void operator()(const TorusShape&) const {}  // refused by upload_scene()
        void operator()(const MeshShape&) const {}
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
        store(r.color, vec3_cast<double>(light.color));
        records.push_back(r);
    }
    return records;
}

}  // namespace footprint::gpu
