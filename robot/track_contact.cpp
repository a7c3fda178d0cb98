// One contact station's shear (see track_contact.h).
#include "trackbed/robot/track_contact.h"

#include <cmath>

#include "trackbed/robot/terramechanics.h"  // ShearStrength; the force as PadShearForce

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
  // Beyond kYieldedModuli moduli the soil has yielded (99.75 % of its strength
  // mobilised): further displacement is plastic flow, not stored, so a reversal
  // unwinds at most that much before the force turns.
  const Eigen::Vector2d in_moduli(shear_m->x() / soil.shear_modulus_m,
                                  shear_m->y() / soil.lateral_shear_modulus_m);
  const double moduli = in_moduli.norm();
  if (moduli > kYieldedModuli) *shear_m *= kYieldedModuli / moduli;
  const Eigen::Vector2d rate = (*shear_m - before) / dt_s;

  const double strength = ShearStrength(soil, load.normal_n, load.area_m2);
  if (!(strength > 0.0)) return Eigen::Vector2d::Zero();
  // Janosi–Hanamoto on the displacement in units of each direction's modulus
  // (PadShearForce and PadShearStiffness, with the bulldozing in the lateral
  // strength), plus the Kelvin–Voigt damping on the rate.
  const double lateral_strength = strength * soil.lateral_strength_ratio + load.bulldozing_n;
  const Eigen::Vector2d jn(shear_m->x() / soil.shear_modulus_m,
                           shear_m->y() / soil.lateral_shear_modulus_m);
  const double r = jn.norm();
  const double decay = std::exp(-r);
  Eigen::Vector2d force = Eigen::Vector2d::Zero();
  if (r > 1e-12) {
    const double mobilised = (1.0 - decay) / r;
    force = {-strength * mobilised * jn.x(), -lateral_strength * mobilised * jn.y()};
  }
  force.x() -= damping_s * strength / soil.shear_modulus_m * decay * rate.x();
  force.y() -= damping_s * lateral_strength / soil.lateral_shear_modulus_m * decay * rate.y();
  // Within the strength ellipse (S along, r·S + R_b across).
  const double ex = force.x() / strength, ey = force.y() / lateral_strength;
  const double e2 = ex * ex + ey * ey;
  if (e2 > 1.0) force /= std::sqrt(e2);
  return force;
}

}  // namespace trackbed::robot
