// Dense asphalt concrete seen from above (the `asphalt` texture; ground_asphalt.cpp):
// coarse aggregate chips graded as a stone mastic asphalt SMA 11 S, their worn tops
// bright between the dark binder-rich mastic, and, per tile variant, cracks and stains
// and a sealed crack, a patch or a worn paint marking. Private to the renderer; the tests
// read the grading and the chips.
#pragma once

#include <cstdint>
#include <vector>

namespace trackbed::render {

namespace texture_blocks {
struct Field;
}

/// One class of the coarse aggregate between two sieves [mm] and its share of the
/// aggregate's mass.
struct SieveClass {
  double lo_mm = 0.0;       ///< lower sieve [mm]
  double hi_mm = 0.0;       ///< upper sieve [mm]
  double mass_share = 0.0;  ///< share of the whole aggregate's mass, [0, 1]
};

/// SMA 11 S (TL Asphalt-StB 07/13, Tabelle 8): mass passing 16 mm 100 %, 11.2 mm
/// 90–100, 8 mm 50–65, 5.6 mm 35–45, 2 mm 20–30; the classes between the envelope's
/// midpoints (100, 95, 57.5, 40, 25 %). The 25 % below 2 mm is the mastic's sand and filler.
inline constexpr SieveClass kSma11Coarse[] = {
    {2.0, 5.6, 0.15}, {5.6, 8.0, 0.175}, {8.0, 11.2, 0.375}, {11.2, 16.0, 0.05}};

/// The aggregate's share of the mix's volume: 93.4 % of the mass (binder 6.6 %, TL
/// Asphalt-StB 07/13's SMA 11 S) at 2.65 g/cm³ (rock), the binder at 1.03 g/cm³, 3 %
/// air voids (the mix's 2.5–3.0 %). By Delesse's principle a plane through the mix, the
/// road's worn surface, shows each class over the share of its area that the class
/// takes of the volume.
double AggregateVolumeShare();

/// A chip of coarse aggregate at the surface of a 1 m tile.
struct AggregateChip {
  double x_m = 0.0, y_m = 0.0;      ///< centre within the tile, [0, 1)
  double diameter_mm = 0.0;         ///< the face's long axis, within its sieve class
  double aspect = 1.0;              ///< short axis over long axis
  double dir_x = 1.0, dir_y = 0.0;  ///< the long axis (unit)
  double reflectance = 0.0;         ///< of the stone where the binder has worn off
  double exposed = 0.0;             ///< share of the face's radius worn clean, the rest coated
  int sieve_class = 0;              ///< index into kSma11Coarse
};

/// The coarse aggregate over one tile from `seed`, smallest class first (each class's
/// faces cover AggregateVolumeShare() × its mass share of the tile's area).
std::vector<AggregateChip> AsphaltAggregate(std::uint64_t seed);

/// Tile variants the `asphalt` texture is made in (ground_tiling.h).
inline constexpr int kAsphaltVariants = 4;

/// The variants' common surface: mastic and aggregate (grey = 255 × reflectance).
void AsphaltSurface(texture_blocks::Field& f, std::uint64_t seed);

/// Adds variant `variant`'s cracks and stains and, in three variants of four, a sealed
/// crack, a patch or a worn marking, each inside one quarter of the tile clear of its
/// edges (the tiling shifts tiles by half a tile).
void AsphaltFeatures(texture_blocks::Field& f, std::uint64_t seed, int variant);

}  // namespace trackbed::render
