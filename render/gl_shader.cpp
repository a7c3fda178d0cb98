// Shader compilation (see gl_shader.h).
#include "gl_shader.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace trackbed::render {

GLuint CompileShader(GLenum type, std::initializer_list<const char*> parts, const char* what) {
  const GLuint shader = glCreateShader(type);
  const std::vector<const char*> sources(parts);
  glShaderSource(shader, static_cast<GLsizei>(sources.size()), sources.data(), nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    throw std::runtime_error(std::string("Renderer: ") + what + " does not compile: " + log);
  }
  return shader;
}

}  // namespace trackbed::render
