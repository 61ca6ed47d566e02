#include "gpu/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <vector>

namespace footprint::gpu {

struct GlContext::Egl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    // The context that was current before this one (another device's, or none): current again
    // when this one goes, so that contexts nest like scopes.
    EGLDisplay previous_display = eglGetCurrentDisplay();
    EGLSurface previous_draw = eglGetCurrentSurface(EGL_DRAW);
    EGLSurface previous_read = eglGetCurrentSurface(EGL_READ);
    EGLContext previous_context = eglGetCurrentContext();

    ~Egl() {
        if (display == EGL_NO_DISPLAY) return;
        if (eglGetCurrentContext() == context || context == EGL_NO_CONTEXT) {
            if (previous_context != EGL_NO_CONTEXT)
                eglMakeCurrent(previous_display, previous_draw, previous_read, previous_context);
            else
                eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        }
        if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
        // Not eglTerminate: displays are shared per platform and device, and terminating one
        // would take the other contexts on it (an enclosing device's) with it.
    }
};

namespace {

bool has_client_extension(const char* name) {
    return epoxy_has_egl_extension(EGL_NO_DISPLAY, name);
}

// The displays worth trying, best first (gl_context.h).
std::vector<EGLDisplay> candidate_displays() {
    std::vector<EGLDisplay> displays;
    if (has_client_extension("EGL_MESA_platform_surfaceless")) {
        EGLDisplay d =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d != EGL_NO_DISPLAY) displays.push_back(d);
    }
    if (has_client_extension("EGL_EXT_platform_device") &&
        has_client_extension("EGL_EXT_device_enumeration")) {
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        if (eglQueryDevicesEXT(8, devices, &count))
            for (EGLint i = 0; i < count; ++i) {
                EGLDisplay d =
                    eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                if (d != EGL_NO_DISPLAY) displays.push_back(d);
            }
    }
    return displays;
}

EGLContext create_core_context(EGLDisplay display) {
    if (!eglBindAPI(EGL_OPENGL_API)) return EGL_NO_CONTEXT;
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 4,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_NONE};
    // No config: the context renders only to framebuffer objects (EGL_KHR_no_config_context).
    return eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
}

}  // namespace

Result<GlContext> GlContext::headless() {
    if (!has_client_extension("EGL_EXT_platform_base"))
        return Error{
            "no EGL with platform displays (EGL_EXT_platform_base): install libegl1 and "
            "a driver (Mesa: libgl1-mesa-dri)"};
    std::string tried;
    for (EGLDisplay display : candidate_displays()) {
        auto egl = std::make_unique<Egl>();
        egl->display = display;
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display, &major, &minor)) {
            egl->display = EGL_NO_DISPLAY;
            tried += " (a display failed to initialise)";
            continue;
        }
        if (!epoxy_has_egl_extension(display, "EGL_KHR_no_config_context") &&
            !epoxy_has_egl_extension(display, "EGL_KHR_surfaceless_context")) {
            tried += " (a display without surfaceless contexts)";
            continue;
        }
        egl->context = create_core_context(display);
        if (egl->context == EGL_NO_CONTEXT) {
            tried += " (a display without an OpenGL 4.5 core context)";
            continue;
        }
        if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl->context)) {
            tried += " (a context that could not be made current)";
            continue;
        }
        GlContext context;
        context.egl_ = std::move(egl);
        context.device_ = current_device_string();
        return context;
    }
    return Error{"no headless OpenGL 4.5 context through EGL" +
                 (tried.empty() ? std::string(": no EGL display (surfaceless or device)") : tried)};
}

GlContext::GlContext(GlContext&&) noexcept = default;
GlContext& GlContext::operator=(GlContext&&) noexcept = default;
GlContext::~GlContext() = default;

std::string current_device_string() {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    return std::string(renderer ? renderer : "?") + " | OpenGL " + (version ? version : "?");
}

}  // namespace footprint::gpu
