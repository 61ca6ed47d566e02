// gpu/gl_objects.h — (private to gpu) owning handles for OpenGL objects, and shader programs
// compiled from the embedded GLSL sources (gpu/shaders/).
#pragma once

#include <epoxy/gl.h>

#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

#include "core/result.h"

namespace footprint::gpu {

// One GL object name, deleted with `Delete` when the handle goes (glDeleteTextures & co.).
template <void (*Delete)(GLuint)>
class GlName {
  public:
    GlName() = default;
    explicit GlName(GLuint name) : name_(name) {}
    GlName(GlName&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
    GlName& operator=(GlName&& other) noexcept {
        if (this != &other) {
            reset();
            name_ = std::exchange(other.name_, 0);
        }
        return *this;
    }
    ~GlName() { reset(); }
    GLuint get() const { return name_; }
    explicit operator bool() const { return name_ != 0; }
    void reset() {
        if (name_) Delete(name_);
        name_ = 0;
    }

  private:
    GLuint name_ = 0;
};

void delete_texture(GLuint name);
void delete_buffer(GLuint name);
void delete_framebuffer(GLuint name);
void delete_vertex_array(GLuint name);
void delete_query(GLuint name);
void delete_program(GLuint name);
void delete_sampler(GLuint name);

using Texture = GlName<delete_texture>;
using Buffer = GlName<delete_buffer>;
using Framebuffer = GlName<delete_framebuffer>;
using VertexArray = GlName<delete_vertex_array>;
using Query = GlName<delete_query>;
using Program = GlName<delete_program>;
using Sampler = GlName<delete_sampler>;

Texture create_texture(GLenum target);
Buffer create_buffer();

// A program of one vertex and one fragment shader, or one compute shader, each given as the
// concatenation of `parts` (the #version line comes first). A compile or link failure is an Error
// holding the driver's log with the stage's name.
Result<Program> compile_graphics_program(std::initializer_list<std::string_view> vertex,
                                         std::initializer_list<std::string_view> fragment);
Result<Program> compile_compute_program(std::initializer_list<std::string_view> compute);

// The first pending GL error as text ("GL_OUT_OF_MEMORY after `what`"), or empty; clears all.
std::string gl_error(std::string_view what);

}  // namespace footprint::gpu
