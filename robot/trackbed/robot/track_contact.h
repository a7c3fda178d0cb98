// One contact station's shear against the ground: the shear-displacement state
// with pad renewal, and the Janosi–Hanamoto force it develops.
//
// Pads (a track's, or a tyre's tread) enter the contact unsheared and travel back
// at the track speed u, so the displacement j (along, across) obeys
//   j' = v_pad − (|u| / L) j,
// L the station's distance from the leading edge of its shear zone (the track's
// front for a continuous track, the patch's for a wheel). In steady slip i this
// is Wong's j(x) = i·x (Theory of Ground Vehicles, §2.4). The renewal term is
// integrated implicitly, so any speed is stable at a 1 ms step. The displacement
// the state remembers is bounded at six moduli (99.75 % of the strength
// mobilised): past that the soil flows plastically, and a pad whose motion
// reverses unwinds only the remembered part before its force turns, instead of
// every centimetre it slid.
#pragma once

#include <Eigen/Core>

#include "trackbed/sim/terrain_material.h"

namespace trackbed::robot {

/// What one station sees in one physics step.
struct StationKinematics {
  /// Pad velocity relative to the ground, (along, across) the track [m/s]:
  /// the chassis point's velocity minus the track surface's u·t.
  Eigen::Vector2d v_pad_mps = Eigen::Vector2d::Zero();
  /// Track surface speed u [m/s].
  double track_speed_mps = 0.0;
  /// Shear length from the leading edge in the current direction of u [m], > 0.
  double lead_m = 1.0;
};

/// What resists one station's shear: its load, patch and the bulldozing of its side.
struct StationLoad {
  double normal_n = 0.0;  ///< Normal load [N], >= 0.
  double area_m2 = 0.0;   ///< Shear area of the patch [m²].
  /// Bulldozing resistance of the station's side face [N] (BulldozingResistance),
  /// added to the lateral strength: the soil wedge's passive pressure is mobilised
  /// by the same sideways displacement that shears the pad.
  double bulldozing_n = 0.0;
};

/// Advances `shear_m` by `dt_s` and returns the shear force on the vehicle
/// (along, across) [N]: PadShearForce with lateral strength r·S + R_b, plus a
/// Kelvin–Voigt term, `damping_s` times each direction's initial stiffness (S/K,
/// (r·S + R_b)/K_y) decayed by e^(−|ĵ|), times the rate of shear displacement,
/// that damps the soil-spring oscillation and vanishes in steady slip. |F| stays
/// within the strength ellipse.
Eigen::Vector2d StepStationShear(const sim::SoilPoint& soil, const StationKinematics& k,
                                 const StationLoad& load, double damping_s, double dt_s,
                                 Eigen::Vector2d* shear_m);

}  // namespace trackbed::robot
