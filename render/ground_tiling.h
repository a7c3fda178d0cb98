// Stochastic tiling of the ground (docs/rendering.md, "Tiles without a period"): each
// tile of a ground material's texture, at integer texture coordinates, takes from a hash
// of its index and a seed one of the texture's variants, mirrored or not, turned by
// whole quarter turns and shifted, as the material's TileVariation allows. The tiled
// ground program computes this per pixel (TilingShaderSource); ChooseTile and
// TiledCoordinates are the same computation on the CPU, for the tests. Private to the
// renderer.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "trackbed/render/procedural_texture.h"

namespace trackbed::render {

/// What one tile takes.
struct TileChoice {
  int quarter_turns = 0;                             ///< counter-clockwise, 0–3
  bool mirrored = false;                             ///< u negated, before the turn
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();  ///< [tile], in [0, 1)
  int variant = 0;                                   ///< in [0, variants)
};

/// The choice of tile (i, j) (the integer parts of its texture coordinates) under `v`
/// with the material's tiling seed.
TileChoice ChooseTile(std::uint32_t seed, int i, int j, const TileVariation& v);

/// Where the ground at texture coordinates `st` [tile] reads its tile's variant, as
/// texture coordinates (the texture repeats: any value is valid).
Eigen::Vector2d TiledCoordinates(const Eigen::Vector2d& st, const TileChoice& c);

/// Whether the terrain material `name` is drawn tiled (its texture's variants): under
/// the detailed look (`detailed`), a material with a texture not among `classic`.
bool DetailedLook(bool detailed, const std::vector<std::string>& classic, const std::string& name);

/// A material's tiling seed from its texture's seed.
std::uint32_t TilingSeed(std::uint64_t texture_seed);

/// GLSL 1.30 of the choice: uniforms `tile_seed` (uint) and `tile_variation` (ivec4:
/// quarter turns, mirror, offsets per side, variants) and `float TileLookup(inout vec2
/// st, inout vec2 tx, inout vec2 ty)`, which moves the texture coordinates and the
/// pixel's sides into the tile's variant and returns the variant.
const char* TilingShaderSource();

}  // namespace trackbed::render
