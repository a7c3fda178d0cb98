// The Bullet world: gravity, a fixed physics step, the terrain heightfield and
// static obstacles. Dynamic bodies (the robot's chassis) register themselves.
//
// The terrain is in Bullet tile by tile (trackbed/sim/terrain_tile.h), each a
// heightfield over its tile's heights: a small world's tiles all from the start,
// a larger one's as ray tests first reach them, at most kGroundTiles at a time
// (more while one ray spans more).
//
// Collision filtering: the terrain is in the world for ray tests, but the chassis does not collide
// with it through Bullet; the robot model computes track and hull contact with the ground itself
// (see robot/tracked_vehicle.h), which is both cheaper than per-triangle GJK and where the
// terramechanics lives. The chassis does collide with obstacles.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "trackbed/sim/static_object.h"
#include "trackbed/sim/terrain.h"
#include "trackbed/sim/triangle_mesh.h"

class btDiscreteDynamicsWorld;
class btRigidBody;

namespace trackbed::sim {

/// Bullet collision groups used by trackbed.
enum CollisionGroup : int {
  kGroupTerrain = 1 << 6,
  kGroupObstacle = 1 << 7,
  kGroupChassis = 1 << 8,
  kGroupOccluder = 1 << 9,
};

struct WorldOptions {
  /// Fixed physics step [s], in (0, 0.01].
  double physics_step_s = 0.001;
  /// Gravitational acceleration [m/s²], along −z.
  double gravity_mps2 = 9.81;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("physics_step_s", &physics_step_s);
    a->Visit("gravity_mps2", &gravity_mps2);
  }
};

/// A `mesh` scene object with the triangles read from its files
/// (assets/trackbed/assets/mesh_reader.h).
struct MeshObject {
  /// The scene entry (shape kMesh); the world fills a NaN base_z_m.
  StaticObject entry;
  /// The mesh file's triangles in the object's frame, before the scale.
  std::shared_ptr<const TriangleMesh> visual;
  /// The collision file's triangles (MeshSource::Collision::kFile), else null.
  std::shared_ptr<const TriangleMesh> collision;

  /// Object frame to world: the origin at (center_m, base_z_m), rotated by
  /// sim::RollPitchYaw(roll, pitch, yaw).
  Eigen::Isometry3d Pose() const;
  /// The triangles Bullet and the clearance take as its solid, in the object's frame
  /// before the scale: the collision file's, the visual's bounding box's, or the visual's.
  std::shared_ptr<const TriangleMesh> Solid() const;
};

/// The twelve triangles of an axis-aligned box's faces, outward facing.
TriangleMesh BoxMesh(const Eigen::AlignedBox3d& box);

/// Result of a ray test.
struct RayHit {
  Eigen::Vector3d point_world;
  Eigen::Vector3d normal_world;
  double fraction = 1.0;  ///< Along the ray, in [0, 1].
};

/// Owns the Bullet dynamics world and the static scene. Not copyable.
class World {
 public:
  /// Terrain tiles held in Bullet at most (beyond what one ray spans).
  static constexpr std::size_t kGroundTiles = 9;

  /// `objects` are the primitives (no shape kMesh); `meshes` the mesh obstacles (not
  /// ground meshes, whose triangles are already the terrain's heights).
  World(const WorldOptions& options, Terrain terrain, std::vector<StaticObject> objects,
        std::vector<MeshObject> meshes = {});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Advances the physics by one fixed step.
  void Step();

  const WorldOptions& options() const { return options_; }
  const Terrain& terrain() const { return terrain_; }
  const std::vector<StaticObject>& objects() const { return objects_; }
  /// The mesh obstacles, their base heights filled.
  const std::vector<MeshObject>& meshes() const { return meshes_; }
  /// Each colliding mesh obstacle's solid placed in the world (for the clearance).
  const std::vector<std::shared_ptr<const PlacedMesh>>& mesh_solids() const { return mesh_solids_; }
  /// The Bullet world, for bodies that add themselves (the robot's chassis).
  btDiscreteDynamicsWorld& bullet();

  /// Closest hit along the segment from `from` to `to` against the collision
  /// groups in `mask`, if any. With the terrain in `mask`, first puts the tiles
  /// under the segment in Bullet (dropping the least recently used beyond
  /// kGroundTiles): not to be called while another thread steps the world.
  std::optional<RayHit> CastRay(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                int mask = kGroupTerrain | kGroupObstacle) const;
  /// Terrain tiles in Bullet now.
  std::size_t ground_tiles() const;

 private:
  void HoldGroundUnder(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

  struct BulletParts;  // Bullet's objects, kept out of this header.
  WorldOptions options_;
  Terrain terrain_;
  std::vector<StaticObject> objects_;
  std::vector<MeshObject> meshes_;
  std::vector<std::shared_ptr<const PlacedMesh>> mesh_solids_;
  std::unique_ptr<BulletParts> bullet_;
};

}  // namespace trackbed::sim
