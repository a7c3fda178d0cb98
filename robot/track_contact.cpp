// One contact station's shear (see track_contact.h).
#include "trackbed/robot/track_contact.h"

#include <cmath>

#include "trackbed/robot/terramechanics.h"

namespace trackbed::robot {
namespace {

// Shear displacement, in moduli, past which the soil counts as yielded.
constexpr double kYieldedModuli = 6.0;

}  // namespace

Eigen::Vector2d StepStationShear(const sim::SoilPoint& soil, const StationKinematics& k,
                                 const StationLoad& load, double damping_s, double dt_s,
                                 Eigen::Vector2d* shear_m) {
  const Eigen::Vector2d before = *shear_m;
  const double renewal_rate = std::abs(k.track_speed_mps) / k.lead_m;
  *shear_m = (before + k.v_pad_mps * dt_s) / (1.0 + renewal_rate * dt_s);
  const Eigen::Vector2d rate = (*shear_m - before) / dt_s;
  // Beyond kYieldedModuli moduli the soil has yielded (99.75 % of its strength
  // mobilised): further displacement is plastic flow, not stored, so a reversal
  // unwinds at most that much before the force turns.
  const double moduli =
      std::hypot(shear_m->x() / soil.shear_modulus_m, shear_m->y() / soil.lateral_shear_modulus_m);
  if (moduli > kYieldedModuli) *shear_m *= kYieldedModuli / moduli;

  const double strength = ShearStrength(soil, load.normal_n, load.area_m2);
  if (!(strength > 0.0)) return Eigen::Vector2d::Zero();
  // The lateral strength with the bulldozing of the side face, as a ratio.
  sim::SoilPoint resisting = soil;
  resisting.lateral_strength_ratio += load.bulldozing_n / strength;
  Eigen::Vector2d force = PadShearForce(resisting, strength, *shear_m);
  // Kelvin–Voigt: the initial stiffness of each direction, S/K and r·S/K_y, decayed
  // as the soil yields, times the rate of displacement.
  const double decay = std::exp(-std::min(moduli, kYieldedModuli));
  const double lateral_strength = strength * resisting.lateral_strength_ratio;
  force.x() -= damping_s * strength / soil.shear_modulus_m * decay * rate.x();
  force.y() -= damping_s * lateral_strength / soil.lateral_shear_modulus_m * decay * rate.y();
  // Within the strength ellipse (S along, r·S + R_b across).
  const double e = std::hypot(force.x() / strength, force.y() / lateral_strength);
  if (e > 1.0) force /= e;
  return force;
}

}  // namespace trackbed::robot
