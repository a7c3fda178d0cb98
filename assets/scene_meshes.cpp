// A scene's meshes read and put to their uses (see scene_meshes.h).
#include "trackbed/assets/scene_meshes.h"

#include <cmath>
#include <map>
#include <string>

#include "trackbed/common/option_error.h"

namespace trackbed::assets {

SceneMeshes LoadSceneMeshes(const std::vector<sim::StaticObject>& objects) {
  SceneMeshes out;
  std::map<std::string, std::shared_ptr<const sim::TriangleMesh>> read;
  const auto mesh_of = [&read](const std::string& file) {
    std::shared_ptr<const sim::TriangleMesh>& m = read[file];
    if (!m) {
      const std::shared_ptr<const MeshRead> r = ReadMeshKept(file);
      m = std::shared_ptr<const sim::TriangleMesh>(r, &r->mesh);  // shares the read's
    }
    return m;
  };
  for (const sim::StaticObject& o : objects) {
    if (o.shape != sim::StaticObject::Shape::kMesh) {
      out.primitives.push_back(o);
      continue;
    }
    sim::MeshObject m;
    m.entry = o;
    m.visual = mesh_of(o.mesh.file);
    if (o.mesh.collision == sim::MeshSource::Collision::kFile) {
      m.collision = mesh_of(o.mesh.collision_file);
    }
    if (o.mesh.ground) {
      if (std::isnan(m.entry.base_z_m)) m.entry.base_z_m = 0.0;
      out.grounds.push_back(std::move(m));
    } else {
      out.obstacles.push_back(std::move(m));
    }
  }
  return out;
}

std::shared_ptr<const sim::ElevationGrid> SampleMeshGround(
    const std::vector<sim::MeshObject>& grounds, const sim::TerrainOptions& terrain) {
  if (grounds.empty()) return nullptr;
  std::vector<sim::PlacedMesh> placed;
  std::string files;
  for (const sim::MeshObject& g : grounds) {
    placed.emplace_back(*g.visual, g.entry.mesh.scale, g.Pose());
    files += (files.empty() ? "" : ", ") + g.entry.mesh.file;
  }
  const Eigen::Vector4d box = terrain.grid_extent_m();
  const double cell = terrain.cell_size_m;
  const int cols = static_cast<int>(std::lround((box[2] - box[0]) / cell)) + 1;
  const int rows = static_cast<int>(std::lround((box[3] - box[1]) / cell)) + 1;
  std::vector<double> heights(static_cast<std::size_t>(cols) * rows);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      // The point as the terrain computes its grid vertices.
      const double x = box[0] + cell * c, y = box[1] + cell * r;
      std::optional<double> top;
      for (const sim::PlacedMesh& p : placed) {
        const std::optional<double> z = p.HighestAt(x, y);
        if (z && (!top || *z > *top)) top = z;
      }
      if (!top) {
        throw AssetError(files + ": the ground mesh" +
                         (grounds.size() > 1 ? "es leave" : " leaves") +
                         " the terrain's grid point (" + option_check::Describe(x) + ", " +
                         option_check::Describe(y) +
                         ") without a triangle above or below it; a ground mesh must cover "
                         "scene.terrain.extent_m");
      }
      heights[static_cast<std::size_t>(r) * cols + c] = *top;
    }
  }
  return std::make_shared<const sim::ElevationGrid>(
      cols, rows, Eigen::Vector2d(box[0], box[1]), Eigen::Vector2d(cell, cell), std::move(heights));
}

}  // namespace trackbed::assets
