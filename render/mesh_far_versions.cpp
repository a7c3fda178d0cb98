// Simplified far versions of a mesh object's chunk (see mesh_far_versions.h).
#include "mesh_far_versions.h"

#include <meshoptimizer.h>

#include "trackbed/render/object_detail.h"

namespace trackbed::render {

std::vector<MeshLevel> MeshFullVersion(const MeshSurface& s) {
  return {{0, static_cast<std::uint32_t>(s.indices.size()), 0.0}};
}

std::vector<MeshLevel> AddMeshFarVersions(MeshSurface* s) {
  std::vector<MeshLevel> levels = MeshFullVersion(*s);
  const std::size_t full = s->indices.size();
  if (full == 0) return levels;
  const auto* positions = &s->vertices.front().x;
  const std::size_t count = s->vertices.size(), stride = sizeof(TerrainVertex);
  const double scale = meshopt_simplifyScale(positions, count, stride);
  std::vector<std::uint32_t> out(full);
  std::size_t previous = full;
  for (int l = 0; l < kMeshMaxFarVersions; ++l) {
    const std::size_t target = previous / 12 * 3;  // a quarter of the triangles
    float error = 0.0f;
    // Error up to the chunk's extent: the distance at which a version is drawn follows
    // from it.
    const std::size_t n =
        meshopt_simplify(out.data(), s->indices.data(), full, positions, count, stride, target,
                         1.0f, meshopt_SimplifyLockBorder, &error);
    if (n == 0 || static_cast<double>(n) > kMeshLevelMinReduction * static_cast<double>(previous))
      break;
    levels.push_back({static_cast<std::uint32_t>(s->indices.size()), static_cast<std::uint32_t>(n),
                      static_cast<double>(error) * scale});
    s->indices.insert(s->indices.end(), out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n));
    previous = n;
  }
  return levels;
}

const MeshLevel& MeshLevelAt(const std::vector<MeshLevel>& levels, const Eigen::AlignedBox3d& box,
                             const Eigen::Vector2d& detail_center_xy, double focal_px,
                             double max_error_px) {
  if (max_error_px <= 0.0 || levels.size() == 1) return levels.front();
  const Eigen::AlignedBox2d plan(box.min().head<2>(), box.max().head<2>());
  const double distance = plan.exteriorDistance(detail_center_xy);
  std::size_t chosen = 0;
  for (std::size_t l = 1; l < levels.size(); ++l) {
    if (distance < FarVersionDistance(levels[l].departure_m, focal_px, max_error_px)) break;
    chosen = l;
  }
  return levels[chosen];
}

}  // namespace trackbed::render
