// Triangle meshes of users' files (scene objects of type `mesh`) once read: the
// geometry in the object's own frame, and the same triangles placed in the world with
// an index over the plane for the questions the simulation asks of them — the highest
// surface above a point (a mesh as ground) and the distance in plan from a footprint
// (clearance). The files are read by assets/trackbed/assets/mesh_reader.h.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace trackbed::sim {

/// A material's image as its file holds it: rows top first, three bytes a texel (red,
/// green, blue as encoded, sRGB). The renderer linearises it (render/mesh_surfaces.h).
struct MeshImage {
  int width = 0, height = 0;      ///< [texels], each > 0
  std::vector<std::uint8_t> rgb;  ///< width · height · 3 bytes
};

/// Triangles sharing one material.
struct MeshPart {
  std::uint32_t first_triangle = 0;  ///< Index of its first triangle in TriangleMesh::triangles.
  std::uint32_t triangles = 0;       ///< How many triangles, consecutive from the first.
  /// The material's base-colour image: an absolute path, empty for none or an image
  /// embedded in the mesh file.
  std::string base_color_texture;
  /// The material's base colour, linear RGBA in [0, 1] (multiplies the texture).
  Eigen::Vector4f base_color{1.0f, 1.0f, 1.0f, 1.0f};
  /// The base-colour image decoded (a file's or an embedded one); null for none.
  std::shared_ptr<const MeshImage> base_color_image;
};

/// A mesh in its object's frame: x forward, y left, z up, metres.
struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices;  ///< Positions [m].
  /// Texture coordinates of each vertex, origin at the image's bottom-left corner,
  /// v upwards; (0, 0) where the file has none. Empty or one per vertex.
  std::vector<Eigen::Vector2f> uvs;
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< Vertex indices, counter-clockwise.
  std::vector<MeshPart> parts;                          ///< Cover the triangles in order.

  /// The vertices' bounding box [m] (empty without vertices).
  Eigen::AlignedBox3d Bounds() const;
};

/// The rotation of roll, pitch and yaw [rad]: R = Rz(yaw) · Ry(pitch) · Rx(roll).
Eigen::Matrix3d RollPitchYaw(double roll_rad, double pitch_rad, double yaw_rad);

/// A mesh's triangles in the world — each vertex scaled per axis in the object's frame,
/// then moved by `pose` — with a grid over the plane that lists the triangles whose
/// plan bounding box meets each cell.
class PlacedMesh {
 public:
  PlacedMesh(const TriangleMesh& mesh, const Eigen::Vector3d& scale, const Eigen::Isometry3d& pose);

  /// The highest point of a triangle above or below (x, y), if a triangle covers the
  /// point in plan (edges included).
  std::optional<double> HighestAt(double x, double y) const;
  /// Signed distance in plan [m] between the convex polygon `polygon` (counter-clockwise
  /// or clockwise corners) and the nearest triangle whose height range meets
  /// [z_lo, z_hi]: the gap when apart, minus the smallest separating overlap when they
  /// overlap; +infinity when no triangle is within that height range.
  double PlanDistance(const std::vector<Eigen::Vector2d>& polygon, double z_lo, double z_hi) const;

  const Eigen::AlignedBox3d& bounds() const { return bounds_; }  ///< World box [m].
  std::size_t triangles() const { return triangles_.size(); }
  const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }  ///< World [m].

 private:
  // The cells a plan box covers, clamped to the grid.
  void CellsOf(const Eigen::AlignedBox2d& box, int* c0, int* r0, int* c1, int* r1) const;

  std::vector<Eigen::Vector3d> vertices_;
  std::vector<std::array<std::uint32_t, 3>> triangles_;
  Eigen::AlignedBox3d bounds_;
  Eigen::Vector2d first_ = Eigen::Vector2d::Zero();  // the grid's lower corner
  double cell_m_ = 1.0;
  int cols_ = 1, rows_ = 1;
  std::vector<std::uint32_t> cell_start_;  // cols_ · rows_ + 1 offsets into cell_triangles_
  std::vector<std::uint32_t> cell_triangles_;
  std::vector<double> cell_z_lo_, cell_z_hi_;  // each cell's triangles' height range
};

}  // namespace trackbed::sim
