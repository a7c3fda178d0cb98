// The robot's own track marks drawn over the ground (see track_mark_drawing.h).
#include "track_mark_drawing.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "gl_shader.h"

namespace trackbed::render {
namespace {

// Each vertex is pulled towards the camera along its ray (the same pixel) by 3 mm and 2 %
// of its distance, so that the strip passes the depth test over the ground drawn at a
// coarser level than the full grid (docs/rendering.md): the marks are drawn, not
// placed in the depth buffer.
const char* kTrackMarkVertex = R"(#version 130
uniform vec3 camera_world;
in vec4 mark;
in vec3 across;
out vec4 mark_v;
out vec3 across_v;
void main() {
  vec3 p = gl_Vertex.xyz;
  vec3 to_camera = camera_world - p;
  float distance = length(to_camera);
  p += to_camera / max(distance, 1e-6) * (0.003 + 0.02 * distance);
  gl_Position = gl_ModelViewProjectionMatrix * vec4(p, 1.0);
  mark_v = mark;
  across_v = across;
}
)";

// Per fragment: the rut's pieces across (wall, floor, wall) and the grouser imprint's
// along its floor (floor, face down, bottom, face up, one pitch), each lit as
// ambient × the sky it sees + diffuse × max(n · sun, 0) over the flat ground's light; the
// mean over the pixel's extent along and across (|d/dx| + |d/dy| of each coordinate) in
// closed form from each piecewise-constant profile's integral, so the pattern does not
// alias. The output is half the factor: the blend doubles it (dst × src × 2). Its head
// ends where Link() writes tan(kReposeAngleRad).
const char* kTrackMarkFragmentHead = R"(#version 130
uniform vec3 sun;
uniform float ambient;
uniform float diffuse;
uniform float pitch_m;
uniform float grouser_m;
in vec4 mark_v;  // grouser phase [pitches], across [m], rut depth [m], half width [m]
in vec3 across_v;
const float tan_repose = )";
const char* kTrackMarkFragmentTail = R"(;
float Light(vec3 n, float sky) { return ambient * sky + diffuse * max(dot(n, sun), 0.0); }
// The integral from 0 to x of one pitch's profile repeated: piece k covers [e[k], e[k+1]).
float AlongIntegral(float x, vec4 e, vec4 v) {
  float whole = floor(x);
  float r = x - whole;
  float one = v.x * (e.y - e.x) + v.y * (e.z - e.y) + v.z * (e.w - e.z) + v.w * (1.0 - e.w);
  float part = v.x * clamp(r - e.x, 0.0, e.y - e.x) + v.y * clamp(r - e.y, 0.0, e.z - e.y) +
               v.z * clamp(r - e.z, 0.0, e.w - e.z) + v.w * clamp(r - e.w, 0.0, 1.0 - e.w);
  return whole * one + part;
}
// The integral from far outside to x of (factor - 1) across the rut.
float AcrossIntegral(float x, float half_width, float wall, float right, float floor_v,
                     float left) {
  return (right - 1.0) * clamp(x + half_width + wall, 0.0, wall) +
         (floor_v - 1.0) * clamp(x + half_width, 0.0, 2.0 * half_width) +
         (left - 1.0) * clamp(x - half_width, 0.0, wall);
}
void main() {
  float phase = mark_v.x, t = mark_v.y, depth = mark_v.z, half_width = mark_v.w;
  vec3 up = vec3(0.0, 0.0, 1.0);
  vec3 a = normalize(vec3(across_v.xy, 0.0));
  vec3 h = vec3(a.y, -a.x, 0.0);  // the track's heading: across is to its left
  float c = inversesqrt(1.0 + tan_repose * tan_repose), s = tan_repose * c;
  float flat_light = max(Light(up, 1.0), 1e-6);
  // Across: walls at the angle of repose, each seeing (1 + cos) / 2 of the sky; the floor
  // at the middle of a trench as wide as the track sees sin(atan(b / 2 d)).
  float wall = depth / tan_repose;
  float sky_wall = 0.5 * (1.0 + c);
  float sky_floor = half_width * inversesqrt(half_width * half_width + depth * depth);
  float left = Light(c * up - s * a, sky_wall) / flat_light;
  float right = Light(c * up + s * a, sky_wall) / flat_light;
  // Along the floor: an imprint half a pitch wide, as deep as the grouser, the rut and the
  // angle of repose over a quarter pitch allow; its faces at the angle of repose.
  float imprint = min(min(grouser_m, depth), 0.25 * pitch_m * tan_repose);
  float face = imprint / tan_repose / pitch_m;  // in pitches
  float sky_bottom = sky_floor * 0.25 * pitch_m *
                     inversesqrt(0.0625 * pitch_m * pitch_m + imprint * imprint);
  vec4 e = vec4(0.0, 0.5, 0.5 + face, 1.0 - face);
  vec4 v = vec4(Light(up, sky_floor), Light(c * up + s * h, sky_wall * sky_floor),
                Light(up, sky_bottom), Light(c * up - s * h, sky_wall * sky_floor)) / flat_light;
  float wu = abs(dFdx(phase)) + abs(dFdy(phase));
  float floor_v = wu > 1e-6
      ? (AlongIntegral(phase + 0.5 * wu, e, v) - AlongIntegral(phase - 0.5 * wu, e, v)) / wu
      : v.x;
  float wt = max(abs(dFdx(t)) + abs(dFdy(t)), 1e-6);
  float factor = 1.0 + (AcrossIntegral(t + 0.5 * wt, half_width, wall, right, floor_v, left) -
                        AcrossIntegral(t - 0.5 * wt, half_width, wall, right, floor_v, left)) / wt;
  if (abs(factor - 1.0) < 1e-3) discard;  // the ground as it is, byte for byte
  gl_FragColor = vec4(vec3(clamp(0.5 * factor, 0.0, 1.0)), 1.0);
}
)";

// Beyond this the marks are not drawn [m]: a rut 10 cm wide is under 2 px there.
constexpr double kTrackMarkReachM = 30.0;
// The strip reaches this far beyond the rut's walls [m], so that the pixels beside them
// take their share of the wall.
constexpr double kTrackMarkMarginM = 0.01;

void AddTrackMarkCorner(const sim::TrackMarkPoint& p, double base_travel_m, double pitch_m,
                        double side, TrackMarkStrip* strip) {
  const double half = 0.5 * p.width_m;
  const double reach = half + p.depth_m / std::tan(kReposeAngleRad) + kTrackMarkMarginM;
  const Eigen::Vector3d across(-std::sin(p.heading_rad), std::cos(p.heading_rad), 0.0);
  const Eigen::Vector3d q = p.p_world + side * reach * across;
  strip->position.insert(
      strip->position.end(),
      {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())});
  strip->mark.insert(strip->mark.end(),
                     {static_cast<float>((p.travel_m - base_travel_m) / pitch_m),
                      static_cast<float>(side * reach), p.depth_m, static_cast<float>(half)});
  strip->across.insert(strip->across.end(),
                       {static_cast<float>(across.x()), static_cast<float>(across.y()), 0.0f});
}

}  // namespace

TrackMarkStrip BuildTrackMarkStrip(const sim::TrackMarks& marks,
                                   const Eigen::Vector3d& camera_world, double reach_m) {
  TrackMarkStrip strip;
  const double pitch = marks.options().grouser_pitch_m;
  const double reach2 = reach_m * reach_m;
  for (int side = 0; side < 2; ++side) {
    const std::size_t n = marks.size(side);
    for (std::size_t i = 1; i < n; ++i) {
      const sim::TrackMarkPoint& b = marks.point(side, i);
      if (b.starts_rut) continue;
      const sim::TrackMarkPoint& a = marks.point(side, i - 1);
      if ((a.p_world - camera_world).head<2>().squaredNorm() > reach2 &&
          (b.p_world - camera_world).head<2>().squaredNorm() > reach2) {
        continue;
      }
      // The phase from a whole number of pitches near the segment, in float.
      const double base = std::floor(a.travel_m / pitch) * pitch;
      // Two triangles, counter-clockwise from above: a right, b right, b left; a right,
      // b left, a left.
      AddTrackMarkCorner(a, base, pitch, -1.0, &strip);
      AddTrackMarkCorner(b, base, pitch, -1.0, &strip);
      AddTrackMarkCorner(b, base, pitch, 1.0, &strip);
      AddTrackMarkCorner(a, base, pitch, -1.0, &strip);
      AddTrackMarkCorner(b, base, pitch, 1.0, &strip);
      AddTrackMarkCorner(a, base, pitch, 1.0, &strip);
    }
  }
  return strip;
}

void TrackMarkDrawing::Link() {
  const GLuint vs =
      CompileShader(GL_VERTEX_SHADER, {kTrackMarkVertex}, "the track marks' vertex shader");
  char tan_repose[32];
  std::snprintf(tan_repose, sizeof tan_repose, "%.17g", std::tan(kReposeAngleRad));
  const GLuint fs = CompileShader(GL_FRAGMENT_SHADER,
                                  {kTrackMarkFragmentHead, tan_repose, kTrackMarkFragmentTail},
                                  "the track marks' fragment shader");
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) throw std::runtime_error("Renderer: the track marks' program does not link");
  glDeleteShader(vs);
  glDeleteShader(fs);
  camera_ = glGetUniformLocation(program_, "camera_world");
  sun_ = glGetUniformLocation(program_, "sun");
  ambient_ = glGetUniformLocation(program_, "ambient");
  diffuse_ = glGetUniformLocation(program_, "diffuse");
  pitch_ = glGetUniformLocation(program_, "pitch_m");
  grouser_ = glGetUniformLocation(program_, "grouser_m");
  mark_attrib_ = glGetAttribLocation(program_, "mark");
  across_attrib_ = glGetAttribLocation(program_, "across");
}

void TrackMarkDrawing::Draw(const Eigen::Vector3d& camera_world, const Eigen::Vector3d& sun_world,
                            double ambient, double diffuse) {
  const TrackMarkStrip strip = BuildTrackMarkStrip(*marks_, camera_world, kTrackMarkReachM);
  if (strip.vertices() == 0) return;
  if (program_ == 0) Link();
  GLint previous = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &previous);
  glPushAttrib(GL_ENABLE_BIT | GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_DST_COLOR, GL_SRC_COLOR);  // dst × src × 2: darker or brighter
  glUseProgram(program_);
  glUniform3f(camera_, static_cast<float>(camera_world.x()), static_cast<float>(camera_world.y()),
              static_cast<float>(camera_world.z()));
  glUniform3f(sun_, static_cast<float>(sun_world.x()), static_cast<float>(sun_world.y()),
              static_cast<float>(sun_world.z()));
  glUniform1f(ambient_, static_cast<float>(ambient));
  glUniform1f(diffuse_, static_cast<float>(diffuse));
  glUniform1f(pitch_, static_cast<float>(marks_->options().grouser_pitch_m));
  glUniform1f(grouser_, static_cast<float>(marks_->options().grouser_height_m));
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, strip.position.data());
  glEnableVertexAttribArray(static_cast<GLuint>(mark_attrib_));
  glVertexAttribPointer(static_cast<GLuint>(mark_attrib_), 4, GL_FLOAT, GL_FALSE, 0,
                        strip.mark.data());
  glEnableVertexAttribArray(static_cast<GLuint>(across_attrib_));
  glVertexAttribPointer(static_cast<GLuint>(across_attrib_), 3, GL_FLOAT, GL_FALSE, 0,
                        strip.across.data());
  glDrawArrays(GL_TRIANGLES, 0, strip.vertices());
  glDisableVertexAttribArray(static_cast<GLuint>(mark_attrib_));
  glDisableVertexAttribArray(static_cast<GLuint>(across_attrib_));
  glDisableClientState(GL_VERTEX_ARRAY);
  glUseProgram(static_cast<GLuint>(previous));
  glPopAttrib();
}

}  // namespace trackbed::render
