// Terramechanics of a track pad (see terramechanics.h).
#include "trackbed/robot/terramechanics.h"

#include <algorithm>
#include <cmath>

namespace trackbed::robot {

double ShearStrength(const sim::SoilPoint& s, double normal_n, double area_m2) {
  return s.cohesion_pa * area_m2 + std::max(normal_n, 0.0) * s.tan_phi;
}

double JanosiHanamotoFraction(double j_m, double k_m) {
  return 1.0 - std::exp(-std::abs(j_m) / k_m);
}

namespace {

// The displacement in units of each direction's modulus.
Eigen::Vector2d Normalised(const sim::SoilPoint& s, const Eigen::Vector2d& j_m) {
  return {j_m.x() / s.shear_modulus_m, j_m.y() / s.lateral_shear_modulus_m};
}

}  // namespace

Eigen::Vector2d PadShearForce(const sim::SoilPoint& s, double strength_n,
                              const Eigen::Vector2d& j_m) {
  const Eigen::Vector2d jn = Normalised(s, j_m);
  const double r = jn.norm();
  if (r < 1e-12) return Eigen::Vector2d::Zero();
  const double mobilised = strength_n * (1.0 - std::exp(-r)) / r;
  return {-mobilised * jn.x(), -mobilised * s.lateral_strength_ratio * jn.y()};
}

double BekkerSinkage(const sim::SoilPoint& s, double pressure_pa, double width_m) {
  if (s.IsRigid() || pressure_pa <= 0.0) return 0.0;
  const double k = s.bekker_kc / width_m + s.bekker_kphi;
  return std::pow(pressure_pa / k, 1.0 / s.bekker_n);
}

double SlipSinkageFactor(double slip) {
  const double i = std::clamp(slip, 0.0, 1.0);
  return (1.0 + i) / (1.0 - 0.5 * i);
}

double CompactionResistance(const sim::SoilPoint& s, double sinkage_m, double width_m) {
  if (s.IsRigid() || sinkage_m <= 0.0) return 0.0;
  const double k = s.bekker_kc / width_m + s.bekker_kphi;
  return width_m * k * std::pow(sinkage_m, s.bekker_n + 1.0) / (s.bekker_n + 1.0);
}

double BulldozingResistance(const sim::SoilPoint& s, double depth_m, double face_width_m) {
  if (s.IsRigid() || depth_m <= 0.0) return 0.0;
  return face_width_m * (0.67 * s.cohesion_pa * depth_m * s.passive_kpc +
                         0.5 * depth_m * depth_m * s.unit_weight_npm3 * s.passive_kpgamma);
}

}  // namespace trackbed::robot
