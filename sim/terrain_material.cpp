// Built-in terrain materials and their sources.
//
// Soil values are from J. Y. Wong, *Theory of Ground Vehicles* (4th ed., Wiley
// 2008): Table 2.3 (Bekker pressure–sinkage and Mohr–Coulomb parameters of
// soils measured by the Land Locomotion Laboratory, LLL, and by Wong) and §2.4
// for the shear deformation modulus K, which Wong gives as about 1 cm for firm
// sandy terrain, 2.5 cm for loose sand, 0.6 cm for clay at maximum compaction
// and 2.5 cm for loose clay. Bekker moduli in the book are in kN/m^(n+1) and
// kN/m^(n+2); here they are in N (×1000).
#include "trackbed/sim/terrain_material.h"

#include <cmath>
#include <stdexcept>

#include "trackbed/common/option_error.h"

namespace trackbed::sim {

void TerrainMaterial::Validate() const {
  if (name.empty()) throw OptionError("name", "must not be empty");
  option_check::NonNegative("cohesion_pa", cohesion_pa);
  option_check::InRange("friction_angle_deg", friction_angle_deg, 0.0, 60.0);
  option_check::Positive("shear_modulus_m", shear_modulus_m);
  option_check::NonNegative("bekker_kc", bekker_kc);
  option_check::NonNegative("bekker_kphi", bekker_kphi);
  option_check::InRange("bekker_n", bekker_n, 0.05, 3.0);
  option_check::InRange("albedo", albedo, 0.0, 1.0);
}

namespace {

TerrainMaterial Make(const char* name, double c_pa, double phi_deg, double k_m, double kc,
                     double kphi, double n, double albedo) {
  TerrainMaterial m;
  m.name = name;
  m.cohesion_pa = c_pa;
  m.friction_angle_deg = phi_deg;
  m.shear_modulus_m = k_m;
  m.bekker_kc = kc;
  m.bekker_kphi = kphi;
  m.bekker_n = n;
  m.albedo = albedo;
  return m;
}

std::vector<TerrainMaterial> MakeBuiltins() {
  const double deg_of_mu_0_8 = std::atan(0.8) * 180.0 / M_PI;  // 38.66°
  return {
      // Indoor hard floor (sealed concrete / vinyl) under rubber track pads: no
      // cohesion, Coulomb friction μ = 0.8 (rubber on dry concrete is 0.6–0.85),
      // K = 3 mm for the pads' own shear compliance; rigid (no sinkage).
      Make("hard_floor", 0.0, deg_of_mu_0_8, 0.003, 0.0, 0.0, 1.0, 0.55),
      // Outdoor paving (asphalt / concrete): μ = 0.9, K = 2 mm, rigid.
      Make("paving", 0.0, std::atan(0.9) * 180.0 / M_PI, 0.002, 0.0, 0.0, 1.0, 0.45),
      // LETE sand (Wong, Table 2.3): n 0.79, k_c 102 kN/m^1.79, k_φ 5301 kN/m^2.79,
      // c 1.3 kPa, φ 31.1°; K 1.2 cm (Wong's measured value for LETE sand).
      Make("lete_sand", 1300.0, 31.1, 0.012, 102e3, 5301e3, 0.79, 0.62),
      // Dry sand (LLL, Table 2.3): n 1.1, k_c 0.99, k_φ 1528.43, c 1.04 kPa, φ 28°;
      // K 2.5 cm (loose sand, §2.4).
      Make("dry_sand", 1040.0, 28.0, 0.025, 0.99e3, 1528.43e3, 1.1, 0.68),
      // Sandy loam, 15 % moisture (LLL, Table 2.3): n 0.7, k_c 5.27, k_φ 1515.04,
      // c 1.72 kPa, φ 29°; K 2.5 cm (loose tilled soil, §2.4).
      Make("sandy_loam", 1720.0, 29.0, 0.025, 5.27e3, 1515.04e3, 0.7, 0.40),
      // Clayey soil, 38 % moisture (Thailand, Table 2.3): n 0.5, k_c 13.19,
      // k_φ 692.15, c 4.14 kPa, φ 13°; K 1.5 cm (between compacted 0.6 cm and
      // loose 2.5 cm clay, §2.4).
      Make("clay", 4140.0, 13.0, 0.015, 13.19e3, 692.15e3, 0.5, 0.35),
      // Grass (turf on loam). Not in Wong's tables: an engineering estimate. The
      // substrate is North Gower clayey loam (Wong, Table 2.3: n 0.73, k_c 41.6,
      // k_φ 2471, c 6.1 kPa, φ 26.6°); the fibrous vegetation mat deforms further
      // than bare soil before reaching peak shear, so K is raised to 3.5 cm.
      Make("grass", 6100.0, 26.6, 0.035, 41.6e3, 2471e3, 0.73, 0.38),
  };
}

}  // namespace

const std::vector<TerrainMaterial>& BuiltinMaterials() {
  static const std::vector<TerrainMaterial> materials = MakeBuiltins();
  return materials;
}

const TerrainMaterial& BuiltinMaterial(const std::string& name) {
  std::string known;
  for (const TerrainMaterial& m : BuiltinMaterials()) {
    if (m.name == name) return m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  throw std::invalid_argument("unknown terrain material '" + name + "' (known: " + known + ")");
}

}  // namespace trackbed::sim
