// The sky (see trackbed/render/sky.h): its model and its shaders.
#include "trackbed/render/sky.h"

#include <algorithm>
#include <cmath>

namespace trackbed::render {
namespace {

// CIE standard general sky, type 12 (CIE S 011/E:2003, table 1).
constexpr double kA = -1.0, kB = -0.32, kC = 10.0, kD = -3.0, kE = 0.45;

constexpr const char* kVertex = R"(#version 130
void main() { gl_Position = vec4(gl_Vertex.xy, 1.0, 1.0); }
)";

constexpr const char* kFragment = R"(#version 130
uniform mat3 world_from_eye;
uniform vec3 sun;         // towards the sun, world
uniform float gray;       // the horizon's grey 90 degrees from the sun, exposed
uniform vec4 ray_from_window;
uniform vec2 cloud_offset;

const float A = -1.0, B = -0.32, C = 10.0, D = -3.0, E = 0.45;

float Luminance(vec3 dir) {
  float cz = max(dir.z, 0.0);
  float phi = cz > 0.0 ? 1.0 + A * exp(B / cz) : 1.0;
  float cc = clamp(dot(dir, sun), -1.0, 1.0);
  float chi = acos(cc);
  float f = 1.0 + C * (exp(D * chi) - exp(D * 1.5707963)) + E * cc * cc;
  return f * phi;
}

#ifdef CLOUDS
uint Hash(ivec2 c) {
  uint h = uint(c.x) * 0x8da6b343u ^ uint(c.y) * 0xd8163841u;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  h *= 0x297a2d39u;
  h ^= h >> 15;
  return h;
}
float Value(ivec2 c) { return float(Hash(c) >> 8u) * (1.0 / 16777216.0); }
float Noise(vec2 p) {
  vec2 i = floor(p);
  vec2 f = p - i;
  f = f * f * (3.0 - 2.0 * f);
  ivec2 c = ivec2(i);
  return mix(mix(Value(c), Value(c + ivec2(1, 0)), f.x),
             mix(Value(c + ivec2(0, 1)), Value(c + ivec2(1, 1)), f.x), f.y);
}
float Fbm(vec2 p) {
  float sum = 0.0, amplitude = 0.5;
  for (int k = 0; k < 5; ++k) {
    sum += amplitude * Noise(p);
    p = p * 2.03 + vec2(17.1, -9.7);
    amplitude *= 0.5;
  }
  return sum / 0.96875;
}
#endif

void main() {
  vec3 ray = vec3(gl_FragCoord.x * ray_from_window.x + ray_from_window.y,
                  gl_FragCoord.y * ray_from_window.z + ray_from_window.w, -1.0);
  vec3 dir = normalize(world_from_eye * ray);
  float grey = gray * Luminance(dir);
#ifdef CLOUDS
  if (dir.z > 0.0) {
    // Seen on a plane over the camera: a direction's point on it, 1.5 noise cells per
    // unit height, the horizon's compression eased.
    vec2 q = dir.xy / (dir.z + 0.08) * 1.5 + cloud_offset;
    float density = Fbm(q);
    float cover = smoothstep(0.48, 0.68, density) * smoothstep(0.0, 0.15, dir.z);
    float cloud = gray * (1.05 + 0.3 * (Fbm(q * 3.0 + vec2(5.3, 1.1)) - 0.5));
    grey = mix(grey, cloud, cover);
  }
#endif
  gl_FragColor = vec4(vec3(grey), 1.0);
}
)";

}  // namespace

double ClearSkyLuminance(const Eigen::Vector3d& dir, const Eigen::Vector3d& sun) {
  const double cz = std::max(dir.z(), 0.0);
  const double phi = cz > 0.0 ? 1.0 + kA * std::exp(kB / cz) : 1.0;
  const double cc = std::clamp(dir.dot(sun), -1.0, 1.0);
  const double chi = std::acos(cc);
  const double f = 1.0 + kC * (std::exp(kD * chi) - std::exp(kD * M_PI / 2)) + kE * cc * cc;
  return f * phi;
}

Eigen::Vector2f CloudOffset(std::uint64_t seed) {
  // Two values in [0, 4096) from the seed (SplitMix64's finaliser).
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return {static_cast<float>(z & 0xfff), static_cast<float>((z >> 12) & 0xfff)};
}

const char* SkyVertexShader() { return kVertex; }
const char* SkyFragmentShader() { return kFragment; }

}  // namespace trackbed::render
