// Static scene objects: walls, boxes and cylinders (trees, posts, benches).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace trackbed::sim {

/// A fixed obstacle. Boxes are oriented by yaw only; cylinders stand upright.
/// Positions are in the world frame; `base_z_m` is where the object meets the
/// ground (the builder fills it from the terrain when not given).
struct StaticObject {
  enum class Shape { kBox, kCylinder };
  Shape shape = Shape::kBox;
  /// What it is, for the renderer and the logs: wall, box, bench, tree, post, …
  std::string kind = "box";
  /// Appearance name for the renderer (e.g. plain_paint, brick, bark, wood).
  std::string appearance = "plain_paint";
  /// Centre of the footprint in the world xy plane [m].
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  /// Height of the object's base [m]; NaN means "on the ground": the scene
  /// builder sets it to the lowest terrain height under the footprint.
  double base_z_m = std::numeric_limits<double>::quiet_NaN();
  /// Yaw of a box about the world z axis [rad].
  double yaw_rad = 0.0;
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
/// Every type: wall, box, bench, cylinder, tree, post, door, poster.
const std::vector<ObjectType>& ObjectTypes();
/// The type called `name`, or null.
const ObjectType* FindObjectType(const std::string& name);

}  // namespace trackbed::sim
