// Terramechanics of a track pad (see terramechanics.h).
#include "trackbed/robot/terramechanics.h"

#include <cmath>

namespace trackbed::robot {

double ShearStrength(const sim::TerrainMaterial& m, double normal_n, double area_m2) {
  const double tan_phi = std::tan(m.friction_angle_deg * M_PI / 180.0);
  return m.cohesion_pa * area_m2 + std::max(normal_n, 0.0) * tan_phi;
}

double JanosiHanamotoFraction(const sim::TerrainMaterial& m, double j_m) {
  return 1.0 - std::exp(-std::abs(j_m) / m.shear_modulus_m);
}

double BekkerSinkage(const sim::TerrainMaterial& m, double pressure_pa, double width_m) {
  if (m.IsRigid() || pressure_pa <= 0.0) return 0.0;
  const double k = m.bekker_kc / width_m + m.bekker_kphi;
  return std::pow(pressure_pa / k, 1.0 / m.bekker_n);
}

double CompactionResistance(const sim::TerrainMaterial& m, double sinkage_m, double width_m) {
  if (m.IsRigid() || sinkage_m <= 0.0) return 0.0;
  const double k = m.bekker_kc / width_m + m.bekker_kphi;
  return width_m * k * std::pow(sinkage_m, m.bekker_n + 1.0) / (m.bekker_n + 1.0);
}

}  // namespace trackbed::robot
