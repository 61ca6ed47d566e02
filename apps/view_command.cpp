#include "view_command.h"

#include <epoxy/gl.h>
// GLFW after the OpenGL loader, which must own the GL declarations.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "cli_options.h"
#include "command_util.h"
#include "gpu/gpu_renderer.h"
#include "image/image_io.h"
#include "render/render_scene.h"

namespace footprint {

namespace {

constexpr int kMaxFrames = 1000000;

// GLSL of the present pass: the frame (linear, image row 0 in texture row 0) flipped onto the
// window, × 2^exposure, sRGB-encoded, with the HUD's text over it.
constexpr const char* kPresentVertex = R"(#version 450 core
out vec2 uv;
void main() {
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    uv = corner;
    gl_Position = vec4(2.0 * corner - 1.0, 0.0, 1.0);
}
)";
constexpr const char* kPresentFragment = R"(#version 450 core
in vec2 uv;
layout(location = 0) out vec4 color;
layout(binding = 0) uniform sampler2D frame;
layout(binding = 1) uniform sampler2D hud;
uniform float scale;      // 2^exposure
uniform vec2 hud_extent;  // the HUD's size as a fraction of the window
float encode(float x) {
    x = clamp(x, 0.0, 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}
void main() {
    vec3 c = scale * texture(frame, vec2(uv.x, 1.0 - uv.y)).rgb;
    vec3 srgb = vec3(encode(c.r), encode(c.g), encode(c.b));
    vec2 h = vec2(uv.x, 1.0 - uv.y) / hud_extent;
    if (h.x <= 1.0 && h.y <= 1.0)  // the HUD: white text on the frame darkened
        srgb = mix(0.35 * srgb, vec3(1.0), texture(hud, h).a);
    color = vec4(srgb, 1.0);
}
)";

GLuint compile(GLenum type, const char* source) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    return shader;
}

GLuint present_program() {
    const GLuint program = glCreateProgram();
    const GLuint vs = compile(GL_VERTEX_SHADER, kPresentVertex);
    const GLuint fs = compile(GL_FRAGMENT_SHADER, kPresentFragment);
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    return ok ? program : 0;
}

// The HUD's line as its text's coverage in alpha, `height` pixels high (OpenImageIO's text).
Image hud_image(const std::string& text, int height) {
    const int size = std::max(10, height * 2 / 3);
    const OIIO::ROI extent = OIIO::ImageBufAlgo::text_size(text, size, kLabelFont);
    const int width = extent.defined() ? extent.width() + height : 8 * height;
    OIIO::ImageBuf buf(OIIO::ImageSpec(width, height, 4, OIIO::TypeDesc::FLOAT));
    OIIO::ImageBufAlgo::zero(buf);
    const float white[4] = {1, 1, 1, 1};
    OIIO::ImageBufAlgo::render_text(buf, height / 2, height / 2, text, size, kLabelFont, white,
                                    OIIO::ImageBufAlgo::TextAlignX::Left,
                                    OIIO::ImageBufAlgo::TextAlignY::Center);
    Image image(width, height, 4);
    buf.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.pixels.data());
    return image;
}

// The orbit camera: the scene's camera turned about its look-at point and moved along its view.
struct Orbit {
    CameraDesc base;
    double yaw = 0, pitch = 0, zoom = 1;  // radians; distance factor

    CameraDesc camera() const {
        const Vec3d offset = base.position - base.look_at;
        const Vec3d up = normalize(base.up);
        // Yaw about the up axis, then pitch about the camera's right axis.
        auto rotate = [](Vec3d v, Vec3d axis, double angle) {
            const double c = std::cos(angle), s = std::sin(angle);
            return c * v + s * cross(axis, v) + (1 - c) * dot(axis, v) * axis;
        };
        Vec3d o = rotate(offset, up, yaw);
        const Vec3d right = normalize(cross(-o, up));
        o = rotate(o, right, pitch);
        CameraDesc c = base;
        c.position = base.look_at + zoom * o;
        return c;
    }
};

struct ViewState {
    Orbit orbit;
    GpuFilter filter = GpuFilter::fa_rough;
    bool dragging = false, zooming = false;
    double last_x = 0, last_y = 0;
};

void on_key(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
    auto* state = static_cast<ViewState*>(glfwGetWindowUserPointer(window));
    const auto filters = all_gpu_filters();
    if (key >= GLFW_KEY_1 && key < GLFW_KEY_1 + static_cast<int>(filters.size()))
        state->filter = filters[static_cast<std::size_t>(key - GLFW_KEY_1)];
    if (key == GLFW_KEY_M)
        state->filter = filters[(static_cast<std::size_t>(state->filter) + 1) % filters.size()];
    if (key == GLFW_KEY_R) state->orbit = Orbit{state->orbit.base};
    if (key == GLFW_KEY_ESCAPE || key == GLFW_KEY_Q) glfwSetWindowShouldClose(window, GLFW_TRUE);
}

void on_button(GLFWwindow* window, int button, int action, int) {
    auto* state = static_cast<ViewState*>(glfwGetWindowUserPointer(window));
    glfwGetCursorPos(window, &state->last_x, &state->last_y);
    if (button == GLFW_MOUSE_BUTTON_LEFT) state->dragging = action == GLFW_PRESS;
    if (button == GLFW_MOUSE_BUTTON_RIGHT) state->zooming = action == GLFW_PRESS;
}

void on_cursor(GLFWwindow* window, double x, double y) {
    auto* state = static_cast<ViewState*>(glfwGetWindowUserPointer(window));
    const double dx = x - state->last_x, dy = y - state->last_y;
    state->last_x = x, state->last_y = y;
    if (state->dragging) {
        state->orbit.yaw -= 0.005 * dx;
        state->orbit.pitch = std::clamp(state->orbit.pitch - 0.005 * dy, -1.5, 1.5);
    }
    if (state->zooming)
        state->orbit.zoom = std::clamp(state->orbit.zoom * std::exp(0.005 * dy), 0.05, 20.0);
}

void on_scroll(GLFWwindow* window, double, double dy) {
    auto* state = static_cast<ViewState*>(glfwGetWindowUserPointer(window));
    state->orbit.zoom = std::clamp(state->orbit.zoom * std::exp(-0.1 * dy), 0.05, 20.0);
}

// What a window and its GL objects hold, released in order.
struct Window {
    GLFWwindow* window = nullptr;
    ~Window() {
        if (window) glfwDestroyWindow(window);
        glfwTerminate();
    }
};

struct FrameTarget {
    GLuint texture = 0, framebuffer = 0;
    int width = 0, height = 0;
    void resize(int w, int h) {
        if (w == width && h == height) return;
        release();
        glCreateTextures(GL_TEXTURE_2D, 1, &texture);
        glTextureStorage2D(texture, 1, GL_RGBA32F, w, h);
        glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glCreateFramebuffers(1, &framebuffer);
        glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
        width = w, height = h;
    }
    void release() {
        if (framebuffer) glDeleteFramebuffers(1, &framebuffer);
        if (texture) glDeleteTextures(1, &texture);
        framebuffer = texture = 0;
    }
};

}  // namespace

int run_view_command(const ViewCommandOptions& options) {
    const Result<GpuFilter> filter = parse_gpu_render_filter(options.filter, "view");
    if (!filter) return fail(filter.error().message);
    int width = 1280, height = 720;
    if (!options.size.empty()) {
        const Result<ImageSize> size = parse_image_size("--size", options.size);
        if (!size) return fail(size.error().message);
        width = size->width;
        height = size->height;
    }
    if (options.frames)
        if (auto p = range_problem("--frames", *options.frames, 1, kMaxFrames)) return fail(*p);
    if (!std::isfinite(options.exposure)) return fail("--exposure: must be finite");
    if (!options.screenshot.empty()) {
        if (!options.frames) return fail("--screenshot needs --frames N (the frame to write)");
        if (auto p = output_file_problem(options.screenshot)) return fail(*p);
    }
    Result<NamedScene> named = resolve_scene(options.scene);
    if (!named) return fail(named.error().message);
    Result<RenderScene> scene = prepare_render_scene(named->desc);
    if (!scene) return fail(scene.error().message);

    Window window;
    if (!glfwInit()) return fail("view: no display (GLFW cannot start; is DISPLAY set?)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window.window = glfwCreateWindow(width, height, ("footprint view — " + named->name).c_str(),
                                     nullptr, nullptr);
    if (!window.window) return fail("view: no OpenGL 4.5 core window on this display");
    glfwMakeContextCurrent(window.window);
    glfwSwapInterval(0);  // frame times, not the display's refresh

    Result<GpuRenderer> renderer = GpuRenderer::create(*scene);
    if (!renderer) return fail(named->name + ": " + renderer.error().message);
    const GLuint present = present_program();
    if (!present) return fail("view: the present shader does not compile");
    GLuint vao = 0, hud_texture = 0;
    glCreateVertexArrays(1, &vao);
    glCreateTextures(GL_TEXTURE_2D, 1, &hud_texture);

    ViewState state;
    state.orbit.base = named->desc.camera;
    state.filter = *filter;
    glfwSetWindowUserPointer(window.window, &state);
    glfwSetKeyCallback(window.window, on_key);
    glfwSetMouseButtonCallback(window.window, on_button);
    glfwSetCursorPosCallback(window.window, on_cursor);
    glfwSetScrollCallback(window.window, on_scroll);

    FrameTarget target;
    Image hud;
    std::string hud_text;
    double ms_sum = 0, shown_ms = -1;
    int ms_count = 0;
    auto last_hud = std::chrono::steady_clock::now() - std::chrono::seconds(1);
    int frame = 0;
    while (!glfwWindowShouldClose(window.window)) {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window.window, &w, &h);
        w = std::max(w, 1), h = std::max(h, 1);
        target.resize(w, h);
        GpuRenderOptions render_options;
        render_options.filter = state.filter;
        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
        const double ms = renderer->draw(state.orbit.camera(), w, h, render_options);
        if (ms >= 0) ms_sum += ms, ++ms_count;
        const auto now = std::chrono::steady_clock::now();
        if (now - last_hud > std::chrono::milliseconds(500)) {
            if (ms_count > 0) shown_ms = ms_sum / ms_count;
            ms_sum = 0, ms_count = 0;
            last_hud = now;
        }
        char line[160];
        std::snprintf(line, sizeof line, "%s  |  %s  |  %dx%d", gpu_filter_name(state.filter),
                      gpu_ms_text(shown_ms).c_str(), w, h);
        if (line != hud_text) {
            hud_text = line;
            // The keys' help where the window is wide enough for it.
            hud = hud_image(hud_text + "  |  1-5 mode, drag orbit, wheel zoom", 24);
            if (hud.width > w) hud = hud_image(hud_text, 24);
            glDeleteTextures(1, &hud_texture);
            glCreateTextures(GL_TEXTURE_2D, 1, &hud_texture);
            glTextureStorage2D(hud_texture, 1, GL_RGBA32F, hud.width, hud.height);
            glTextureSubImage2D(hud_texture, 0, 0, 0, hud.width, hud.height, GL_RGBA, GL_FLOAT,
                                hud.pixels.data());
            glTextureParameteri(hud_texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, w, h);
        glUseProgram(present);
        glUniform1f(glGetUniformLocation(present, "scale"), std::exp2(options.exposure));
        glUniform2f(glGetUniformLocation(present, "hud_extent"),
                    static_cast<float>(hud.width) / static_cast<float>(w),
                    static_cast<float>(hud.height) / static_cast<float>(h));
        glBindTextureUnit(0, target.texture);
        glBindTextureUnit(1, hud_texture);
        glBindVertexArray(vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glfwSwapBuffers(window.window);
        glfwPollEvents();
        ++frame;
        if (options.frames && frame >= *options.frames) break;
    }
    if (!options.screenshot.empty()) {
        Result<Image> image = renderer->render(state.orbit.camera(), target.width, target.height,
                                               GpuRenderOptions{state.filter});
        if (!image) return fail("view: " + image.error().message);
        if (!is_float_image_file(options.screenshot) && options.exposure != 0)
            for (float& v : image->pixels) v *= std::exp2(options.exposure);
        if (Status s = save_image(*image, options.screenshot); !s) return fail(s.error().message);
    }
    glDeleteTextures(1, &hud_texture);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(present);
    target.release();
    return 0;
}

}  // namespace footprint
