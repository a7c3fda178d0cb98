// Dry wind-rippled sand seen from above (the detailed look's `dry_sand`; ground_sand.cpp):
// impact ripples of a cited wavelength and ripple index with their junctions and
// terminations, the sand's grains below a texel as a speckle, coarse grains and granules
// on the crests, a few pebbles, shell fragments and twigs. Private to the renderer; the
// tests read the ripple field.
#pragma once

#include <cstdint>

namespace trackbed::render {

namespace texture_blocks {
struct Field;
}

/// The tile of the detailed dry sand [m]: 256 texels give 2 mm, under the near pixel's
/// footprint (about 3 mm at 1 m for the robot's camera).
inline constexpr double kSandTileM = 0.5;

/// Tile variants the detailed dry sand is made in (ground_tiling.h).
inline constexpr int kSandVariants = 4;

/// Wind (impact) ripples of dune sand: wavelength [m] and ripple index (wavelength over
/// height) ranges the recipe draws from (docs/rendering.md, "Dry sand").
inline constexpr double kRippleWavelengthMinM = 0.06;
inline constexpr double kRippleWavelengthMaxM = 0.125;
inline constexpr double kRippleIndexMin = 30.0;
inline constexpr double kRippleIndexMax = 70.0;

/// The ripple field every variant of a seed shares at its edges.
struct RippleField {
  int kx = 0;                 ///< crests' wave number along u [per tile]
  int ky = 0;                 ///< along v [per tile]
  double wavelength_m = 0.0;  ///< 1 / |k| of the tile
  double height_m = 0.0;      ///< crest above trough: wavelength / ripple index
};

/// The ripple field of the detailed dry sand of `seed`.
RippleField SandRipples(std::uint64_t seed);

/// The variants' common surface: nothing but the sand's colour (the ripples vary inside
/// each variant, so they are drawn by SandFeatures).
void SandSurface(texture_blocks::Field& f, std::uint64_t seed);

/// Variant `variant`: the ripples (shared at the tile's edges, with the variant's own
/// meander, junctions and terminations inside), the speckle of the sand's grains and the
/// variant's granules, pebbles, shells and twigs, all clear of the tile's edges.
void SandFeatures(texture_blocks::Field& f, std::uint64_t seed, int variant);

}  // namespace trackbed::render
