// Stochastic tiling (see ground_tiling.h). The hash is Wellons' "lowbias32" (a 32-bit
// integer finaliser, two multiply–xorshift rounds), the same in GLSL and C++, so that the
// tests can say which tile took what.
#include "ground_tiling.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace trackbed::render {
namespace {

std::uint32_t Hash32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

constexpr const char* kTilingShader = R"(
uniform uint tile_seed;
uniform ivec4 tile_variation;  // quarter turns, mirror, offsets per side (0: any), variants
uint TileHash(uint x) {
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return x;
}
float TileLookup(inout vec2 st, inout vec2 tx, inout vec2 ty) {
  vec2 cell = floor(st);
  ivec2 ij = ivec2(cell);
  uint h = TileHash(tile_seed ^ TileHash(uint(ij.x) ^ TileHash(uint(ij.y) + 0x9e3779b9u)));
  uint turns = h & 3u & uint(tile_variation.x - 1);
  vec2 cs = turns == 0u ? vec2(1.0, 0.0)
          : turns == 1u ? vec2(0.0, 1.0)
          : turns == 2u ? vec2(-1.0, 0.0) : vec2(0.0, -1.0);
  mat2 m = mat2(cs.x, cs.y, -cs.y, cs.x);
  if (tile_variation.y != 0 && ((h >> 2u) & 1u) != 0u) m = m * mat2(-1.0, 0.0, 0.0, 1.0);
  uint n = uint(tile_variation.z);
  uvec2 bits = uvec2((h >> 3u) & 1023u, (h >> 13u) & 1023u);
  vec2 offset = n == 0u ? vec2(bits) / 1024.0 : vec2(bits % n) / float(n);
  st = m * (st - cell) + offset;
  tx = m * tx;
  ty = m * ty;
  return float((h >> 23u) % uint(tile_variation.w));
}
)";

}  // namespace

TileChoice ChooseTile(std::uint32_t seed, int i, int j, const TileVariation& v) {
  const std::uint32_t h =
      Hash32(seed ^ Hash32(static_cast<std::uint32_t>(i) ^
                           Hash32(static_cast<std::uint32_t>(j) + 0x9e3779b9U)));
  TileChoice c;
  c.quarter_turns = static_cast<int>(h & 3U & static_cast<std::uint32_t>(v.quarter_turns - 1));
  c.mirrored = v.mirror && ((h >> 2) & 1U) != 0;
  const std::uint32_t bu = (h >> 3) & 1023U;
  const std::uint32_t bv = (h >> 13) & 1023U;
  if (v.offsets_per_side == 0) {
    c.offset = Eigen::Vector2d(bu / 1024.0, bv / 1024.0);
  } else {
    const auto n = static_cast<std::uint32_t>(v.offsets_per_side);
    c.offset = Eigen::Vector2d(static_cast<double>(bu % n) / n, static_cast<double>(bv % n) / n);
  }
  c.variant = static_cast<int>((h >> 23) % static_cast<std::uint32_t>(v.variants));
  return c;
}

Eigen::Vector2d TiledCoordinates(const Eigen::Vector2d& st, const TileChoice& c) {
  Eigen::Vector2d f(st.x() - std::floor(st.x()), st.y() - std::floor(st.y()));
  if (c.mirrored) f.x() = -f.x();
  static constexpr double kCos[4] = {1.0, 0.0, -1.0, 0.0};
  const double cs = kCos[c.quarter_turns];
  const double sn = kCos[(c.quarter_turns + 3) % 4];
  return Eigen::Vector2d(cs * f.x() - sn * f.y(), sn * f.x() + cs * f.y()) + c.offset;
}

bool DetailedLook(bool detailed, const std::vector<std::string>& classic, const std::string& name) {
  return detailed && HasTexture(name) &&
         std::find(classic.begin(), classic.end(), name) == classic.end();
}

std::uint32_t TilingSeed(std::uint64_t texture_seed) {
  return Hash32(static_cast<std::uint32_t>(texture_seed) ^
                Hash32(static_cast<std::uint32_t>(texture_seed >> 32)));
}

const char* TilingShaderSource() { return kTilingShader; }

}  // namespace trackbed::render
