// Fuzzes the project's own mapping of mesh triangles (sim/triangle_mesh.h,
// assets/scene_meshes.h), not assimp's parsers: the input's bytes are a mesh's
// vertices and triangles as assimp would hand them over, and a scale and a pose. The
// placed mesh's plan grid must answer as a search of every triangle does: the highest
// triangle over a point, and the plan distance from a footprint (each triangle placed
// alone); a ground mesh sampled onto a terrain's grid must give those heights or name
// a grid point it leaves uncovered.
//
// Finding: a crash, a sanitizer report, a hang, an exception other than the documented
// assets::AssetError, or an answer that differs from the search of every triangle.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "trackbed/assets/scene_meshes.h"
#include "trackbed/sim/triangle_mesh.h"

namespace {

using trackbed::fuzz::Finding;
namespace sim = trackbed::sim;

constexpr const char* kTarget = "mesh_ground_fuzz";

// The input read from its start: bytes past its end are 0.
class Bytes {
 public:
  Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  uint8_t Next() { return at_ < size_ ? data_[at_++] : 0; }
  // A coordinate in [-8, 8) m in steps of 1/16 m.
  float Coordinate() { return static_cast<float>((Next() << 1 | (Next() & 1)) - 256) / 32.0f; }
  bool done() const { return at_ >= size_; }

 private:
  const uint8_t* data_;
  size_t size_, at_ = 0;
};

void Near(double a, double b, const std::string& what) {
  if (!(std::abs(a - b) <= 1e-9 * (1.0 + std::abs(a) + std::abs(b))) && !(a == b)) {
    Finding(kTarget, what + ": " + std::to_string(a) + " against " + std::to_string(b));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Bytes in(data, size);
  sim::TriangleMesh mesh;
  const int vertices = 3 + in.Next() % 30;
  for (int v = 0; v < vertices; ++v) {
    const float x = in.Coordinate(), y = in.Coordinate(), z = in.Coordinate();
    mesh.vertices.emplace_back(x, y, z);
  }
  const int triangles = 1 + in.Next() % 40;
  for (int t = 0; t < triangles; ++t) {
    mesh.triangles.push_back({static_cast<std::uint32_t>(in.Next() % vertices),
                              static_cast<std::uint32_t>(in.Next() % vertices),
                              static_cast<std::uint32_t>(in.Next() % vertices)});
  }
  // The mesh as a scene object: its scale and pose.
  sim::MeshObject object;
  sim::StaticObject& e = object.entry;
  e.shape = sim::StaticObject::Shape::kMesh;
  e.mesh.ground = true;
  e.mesh.scale =
      Eigen::Vector3d(0.25 + in.Next() / 64.0, 0.25 + in.Next() / 64.0, 0.25 + in.Next() / 64.0);
  e.roll_rad = in.Next() / 40.0;
  e.pitch_rad = in.Next() / 40.0;
  e.yaw_rad = in.Next() / 40.0;
  e.center_m = Eigen::Vector2d(in.Coordinate(), in.Coordinate());
  e.base_z_m = in.Coordinate();
  object.visual = std::make_shared<const sim::TriangleMesh>(mesh);
  const Eigen::Vector3d& scale = e.mesh.scale;
  const Eigen::Isometry3d pose = object.Pose();
  const sim::PlacedMesh placed(mesh, scale, pose);
  // Each triangle alone: the search of every triangle.
  std::vector<sim::PlacedMesh> alone;
  for (const auto& t : mesh.triangles) {
    sim::TriangleMesh one;
    for (std::uint32_t v : t) one.vertices.push_back(mesh.vertices[v]);
    one.triangles.push_back({0, 1, 2});
    alone.emplace_back(one, scale, pose);
  }
  while (!in.done()) {
    const double x = in.Coordinate(), y = in.Coordinate();
    std::optional<double> top;
    for (const sim::PlacedMesh& p : alone) {
      const std::optional<double> z = p.HighestAt(x, y);
      if (z && (!top || *z > *top)) top = z;
    }
    const std::optional<double> got = placed.HighestAt(x, y);
    if (got.has_value() != top.has_value()) Finding(kTarget, "a point covered in one search only");
    if (got) Near(*got, *top, "the highest triangle");
    const double half = 0.05 + in.Next() / 32.0, z_lo = in.Coordinate();
    const double z_hi = z_lo + in.Next() / 16.0;
    const std::vector<Eigen::Vector2d> square = {
        {x - half, y - half}, {x + half, y - half}, {x + half, y + half}, {x - half, y + half}};
    double nearest = std::numeric_limits<double>::infinity();
    for (const sim::PlacedMesh& p : alone) {
      nearest = std::min(nearest, p.PlanDistance(square, z_lo, z_hi));
    }
    Near(placed.PlanDistance(square, z_lo, z_hi), nearest, "the plan distance");
  }
  // The mesh as ground under a small terrain around its middle.
  sim::TerrainOptions terrain;
  const Eigen::Vector3d mid = placed.bounds().center();
  terrain.extent_m = Eigen::Vector4d(mid.x() - 0.5, mid.y() - 0.5, mid.x() + 0.5, mid.y() + 0.5);
  terrain.cell_size_m = 0.25;
  try {
    const auto grid = trackbed::assets::SampleMeshGround({object}, terrain);
    for (int r = 0; r < grid->rows(); ++r) {
      for (int c = 0; c < grid->cols(); ++c) {
        const std::optional<double> z =
            placed.HighestAt(grid->first_m().x() + 0.25 * c, grid->first_m().y() + 0.25 * r);
        if (!z) Finding(kTarget, "a sampled grid point no triangle covers");
        Near(grid->Sample(c, r), *z, "a ground height");
      }
    }
  } catch (const trackbed::assets::AssetError&) {
  }
  return 0;
}
