// Static scene objects: walls, boxes and cylinders (trees, posts, benches), and
// meshes read from users' files (sim/trackbed/sim/triangle_mesh.h).
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace trackbed::sim {

/// Where a `mesh` object's triangles come from and how they are used
/// (docs/user_files.md).
struct MeshSource {
  /// What Bullet and the footprint clearance take as the object's solid.
  enum class Collision {
    kMesh,  ///< The mesh's own triangles.
    kFile,  ///< The triangles of `collision_file`, placed like the mesh.
    kBox,   ///< The mesh's bounding box in its own frame (scaled), placed like the mesh.
  };
  /// The mesh file (.gltf, .glb, .obj, .ply, .dae, .stl), relative to the scenario's
  /// folder; absolute once the scenario is loaded.
  std::string file;
  /// Scale along the object's own x, y, z [-], each > 0 (applied before the rotation).
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Collision collision = Collision::kMesh;
  /// The collision mesh's file when `collision` is kFile; empty otherwise.
  std::string collision_file;
  /// Ground, not an obstacle: the terrain's heights are sampled from its triangles.
  bool ground = false;
};

/// A fixed obstacle. Boxes are oriented by yaw only; cylinders stand upright; meshes
/// take a full rotation (roll, pitch, yaw).
/// Positions are in the world frame; `base_z_m` is where the object meets the
/// ground (the builder fills it from the terrain when not given).
struct StaticObject {
  enum class Shape { kBox, kCylinder, kMesh };
  Shape shape = Shape::kBox;
  /// What it is, for the renderer and the logs: wall, box, bench, tree, post, …
  std::string kind = "box";
  /// Appearance name for the renderer (e.g. plain_paint, brick, bark, wood).
  std::string appearance = "plain_paint";
  /// Grey albedo in [0, 1] of a plain surface drawn instead of the appearance's texture
  /// (and a mesh's materials): a colour given in the user's own description (an SDF
  /// visual's <diffuse>). Absent: the appearance's.
  std::optional<double> albedo;
  /// Centre of the footprint in the world xy plane [m].
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  /// Height of the object's base [m]; NaN means "on the ground": the scene
  /// builder sets it to the lowest terrain height under the footprint.
  double base_z_m = std::numeric_limits<double>::quiet_NaN();
  /// Yaw of a box or a mesh about the world z axis [rad].
  double yaw_rad = 0.0;
  /// A mesh's roll about x and pitch about y [rad], applied before the yaw
  /// (sim::RollPitchYaw); a mesh's origin sits at (center_m, base_z_m).
  double roll_rad = 0.0, pitch_rad = 0.0;
  /// A mesh's file and use (shape kMesh only).
  MeshSource mesh;
  /// Box full extents [m]: length along its x, width along its y, height.
  Eigen::Vector3d size_m{1.0, 1.0, 1.0};
  /// Cylinder radius [m] and height [m].
  double radius_m = 0.1;
  double height_m = 1.0;
  /// Whether it is a physical obstacle; visual-only dressing (doors and posters
  /// flat on a wall) is drawn but not simulated.
  bool collides = true;

  void Validate() const;
};

/// A type of scene object as scene files name it: its shape and default appearance.
struct ObjectType {
  const char* name;
  StaticObject::Shape shape;
  const char* appearance;
};
/// Every type: wall, box, bench, cylinder, tree, post, door, poster, mesh, car (a
/// box to everything but the renderer, which draws a parked car: render/car_model.h).
const std::vector<ObjectType>& ObjectTypes();
/// The type called `name`, or null.
const ObjectType* FindObjectType(const std::string& name);

}  // namespace trackbed::sim
