#include <project/gl/detail/gl_program.h>

#include <epoxy/gl.h>

#include <string>
#include <vector>

namespace tr::gl::detail {
namespace {

constexpr const char* kGlslVersion = "#version 330 core\n";

Result<GLuint> compile(GLenum type, std::initializer_list<const char*> parts, const char* name) {
    std::vector<const char*> sources{kGlslVersion};
    sources.insert(sources.end(), parts.begin(), parts.end());
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, static_cast<GLsizei>(sources.size()), sources.data(), nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = {0};
        glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
        glDeleteShader(shader);
        return make_error(ErrorCode::kUnsupported,
                          std::string("GL shader '") + name + "' does not compile: " + log);
    }
    return shader;
}

}  // namespace

Result<unsigned int> link_program(std::initializer_list<const char*> vertex_parts,
                                  std::initializer_list<const char*> fragment_parts,
                                  const char* name) {
    TR_TRY(const GLuint v, compile(GL_VERTEX_SHADER, vertex_parts, name));
    auto f = compile(GL_FRAGMENT_SHADER, fragment_parts, name);
    if (!f.ok()) {
        glDeleteShader(v);
        return f.error();
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, v);
    glAttachShader(program, *f);
    glLinkProgram(program);
    glDeleteShader(v);
    glDeleteShader(*f);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {0};
        glGetProgramInfoLog(program, sizeof(log), nullptr, log);
        glDeleteProgram(program);
        return make_error(ErrorCode::kUnsupported,
                          std::string("GL program '") + name + "' does not link: " + log);
    }
    return program;
}

}  // namespace tr::gl::detail
