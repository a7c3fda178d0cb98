// Bare sandy loam seen from above (the detailed look's `sandy_loam`; ground_soil.cpp):
// aggregates in the size classes of soil structure, a few clods, a dried surface crust
// broken by desiccation cracks, sand grains and bits of straw, over fine earth with its
// micro-relief. Private to the renderer; the tests read the cracks.
#pragma once

#include <cstdint>

namespace trackbed::render {

namespace texture_blocks {
struct Field;
}

/// The tile of the detailed soil [m]: 256 texels give 2 mm.
inline constexpr double kSoilTileM = 0.5;

/// Tile variants the detailed soil is made in (ground_tiling.h).
inline constexpr int kSoilVariants = 4;

/// The largest share of a surface that desiccation cracks were measured to open
/// (docs/rendering.md, "Soil"): a Vertisol's crack intensity factor at its driest.
inline constexpr double kMaxCrackShare = 0.0575;

/// The share of variant `variant`'s tile that its cracks cover, at `size_px` texels.
double SoilCrackShare(std::uint64_t seed, int variant, int size_px);

/// The variants' common surface: none (each variant is its own patch of ground).
void SoilSurface(texture_blocks::Field& f, std::uint64_t seed);

/// Variant `variant`: fine earth, crust and cracks, aggregates, clods, grains, straw.
void SoilFeatures(texture_blocks::Field& f, std::uint64_t seed, int variant);

}  // namespace trackbed::render
