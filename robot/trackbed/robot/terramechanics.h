// Terramechanics of a track pad or wheel patch on the ground: pure functions.
//
// Janosi–Hanamoto shear, Bekker pressure–sinkage and compaction, slip sinkage,
// bulldozing and running-gear resistance, as in J. Y. Wong, *Theory of Ground
// Vehicles* (4th ed., Wiley 2008), ch. 2 and 4, and the papers docs/physics.md
// names beside each. All take a SoilPoint: a material's parameters at one point.
#pragma once

#include <Eigen/Core>

#include "trackbed/sim/terrain_material.h"

namespace trackbed::robot {

/// Maximum longitudinal shear force [N] a patch of area `area_m2` carrying normal
/// load `normal_n` can develop: (c + σ tan φ)·A = c·A + N·tan φ (Mohr–Coulomb).
double ShearStrength(const sim::SoilPoint& s, double normal_n, double area_m2);

/// Janosi–Hanamoto: fraction of the shear strength developed at shear
/// displacement magnitude `j_m` [m] for modulus `k_m` [m]: 1 − exp(−|j|/K). In [0, 1).
double JanosiHanamotoFraction(double j_m, double k_m);

/// Shear force [N] on the vehicle, (along, across) the track, from the pad's shear
/// displacement `j_m` (along, across) [m] under a patch of longitudinal strength
/// `strength_n`: Janosi–Hanamoto on the displacement normalised by each direction's
/// modulus, ĵ = (j_x/K, j_y/K_y), |F| mobilised as 1 − e^(−|ĵ|) of the strength
/// ellipse (S, r·S), r the lateral strength ratio, opposing ĵ. Isotropic soil gives
/// Wong & Chiang's vector form, −S (1 − e^(−|j|/K)) j/|j|.
Eigen::Vector2d PadShearForce(const sim::SoilPoint& s, double strength_n,
                              const Eigen::Vector2d& j_m);

/// Bekker sinkage [m] of a plate of width `width_m` under pressure `pressure_pa`:
/// z = (p / (k_c/b + k_φ))^(1/n). Zero on rigid ground.
double BekkerSinkage(const sim::SoilPoint& s, double pressure_pa, double width_m);

/// Slip sinkage factor [-]: total sinkage over static sinkage at slip ratio
/// `slip` (Lyasko 2010, J. Terramechanics 47, eq. 18): (1 + i) / (1 − 0.5 i),
/// with i clamped to [0, 1]; 1 for a braked or free-rolling pad.
double SlipSinkageFactor(double slip);

/// Compaction (motion) resistance [N] of a track of width `width_m` making a rut
/// of depth `sinkage_m`: R_c = b (k_c/b + k_φ) z^(n+1) / (n + 1) (Bekker; Wong §4.2).
double CompactionResistance(const sim::SoilPoint& s, double sinkage_m, double width_m);

/// Bulldozing resistance [N] of a vertical face `face_width_m` wide pushed
/// through soil `depth_m` deep (Bekker 1969; Wong §4.2, eq. 4.15):
/// R_b = b (0.67 c z K_pc + 0.5 z² γ K_pγ), with the point's passive-pressure
/// coefficients (sim::SoilPoint). Zero on rigid ground or at zero depth.
double BulldozingResistance(const sim::SoilPoint& s, double depth_m, double face_width_m);

}  // namespace trackbed::robot
