// Terramechanics of a track pad on the ground: pure functions.
//
// Janosi–Hanamoto shear law and Bekker pressure–sinkage as in J. Y. Wong,
// *Theory of Ground Vehicles* (4th ed.), §2.4 (shear) and §2.2–2.3 (sinkage).
#pragma once

#include "trackbed/sim/terrain_material.h"

namespace trackbed::robot {

/// Maximum shear force [N] a contact patch of area `area_m2` carrying normal
/// load `normal_n` can develop: (c + σ tan φ)·A = c·A + N·tan φ (Mohr–Coulomb).
double ShearStrength(const sim::TerrainMaterial& m, double normal_n, double area_m2);

/// Janosi–Hanamoto: fraction of the shear strength developed at shear
/// displacement magnitude `j_m` [m]: 1 − exp(−j/K). In [0, 1).
double JanosiHanamotoFraction(const sim::TerrainMaterial& m, double j_m);

/// Bekker sinkage [m] of a plate of width `width_m` under pressure `pressure_pa`:
/// z = (p / (k_c/b + k_φ))^(1/n). Zero on rigid ground.
double BekkerSinkage(const sim::TerrainMaterial& m, double pressure_pa, double width_m);

/// Compaction (motion) resistance [N] of a track of width `width_m` making a rut
/// of depth `sinkage_m`: R_c = b (k_c/b + k_φ) z^(n+1) / (n + 1) (Bekker; Wong ch. 2–4).
double CompactionResistance(const sim::TerrainMaterial& m, double sinkage_m, double width_m);

}  // namespace trackbed::robot
