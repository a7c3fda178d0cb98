// A scene's `mesh` objects read from their files and put to their uses: obstacles
// for the world (sim::World's meshes), and ground meshes sampled onto the terrain's
// grid as its heights (docs/user_files.md).
#pragma once

#include <memory>
#include <vector>

#include "trackbed/assets/mesh_reader.h"
#include "trackbed/sim/elevation_grid.h"
#include "trackbed/sim/terrain.h"
#include "trackbed/sim/world.h"

namespace trackbed::assets {

/// A scene's objects sorted by use.
struct SceneMeshes {
  std::vector<sim::StaticObject> primitives;  ///< Boxes and cylinders, as given.
  std::vector<sim::MeshObject> obstacles;     ///< Meshes that are not ground.
  /// Ground meshes; a NaN base_z_m becomes 0 (the file's heights as they are).
  std::vector<sim::MeshObject> grounds;
};

/// Reads every mesh object's files (assets::ReadMeshKept). Throws AssetError naming the
/// file (ReadMesh).
SceneMeshes LoadSceneMeshes(const std::vector<sim::StaticObject>& objects);

/// The terrain's grid points' heights from the ground meshes: at each point the highest
/// of their triangles above or below it. Throws AssetError naming the meshes' files and
/// the first grid point none of them covers. Null without ground meshes.
std::shared_ptr<const sim::ElevationGrid> SampleMeshGround(
    const std::vector<sim::MeshObject>& grounds, const sim::TerrainOptions& terrain);

}  // namespace trackbed::assets
