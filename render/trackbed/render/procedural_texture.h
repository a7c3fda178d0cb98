// Seeded procedural grayscale textures for the renderer's surfaces.
//
// The renderer draws every surface with a texture that repeats (GL_REPEAT), so each
// texture here is one seamless tile. Textures drive a visual-odometry experiment:
// indoor appearances (paint, ceiling, floor, metal) are nearly featureless on purpose,
// so that corridors starve a corner detector, while outdoor appearances (grass, soil,
// gravel, bark, ...) are rich in high-contrast detail at scales of a few to a few tens
// of texels. Generation is bit-exact across machines: only integer hashing and
// IEEE-exact floating-point operations (+ − × ÷ sqrt floor) are used, never the
// standard library's distributions or transcendental functions, whose results may
// differ between implementations.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace trackbed::render {

/// A square grayscale texture that tiles seamlessly (its left edge continues its right
/// edge, its top edge its bottom edge), for GL_REPEAT.
struct Texture {
  int size_px = 0;                   ///< Width = height, a power of two.
  std::vector<std::uint8_t> texels;  ///< Row-major, size_px * size_px.
  /// World size of one tile [m]: how the renderer scales texture coordinates.
  double meters_per_repeat = 1.0;

  /// The texel at column x, row y; both wrap around (any integer is valid).
  std::uint8_t at(int x, int y) const;
};

/// The appearance names MakeTexture knows, sorted.
const std::vector<std::string>& TextureNames();

/// True when MakeTexture knows `appearance`.
bool HasTexture(const std::string& appearance);

/// Generates the texture of `appearance` from `seed`: the same inputs give identical
/// bytes on any machine; different seeds give different tiles of the same look.
/// Features are laid out in tile units, so `size_px` sets the resolution, not the
/// content. Throws std::invalid_argument naming the appearance and listing the known
/// ones when `appearance` is unknown, and when `size_px` is not a power of two in
/// [16, 2048].
Texture MakeTexture(const std::string& appearance, std::uint64_t seed, int size_px = 256);

/// How the tiles of a ground's texture vary when the ground is drawn with stochastic
/// tiling (`scene.appearance.ground_look: detailed`, docs/rendering.md): each tile of the
/// ground takes, from a hash of its index and the seed, one of `variants` textures,
/// mirrored or not, turned by whole quarter turns and shifted. The defaults: no variation.
struct TileVariation {
  int quarter_turns = 1;     ///< turns a tile may take: 1 (none), 2 (half turns) or 4
  bool mirror = false;       ///< whether a tile may be mirrored (across its u axis)
  int offsets_per_side = 1;  ///< shifts by multiples of 1 / this of the tile; 0: any shift
  int variants = 1;          ///< textures the tiles choose among (MakeTextureVariants)
};

/// The tile variation of `appearance`'s texture as a ground under the detailed look: free
/// for textures without a direction or a grid, whole cells for a grid (paving, hard
/// floor), none of turns and mirrors for wind ripples (sand; the detailed dry sand's
/// variants agree at their edges and take no shift either). Throws
/// std::invalid_argument as MakeTexture.
TileVariation GroundTileVariation(const std::string& appearance);

/// The `GroundTileVariation(appearance).variants` textures of `appearance` as a ground
/// under the detailed look: one common surface with each variant's own features (variant 0
/// is MakeTexture's); one texture for an appearance of one variant. `dry_sand`, `grass` and
/// `sandy_loam` are made by their own detailed recipes instead (ground_sand.h,
/// ground_grass.h, ground_soil.h: 0.5 m tiles, four variants), which MakeTexture does not
/// use. Throws as MakeTexture.
std::vector<Texture> MakeTextureVariants(const std::string& appearance, std::uint64_t seed,
                                         int size_px = 256);

/// A plain texture of one grey level (`albedo` in [0, 1], 1 = white) with faint smooth
/// seeded noise (standard deviation about one grey level), for a material that has no
/// texture of its own. meters_per_repeat is 1 m. Throws std::invalid_argument when
/// `albedo` is outside [0, 1] or `size_px` is not a power of two in [16, 2048].
Texture MakePlainTexture(double albedo, std::uint64_t seed, int size_px = 64);

}  // namespace trackbed::render
