#include "gpu/gpu_renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iterator>

#include "gpu/gl_context.h"
#include "gpu/gl_objects.h"
#include "gpu/gpu_scene.h"
#include "gpu/gpu_shaders.h"
#include "render/camera.h"
#include "texture/footprint_assembly.h"

namespace footprint {

namespace {

constexpr GpuFilter kAllGpuFilters[] = {GpuFilter::point, GpuFilter::trilinear, GpuFilter::fa,
                                        GpuFilter::fa_rough, GpuFilter::hw_aniso};

}  // namespace

std::optional<GpuFilter> parse_gpu_filter(std::string_view name) {
    for (GpuFilter f : kAllGpuFilters)
        if (name == gpu_filter_name(f)) return f;
    return std::nullopt;
}

const char* gpu_filter_name(GpuFilter filter) {
    switch (filter) {
        case GpuFilter::point:
            return "point";
        case GpuFilter::trilinear:
            return "trilinear";
        case GpuFilter::fa:
            return "fa";
        case GpuFilter::fa_rough:
            return "fa-rough";
        case GpuFilter::hw_aniso:
            return "hw-aniso";
    }
    return "?";
}

std::span<const GpuFilter> all_gpu_filters() {
    return kAllGpuFilters;
}

// ---- GpuDevice.

struct GpuDevice::Impl {
    gpu::GlContext context;
};

GpuDevice::GpuDevice() = default;
GpuDevice::GpuDevice(GpuDevice&&) noexcept = default;
GpuDevice& GpuDevice::operator=(GpuDevice&&) noexcept = default;
GpuDevice::~GpuDevice() = default;

Result<GpuDevice> GpuDevice::headless() {
    Result<gpu::GlContext> context = gpu::GlContext::headless();
    if (!context) return context.error();
    GpuDevice device;
    device.impl_ = std::make_unique<Impl>(Impl{std::move(*context)});
    return device;
}

const std::string& GpuDevice::description() const {
    return impl_->context.device();
}

// ---- GpuRenderer.

struct GpuRenderer::Impl {
    const RenderScene* scene = nullptr;
    // The filters drawn once already, and the time their first draws took (warm_up()).
    std::array<bool, std::size(kAllGpuFilters)> warmed{};
    double warmup_ms = 0;
    gpu::GpuScene gpu;
    gpu::Program program, mesh_program;  // the shading pass; the meshes' raster pass
    gpu::VertexArray vertex_array;
    gpu::Buffer objects, lights;
    // The offscreen target of render(), resized on demand.
    gpu::Framebuffer framebuffer;
    gpu::Texture color;
    int target_width = 0, target_height = 0;
    // The meshes' raster pass: the nearest triangle per pixel, resized on demand.
    gpu::Framebuffer visibility;
    gpu::Texture triangle_ids, depth;
    int visibility_width = 0, visibility_height = 0;
    // Timestamps before and after a frame's draw (GL_TIMESTAMP, which every driver implements
    // alike; llvmpipe's GL_TIME_ELAPSED is not a duration), two frames' worth: draw() reads the
    // previous frame's, so that the CPU never waits on the GPU.
    gpu::Query queries[2][2];
    int frame_index = 0;

    void begin_timing(int slot) const { glQueryCounter(queries[slot][0].get(), GL_TIMESTAMP); }
    void end_timing(int slot) const { glQueryCounter(queries[slot][1].get(), GL_TIMESTAMP); }
    double elapsed_ms(int slot) const {
        GLuint64 start = 0, end = 0;
        glGetQueryObjectui64v(queries[slot][0].get(), GL_QUERY_RESULT, &start);
        glGetQueryObjectui64v(queries[slot][1].get(), GL_QUERY_RESULT, &end);
        return static_cast<double>(end - start) * 1e-6;
    }

    GLint uniform(const char* name) const { return glGetUniformLocation(program.get(), name); }
    void set_frame_uniforms(const CameraDesc& camera, int width, int height,
                            const GpuRenderOptions& options);
    void set_proxy_uniforms(const std::optional<EnvProxy>& proxy, const std::string& name,
                            const std::string& index);
    void set_slot_uniforms();
    void bind_textures(GpuFilter filter) const;
    void ensure_target(int width, int height);
    void ensure_visibility(int width, int height);
    void draw_meshes(const CameraDesc& camera, int width, int height);
    void draw_pass(const CameraDesc& camera, int width, int height,
                   const GpuRenderOptions& options);
    // A filter's first draw, on one pixel of the bound framebuffer, untimed: a driver that
    // compiles a shader (or its variant for a sampler's state) at its first draw, as Mesa's
    // llvmpipe does (seconds on a cold shader cache), does it here and not in a frame's time.
    void warm_up(const CameraDesc& camera, int width, int height, const GpuRenderOptions& options);
};

namespace {

int mode_code(GpuFilter filter) {
    return static_cast<int>(filter);  // common.glsl's MODE_* are in GpuFilter's order
}

int layout_code(const gpu::GpuScene& gpu) {
    if (!gpu.has_environment) return -1;
    return static_cast<int>(gpu.layout);  // environment.glsl's ENV_* are in EnvLayout's order
}

void set_vec3(GLint location, Vec3d v) {
    glUniform3f(location, static_cast<float>(v.x), static_cast<float>(v.y),
                static_cast<float>(v.z));
}

// render/camera.h's pinhole camera, at the origin (gpu_scene.h: camera-relative positions), and
// the meshes' offset from it, as the uniforms of the program in use.
void set_camera_uniforms(GLuint program, const CameraDesc& camera, int width, int height,
                         const gpu::GpuScene& gpu) {
    auto location = [&](const char* name) { return glGetUniformLocation(program, name); };
    const PinholeCamera pinhole(camera, width, height);
    set_vec3(location("u_camera_forward"), pinhole.forward());
    set_vec3(location("u_camera_right"), pinhole.right());
    set_vec3(location("u_camera_up"), pinhole.up());
    glUniform1f(location("u_pixel_angle"), static_cast<float>(pinhole.pixel_angle()));
    glUniform2i(location("u_size"), width, height);
    set_vec3(location("u_mesh_offset"), gpu.meshes.anchor - camera.position);
    set_vec3(location("u_camera_position"), camera.position);
}

}  // namespace

void GpuRenderer::Impl::set_frame_uniforms(const CameraDesc& camera, int width, int height,
                                           const GpuRenderOptions& options) {
    set_camera_uniforms(program.get(), camera, width, height, gpu);
    glUniform1i(uniform("u_mesh_triangles"), gpu.meshes.triangle_count);
    glUniform1i(uniform("u_mode"), mode_code(options.filter));
    glUniform1i(uniform("u_max_probes"), std::clamp(options.max_probes, 1, kMaxProbeCount));
    glUniform1f(uniform("u_kappa"), options.kappa);
    const Vec3 b = scene->desc().background;
    glUniform3f(uniform("u_background"), b.x, b.y, b.z);

    const std::vector<gpu::ObjectRecord> objects_now =
        gpu::object_records(*scene, gpu, camera.position);
    const std::vector<gpu::LightRecord> lights_now =
        gpu::light_records(scene->desc(), camera.position);
    glNamedBufferSubData(objects.get(), 0,
                         static_cast<GLsizeiptr>(objects_now.size() * sizeof(gpu::ObjectRecord)),
                         objects_now.data());
    glNamedBufferSubData(lights.get(), 0,
                         static_cast<GLsizeiptr>(lights_now.size() * sizeof(gpu::LightRecord)),
                         lights_now.data());
    glUniform1i(uniform("u_object_count"), static_cast<int>(objects_now.size()));
    glUniform1i(uniform("u_light_count"), static_cast<int>(lights_now.size()));

    glUniform1i(uniform("u_env_layout"), layout_code(gpu));
    set_slot_uniforms();
    if (const RenderEnvironment* env = scene->environment()) {
        glUniformMatrix3fv(uniform("u_env_rotation"), 1, GL_TRUE, &env->rotation.m[0][0]);
        const Vec2 s = env->texel_scale;
        glUniform2f(uniform("u_env_texel_scale"), s.x, s.y);
        glUniform1i(uniform("u_env_caps"), gpu.has_caps ? 1 : 0);
        glUniform3fv(uniform("u_env_sh"), 9, &env->irradiance.coefficients[0].x);
        set_proxy_uniforms(env->proxy, "u_env_proxy", "");
        constexpr int kMaxEnvLevels = 16;  // environment.glsl's
        std::array<float, kMaxEnvLevels> prefilter{};
        for (std::size_t l = 0; l < gpu.env_prefilter.size(); ++l)
            prefilter[std::min<std::size_t>(l, kMaxEnvLevels - 1)] = gpu.env_prefilter[l];
        glUniform1fv(uniform("u_env_prefilter"), kMaxEnvLevels, prefilter.data());
        glUniform2i(uniform("u_env_wrap"), gpu.env_repeat[0] ? 1 : 0, gpu.env_repeat[1] ? 1 : 0);
    }
}

// A proxy as environment.glsl's uniforms `name` (its shape), `name`_min, _max and _capture, each
// with `index` ("" or "[k]") after it.
void GpuRenderer::Impl::set_proxy_uniforms(const std::optional<EnvProxy>& proxy,
                                           const std::string& name, const std::string& index) {
    glUniform1i(uniform((name + index).c_str()), !proxy                                 ? 0
                                                 : proxy->shape == EnvProxy::Shape::box ? 1
                                                                                        : 2);
    if (!proxy) return;
    const bool box = proxy->shape == EnvProxy::Shape::box;
    const Vec3 lo = box ? proxy->min : proxy->center;
    const Vec3 hi = box ? proxy->max : Vec3{proxy->radius, 0, 0};
    const Vec3 c = proxy->capture;
    glUniform3f(uniform((name + "_min" + index).c_str()), lo.x, lo.y, lo.z);
    glUniform3f(uniform((name + "_max" + index).c_str()), hi.x, hi.y, hi.z);
    glUniform3f(uniform((name + "_capture" + index).c_str()), c.x, c.y, c.z);
}

// Each cube slot's size, rotation, proxy and irradiance (environment.glsl's u_slot_*).
void GpuRenderer::Impl::set_slot_uniforms() {
    glUniform1i(uniform("u_local_count"), gpu.local_count);
    for (std::size_t k = 0; k < gpu.slots.size(); ++k) {
        const RenderEnvironment& env = *gpu.slots[k].source;
        const std::string index = "[" + std::to_string(k) + "]";
        glUniform1f(uniform(("u_slot_size" + index).c_str()), gpu.slots[k].size);
        glUniformMatrix3fv(uniform(("u_slot_rotation" + index).c_str()), 1, GL_TRUE,
                           &env.rotation.m[0][0]);
        set_proxy_uniforms(env.proxy, "u_slot_proxy", index);
        glUniform3fv(uniform(("u_slot_sh[" + std::to_string(9 * k) + "]").c_str()), 9,
                     &env.irradiance.coefficients[0].x);
    }
}

void GpuRenderer::Impl::bind_textures(GpuFilter filter) const {
    const bool anisotropic = filter == GpuFilter::hw_aniso;
    auto bind = [&](int unit, const gpu::MapTexture& map) {
        glBindTextureUnit(static_cast<GLuint>(unit), map.texture.get());
        glBindSampler(static_cast<GLuint>(unit),
                      anisotropic ? map.anisotropic.get() : map.trilinear.get());
        glUniform4f(uniform(("u_map_info[" + std::to_string(unit) + "]").c_str()),
                    static_cast<float>(map.width), static_cast<float>(map.height),
                    static_cast<float>(map.levels - 1), static_cast<float>(map.layers));
    };
    for (std::size_t i = 0; i < gpu.material_maps.size(); ++i)
        bind(static_cast<int>(i), gpu.material_maps[i]);
    if (gpu.env_map.texture) bind(gpu::kEnvUnit, gpu.env_map);
    if (gpu.caps.texture) bind(gpu::kCapsUnit, gpu.caps);
    if (gpu.cube) {
        glBindTextureUnit(gpu::kCubeUnit, gpu.cube.get());
        glBindSampler(gpu::kCubeUnit, gpu.cube_sampler.get());
    }
    for (std::size_t k = 0; k < gpu.slots.size(); ++k) {
        const auto unit = static_cast<GLuint>(gpu::kSlotUnit + static_cast<int>(k));
        glBindTextureUnit(unit, gpu.slots[k].cube.get());
        glBindSampler(unit, gpu.slot_sampler.get());
    }
    if (gpu.meshes.triangle_count > 0) {
        glBindTextureUnit(gpu::kVisibilityUnit, triangle_ids.get());
        glBindSampler(gpu::kVisibilityUnit, 0);
    }
}

void GpuRenderer::Impl::ensure_target(int width, int height) {
    if (width == target_width && height == target_height) return;
    color = gpu::create_texture(GL_TEXTURE_2D);
    glTextureStorage2D(color.get(), 1, GL_RGBA32F, width, height);
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    framebuffer = gpu::Framebuffer(name);
    glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT0, color.get(), 0);
    target_width = width;
    target_height = height;
}

void GpuRenderer::Impl::ensure_visibility(int width, int height) {
    if (width == visibility_width && height == visibility_height) return;
    triangle_ids = gpu::create_texture(GL_TEXTURE_2D);
    glTextureStorage2D(triangle_ids.get(), 1, GL_R32UI, width, height);
    // An integer texture is complete only with nearest filtering (texelFetch reads it).
    glTextureParameteri(triangle_ids.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(triangle_ids.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    depth = gpu::create_texture(GL_TEXTURE_2D);
    glTextureStorage2D(depth.get(), 1, GL_DEPTH_COMPONENT32F, width, height);
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    visibility = gpu::Framebuffer(name);
    glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT0, triangle_ids.get(), 0);
    glNamedFramebufferTexture(name, GL_DEPTH_ATTACHMENT, depth.get(), 0);
    visibility_width = width;
    visibility_height = height;
}

// The meshes' raster pass (mesh.vert, visibility.frag): the nearest triangle at each pixel centre,
// with reversed depth; it leaves the depth state as it found it (off, GL's default clip range).
void GpuRenderer::Impl::draw_meshes(const CameraDesc& camera, int width, int height) {
    ensure_visibility(width, height);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, visibility.get());
    glViewport(0, 0, width, height);
    const GLuint no_triangle[4] = {0, 0, 0, 0};
    const GLfloat farthest = 0;
    glDepthMask(GL_TRUE);
    glClearNamedFramebufferuiv(visibility.get(), GL_COLOR, 0, no_triangle);
    glClearNamedFramebufferfv(visibility.get(), GL_DEPTH, 0, &farthest);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glUseProgram(mesh_program.get());
    set_camera_uniforms(mesh_program.get(), camera, width, height, gpu);
    glBindVertexArray(gpu.meshes.vertex_array.get());
    glDrawElements(GL_TRIANGLES, 3 * gpu.meshes.triangle_count, GL_UNSIGNED_INT, nullptr);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
}

void GpuRenderer::Impl::draw_pass(const CameraDesc& camera, int width, int height,
                                  const GpuRenderOptions& options) {
    if (gpu.meshes.triangle_count > 0) {
        GLint target = 0;
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
        draw_meshes(camera, width, height);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(target));
    }
    glUseProgram(program.get());
    set_frame_uniforms(camera, width, height, options);
    bind_textures(options.filter);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, objects.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, gpu.material_buffer.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, lights.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, gpu.meshes.vertices.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, gpu.meshes.triangles.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, gpu.meshes.parts.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, gpu.meshes.bvh_nodes.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, gpu.meshes.bvh_triangles.get());
    glBindVertexArray(vertex_array.get());
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

GpuRenderer::GpuRenderer() = default;
GpuRenderer::GpuRenderer(GpuRenderer&&) noexcept = default;
GpuRenderer& GpuRenderer::operator=(GpuRenderer&&) noexcept = default;
GpuRenderer::~GpuRenderer() = default;

namespace {

// The sampler uniforms point at their texture units once (gpu_scene.h's kMaterialUnits …).
void assign_units(GLuint program) {
    auto set = [&](const std::string& name, int unit) {
        const GLint location = glGetUniformLocation(program, name.c_str());
        if (location >= 0) glProgramUniform1i(program, location, unit);
    };
    for (int unit = 0; unit <= gpu::kCapsUnit; ++unit)
        set("u_maps[" + std::to_string(unit) + "]", unit);
    set("u_env_cube", gpu::kCubeUnit);
    set("u_visibility", gpu::kVisibilityUnit);
    for (std::size_t k = 0; k < gpu::kMaxCubeSlots; ++k)
        set("u_slot_cubes[" + std::to_string(k) + "]", gpu::kSlotUnit + static_cast<int>(k));
}

}  // namespace

Result<GpuRenderer> GpuRenderer::create(const RenderScene& scene) {
    auto impl = std::make_unique<Impl>();
    impl->scene = &scene;
    Result<gpu::GpuScene> uploaded = gpu::upload_scene(scene);
    if (!uploaded) return uploaded.error();
    impl->gpu = std::move(*uploaded);
    using namespace gpu::shaders;
    Result<gpu::Program> program = gpu::compile_graphics_program(
        {kFullscreenVert}, {kCommonGlsl, kGeometryGlsl, kFilteringGlsl, kProceduralGlsl, kBumpGlsl,
                            kEnvironmentGlsl, kShadingGlsl, kRenderFrag});
    if (!program) return program.error();
    impl->program = std::move(*program);
    assign_units(impl->program.get());
    if (impl->gpu.meshes.triangle_count > 0) {
        Result<gpu::Program> mesh_program =
            gpu::compile_graphics_program({kMeshVert}, {kVisibilityFrag});
        if (!mesh_program) return mesh_program.error();
        impl->mesh_program = std::move(*mesh_program);
    }
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    impl->vertex_array = gpu::VertexArray(vao);
    const std::size_t objects = std::max<std::size_t>(1, scene.desc().objects.size());
    const std::size_t lights = std::max<std::size_t>(1, scene.desc().lights.size());
    impl->objects = gpu::create_buffer();
    glNamedBufferStorage(impl->objects.get(),
                         static_cast<GLsizeiptr>(objects * sizeof(gpu::ObjectRecord)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    impl->lights = gpu::create_buffer();
    glNamedBufferStorage(impl->lights.get(),
                         static_cast<GLsizeiptr>(lights * sizeof(gpu::LightRecord)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    for (auto& pair : impl->queries)
        for (gpu::Query& q : pair) {
            GLuint name = 0;
            glCreateQueries(GL_TIMESTAMP, 1, &name);
            q = gpu::Query(name);
        }
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    if (std::string e = gpu::gl_error("preparing the GPU renderer"); !e.empty()) return Error{e};
    GpuRenderer renderer;
    renderer.impl_ = std::move(impl);
    return renderer;
}

void GpuRenderer::Impl::warm_up(const CameraDesc& camera, int width, int height,
                                const GpuRenderOptions& options) {
    bool& done = warmed[static_cast<std::size_t>(options.filter)];
    if (done) return;
    const auto start = std::chrono::steady_clock::now();
    GLboolean scissored = GL_FALSE;
    GLint box[4] = {0, 0, 0, 0};
    glGetBooleanv(GL_SCISSOR_TEST, &scissored);
    glGetIntegerv(GL_SCISSOR_BOX, box);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 1, 1);
    draw_pass(camera, width, height, options);
    glFinish();
    glScissor(box[0], box[1], box[2], box[3]);
    if (!scissored) glDisable(GL_SCISSOR_TEST);
    warmup_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    done = true;
}

double GpuRenderer::warmup_ms() const {
    return impl_->warmup_ms;
}

Result<Image> GpuRenderer::render(const GpuRenderOptions& options, GpuFrameStats* stats) {
    const SceneDesc& desc = impl_->scene->desc();
    const CameraDesc camera = options.frame_count >= 1
                                  ? camera_for_frame(desc, options.frame, options.frame_count)
                                  : desc.camera;
    return render(camera, desc.width, desc.height, options, stats);
}

Result<Image> GpuRenderer::render(const CameraDesc& camera, int width, int height,
                                  const GpuRenderOptions& options, GpuFrameStats* stats) {
    GLint max_size[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, max_size);
    if (width < 1 || height < 1 || width > max_size[0] || height > max_size[1])
        return Error{"image size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is outside 1x1 to " + std::to_string(max_size[0]) + "x" +
                     std::to_string(max_size[1]) + " on this GPU"};
    Impl& impl = *impl_;
    impl.ensure_target(width, height);
    // Framebuffer row j is image row j (render.frag), so a band is a scissor of its rows.
    const int first = options.rows ? std::clamp(options.rows->begin, 0, height) : 0;
    const int rows = options.rows ? std::clamp(options.rows->end, first, height) - first : height;
    if (rows == 0) return Image(width, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, impl.framebuffer.get());
    if (options.rows) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, first, width, rows);
    }
    impl.warm_up(camera, width, height, options);
    const auto start = std::chrono::steady_clock::now();
    impl.begin_timing(0);
    impl.draw_pass(camera, width, height, options);
    impl.end_timing(0);
    glFinish();
    glDisable(GL_SCISSOR_TEST);
    const double wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::vector<float> rgba(static_cast<std::size_t>(width) * rows * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, first, width, rows, GL_RGBA, GL_FLOAT, rgba.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    const double gpu_ms = impl.elapsed_ms(0);
    if (std::string e = gpu::gl_error("rendering a frame"); !e.empty()) return Error{e};
    if (stats) *stats = {gpu_ms, wall_ms};
    Image image(width, rows, 3);
    for (std::size_t i = 0; i < image.pixel_count(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels[i * 3 + c] = rgba[i * 4 + c];
    return image;
}

double GpuRenderer::draw(const CameraDesc& camera, int width, int height,
                         const GpuRenderOptions& options) {
    Impl& impl = *impl_;
    impl.warm_up(camera, width, height, options);
    const int now = impl.frame_index % 2, previous = 1 - now;
    impl.begin_timing(now);
    impl.draw_pass(camera, width, height, options);
    impl.end_timing(now);
    const double ms = impl.frame_index > 0 ? impl.elapsed_ms(previous) : -1.0;
    ++impl.frame_index;
    return ms;
}

}  // namespace footprint
