// A mown lawn seen from above (the detailed look's `grass`; ground_grass.cpp): tufts of
// shoots of Kentucky bluegrass with their leaf blades at a cited width and count, each
// blade folded along its midrib and lit on its own, darker deeper in the canopy, the cut
// tips browned, over thatch and soil showing in the gaps. Private to the renderer; the
// tests read the sward.
#pragma once

#include <cstdint>
#include <vector>

namespace trackbed::render {

namespace texture_blocks {
struct Field;
}

/// The tile of the detailed grass [m]: 256 texels give 2 mm, a blade one to two texels.
inline constexpr double kGrassTileM = 0.5;

/// Tile variants the detailed grass is made in (ground_tiling.h).
inline constexpr int kGrassVariants = 4;

/// Leaf blade width of Kentucky bluegrass [mm] (docs/rendering.md, "Grass").
inline constexpr double kBladeWidthMinMm = 2.0;
inline constexpr double kBladeWidthMaxMm = 4.0;

/// Shoots per dm² of the lawn and green leaves per shoot.
inline constexpr double kShootsPerDm2 = 150.0;
inline constexpr int kLeavesPerShootMin = 3;
inline constexpr int kLeavesPerShootMax = 4;

/// One leaf blade as seen from above, in tile units.
struct GrassBlade {
  double x = 0.0, y = 0.0;          ///< where it leaves the shoot, [0, 1)
  double dir_x = 1.0, dir_y = 0.0;  ///< towards its tip (unit)
  double length = 0.0;              ///< projected length [tile]
  double width_mm = 0.0;            ///< at its base
  double depth = 0.0;               ///< 0 at the canopy's bottom, 1 at its top
  double tone = 1.0;                ///< relative to the mean green leaf
};

/// The variant's blades, bottom of the canopy first.
std::vector<GrassBlade> GrassSward(std::uint64_t seed, int variant);

/// The variants' common surface: none (each variant is its own sward).
void GrassSurface(texture_blocks::Field& f, std::uint64_t seed);

/// Variant `variant`: soil and thatch, then the sward's blades.
void GrassFeatures(texture_blocks::Field& f, std::uint64_t seed, int variant);

}  // namespace trackbed::render
