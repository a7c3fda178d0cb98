// Draws leafy tree crowns (see leaf_crown_drawing.h).
#include "leaf_crown_drawing.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "gl_shader.h"
#include "trackbed/render/leaf_crown.h"

namespace trackbed::render {
namespace {

constexpr const char* kLeafVersion = "#version 130\n";

// Lit on either face: the ambient and the sun's diffuse term by |n . sun|.
constexpr const char* kLeafVertexShader = R"(
uniform vec3 sun_eye;
uniform float ambient;
uniform float diffuse;
out vec3 spray_st;
out float shade;
void main() {
  vec3 normal = gl_NormalMatrix * gl_Normal;
  shade = min(ambient + diffuse * abs(dot(normal, sun_eye)), 1.0);
  spray_st = gl_MultiTexCoord0.xyz;
  gl_Position = gl_ProjectionMatrix * (gl_ModelViewMatrix * gl_Vertex);
}
)";

// The spray's coverage over the pixel's footprint (the mip level llvmpipe takes from the
// quad's derivatives), and its grey where covered: each pass keeps its pixels.
constexpr const char* kLeafFragmentShader = R"(
uniform sampler2DArray sprays;
uniform float exposure;
in vec3 spray_st;
in float shade;
void main() {
  vec2 gc = texture(sprays, spray_st).rg;
  float c = gc.g;
#if defined(CORE)
  if (c < WHOLE) discard;
#elif defined(FRINGE)
  if (c >= WHOLE || c < 0.5 / 255.0) discard;
#else
  if (c < 0.5) discard;
#endif
  float grey = gc.r / max(c, 1.0 / 255.0);
  gl_FragColor = vec4(vec3(grey * shade * exposure), c);
}
)";

// Coverage at or above which a pixel is wholly a leaf's: the top 8-bit level.
constexpr const char* kWhole = "#define WHOLE (254.5 / 255.0)\n";

// The sprays as one texture array of two channels (grey premultiplied by coverage, and
// coverage), each layer with its mip chain box-filtered 2 x 2 down to 1 x 1, every level
// rounded from the exact means of level 0 (so no rounding accumulates).
GLuint UploadSprays(const std::vector<LeafSpray>& sprays) {
  const int n = sprays.front().size_px;
  const int layers = static_cast<int>(sprays.size());
  GLuint name = 0;
  glGenTextures(1, &name);
  glBindTexture(GL_TEXTURE_2D_ARRAY, name);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  // Level 0 as doubles: premultiplied grey and coverage, both 0-255.
  std::vector<double> level(static_cast<std::size_t>(2) * n * n * layers);
  for (int l = 0; l < layers; ++l) {
    for (int k = 0; k < n * n; ++k) {
      const double c = sprays[static_cast<std::size_t>(l)].coverage[static_cast<std::size_t>(k)];
      const double g = sprays[static_cast<std::size_t>(l)].grey[static_cast<std::size_t>(k)];
      const std::size_t at = 2 * (static_cast<std::size_t>(l) * n * n + k);
      level[at] = g * c / 255.0;
      level[at + 1] = c;
    }
  }
  int lod = 0;
  for (int size = n;; size /= 2, ++lod) {
    std::vector<std::uint8_t> bytes(level.size());
    for (std::size_t k = 0; k < level.size(); ++k) {
      bytes[k] = static_cast<std::uint8_t>(std::lround(level[k]));
    }
    glTexImage3D(GL_TEXTURE_2D_ARRAY, lod, GL_RG8, size, size, layers, 0, GL_RG, GL_UNSIGNED_BYTE,
                 bytes.data());
    if (size == 1) break;
    const int half = size / 2;
    std::vector<double> next(static_cast<std::size_t>(2) * half * half * layers);
    for (int l = 0; l < layers; ++l) {
      for (int y = 0; y < half; ++y) {
        for (int x = 0; x < half; ++x) {
          for (int ch = 0; ch < 2; ++ch) {
            const auto src = [&](int xx, int yy) {
              return level[2 * ((static_cast<std::size_t>(l) * size + yy) * size + xx) +
                           static_cast<std::size_t>(ch)];
            };
            next[2 * ((static_cast<std::size_t>(l) * half + y) * half + x) +
                 static_cast<std::size_t>(ch)] =
                0.25 * (src(2 * x, 2 * y) + src(2 * x + 1, 2 * y) + src(2 * x, 2 * y + 1) +
                        src(2 * x + 1, 2 * y + 1));
          }
        }
      }
    }
    level = std::move(next);
  }
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, lod);
  return name;
}

}  // namespace

LeafCrowns::LeafCrowns(std::uint64_t seed, double ambient, double diffuse) {
  const std::vector<LeafSpray> sprays = MakeLeafSprays(seed);
  for (const LeafSpray& s : sprays) leaf_area_m2_.push_back(s.leaf_area_m2);
  const char* passes[3] = {"#define CORE\n", "#define FRINGE\n", "#define DEPTH\n"};
  for (int p = 0; p < 3; ++p) {
    Program& out = programs_[p];
    out.program = glCreateProgram();
    glAttachShader(out.program, CompileShader(GL_VERTEX_SHADER, {kLeafVersion, kLeafVertexShader},
                                              "the leaf shader"));
    glAttachShader(
        out.program,
        CompileShader(GL_FRAGMENT_SHADER, {kLeafVersion, passes[p], kWhole, kLeafFragmentShader},
                      "the leaf shader"));
    glLinkProgram(out.program);
    GLint ok = GL_FALSE;
    glGetProgramiv(out.program, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) throw std::runtime_error("Renderer: the leaf shader does not link");
    glUseProgram(out.program);
    glUniform1i(glGetUniformLocation(out.program, "sprays"), 0);
    glUniform1f(glGetUniformLocation(out.program, "ambient"), static_cast<float>(ambient));
    glUniform1f(glGetUniformLocation(out.program, "diffuse"), static_cast<float>(diffuse));
    out.sun_eye = glGetUniformLocation(out.program, "sun_eye");
    out.exposure = glGetUniformLocation(out.program, "exposure");
  }
  glUseProgram(0);
  texture_ = UploadSprays(sprays);
}

GLuint LeafCrowns::Compile(const sim::StaticObject& tree, double radius_m,
                           std::uint64_t scene_seed) const {
  const Eigen::Vector3d top(tree.center_m.x(), tree.center_m.y(), tree.base_z_m + tree.height_m);
  const std::vector<LeafCard> cards =
      LeafCrownCards(top, radius_m, LeafCrownSeed(scene_seed, tree.center_m), leaf_area_m2_);
  const GLuint list = glGenLists(1);
  glNewList(list, GL_COMPILE);
  glBegin(GL_QUADS);
  for (const LeafCard& c : cards) {
    const Eigen::Vector3d n = c.Normal();
    glNormal3d(n.x(), n.y(), n.z());
    for (const auto& [s, t] :
         {std::pair{0.0, 0.0}, std::pair{1.0, 0.0}, std::pair{1.0, 1.0}, std::pair{0.0, 1.0}}) {
      const Eigen::Vector3d p = c.center + (2 * s - 1) * c.half_u + (2 * t - 1) * c.half_v;
      glMultiTexCoord3d(GL_TEXTURE0, s, t, c.variant);
      glVertex3d(p.x(), p.y(), p.z());
    }
  }
  glEnd();
  glEndList();
  return list;
}

void LeafCrowns::Begin(const Eigen::Matrix4d& view, const Eigen::Vector3d& sun, double exposure) {
  const Eigen::Vector3f sun_eye = (view.topLeftCorner<3, 3>() * sun).cast<float>();
  GLint previous = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &previous);
  for (const Program& p : programs_) {
    glUseProgram(p.program);
    glUniform3f(p.sun_eye, sun_eye.x(), sun_eye.y(), sun_eye.z());
    glUniform1f(p.exposure, static_cast<float>(exposure));
  }
  glUseProgram(static_cast<GLuint>(previous));
}

GLint LeafCrowns::Start(Pass pass) const {
  GLint previous = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &previous);
  cull_ = glIsEnabled(GL_CULL_FACE) == GL_TRUE;
  glDisable(GL_CULL_FACE);  // a card shows both faces
  glUseProgram(programs_[static_cast<int>(pass)].program);
  glBindTexture(GL_TEXTURE_2D_ARRAY, texture_);
  return previous;
}

void LeafCrowns::Finish(GLint previous) const {
  if (cull_) glEnable(GL_CULL_FACE);
  glUseProgram(static_cast<GLuint>(previous));
}

}  // namespace trackbed::render
