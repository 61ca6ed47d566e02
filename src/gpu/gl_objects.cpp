#include "gpu/gl_objects.h"

#include <vector>

namespace footprint::gpu {

void delete_texture(GLuint name) {
    glDeleteTextures(1, &name);
}
void delete_buffer(GLuint name) {
    glDeleteBuffers(1, &name);
}
void delete_framebuffer(GLuint name) {
    glDeleteFramebuffers(1, &name);
}
void delete_vertex_array(GLuint name) {
    glDeleteVertexArrays(1, &name);
}
void delete_query(GLuint name) {
    glDeleteQueries(1, &name);
}
void delete_program(GLuint name) {
    glDeleteProgram(name);
}
void delete_sampler(GLuint name) {
    glDeleteSamplers(1, &name);
}

Texture create_texture(GLenum target) {
    GLuint name = 0;
    glCreateTextures(target, 1, &name);
    return Texture(name);
}

Buffer create_buffer() {
    GLuint name = 0;
    glCreateBuffers(1, &name);
    return Buffer(name);
}

namespace {

struct ShaderStage {
    GLenum type;
    const char* name;
    std::initializer_list<std::string_view> parts;
};

std::string shader_log(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    return log.c_str();
}

Result<Program> link(std::initializer_list<ShaderStage> stages) {
    Program program(glCreateProgram());
    std::vector<GLuint> shaders;
    auto release = [&] {
        for (GLuint s : shaders) glDeleteShader(s);
    };
    for (const ShaderStage& stage : stages) {
        std::vector<const GLchar*> text;
        std::vector<GLint> lengths;
        for (std::string_view part : stage.parts) {
            text.push_back(part.data());
            lengths.push_back(static_cast<GLint>(part.size()));
        }
        const GLuint shader = glCreateShader(stage.type);
        shaders.push_back(shader);
        glShaderSource(shader, static_cast<GLsizei>(text.size()), text.data(), lengths.data());
        glCompileShader(shader);
        GLint ok = GL_FALSE;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            const std::string log = shader_log(shader);
            release();
            return Error{std::string(stage.name) + " shader does not compile: " + log};
        }
        glAttachShader(program.get(), shader);
    }
    glLinkProgram(program.get());
    release();
    GLint ok = GL_FALSE;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program.get(), length, nullptr, log.data());
        return Error{"shader program does not link: " + std::string(log.c_str())};
    }
    return program;
}

}  // namespace

Result<Program> compile_graphics_program(std::initializer_list<std::string_view> vertex,
                                         std::initializer_list<std::string_view> fragment) {
    return link({{GL_VERTEX_SHADER, "vertex", vertex}, {GL_FRAGMENT_SHADER, "fragment", fragment}});
}

Result<Program> compile_compute_program(std::initializer_list<std::string_view> compute) {
    return link({{GL_COMPUTE_SHADER, "compute", compute}});
}

std::string gl_error(std::string_view what) {
    std::string first;
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
        if (!first.empty()) continue;
        switch (e) {
            case GL_OUT_OF_MEMORY:
                first = "GL_OUT_OF_MEMORY";
                break;
            case GL_INVALID_ENUM:
                first = "GL_INVALID_ENUM";
                break;
            case GL_INVALID_VALUE:
                first = "GL_INVALID_VALUE";
                break;
            case GL_INVALID_OPERATION:
                first = "GL_INVALID_OPERATION";
                break;
            case GL_INVALID_FRAMEBUFFER_OPERATION:
                first = "GL_INVALID_FRAMEBUFFER_OPERATION";
                break;
            default:
                first = "GL error " + std::to_string(e);
        }
        first += " after " + std::string(what);
    }
    return first;
}

}  // namespace footprint::gpu
