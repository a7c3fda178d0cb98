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
#include "trackbed/common/units.h"

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
  option_check::Positive("lateral_shear_modulus_ratio", lateral_shear_modulus_ratio);
  option_check::Positive("lateral_strength_ratio", lateral_strength_ratio);
  option_check::NonNegative("unit_weight_npm3", unit_weight_npm3);
}

BearingCapacityFactors BearingCapacity(double tan_phi) {
  BearingCapacityFactors f;
  const double phi = std::atan(tan_phi);
  const double t = std::tan(M_PI / 4.0 + phi / 2.0);
  f.n_q = std::exp(M_PI * tan_phi) * t * t;
  f.n_c = tan_phi > 1e-9 ? (f.n_q - 1.0) / tan_phi : M_PI + 2.0;
  f.n_gamma = 2.0 * (f.n_q + 1.0) * tan_phi;
  return f;
}

void SoilPoint::SetTanPhi(double t) {
  tan_phi = t;
  const BearingCapacityFactors f = BearingCapacity(t);
  const double cos2 = 1.0 / (1.0 + t * t);
  passive_kpc = (f.n_c - t) * cos2;
  // 2 N_γ / tan φ = 4 (N_q + 1): finite as φ → 0.
  passive_kpgamma = (4.0 * (f.n_q + 1.0) + 1.0) * cos2;
}

SoilPoint SoilOf(const TerrainMaterial& m) {
  SoilPoint s;
  s.cohesion_pa = m.cohesion_pa;
  s.SetTanPhi(std::tan(units::Radians(m.friction_angle_deg)));
  s.shear_modulus_m = m.shear_modulus_m;
  s.lateral_shear_modulus_m = m.shear_modulus_m * m.lateral_shear_modulus_ratio;
  s.lateral_strength_ratio = m.lateral_strength_ratio;
  s.bekker_kc = m.bekker_kc;
  s.bekker_kphi = m.bekker_kphi;
  s.bekker_n = m.bekker_n;
  s.unit_weight_npm3 = m.unit_weight_npm3;
  return s;
}

namespace {

TerrainMaterial Make(const char* name, double c_pa, double phi_deg, double k_m, double kc,
                     double kphi, double n, double unit_weight, double albedo) {
  TerrainMaterial m;
  m.name = name;
  m.cohesion_pa = c_pa;
  m.friction_angle_deg = phi_deg;
  m.shear_modulus_m = k_m;
  m.bekker_kc = kc;
  m.bekker_kphi = kphi;
  m.bekker_n = n;
  m.unit_weight_npm3 = unit_weight;
  m.albedo = albedo;
  return m;
}

double DegOfFriction(double mu) { return units::Degrees(std::atan(mu)); }

// Bulk unit weights γ [N/m³] (Das, Principles of Geotechnical Engineering: loose
// dry sand 14–16 kN/m³, moist loams and clays 17–19 kN/m³): only the weight
// term of the bulldozing resistance reads them.
constexpr double kDrySandWeight = 15.7e3;    // 1600 kg/m³
constexpr double kMoistSoilWeight = 17.7e3;  // 1800 kg/m³

std::vector<TerrainMaterial> MakeBuiltins() {
  // Lateral shear is isotropic in every built-in set (lateral_shear_modulus_ratio
  // and lateral_strength_ratio 1): no grouser-specific measurement for rubber
  // track pads was found (docs/physics.md).
  return {
      // Indoor hard floor (sealed concrete / vinyl) under rubber pads: no cohesion,
      // Coulomb friction μ 0.8 (tyres on dry asphalt and concrete: peak 0.8–0.9,
      // sliding 0.75, Wong Table 1.1); K 3 mm for the pads' own shear compliance;
      // rigid (no sinkage).
      Make("hard_floor", 0.0, DegOfFriction(0.8), 0.003, 0.0, 0.0, 1.0, 0.0, 0.55),
      // Outdoor paving (asphalt / concrete): μ 0.9, the peak of the same range; K 2 mm.
      Make("paving", 0.0, DegOfFriction(0.9), 0.002, 0.0, 0.0, 1.0, 0.0, 0.45),
      // Dry asphalt concrete, rigid as paving: μ 0.85, the middle of the peak range for
      // tyres on dry asphalt (0.8–0.9, Wong Table 1.1); K 2 mm, paving's pad compliance;
      // albedo 0.12, aged asphalt (0.10–0.15: Pomerantz, Akbari & Harvey 2000).
      Make("asphalt", 0.0, DegOfFriction(0.85), 0.002, 0.0, 0.0, 1.0, 0.0, 0.12),
      // LETE sand (Wong, Table 2.3): n 0.79, k_c 102 kN/m^1.79, k_φ 5301 kN/m^2.79,
      // c 1.3 kPa, φ 31.1°; K 1.2 cm (Wong's measured value for LETE sand).
      Make("lete_sand", 1300.0, 31.1, 0.012, 102e3, 5301e3, 0.79, kDrySandWeight, 0.62),
      // Dry sand for a light vehicle: the LLL dry sand below without its cohesion.
      // Dry sand is cohesionless; the LLL row's 1.04 kPa is the intercept of a
      // Mohr–Coulomb fit to shear-plate tests at vehicle-scale pressures, which at
      // this robot's 3.6 kPa would raise its traction coefficient from 0.53 to 0.82.
      Make("dry_sand", 0.0, 28.0, 0.025, 0.99e3, 1528.43e3, 1.1, kDrySandWeight, 0.68),
      // Dry sand (LLL, Table 2.3) as measured: n 1.1, k_c 0.99, k_φ 1528.43,
      // c 1.04 kPa, φ 28°; K 2.5 cm (loose sand, §2.4).
      Make("dry_sand_wong", 1040.0, 28.0, 0.025, 0.99e3, 1528.43e3, 1.1, kDrySandWeight, 0.68),
      // Sandy loam, 15 % moisture (LLL, Table 2.3): n 0.7, k_c 5.27, k_φ 1515.04,
      // c 1.72 kPa, φ 29°; K 2.5 cm (loose tilled soil, §2.4). No low-pressure or
      // rubber–soil measurement was found: Wong's set, flagged in docs/physics.md.
      Make("sandy_loam", 1720.0, 29.0, 0.025, 5.27e3, 1515.04e3, 0.7, kMoistSoilWeight, 0.40),
      // Clayey soil, 38 % moisture (Thailand, Table 2.3): n 0.5, k_c 13.19,
      // k_φ 692.15, c 4.14 kPa, φ 13°; K 1.5 cm (between compacted 0.6 cm and
      // loose 2.5 cm clay, §2.4). Wong's set, flagged as sandy loam is.
      Make("clay", 4140.0, 13.0, 0.015, 13.19e3, 692.15e3, 0.5, kMoistSoilWeight, 0.35),
      // Grass for a light vehicle: turf as a friction-dominated surface. A rubber
      // track shears the vegetation mat, not the soil's cohesion: c 0, the
      // substrate's friction angle (North Gower clayey loam, φ 26.6°, μ 0.50),
      // its Bekker moduli for sinkage and K 2.5 cm (loose soil, §2.4).
      Make("grass", 0.0, 26.6, 0.025, 41.6e3, 2471e3, 0.73, kMoistSoilWeight, 0.38),
      // North Gower clayey loam (Wong, Table 2.3) as measured: n 0.73, k_c 41.6,
      // k_φ 2471, c 6.1 kPa, φ 26.6°; K 2.5 cm (§2.4).
      Make("north_gower_clayey_loam_wong", 6100.0, 26.6, 0.025, 41.6e3, 2471e3, 0.73,
           kMoistSoilWeight, 0.38),
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
