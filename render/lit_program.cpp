// The lit shader program (see lit_program.h).
#include "lit_program.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace trackbed::render {
namespace {

// Per vertex, as the fixed-function pipeline lights: ambient, and the sun's diffuse
// term (normals are unit and the model-view rigid, so no renormalisation).
constexpr const char* kVertexShader = R"(#version 120
uniform mat4 world_from_eye;
uniform vec3 sun_eye;
uniform vec2 light_origin;
uniform vec2 light_per_m;
uniform float diffuse;
varying vec2 albedo_st;
varying vec2 light_st;
varying float direct;
void main() {
  vec4 eye = gl_ModelViewMatrix * gl_Vertex;
  direct = diffuse * max(dot(gl_NormalMatrix * gl_Normal, sun_eye), 0.0);
  light_st = ((world_from_eye * eye).xy - light_origin) * light_per_m;
  albedo_st = gl_MultiTexCoord0.xy;
  gl_Position = gl_ProjectionMatrix * eye;
}
)";

// Per fragment: the sun's term shadowed by the texel's sunlit fraction, clamped as the
// fixed-function lit colour is, then the zones' gain and the exposure (the 8-bit
// output clips).
constexpr const char* kFragmentShader = R"(#version 120
uniform sampler2D albedo;
uniform sampler2D light;
uniform float ambient;
uniform float exposure;
varying vec2 albedo_st;
varying vec2 light_st;
varying float direct;
void main() {
  vec2 l = texture2D(light, light_st).rg;
  float shade = min(ambient + direct * l.r, 1.0) * l.g;
  gl_FragColor = vec4(vec3(texture2D(albedo, albedo_st).r * shade * exposure), 1.0);
}
)";

GLuint Compile(GLenum type, const char* source) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    throw std::runtime_error(std::string("Renderer: the lit shader does not compile: ") + log);
  }
  return shader;
}

}  // namespace

LitProgram::LitProgram(const LightMap& map, double ambient, double diffuse) {
  program_ = glCreateProgram();
  glAttachShader(program_, Compile(GL_VERTEX_SHADER, kVertexShader));
  glAttachShader(program_, Compile(GL_FRAGMENT_SHADER, kFragmentShader));
  glLinkProgram(program_);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) throw std::runtime_error("Renderer: the lit shader does not link");
  glUseProgram(program_);
  glUniform1i(glGetUniformLocation(program_, "albedo"), 0);
  glUniform1i(glGetUniformLocation(program_, "light"), 1);
  glUniform1f(glGetUniformLocation(program_, "ambient"), static_cast<float>(ambient));
  glUniform1f(glGetUniformLocation(program_, "diffuse"), static_cast<float>(diffuse));
  glUniform2f(glGetUniformLocation(program_, "light_origin"), static_cast<float>(map.x_min),
              static_cast<float>(map.y_min));
  glUniform2f(glGetUniformLocation(program_, "light_per_m"),
              static_cast<float>(1.0 / (map.width * map.texel_m)),
              static_cast<float>(1.0 / (map.height * map.texel_m)));
  world_from_eye_ = glGetUniformLocation(program_, "world_from_eye");
  sun_eye_ = glGetUniformLocation(program_, "sun_eye");
  exposure_ = glGetUniformLocation(program_, "exposure");
  glUseProgram(0);
  // The map as one two-channel float texture on unit 1: sunlit fraction, gain.
  std::vector<float> texels(2 * map.sunlit.size());
  for (std::size_t i = 0; i < map.sunlit.size(); ++i) {
    texels[2 * i] = map.sunlit[i];
    texels[2 * i + 1] = map.gain[i];
  }
  glActiveTexture(GL_TEXTURE1);
  glGenTextures(1, &light_texture_);
  glBindTexture(GL_TEXTURE_2D, light_texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, map.width, map.height, 0, GL_RG, GL_FLOAT,
               texels.data());
  glActiveTexture(GL_TEXTURE0);
  if (glGetError() != GL_NO_ERROR) {
    throw std::runtime_error("Renderer: the light map cannot be uploaded");
  }
}

void LitProgram::Begin(const Eigen::Matrix4d& view, const Eigen::Vector3d& sun,
                       double exposure) const {
  glUseProgram(program_);
  const Eigen::Matrix4f world_from_eye = view.inverse().cast<float>();
  glUniformMatrix4fv(world_from_eye_, 1, GL_FALSE, world_from_eye.data());
  const Eigen::Vector3f sun_eye = (view.topLeftCorner<3, 3>() * sun).cast<float>();
  glUniform3f(sun_eye_, sun_eye.x(), sun_eye.y(), sun_eye.z());
  glUniform1f(exposure_, static_cast<float>(exposure));
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, light_texture_);
  glActiveTexture(GL_TEXTURE0);
}

void LitProgram::End() const { glUseProgram(0); }

}  // namespace trackbed::render
