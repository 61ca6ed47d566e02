// gpu/gl_context.h — (private to gpu) an OpenGL 4.5 core context made current on this thread:
// headless through EGL, for rendering to images and for the tests, with no display or window.
//
// EGL's platforms are tried in this order:
//   surfaceless (EGL_MESA_platform_surfaceless)  Mesa: llvmpipe in CI, and Mesa's GPU drivers
//   device      (EGL_EXT_platform_device)        NVIDIA's and other vendors' drivers without X
// A context that cannot be made (no EGL, no OpenGL 4.5 core) is an Error that says which step
// failed, so that callers can report it (the tests skip with it where no EGL device exists).
// Contexts nest like scopes: destroying one makes the context current again that was current
// when it was made.
#pragma once

#include <memory>
#include <string>

#include "core/result.h"

namespace footprint::gpu {

class GlContext {
  public:
    static Result<GlContext> headless();

    GlContext(GlContext&&) noexcept;
    GlContext& operator=(GlContext&&) noexcept;
    ~GlContext();

    // "renderer | OpenGL version" of the context (GL_RENDERER, GL_VERSION).
    const std::string& device() const { return device_; }

  private:
    GlContext() = default;
    struct Egl;
    std::unique_ptr<Egl> egl_;
    std::string device_;
};

// The device string of the context current on this thread.
std::string current_device_string();

}  // namespace footprint::gpu
