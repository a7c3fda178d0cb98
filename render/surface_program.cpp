// The shader program every surface is drawn with (see surface_program.h).
#include "surface_program.h"

#include "footprint_mips.h"
#include "gl_shader.h"
#include "ground_tiling.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace trackbed::render {
namespace {

// GLSL 1.30 (the compatibility profile's built-in matrices and attributes, and
// textureGrad in the fragment shader); LIGHT_MAP defined with scene lighting.
constexpr const char* kVersion = "#version 130\n";

// Per vertex, as the fixed-function pipeline lights: ambient, and the sun's diffuse
// term (normals are unit and the model-view rigid, so no renormalisation).
constexpr const char* kVertexShader = R"(
uniform mat4 world_from_eye;
uniform vec3 sun_eye;
uniform vec2 light_origin;
uniform vec2 light_per_m;
uniform float diffuse;
out vec2 albedo_st;
out vec2 light_st;
out float direct;
#ifdef OUTLINE
flat out vec4 shape_eye;  // the shape's centre in eye coordinates, its signed radius
flat out vec3 axis_eye;   // a cylinder's axis
#endif
#if defined(OUTLINE) || defined(ROBOT_SHADOW)
out vec3 position_eye;
#endif
void main() {
  vec3 normal = gl_NormalMatrix * gl_Normal;
  vec4 eye = gl_ModelViewMatrix * gl_Vertex;
  direct = diffuse * max(dot(normal, sun_eye), 0.0);
#ifdef OUTLINE
  vec4 shape = gl_MultiTexCoord1;
  shape_eye = vec4((gl_ModelViewMatrix * vec4(shape.xyz, 1.0)).xyz, shape.w);
  axis_eye = gl_NormalMatrix * vec3(0.0, 0.0, 1.0);
#endif
#if defined(OUTLINE) || defined(ROBOT_SHADOW)
  position_eye = eye.xyz;
#endif
#ifdef LIGHT_MAP
  light_st = ((world_from_eye * eye).xy - light_origin) * light_per_m;
#else
  light_st = vec2(0.0);
#endif
  albedo_st = gl_MultiTexCoord0.xy;
  gl_Position = gl_ProjectionMatrix * eye;
}
)";

// Per fragment: the albedo over the pixel's footprint (surface_program.h); the sun's
// term shadowed by the texel's sunlit fraction, clamped as the fixed-function lit
// colour is, then the zones' gain and the exposure (the 8-bit output clips).
constexpr const char* kFragmentShader = R"(
uniform sampler2DArray albedo;
uniform sampler2D light;
uniform float ambient;
uniform float exposure;
in vec2 albedo_st;
in vec2 light_st;
in float direct;
#if defined(OUTLINE) || defined(ROBOT_SHADOW)
in vec3 position_eye;
#endif

float FootprintMean() {
  vec3 size = vec3(textureSize(albedo, 0));
  vec2 st = albedo_st;
  vec2 tx = dFdx(albedo_st) * size.xy;  // the pixel's sides in texels
  vec2 ty = dFdy(albedo_st) * size.xy;
#ifdef TILED
  // The tile's variant (ground_tiling.h): its layers follow the variants before it.
  float variant = TileLookup(st, tx, ty);
  size.z = size.z / float(tile_variation.w);
#endif
  // The footprint's ellipse: eigenvalues and major eigenvector of J J^T, J = [tx ty].
  float a = tx.x * tx.x + ty.x * ty.x;
  float b = tx.x * tx.y + ty.x * ty.y;
  float c = tx.y * tx.y + ty.y * ty.y;
  float mid = 0.5 * (a + c);
  float root = sqrt(0.25 * (a - c) * (a - c) + b * b);
  float major = sqrt(mid + root);
  float minor = sqrt(max(mid - root, 0.0));
  vec2 v = a >= c ? vec2(mid + root - c, b) : vec2(b, mid + root - a);
  // The layer for the footprint's length over its width (or over a texel, magnified)
  // and for the direction of its major axis; the level for its length over the layer's.
  float directions = (size.z - 1.0) / MAX_ANISOTROPY_LOG2;
  float m = directions > 0.0
                ? clamp(floor(log2(major / max(minor, 1.0)) + 0.5), 0.0, MAX_ANISOTROPY_LOG2)
                : 0.0;
  float k = mod(floor(atan(v.y, v.x) * (directions / 3.14159265) + 0.5), max(directions, 1.0));
  float layer = m > 0.0 ? 1.0 + (m - 1.0) * directions + k : 0.0;
#ifdef TILED
  layer += variant * size.z;
#endif
  // The lookup's level from gradients along the footprint's axes, the major one its
  // length over the layer's: the level of the larger of the two, as textureLod at
  // log2(max(major / 2^m, minor)) would take, in llvmpipe's faster path.
  float len = length(v);
  vec2 dir = (len > 0.0 ? v / len : vec2(1.0, 0.0)) / size.xy * exp2(LOD_BIAS);
  return textureGrad(albedo, vec3(st, layer), dir * (major / exp2(m)),
                     vec2(-dir.y, dir.x) * minor)
      .r;
}

// An object's texture (one layer): the implicit level, the footprint's length.
float IsotropicMean() { return texture(albedo, vec3(albedo_st, 0.0)).r; }

#ifdef OUTLINE
uniform float outline_px_per_depth;
flat in vec4 shape_eye;
flat in vec3 axis_eye;
// How far the pixel centre's ray passes inside the outline of the true sphere
// (radius > 0) or cylinder (radius < 0, about axis_eye) [px]: the ray's distance from
// the centre or the axis, against the radius, at the depth of its closest approach.
float OutlineDistance() {
  vec3 r = normalize(position_eye);
  vec3 c = shape_eye.xyz;
  float t, off;
  if (shape_eye.w > 0.0) {
    t = dot(c, r);
    off = length(c - t * r);
  } else {
    vec3 rp = r - dot(r, axis_eye) * axis_eye;
    vec3 cp = c - dot(c, axis_eye) * axis_eye;
    t = dot(cp, rp) / dot(rp, rp);
    off = length(cp - t * rp);
  }
  return (abs(shape_eye.w) - off) / (t * -r.z * outline_px_per_depth);
}
#endif

void main() {
  // First whether the pixel is this pass's: llvmpipe skips the rest for a block of
  // pixels all discarded.
#ifdef OUTLINE
  if (OutlineDistance() < 0.5) discard;  // a pixel the outline crosses: the band's
#endif
#ifdef LIGHT_MAP
  vec2 l = texture(light, light_st).rg;
#else
  vec2 l = vec2(1.0);
#endif
#ifdef ROBOT_SHADOW
  l.r *= RobotSunlit(position_eye);  // the robot's own shadow (robot_shadow.h)
#endif
  float shade = min(ambient + direct * l.r, 1.0) * l.g;
#ifdef FOOTPRINT
  float albedo_mean = FootprintMean();
#else
  float albedo_mean = IsotropicMean();
#endif
  gl_FragColor = vec4(vec3(albedo_mean * shade * exposure), 1.0);
}
)";

// The band about a curved object's outline that the fringe and depth programs draw:
// per vertex, from the shape (texture unit 1's coordinate: the centre of a sphere or
// the base of an upright cylinder, and the signed radius) and where the vertex lies on
// the band (unit 0's: a cylinder's side ±1 and end ±1, a sphere's direction (cos, sin)
// about its outline; then −1 on the inner edge, +1 on the outer). A cylinder's band is
// a quad along each of its two silhouette lines, a sphere's an annulus about its
// outline circle, in the plane square to the ray to its centre: from 1.25 pixels and
// the facets' chords (2 % of the radius) inside the outline to 0.75 pixels outside, so
// that it holds the centre of every pixel the fringe draws (a pixel at distance d
// from the vertex spans at least d / f of the view).
constexpr const char* kBandVertexShader = R"(
uniform float outline_px_per_depth;  // a pixel's width at unit depth (1 / f)
flat out vec4 shape_eye;  // the shape's centre or base in eye coordinates, its signed radius
flat out vec3 axis_eye;   // the object's z axis (a cylinder's), x and y in eye coordinates
flat out vec3 east_eye;
flat out vec3 north_eye;
flat out vec3 band;       // 1 / metres per texture repeat, a cylinder's height, its side
void main() {
  vec4 shape = gl_MultiTexCoord1;
  vec4 place = gl_MultiTexCoord0;
  vec3 c = (gl_ModelViewMatrix * vec4(shape.xyz, 1.0)).xyz;
  float radius = abs(shape.w);
  axis_eye = gl_NormalMatrix * vec3(0.0, 0.0, 1.0);
  east_eye = gl_NormalMatrix * vec3(1.0, 0.0, 0.0);
  north_eye = gl_NormalMatrix * vec3(0.0, 1.0, 0.0);
  shape_eye = vec4(c, shape.w);
  band = vec3(gl_MultiTexCoord2.xy, place.x);
  vec3 at = (gl_ModelViewMatrix * gl_Vertex).xyz;  // on the axis, or the centre
  vec3 eye;
  float width;
  if (shape.w < 0.0) {
    // The silhouette line on this side: where the plane through the camera touches
    // the cylinder; its normal there is square to the ray.
    vec3 across = -at - dot(-at, axis_eye) * axis_eye;  // from the axis to the camera
    float distance = length(across);
    float cs = min(radius / max(distance, 1e-9), 1.0);
    vec3 n = cs * across / max(distance, 1e-9) +
             place.x * sqrt(1.0 - cs * cs) * cross(axis_eye, across / max(distance, 1e-9));
    vec3 touch = at + radius * n;
    float pixel = length(touch) * outline_px_per_depth;
    float inner = 1.25 * pixel + 0.02 * radius;
    eye = touch + n * (place.z > 0.0 ? 0.75 * pixel : -inner) +
          axis_eye * (place.y * 2.0 * pixel);
    width = inner + 0.75 * pixel;
  } else {
    // The outline circle: where the cone from the camera touches the sphere.
    float distance = length(c);
    vec3 view = c / distance;
    vec3 u = normalize(cross(view, abs(view.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 v = cross(view, u);
    float cs = min(radius / distance, 1.0);
    float rho = radius * sqrt(1.0 - cs * cs);
    float pixel = distance * outline_px_per_depth;
    float inner = 1.25 * pixel + 0.02 * radius;
    float ring = place.z > 0.0 ? (rho + 0.75 * pixel) / OUTLINE_RING_COS : max(rho - inner, 0.0);
    eye = c * (1.0 - cs * cs) + ring * (place.x * u + place.y * v);
    width = inner + 0.75 * pixel;
  }
  // Drawn nearer along each vertex's ray, where it covers the same pixels, by as much
  // as the shape's near side can lie in front of the band (a circle's arc over a chord
  // `width` from its end, and the width): the depth test then passes what the shape is
  // in front of, and llvmpipe rejects the band's hidden parts before shading them.
  eye *= max(1.0 - (sqrt(2.0 * radius * width) + width) / length(eye), 0.5);
  gl_Position = gl_ProjectionMatrix * vec4(eye, 1.0);
}
)";

// Per fragment of the band: how far the pixel centre's ray passes inside the true
// shape's outline [px] (its distance from the centre or the axis against the radius, at
// the depth of its closest approach) and the shape's point it sees (where it enters
// the shape, or the nearest to it when it passes outside). The fringe program draws
// the pixels less than one pixel and the chords inside, by the fraction inside (as for
// a straight edge), shaded where the ray meets the shape grown by a pixel and the
// chords; the depth program writes the true point's depth where the shape covers at
// least half the pixel.
constexpr const char* kBandFragmentShader = R"(
uniform sampler2DArray albedo;
uniform sampler2D light;
uniform float ambient;
uniform float diffuse;
uniform float exposure;
uniform vec3 sun_eye;
uniform mat4 world_from_eye;
uniform vec2 light_origin;
uniform vec2 light_per_m;
uniform float outline_px_per_depth;
uniform vec4 ray_from_window;  // the eye ray (x, y, -1) of window position (wx, wy): a wx + b, c wy + d
flat in vec4 shape_eye;
flat in vec3 axis_eye;
flat in vec3 east_eye;
flat in vec3 north_eye;
flat in vec3 band;

float Angle(vec3 n) {  // about the object's z axis from its x axis, in [0, 2 pi)
  float a = atan(dot(n, north_eye), dot(n, east_eye));
  return a < 0.0 ? a + 6.28318531 : a;
}

void main() {
  vec3 r = normalize(vec3(gl_FragCoord.x * ray_from_window.x + ray_from_window.y,
                          gl_FragCoord.y * ray_from_window.z + ray_from_window.w, -1.0));
  vec3 c = shape_eye.xyz;
  float radius = abs(shape_eye.w);
  bool sphere = shape_eye.w > 0.0;
  // First whether the pixel is the band's, before the rest (see kFragmentShader).
  vec3 rp = sphere ? r : r - dot(r, axis_eye) * axis_eye;
  vec3 cp = sphere ? c : c - dot(c, axis_eye) * axis_eye;
  float rr = dot(rp, rp);
  float t = dot(cp, rp) / rr;
  float off = length(cp - t * rp);
  float pixel = t * -r.z * outline_px_per_depth;
  float inside = (radius - off) / pixel;
#ifdef OUTLINE_DEPTH
  if (inside < 0.0) discard;  // less than half covered: the depth of what is behind
#else
  if (inside <= -0.5) discard;
#endif
  if (inside >= 1.0 + 0.02 * radius / pixel) discard;  // the core's
  vec3 point = (t - sqrt(max(radius * radius - off * off, 0.0) / rr)) * r;
  vec3 d = point - c;
  vec3 n;
  vec2 st;
  if (sphere) {
    n = normalize(d);
    st = vec2(Angle(n), asin(clamp(dot(n, axis_eye), -1.0, 1.0))) * (radius * band.x);
  } else {
    float z = dot(d, axis_eye);
    n = normalize(d - z * axis_eye);
    // Each side's quad draws the pixels on its side of the axis: none twice.
    if (dot(n, cross(axis_eye, -cp)) * band.z < 0.0) discard;
    if (z < 0.0) discard;  // below the base
    if (z > band.y) {  // above the top: the cap, where the ray comes down through it
      float down = dot(r, axis_eye);
      if (down >= 0.0) discard;
      point = r * ((band.y + dot(c, axis_eye)) / down);
      d = point - c - band.y * axis_eye;
      if (dot(d, d) > radius * radius) discard;
      n = axis_eye;
      st = vec2(dot(d, east_eye), dot(d, north_eye)) * band.x;
    } else {
      st = vec2(Angle(n) * radius, z) * band.x;
    }
  }
#ifdef OUTLINE_DEPTH
  vec4 clip = gl_ProjectionMatrix * vec4(point, 1.0);
  gl_FragDepth = 0.5 + 0.5 * clip.z / clip.w;
  gl_FragColor = vec4(0.0);
#else
  // Shaded where the ray meets the shape grown by a pixel and the chords (a sphere's or
  // the side's radius, a cylinder's top raised), whose outline lies beyond every pixel
  // drawn: its texture coordinates and normal there, and the texture at the level their
  // derivatives give (the true shape, grazing at its outline, gives a coarser one).
  float grown = pixel + 0.02 * radius;
  float rg = radius + grown;
  point = (t - sqrt(max(rg * rg - off * off, 0.0) / rr)) * r;
  d = point - c;
  if (sphere) {
    n = normalize(d);
    st = vec2(Angle(n), asin(clamp(dot(n, axis_eye), -1.0, 1.0))) * (radius * band.x);
  } else {
    float z = dot(d, axis_eye);
    float down = dot(r, axis_eye);
    if (z > band.y && down < 0.0) {  // the raised top
      point = r * ((band.y + grown + dot(c, axis_eye)) / down);
      d = point - c - (band.y + grown) * axis_eye;
      n = axis_eye;
      st = vec2(dot(d, east_eye), dot(d, north_eye)) * band.x;
    } else {
      n = normalize(d - z * axis_eye);
      st = vec2(Angle(n) * radius, clamp(z, 0.0, band.y)) * band.x;
    }
  }
#ifdef LIGHT_MAP
  vec2 l = texture(light, ((world_from_eye * vec4(point, 1.0)).xy - light_origin) * light_per_m).rg;
#else
  vec2 l = vec2(1.0);
#endif
#ifdef ROBOT_SHADOW
  l.r *= RobotSunlit(point);
#endif
  float shade = min(ambient + diffuse * max(dot(n, sun_eye), 0.0) * l.r, 1.0) * l.g;
  float albedo_mean = texture(albedo, vec3(st, 0.0)).r;
  gl_FragColor = vec4(vec3(albedo_mean * shade * exposure), clamp(0.5 + inside, 0.0, 1.0));
#endif
}
)";

// Mip levels added to the footprint's: 0 would take the level whose texel is the
// footprint's width, but a trilinear lookup there (a box of a texel, then a tent of
// one) is blurrier than a pixel's box; half a level finer keeps the stripes of
// ground_sampling_test within 5 % of a 4 × 4 supersampled render's contrast at 1–5 m
// (at 0: 12 and 24 % under at 3 and 5 m), with no more energy above their frequency.
constexpr const char* kLodBias = "-0.5";

GLuint Compile(GLenum type, const std::string& defines, const char* source,
               const char* functions = "") {
  return CompileShader(type, {kVersion, defines.c_str(), functions, source}, "the surface shader");
}

// The light map as one two-channel float texture on unit 1: sunlit fraction, gain.
GLuint UploadLightMap(const LightMap& map) {
  std::vector<float> texels(2 * map.sunlit.size());
  for (std::size_t i = 0; i < map.sunlit.size(); ++i) {
    texels[2 * i] = map.sunlit[i];
    texels[2 * i + 1] = map.gain[i];
  }
  GLuint name = 0;
  glActiveTexture(GL_TEXTURE1);
  glGenTextures(1, &name);
  glBindTexture(GL_TEXTURE_2D, name);
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
  return name;
}

}  // namespace

SurfaceProgram::SurfaceProgram(const LightMap* map, double ambient, double diffuse,
                               bool robot_shadow) {
  for (Kind kind : {Kind::kFootprint, Kind::kIsotropic, Kind::kOutlineCore, Kind::kOutlineFringe,
                    Kind::kOutlineDepth, Kind::kFootprintTiled}) {
    programs_[static_cast<int>(kind)] = Link(kind, map, ambient, diffuse, robot_shadow);
  }
  if (map) light_texture_ = UploadLightMap(*map);
}

SurfaceProgram::Linked SurfaceProgram::Link(Kind kind, const LightMap* map, double ambient,
                                            double diffuse, bool robot_shadow) {
  const std::string defines =
      std::string(map ? "#define LIGHT_MAP\n" : "") +
      (robot_shadow
           ? "#define ROBOT_SHADOW\n#define MAX_CASTERS " + std::to_string(kMaxShadowBoxes + 1) +
                 "\n#define SUN_RADIUS " + std::to_string(kSunAngularRadiusRad) + "\n"
           : std::string()) +
      (kind == Kind::kFootprint || kind == Kind::kFootprintTiled ? "#define FOOTPRINT\n" : "") +
      (kind == Kind::kFootprintTiled ? "#define TILED\n" : "") +
      (kind == Kind::kOutlineCore ? "#define OUTLINE\n" : "") +
      (kind == Kind::kOutlineDepth ? "#define OUTLINE_DEPTH\n" : "") +
      "#define MAX_ANISOTROPY_LOG2 " + std::to_string(kMaxAnisotropyLog2) +
      ".0\n#define LOD_BIAS " + kLodBias + "\n#define OUTLINE_RING_COS " +
      std::to_string(std::cos(M_PI / kOutlineRingSegments)) + "\n";
  const bool band = kind == Kind::kOutlineFringe || kind == Kind::kOutlineDepth;
  Linked out;
  out.program = glCreateProgram();
  const GLuint program_ = out.program;
  glAttachShader(program_,
                 Compile(GL_VERTEX_SHADER, defines, band ? kBandVertexShader : kVertexShader));
  const std::string functions =
      std::string(kind == Kind::kFootprintTiled ? TilingShaderSource() : "") +
      (robot_shadow ? RobotShadowShaderSource() : "");
  glAttachShader(program_,
                 Compile(GL_FRAGMENT_SHADER, defines, band ? kBandFragmentShader : kFragmentShader,
                         functions.c_str()));
  glLinkProgram(program_);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) throw std::runtime_error("Renderer: the surface shader does not link");
  glUseProgram(program_);
  glUniform1i(glGetUniformLocation(program_, "albedo"), 0);
  glUniform1f(glGetUniformLocation(program_, "ambient"), static_cast<float>(ambient));
  glUniform1f(glGetUniformLocation(program_, "diffuse"), static_cast<float>(diffuse));
  if (map) {
    glUniform1i(glGetUniformLocation(program_, "light"), 1);
    glUniform2f(glGetUniformLocation(program_, "light_origin"), static_cast<float>(map->x_min),
                static_cast<float>(map->y_min));
    glUniform2f(glGetUniformLocation(program_, "light_per_m"),
                static_cast<float>(1.0 / (map->width * map->texel_m)),
                static_cast<float>(1.0 / (map->height * map->texel_m)));
  }
  out.world_from_eye = glGetUniformLocation(program_, "world_from_eye");
  out.sun_eye = glGetUniformLocation(program_, "sun_eye");
  out.exposure = glGetUniformLocation(program_, "exposure");
  out.outline_px_per_depth = glGetUniformLocation(program_, "outline_px_per_depth");
  out.ray_from_window = glGetUniformLocation(program_, "ray_from_window");
  out.tile_seed = glGetUniformLocation(program_, "tile_seed");
  out.tile_variation = glGetUniformLocation(program_, "tile_variation");
  out.caster_from_eye = glGetUniformLocation(program_, "caster_from_eye");
  out.caster_half = glGetUniformLocation(program_, "caster_half");
  out.caster_sun = glGetUniformLocation(program_, "caster_sun");
  out.caster_count = glGetUniformLocation(program_, "caster_count");
  glUseProgram(0);
  return out;
}

void SurfaceProgram::Begin(const Eigen::Matrix4d& view, const Eigen::Vector3d& sun, double exposure,
                           const geometry::PinholeCamera& K, const ShadowFrame* shadow) {
  const Eigen::Matrix4f world_from_eye = view.inverse().cast<float>();
  const Eigen::Vector3f sun_eye = (view.topLeftCorner<3, 3>() * sun).cast<float>();
  for (const Linked& p : programs_) {
    glUseProgram(p.program);
    if (light_texture_ != 0) {
      glUniformMatrix4fv(p.world_from_eye, 1, GL_FALSE, world_from_eye.data());
    }
    glUniform3f(p.sun_eye, sun_eye.x(), sun_eye.y(), sun_eye.z());
    glUniform1f(p.exposure, static_cast<float>(exposure));
    if (p.outline_px_per_depth >= 0) {
      glUniform1f(p.outline_px_per_depth, static_cast<float>(1.0 / K.fx));
    }
    if (p.ray_from_window >= 0) {  // window (x, y) to the eye ray (pinhole.cpp's derivation)
      glUniform4f(p.ray_from_window, static_cast<float>(1.0 / K.fx),
                  static_cast<float>(-(K.cx + 0.5) / K.fx), static_cast<float>(1.0 / K.fy),
                  static_cast<float>((K.cy + 0.5 - K.height_px) / K.fy));
    }
    if (p.caster_count >= 0) {
      const int n = shadow ? shadow->count : 0;
      glUniform1i(p.caster_count, n);
      if (n > 0) {
        glUniformMatrix4fv(p.caster_from_eye, n, GL_FALSE, shadow->box_from_eye.data());
        glUniform3fv(p.caster_half, n, shadow->half_m.data());
        glUniform3fv(p.caster_sun, n, shadow->sun_box.data());
      }
    }
  }
  current_ = Kind::kIsotropic;
  if (light_texture_ != 0) {
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, light_texture_);
    glActiveTexture(GL_TEXTURE0);
  }
}

void SurfaceProgram::Use(Kind kind) {
  if (kind == current_) return;
  glUseProgram(programs_[static_cast<int>(kind)].program);
  current_ = kind;
}

void SurfaceProgram::UseTiled(std::uint32_t seed, const TileVariation& v) {
  Use(Kind::kFootprintTiled);
  const Linked& p = programs_[static_cast<int>(Kind::kFootprintTiled)];
  const bool same = tiled_set_ && seed == tile_seed_ && v.quarter_turns == tiling_.quarter_turns &&
                    v.mirror == tiling_.mirror && v.offsets_per_side == tiling_.offsets_per_side &&
                    v.variants == tiling_.variants;
  if (same) return;
  glUniform1ui(p.tile_seed, seed);
  glUniform4i(p.tile_variation, v.quarter_turns, v.mirror ? 1 : 0, v.offsets_per_side, v.variants);
  tiled_set_ = true;
  tile_seed_ = seed;
  tiling_ = v;
}

void SurfaceProgram::End() const { glUseProgram(0); }

}  // namespace trackbed::render
