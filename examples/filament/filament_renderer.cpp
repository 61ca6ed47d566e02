// examples/filament/filament_renderer.cpp — Filament objects for one scene (filament_renderer.h).
#include "filament_renderer.h"

#include <filament/Camera.h>
#include <filament/Engine.h>
#include <filament/IndexBuffer.h>
#include <filament/IndirectLight.h>
#include <filament/Material.h>
#include <filament/MaterialInstance.h>
#include <filament/RenderTarget.h>
#include <filament/RenderableManager.h>
#include <filament/Renderer.h>
#include <filament/Scene.h>
#include <filament/Skybox.h>
#include <filament/SwapChain.h>
#include <filament/Texture.h>
#include <filament/TextureSampler.h>
#include <filament/VertexBuffer.h>
#include <filament/View.h>
#include <filament/Viewport.h>
#include <geometry/SurfaceOrientation.h>
#include <image/KtxBundle.h>
#include <image/KtxUtility.h>
#include <utils/EntityManager.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>

#include "filament_tools.h"
#include "x_display.h"

namespace footprint::filament_example {
namespace fs = std::filesystem;
using filament::math::float2;
using filament::math::float3;
using filament::math::float4;
using filament::math::short4;
using filament::math::uint3;

const char* material_name(MaterialKind kind) {
    switch (kind) {
        case MaterialKind::filament:
            return "filament";
        case MaterialKind::footprint:
            return "footprint";
        case MaterialKind::truth:
            return "truth";
    }
    return "?";
}

namespace {

// Anisotropic filtering for Filament's best practice: 16×, which Filament's GL backend clamps to
// the driver's GL_MAX_TEXTURE_MAX_ANISOTROPY (16 on llvmpipe and on desktop GPUs).
constexpr float kMaxAnisotropy = 16.0f;
// footprint assembly's probe budget N_max in the material: footprint's default (LookupOptions).
constexpr std::int32_t kFootprintMaxProbes = 30;

std::vector<char> read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<char>((std::istreambuf_iterator<char>(in)), {});
}

// A .filamat is a flat chunk container: (uint64 tag, uint32 size, size bytes)*, the first tag
// "MAT_VERS". Filament aborts on a package it cannot parse, so a file must pass this first.
Status check_material_package(const fs::path& path, const std::vector<char>& bytes) {
    if (bytes.empty())
        return Error{"cannot read the material '" + path.string() + "' (missing or empty)"};
    const char kFirstTag[8] = {'S', 'R', 'E', 'V',
                               '_', 'T', 'A', 'M'};  // "MAT_VERS", little-endian
    if (bytes.size() < 12 || std::memcmp(bytes.data(), kFirstTag, 8) != 0)
        return Error{"'" + path.string() +
                     "' is not a Filament material package (compile it with matc)"};
    std::size_t at = 0;
    while (at < bytes.size()) {
        if (bytes.size() - at < 12)
            return Error{"the material '" + path.string() +
                         "' is truncated (a chunk header at byte " + std::to_string(at) + ")"};
        std::uint32_t size = 0;
        std::memcpy(&size, bytes.data() + at + 8, 4);
        if (bytes.size() - at - 12 < size)
            return Error{"the material '" + path.string() + "' is truncated (a chunk of " +
                         std::to_string(size) + " bytes at byte " + std::to_string(at) + ")"};
        at += 12 + size;
    }
    return {};
}

// Parameters each material must declare (Filament aborts on setParameter of an unknown name).
const std::vector<const char*>& lit_parameters() {
    static const std::vector<const char*> names{
        "baseColorMap",    "normalMap", "roughnessMap",    "metallicMap",
        "baseColorFactor", "metallic",  "roughnessFactor", "uvScale"};
    return names;
}

}  // namespace

struct FilamentRenderer::State {
    RendererOptions options;
    void* display = nullptr;
    filament::Engine* engine = nullptr;
    filament::SwapChain* swap_chain = nullptr;
    filament::Renderer* renderer = nullptr;
    filament::Scene* scene = nullptr;
    filament::View* view = nullptr;
    utils::Entity camera_entity;
    filament::Camera* camera = nullptr;
    std::map<MaterialKind, filament::Material*> materials;
    filament::Material* id_material = nullptr;

    // The loaded scene.
    struct Renderable {
        utils::Entity entity;
        filament::VertexBuffer* vertices = nullptr;
        filament::IndexBuffer* indices = nullptr;
        std::map<MaterialKind, filament::MaterialInstance*> instances;
        filament::MaterialInstance* id_instance = nullptr;
    };
    std::vector<Renderable> renderables;
    std::vector<filament::Texture*> textures;
    filament::IndirectLight* indirect_light = nullptr;
    filament::Skybox* skybox = nullptr;
    filament::Texture* ibl_texture = nullptr;
    filament::Texture* skybox_texture = nullptr;
    CameraSetup camera_setup;

    void clear_scene();
    ~State();
};

void FilamentRenderer::State::clear_scene() {
    if (!engine) return;
    for (Renderable& r : renderables) {
        scene->remove(r.entity);
        engine->destroy(r.entity);
        for (auto& [kind, instance] : r.instances) engine->destroy(instance);
        if (r.id_instance) engine->destroy(r.id_instance);
        engine->destroy(r.vertices);
        engine->destroy(r.indices);
        utils::EntityManager::get().destroy(r.entity);
    }
    renderables.clear();
    for (filament::Texture* t : textures) engine->destroy(t);
    textures.clear();
    scene->setIndirectLight(nullptr);
    scene->setSkybox(nullptr);
    if (indirect_light) engine->destroy(indirect_light);
    if (skybox) engine->destroy(skybox);
    if (ibl_texture) engine->destroy(ibl_texture);
    if (skybox_texture) engine->destroy(skybox_texture);
    indirect_light = nullptr;
    skybox = nullptr;
    ibl_texture = skybox_texture = nullptr;
}

FilamentRenderer::State::~State() {
    if (engine) {
        clear_scene();
        for (auto& [kind, material] : materials) engine->destroy(material);
        if (id_material) engine->destroy(id_material);
        engine->destroy(view);
        engine->destroy(scene);
        engine->destroy(renderer);
        engine->destroy(swap_chain);
        engine->destroyCameraComponent(camera_entity);
        utils::EntityManager::get().destroy(camera_entity);
        filament::Engine::destroy(&engine);
    }
    close_x_display(display);
}

FilamentRenderer::FilamentRenderer(std::unique_ptr<State> state) : state_(std::move(state)) {}
FilamentRenderer::~FilamentRenderer() = default;

bool FilamentRenderer::has_material(MaterialKind kind) const {
    return state_->materials.count(kind) > 0;
}

Result<std::unique_ptr<FilamentRenderer>> FilamentRenderer::create(const RendererOptions& options) {
    auto state = std::make_unique<State>();
    state->options = options;

    // Read and check every package before the engine exists: a bad file is an error, not an abort.
    struct Package {
        MaterialKind kind;
        const char* file;
        bool optional;
    };
    const Package packages[] = {{MaterialKind::filament, "filament_best.filamat", false},
                                {MaterialKind::truth, "truth.filamat", false},
                                {MaterialKind::footprint, "footprint.filamat", true}};
    std::map<MaterialKind, std::vector<char>> bytes;
    std::map<MaterialKind, fs::path> paths;
    for (const Package& p : packages) {
        const fs::path path = options.materials_dir / p.file;
        std::error_code ec;
        if (p.optional && !fs::exists(path, ec)) continue;
        std::vector<char> data = read_file(path);
        if (Status s = check_material_package(path, data); !s) return s.error();
        bytes[p.kind] = std::move(data);
        paths[p.kind] = path;
    }
    const fs::path id_path = options.materials_dir / "object_id.filamat";
    std::vector<char> id_bytes = read_file(id_path);
    if (Status s = check_material_package(id_path, id_bytes); !s) return s.error();

    // GLX needs an X display; Filament aborts without one, so look first.
    std::string why;
    state->display = open_x_display(&why);
    if (!state->display) return Error{why};

    state->engine = filament::Engine::create(filament::Engine::Backend::OPENGL);
    if (!state->engine) return Error{"Filament could not create an OpenGL engine"};
    filament::Engine& engine = *state->engine;
    state->swap_chain = engine.createSwapChain(16, 16, filament::SwapChain::CONFIG_READABLE);
    state->renderer = engine.createRenderer();
    state->scene = engine.createScene();
    state->view = engine.createView();
    state->view->setScene(state->scene);
    state->view->setPostProcessingEnabled(false);
    state->camera_entity = utils::EntityManager::get().create();
    state->camera = engine.createCamera(state->camera_entity);
    state->camera->setExposure(1.0f, 1.2f, 100.0f);  // exposure 1: pixels in radiance units
    state->view->setCamera(state->camera);

    for (auto& [kind, data] : bytes) {
        filament::Material* material =
            filament::Material::Builder().package(data.data(), data.size()).build(engine);
        const fs::path& path = paths.at(kind);
        if (!material) return Error{"Filament rejected the material '" + path.string() + "'"};
        state->materials[kind] = material;
        for (const char* name : lit_parameters()) {
            if (!material->hasParameter(name))
                return Error{"the material '" + path.string() + "' has no parameter '" + name +
                             "' (it must declare those of materials/lit_maps.glsl)"};
        }
    }
    state->id_material =
        filament::Material::Builder().package(id_bytes.data(), id_bytes.size()).build(engine);
    if (!state->id_material || !state->id_material->hasParameter("objectId"))
        return Error{"the material '" + id_path.string() + "' has no parameter 'objectId'"};
    return std::unique_ptr<FilamentRenderer>(new FilamentRenderer(std::move(state)));
}

namespace {

// An RGBA16F texture of an image (1–4 channels; missing ones from the last, alpha 1), with a full
// MIP chain generated on the GPU (box filter) unless `levels` are given.
filament::Texture* make_texture(filament::Engine& engine, const std::vector<Image>& levels,
                                bool mipmaps) {
    const Image& base = levels.front();
    int count = 1;
    if (mipmaps) {
        while ((std::max(base.width, base.height) >> count) > 0) ++count;
    }
    filament::Texture* texture = filament::Texture::Builder()
                                     .width(base.width)
                                     .height(base.height)
                                     .levels(static_cast<std::uint8_t>(count))
                                     .format(filament::Texture::InternalFormat::RGBA16F)
                                     .sampler(filament::Texture::Sampler::SAMPLER_2D)
                                     .build(engine);
    const int given = static_cast<int>(std::min<std::size_t>(levels.size(), count));
    for (int level = 0; level < given; ++level) {
        const Image& image = levels[level];
        const std::size_t n = image.pixel_count();
        auto* rgba = new float[n * 4];
        for (std::size_t i = 0; i < n; ++i) {
            const float* p = image.pixels.data() + i * image.channels;
            for (int c = 0; c < 3; ++c) rgba[i * 4 + c] = p[std::min(c, image.channels - 1)];
            rgba[i * 4 + 3] = image.channels == 4 ? p[3] : 1.0f;
        }
        texture->setImage(engine, level,
                          filament::Texture::PixelBufferDescriptor(
                              rgba, n * 4 * sizeof(float), filament::Texture::Format::RGBA,
                              filament::Texture::Type::FLOAT, [](void* buffer, std::size_t, void*) {
                                  delete[] static_cast<float*>(buffer);
                              }));
    }
    if (mipmaps && given < count) texture->generateMipmaps(engine);
    return texture;
}

Image constant_image(float r, float g, float b) {
    Image image(1, 1, 3);
    image.pixels = {r, g, b};
    return image;
}

Result<filament::Texture*> load_ktx(filament::Engine& engine, const fs::path& path, float3* sh) {
    std::vector<char> bytes = read_file(path);
    if (bytes.empty()) return Error{"cannot read '" + path.string() + "'"};
    auto* bundle = new image::KtxBundle(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                        static_cast<std::uint32_t>(bytes.size()));
    if (sh && !bundle->getSphericalHarmonics(sh)) {
        delete bundle;
        return Error{"'" + path.string() +
                     "' has no spherical harmonics (cmgen --format=ktx writes them)"};
    }
    return image::ktx::createTexture(&engine, bundle, false);  // frees the bundle once uploaded
}

struct Vertex {
    float3 position;
    short4 tangents;
    float2 uv;
};

}  // namespace

// One surface's textures, shared by every object that uses it: the same maps for every material,
// each material binding its own samplers (and Filament's its roughness chain).
struct FilamentRenderer::SurfaceTextures {
    filament::Texture* colour = nullptr;
    filament::Texture* normal = nullptr;
    filament::Texture* roughness_chain = nullptr;     // Filament's: roughness-prefilter's levels
    filament::Texture* authored_roughness = nullptr;  // footprint's and the truth's
    filament::Texture* metallic = nullptr;
    filament::Texture* moments0 = nullptr;  // footprint's bump moments, when its material exists
    filament::Texture* moments1 = nullptr;
    float2 slope_offset{0, 0};
    const SurfaceDesc* desc = nullptr;
};

// The maps of one surface, as every scene's go to the GPU: footprint's colour pyramid, the normal
// map (its bump moments for footprint's material), the authored roughness and metallic (a glTF's
// metallic-roughness channels times their factors, else the factors), and Filament's roughness
// chain from roughness-prefilter.
Result<FilamentRenderer::SurfaceTextures> FilamentRenderer::make_surface_textures(
    const SurfaceDesc& surface) {
    State& s = *state_;
    filament::Engine& engine = *s.engine;
    std::vector<filament::Texture*>& owned = s.textures;
    SurfaceTextures out;
    out.desc = &surface;
    Result<Image> colour = surface.base_color.empty() ? Result<Image>(constant_image(1, 1, 1))
                                                      : load_map(surface.base_color, false);
    if (!colour) return colour.error();
    Result<Image> normal = surface.normal.empty() ? Result<Image>(constant_image(0.5f, 0.5f, 1))
                                                  : load_map(surface.normal, true);
    if (!normal) return normal.error();
    // Authored roughness and metallic: 1×1 constants, or the metallic-roughness map's G and B.
    Image authored = constant_image(surface.roughness, surface.roughness, surface.roughness);
    Image metallic = constant_image(1, 1, 1);
    if (!surface.metallic_roughness.empty()) {
        Result<Image> mr = load_map(surface.metallic_roughness, true);
        if (!mr) return mr.error();
        authored = Image(mr->width, mr->height, 1);
        metallic = Image(mr->width, mr->height, 1);
        for (int y = 0; y < mr->height; ++y) {
            for (int x = 0; x < mr->width; ++x) {
                const float* p = mr->at(x, y);
                authored.at(x, y, 0) = surface.roughness * p[std::min(1, mr->channels - 1)];
                metallic.at(x, y, 0) = p[std::min(2, mr->channels - 1)];
            }
        }
    }
    // Filament's roughness map: roughness-prefilter's chain; without a normal map there is no
    // variance to add, so the authored roughness as it is (its MIP levels from the GPU).
    std::vector<Image> roughness_chain{authored};
    if (!surface.normal.empty()) {
        Result<std::vector<Image>> chain =
            prefilter_roughness(*normal, surface.normal.label, authored,
                                surface.metallic_roughness.label, s.options.cache_dir);
        if (!chain) return chain.error();
        roughness_chain = std::move(*chain);
    }
    // The colour map's levels as footprint builds them (not the driver's glGenerateMipmap).
    out.colour = make_texture(engine, colour_pyramid(*colour), true);
    out.normal = make_texture(engine, {*normal}, true);
    out.roughness_chain = make_texture(engine, roughness_chain, true);
    const bool authored_map = authored.width > 1 || authored.height > 1;
    out.authored_roughness = make_texture(engine, {authored}, authored_map);
    out.metallic = make_texture(engine, {metallic}, authored_map);
    owned.insert(owned.end(), {out.colour, out.normal, out.roughness_chain, out.authored_roughness,
                               out.metallic});
    // footprint's bump moments, when its material was built.
    if (has_material(MaterialKind::footprint)) {
        Result<BumpMoments> moments =
            make_bump_moments(*normal, surface.normal.empty() ? std::string("flat normal map")
                                                              : surface.normal.label);
        if (!moments) return moments.error();
        out.moments0 = make_texture(engine, moments->moments0, true);
        out.moments1 = make_texture(engine, moments->moments1, true);
        out.slope_offset = {moments->slope_offset[0], moments->slope_offset[1]};
        owned.push_back(out.moments0);
        owned.push_back(out.moments1);
    }
    return out;
}

Status FilamentRenderer::load(const SceneSetup& scene, const MapSource& environment_override) {
    State& s = *state_;
    filament::Engine& engine = *s.engine;
    s.clear_scene();
    s.camera_setup = scene.camera;
    if (scene.objects.empty()) return Error{"the scene '" + scene.name + "' has no objects"};

    // Maps, once per surface.
    std::vector<SurfaceTextures> surfaces;
    for (const SurfaceDesc& surface : scene.surfaces) {
        Result<SurfaceTextures> textures = make_surface_textures(surface);
        if (!textures) return textures.error();
        surfaces.push_back(*textures);
    }

    // Environment: cmgen's IBL and skybox.
    const MapSource& env_source =
        environment_override.empty() ? scene.environment : environment_override;
    Result<Image> latlong = load_map(env_source, false);
    if (!latlong) return latlong.error();
    if (std::abs(latlong->width - 2 * latlong->height) > std::max(1, latlong->height / 50))
        return Error{"the environment '" + env_source.label + "' is " +
                     std::to_string(latlong->width) + "x" + std::to_string(latlong->height) +
                     ", not an equirectangular (2:1) image"};
    Result<PrefilteredEnvironment> env =
        prefilter_environment(*latlong, s.options.cache_dir, s.options.ibl_size);
    if (!env) return env.error();
    float3 sh[9];
    Result<filament::Texture*> ibl = load_ktx(engine, env->ibl_ktx, sh);
    if (!ibl) return ibl.error();
    s.ibl_texture = *ibl;
    Result<filament::Texture*> sky = load_ktx(engine, env->skybox_ktx, nullptr);
    if (!sky) return sky.error();
    s.skybox_texture = *sky;
    s.indirect_light = filament::IndirectLight::Builder()
                           .reflections(s.ibl_texture)
                           .irradiance(3, sh)
                           .intensity(1.0f)
                           .build(engine);
    s.skybox = filament::Skybox::Builder().environment(s.skybox_texture).build(engine);
    s.scene->setIndirectLight(s.indirect_light);
    s.scene->setSkybox(s.skybox);

    for (const SceneObject& object : scene.objects) {
        if (object.surface >= surfaces.size())
            return Error{"the scene '" + scene.name + "' names a surface it does not have"};
        add_renderable(object.mesh, surfaces[object.surface]);
    }
    return {};
}

// One object: its geometry and one material instance per material.
void FilamentRenderer::add_renderable(const Mesh& mesh, const SurfaceTextures& textures) {
    State& s = *state_;
    filament::Engine& engine = *s.engine;
    const SurfaceDesc& surface = *textures.desc;

    // Geometry: positions, tangent frames (from normals and uvs), uvs.
    const std::size_t n = mesh.positions.size();
    const bool has_uvs = mesh.uvs.size() == n;
    std::vector<float3> positions(n), normals(n);
    std::vector<float2> uvs(n, float2{0, 0});
    for (std::size_t i = 0; i < n; ++i) {
        positions[i] = {mesh.positions[i][0], mesh.positions[i][1], mesh.positions[i][2]};
        normals[i] = {mesh.normals[i][0], mesh.normals[i][1], mesh.normals[i][2]};
        if (has_uvs) uvs[i] = {mesh.uvs[i][0], mesh.uvs[i][1]};
    }
    std::vector<uint3> triangles(mesh.triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i)
        triangles[i] = {mesh.triangles[i][0], mesh.triangles[i][1], mesh.triangles[i][2]};
    // Without uvs (a glTF primitive without TEXCOORD_0) Lengyel's method has nothing to follow:
    // any tangent, and every map reads its texel (0, 0).
    filament::geometry::SurfaceOrientation::Builder orientation_builder;
    orientation_builder.vertexCount(n).normals(normals.data());
    if (has_uvs) {
        orientation_builder.positions(positions.data())
            .uvs(uvs.data())
            .triangleCount(triangles.size())
            .triangles(triangles.data());
    }
    filament::geometry::SurfaceOrientation* orientation = orientation_builder.build();
    std::vector<short4> quats(n);
    orientation->getQuats(quats.data(), n);
    delete orientation;
    auto* vertices = new Vertex[n];
    for (std::size_t i = 0; i < n; ++i) vertices[i] = {positions[i], quats[i], uvs[i]};
    auto* indices = new uint3[triangles.size()];
    std::copy(triangles.begin(), triangles.end(), indices);
    State::Renderable r;
    r.vertices = filament::VertexBuffer::Builder()
                     .vertexCount(static_cast<std::uint32_t>(n))
                     .bufferCount(1)
                     .attribute(filament::VertexAttribute::POSITION, 0,
                                filament::VertexBuffer::AttributeType::FLOAT3,
                                offsetof(Vertex, position), sizeof(Vertex))
                     .attribute(filament::VertexAttribute::TANGENTS, 0,
                                filament::VertexBuffer::AttributeType::SHORT4,
                                offsetof(Vertex, tangents), sizeof(Vertex))
                     .normalized(filament::VertexAttribute::TANGENTS)
                     .attribute(filament::VertexAttribute::UV0, 0,
                                filament::VertexBuffer::AttributeType::FLOAT2, offsetof(Vertex, uv),
                                sizeof(Vertex))
                     .build(engine);
    r.vertices->setBufferAt(engine, 0,
                            filament::VertexBuffer::BufferDescriptor(
                                vertices, n * sizeof(Vertex), [](void* buffer, std::size_t, void*) {
                                    delete[] static_cast<Vertex*>(buffer);
                                }));
    r.indices = filament::IndexBuffer::Builder()
                    .indexCount(static_cast<std::uint32_t>(triangles.size() * 3))
                    .bufferType(filament::IndexBuffer::IndexType::UINT)
                    .build(engine);
    r.indices->setBuffer(
        engine, filament::IndexBuffer::BufferDescriptor(indices, triangles.size() * sizeof(uint3),
                                                        [](void* buffer, std::size_t, void*) {
                                                            delete[] static_cast<uint3*>(buffer);
                                                        }));

    // One instance per material: the same inputs, each with its own samplers and roughness map.
    using Sampler = filament::TextureSampler;
    Sampler trilinear_aniso(Sampler::MinFilter::LINEAR_MIPMAP_LINEAR, Sampler::MagFilter::LINEAR,
                            Sampler::WrapMode::REPEAT);
    trilinear_aniso.setAnisotropy(kMaxAnisotropy);
    const Sampler trilinear(Sampler::MinFilter::LINEAR_MIPMAP_LINEAR, Sampler::MagFilter::LINEAR,
                            Sampler::WrapMode::REPEAT);
    // Level 0 only: LINEAR minification never reads a MIP level.
    const Sampler level0(Sampler::MinFilter::LINEAR, Sampler::MagFilter::LINEAR,
                         Sampler::WrapMode::REPEAT);
    for (auto& [kind, material] : s.materials) {
        filament::MaterialInstance* mi = material->createInstance();
        const bool truth = kind == MaterialKind::truth;
        // footprint reads explicit levels (textureLod): plain trilinear, no hardware anisotropy.
        const Sampler& sampler = truth                             ? level0
                                 : kind == MaterialKind::footprint ? trilinear
                                                                   : trilinear_aniso;
        if (kind == MaterialKind::footprint) {
            mi->setParameter("moments0", textures.moments0, trilinear);
            mi->setParameter("moments1", textures.moments1, trilinear);
            mi->setParameter("slopeOffset", textures.slope_offset);
            mi->setParameter("maxProbes", kFootprintMaxProbes);
        }
        mi->setParameter("baseColorMap", textures.colour, sampler);
        mi->setParameter("normalMap", textures.normal, sampler);
        // footprint's material gets the authored roughness: it widens it from the bump moments.
        mi->setParameter(
            "roughnessMap",
            kind == MaterialKind::filament ? textures.roughness_chain : textures.authored_roughness,
            sampler);
        mi->setParameter("metallicMap", textures.metallic, sampler);
        mi->setParameter("baseColorFactor",
                         float3{surface.base_color_factor[0], surface.base_color_factor[1],
                                surface.base_color_factor[2]});
        mi->setParameter("metallic", surface.metallic);
        mi->setParameter("roughnessFactor", 1.0f);
        mi->setParameter("uvScale", float2{surface.uv_scale[0], surface.uv_scale[1]});
        r.instances[kind] = mi;
    }
    r.id_instance = s.id_material->createInstance();
    r.id_instance->setParameter("objectId", 1.0f + static_cast<float>(s.renderables.size()));

    r.entity = utils::EntityManager::get().create();
    filament::math::float3 lo{1e30f}, hi{-1e30f};
    for (const float3& p : positions) {
        lo = min(lo, p);
        hi = max(hi, p);
    }
    filament::RenderableManager::Builder(1)
        .boundingBox({lo, hi})
        .material(0, r.instances.at(MaterialKind::filament))
        .geometry(0, filament::RenderableManager::PrimitiveType::TRIANGLES, r.vertices, r.indices)
        .culling(false)
        .castShadows(false)
        .receiveShadows(false)
        .build(engine, r.entity);
    s.scene->addEntity(r.entity);
    s.renderables.push_back(std::move(r));
}

namespace {

// Renders `frames` frames into a fresh float target and reads the last one back.
Result<RenderedFrame> render_frames(filament::Engine& engine, filament::Renderer& renderer,
                                    filament::SwapChain& swap_chain, filament::View& view,
                                    int width, int height, int frames) {
    using filament::Texture;
    Texture* colour = Texture::Builder()
                          .width(width)
                          .height(height)
                          .levels(1)
                          .format(Texture::InternalFormat::RGBA16F)
                          .usage(Texture::Usage::COLOR_ATTACHMENT | Texture::Usage::SAMPLEABLE)
                          .build(engine);
    Texture* depth = Texture::Builder()
                         .width(width)
                         .height(height)
                         .levels(1)
                         .format(Texture::InternalFormat::DEPTH24)
                         .usage(Texture::Usage::DEPTH_ATTACHMENT)
                         .build(engine);
    filament::RenderTarget* target =
        filament::RenderTarget::Builder()
            .texture(filament::RenderTarget::AttachmentPoint::COLOR, colour)
            .texture(filament::RenderTarget::AttachmentPoint::DEPTH, depth)
            .build(engine);
    view.setRenderTarget(target);
    view.setViewport({0, 0, static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height)});

    RenderedFrame out;
    std::vector<double> times;
    std::vector<float> rgba(static_cast<std::size_t>(width) * height * 4);
    bool failed = false;
    for (int frame = 0; frame < frames; ++frame) {
        const auto start = std::chrono::steady_clock::now();
        if (!renderer.beginFrame(&swap_chain)) {
            failed = true;
            break;
        }
        renderer.render(&view);
        if (frame + 1 == frames) {
            renderer.readPixels(
                target, 0, 0, width, height,
                filament::backend::PixelBufferDescriptor(rgba.data(), rgba.size() * sizeof(float),
                                                         filament::backend::PixelDataFormat::RGBA,
                                                         filament::backend::PixelDataType::FLOAT));
        }
        renderer.endFrame();
        engine.flushAndWait();
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        if (frame == 0) out.first_ms = ms;
        // The read-back frame is left out of the timing: it measures the copy, not the method.
        if (frame > 0 && frame + 1 < frames) times.push_back(ms);
    }
    view.setRenderTarget(nullptr);
    engine.destroy(target);
    engine.destroy(colour);
    engine.destroy(depth);
    engine.flushAndWait();
    if (failed) return Error{"Filament skipped a frame (Renderer::beginFrame returned false)"};
    if (!times.empty()) {
        std::sort(times.begin(), times.end());
        out.frame_ms = times[times.size() / 2];
    } else {
        out.frame_ms = out.first_ms;
    }
    // Top row first: Filament's readPixels() of a render target's texture gives the rows in the
    // order of the image seen (the orientation test, tests/run_test.sh, renders the sky with the
    // zenith up and checks it).
    out.image = Image(width, height, 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float* p = rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4;
            float* q = out.image.at(x, y);
            q[0] = p[0];
            q[1] = p[1];
            q[2] = p[2];
        }
    }
    return out;
}

}  // namespace

static void set_camera(filament::Camera& camera, const CameraSetup& c, int width, int height) {
    camera.setProjection(c.fov_y_deg, static_cast<double>(width) / height, c.near, c.far,
                         filament::Camera::Fov::VERTICAL);
    camera.lookAt(filament::math::double3{c.eye[0], c.eye[1], c.eye[2]},
                  filament::math::double3{c.target[0], c.target[1], c.target[2]},
                  filament::math::double3{c.up[0], c.up[1], c.up[2]});
}

Result<RenderedFrame> FilamentRenderer::render(MaterialKind kind, int width, int height,
                                               int frames) {
    State& s = *state_;
    if (!has_material(kind))
        return Error{std::string("the ") + material_name(kind) + " material was not built (" +
                     (s.options.materials_dir / "footprint.filamat").string() + " is missing)"};
    if (s.renderables.empty()) return Error{"no scene loaded"};
    filament::RenderableManager& rm = s.engine->getRenderableManager();
    for (State::Renderable& r : s.renderables)
        rm.setMaterialInstanceAt(rm.getInstance(r.entity), 0, r.instances.at(kind));
    set_camera(*s.camera, s.camera_setup, width, height);
    return render_frames(*s.engine, *s.renderer, *s.swap_chain, *s.view, width, height,
                         std::max(1, frames));
}

Result<Image> FilamentRenderer::render_object_ids(int width, int height) {
    State& s = *state_;
    filament::RenderableManager& rm = s.engine->getRenderableManager();
    for (State::Renderable& r : s.renderables)
        rm.setMaterialInstanceAt(rm.getInstance(r.entity), 0, r.id_instance);
    s.scene->setSkybox(nullptr);
    filament::Renderer::ClearOptions clear;
    clear.clearColor = {0, 0, 0, 0};
    clear.clear = true;
    s.renderer->setClearOptions(clear);
    set_camera(*s.camera, s.camera_setup, width, height);
    Result<RenderedFrame> frame =
        render_frames(*s.engine, *s.renderer, *s.swap_chain, *s.view, width, height, 1);
    s.scene->setSkybox(s.skybox);
    clear.clear = false;
    s.renderer->setClearOptions(clear);
    if (!frame) return frame.error();
    return std::move(frame->image);
}

}  // namespace footprint::filament_example
