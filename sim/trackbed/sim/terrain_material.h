// Terrain materials: the terramechanical parameters of the ground under a track.
//
// Traction follows the Janosi–Hanamoto shear law τ = (c + σ tan φ)(1 − e^(−j/K))
// and sinkage follows Bekker's pressure–sinkage law p = (k_c/b + k_φ) z^n
// (Wong, *Theory of Ground Vehicles*, 4th ed., §2.4 and §2.5). Values and their
// sources are in terrain_material.cpp and docs/terrain_materials.md.
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
  /// Grey level [0, 1] the renderer uses as the material's base tone.
  double albedo = 0.5;

  /// True when the ground does not sink (k_c = k_φ = 0).
  bool IsRigid() const { return bekker_kc == 0.0 && bekker_kphi == 0.0; }
  /// Throws OptionError naming the field when a parameter is out of range.
  void Validate() const;
};

/// The built-in materials (hard floor, concrete, LETE sand, dry sand, sandy loam,
/// clay, grass), each documented with its source.
const std::vector<TerrainMaterial>& BuiltinMaterials();

/// Looks a built-in material up by name; throws std::invalid_argument listing
/// the known names when there is none.
const TerrainMaterial& BuiltinMaterial(const std::string& name);

}  // namespace trackbed::sim
