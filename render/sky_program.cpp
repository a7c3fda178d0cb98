// The program that draws the sky (see sky_program.h).
#include "sky_program.h"

#include "gl_shader.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace trackbed::render {
namespace {

GLuint CompileWithDefines(GLenum type, const std::string& defines, const char* source) {
  // The version line first, then the defines.
  const std::string text(source);
  const std::size_t eol = text.find('\n') + 1;
  const std::string version = text.substr(0, eol);
  return CompileShader(type, {version.c_str(), defines.c_str(), source + eol}, "the sky shader");
}

}  // namespace

SkyProgram::SkyProgram(SkyLook look, std::uint64_t seed) {
  const std::string defines = look == SkyLook::kCloudy ? "#define CLOUDS\n" : "";
  program_ = glCreateProgram();
  glAttachShader(program_, CompileWithDefines(GL_VERTEX_SHADER, "", SkyVertexShader()));
  glAttachShader(program_, CompileWithDefines(GL_FRAGMENT_SHADER, defines, SkyFragmentShader()));
  glLinkProgram(program_);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) throw std::runtime_error("Renderer: the sky shader does not link");
  world_from_eye_ = glGetUniformLocation(program_, "world_from_eye");
  sun_ = glGetUniformLocation(program_, "sun");
  gray_ = glGetUniformLocation(program_, "gray");
  ray_from_window_ = glGetUniformLocation(program_, "ray_from_window");
  glUseProgram(program_);
  const Eigen::Vector2f offset = CloudOffset(seed);
  glUniform2f(glGetUniformLocation(program_, "cloud_offset"), offset.x(), offset.y());
  glUseProgram(0);
}

void SkyProgram::Draw(const Eigen::Matrix4d& view, const Eigen::Vector3d& sun, double gray,
                      double exposure, const geometry::PinholeCamera& K) const {
  const Eigen::Matrix3f world_from_eye = view.topLeftCorner<3, 3>().transpose().cast<float>();
  glUseProgram(program_);
  glUniformMatrix3fv(world_from_eye_, 1, GL_FALSE, world_from_eye.data());
  glUniform3f(sun_, static_cast<float>(sun.x()), static_cast<float>(sun.y()),
              static_cast<float>(sun.z()));
  glUniform1f(gray_, static_cast<float>(gray * exposure));
  // Window (x, y) to the eye ray (x, y, -1), as the outline's band (pinhole.cpp).
  glUniform4f(ray_from_window_, static_cast<float>(1.0 / K.fx),
              static_cast<float>(-(K.cx + 0.5) / K.fx), static_cast<float>(1.0 / K.fy),
              static_cast<float>((K.cy + 0.5 - K.height_px) / K.fy));
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glBegin(GL_QUADS);
  for (const auto& [x, y] :
       {std::pair{-1.0, -1.0}, std::pair{1.0, -1.0}, std::pair{1.0, 1.0}, std::pair{-1.0, 1.0}}) {
    glVertex2d(x, y);
  }
  glEnd();
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glUseProgram(0);
}

}  // namespace trackbed::render
