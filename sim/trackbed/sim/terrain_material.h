// Terrain materials: the terramechanical parameters of the ground under a track.
//
// Traction follows the Janosi–Hanamoto shear law τ = (c + σ tan φ)(1 − e^(−j/K))
// and sinkage follows Bekker's pressure–sinkage law p = (k_c/b + k_φ) z^n
// (Wong, *Theory of Ground Vehicles*, 4th ed., §2.4 and §2.5). Values and their
// sources are in terrain_material.cpp and docs/physics.md.
#pragma once

#include <string>
#include <vector>

namespace trackbed::sim {

/// Physical parameters of one ground material. SI units throughout.
struct TerrainMaterial {
  /// Name used in scenario files (`scene.terrain.materials[].name`).
  std::string name;
  /// Cohesion c of the Mohr–Coulomb failure criterion [Pa], >= 0.
  double cohesion_pa = 0.0;
  /// Internal friction angle φ [deg] (for a hard floor: atan of the friction coefficient).
  double friction_angle_deg = 38.66;
  /// Shear deformation modulus K of the Janosi–Hanamoto law [m], > 0.
  double shear_modulus_m = 0.003;
  /// Bekker cohesive modulus k_c [N/m^(n+1)], >= 0. Zero with k_phi = 0 means rigid ground.
  double bekker_kc = 0.0;
  /// Bekker frictional modulus k_φ [N/m^(n+2)], >= 0.
  double bekker_kphi = 0.0;
  /// Bekker sinkage exponent n [-], > 0.
  double bekker_n = 1.0;
  /// Lateral (across the track) over longitudinal shear deformation modulus,
  /// K_y / K [-], > 0. Grousers make the two differ (docs/physics.md).
  double lateral_shear_modulus_ratio = 1.0;
  /// Lateral over longitudinal shear strength of a pad [-], > 0 (1: isotropic).
  double lateral_strength_ratio = 1.0;
  /// Bulk unit weight γ of the soil [N/m³], >= 0: the weight term of the
  /// bulldozing resistance in skid turns. Unused on rigid ground.
  double unit_weight_npm3 = 0.0;
  /// Grey level [0, 1] the renderer uses as the material's base tone.
  double albedo = 0.5;

  /// True when the ground does not sink (k_c = k_φ = 0).
  bool IsRigid() const { return bekker_kc == 0.0 && bekker_kphi == 0.0; }
  /// Throws OptionError naming the field when a parameter is out of range.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("name", &name);
    a->Visit("cohesion_pa", &cohesion_pa);
    a->Visit("friction_angle_deg", &friction_angle_deg);
    a->Visit("shear_modulus_m", &shear_modulus_m);
    a->Visit("bekker_kc", &bekker_kc);
    a->Visit("bekker_kphi", &bekker_kphi);
    a->Visit("bekker_n", &bekker_n);
    a->Visit("lateral_shear_modulus_ratio", &lateral_shear_modulus_ratio);
    a->Visit("lateral_strength_ratio", &lateral_strength_ratio);
    a->Visit("unit_weight_npm3", &unit_weight_npm3);
    a->Visit("albedo", &albedo);
  }
};

/// The mechanical parameters of the ground at one point: a material's values,
/// after the terrain's spatial soil variation (sim/soil_variation.h). What the
/// track model reads per contact station and step; a plain value, no name.
struct SoilPoint {
  double cohesion_pa = 0.0;                ///< c [Pa].
  double tan_phi = 0.8;                    ///< tan φ [-].
  double shear_modulus_m = 0.003;          ///< K along the track [m].
  double lateral_shear_modulus_m = 0.003;  ///< K across the track [m].
  double lateral_strength_ratio = 1.0;     ///< Lateral / longitudinal shear strength [-].
  double bekker_kc = 0.0;                  ///< k_c [N/m^(n+1)].
  double bekker_kphi = 0.0;                ///< k_φ [N/m^(n+2)].
  double bekker_n = 1.0;                   ///< n [-].
  double unit_weight_npm3 = 0.0;           ///< γ [N/m³].
  /// Bekker's passive-pressure coefficients of bulldozing at this φ:
  /// K_pc = (N_c − tan φ) cos² φ and K_pγ = (2 N_γ / tan φ + 1) cos² φ (see
  /// BearingCapacity); kept with the point because φ fixes them.
  double passive_kpc = 0.0;
  double passive_kpgamma = 0.0;

  /// True when the ground does not sink (k_c = k_φ = 0).
  bool IsRigid() const { return bekker_kc == 0.0 && bekker_kphi == 0.0; }
  /// Sets tan φ and the passive-pressure coefficients that follow from it.
  void SetTanPhi(double tan_phi);
};

/// Bearing capacity factors for friction angle φ: Prandtl–Reissner
/// N_q = e^(π tan φ) tan²(45° + φ/2), N_c = (N_q − 1) cot φ (→ π + 2 as φ → 0),
/// and Vesić's (1973) N_γ = 2 (N_q + 1) tan φ.
struct BearingCapacityFactors {
  double n_c = 0.0;
  double n_q = 0.0;
  double n_gamma = 0.0;
};
BearingCapacityFactors BearingCapacity(double tan_phi);

/// The material's parameters as a SoilPoint (no spatial variation).
SoilPoint SoilOf(const TerrainMaterial& m);

/// The built-in materials, each documented with its source: rigid floors
/// (hard_floor, paving, asphalt), soils for a light vehicle under their common names
/// (dry_sand, sandy_loam, clay, grass), and Wong's measured sets (lete_sand,
/// dry_sand_wong, north_gower_clayey_loam_wong).
const std::vector<TerrainMaterial>& BuiltinMaterials();

/// Looks a built-in material up by name; throws std::invalid_argument listing
/// the known names when there is none.
const TerrainMaterial& BuiltinMaterial(const std::string& name);

}  // namespace trackbed::sim
