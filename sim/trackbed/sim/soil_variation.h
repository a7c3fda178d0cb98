// Uneven soil: seeded spatial fields that scale a material's strength and
// stiffness parameters from point to point.
//
// Natural soil varies within a field: Phoon & Kulhawy (1999, Can. Geotech. J. 36,
// "Characterization of geotechnical variability") compile coefficients of
// variation of roughly 10–50 % for soil strength and 5–15 % for the friction
// angle (docs/physics.md). Each
// varied parameter p (c, tan φ, K — along and across alike —, k_c, k_φ) becomes
// p·(1 + a·f_p(x, y)), with f_p a smooth value-noise field in [−1, 1] whose
// lattice spacing is the correlation length. Every value is a pure function of
// the seed and the point, so any tile of an unbounded world can be computed
// without the others.
#pragma once

#include <cstdint>

#include "trackbed/sim/terrain_material.h"

namespace trackbed::sim {

/// `scene.terrain.soil_variation`: how much and over what distance soil varies.
struct SoilVariationOptions {
  /// Peak relative change of each parameter [-], in [0, 0.9]; 0 turns variation off.
  double amplitude = 0.0;
  /// Lattice spacing of the noise [m], > 0: the fields' correlation falls to about
  /// 0.13 at this distance and to zero at twice it.
  double correlation_length_m = 2.0;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("amplitude", &amplitude);
    a->Visit("correlation_length_m", &correlation_length_m);
  }
};

/// The seeded variation fields. Cheap to copy; thread-safe (no state).
class SoilVariation {
 public:
  /// The parameters a field exists for, one independent field each.
  enum Field { kCohesion = 0, kTanPhi, kShearModulus, kKc, kKphi, kFields };

  SoilVariation(const SoilVariationOptions& options, std::uint64_t seed);

  /// True when the amplitude is zero: SoilAt returns the material unchanged.
  bool off() const { return options_.amplitude == 0.0; }
  /// Field `f` at (x, y), in [−1, 1]; continuous with a continuous gradient.
  double Value(Field f, double x_m, double y_m) const;
  /// `base` scaled by the fields at (x, y); rigid ground (floors, paving) unchanged.
  SoilPoint Apply(const SoilPoint& base, double x_m, double y_m) const;

 private:
  SoilVariationOptions options_;
  std::uint64_t seed_;
};

}  // namespace trackbed::sim
