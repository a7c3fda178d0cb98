// The Bullet world (see world.h).
#include "trackbed/sim/world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <btBulletDynamicsCommon.h>

#include "trackbed/common/least_recently_used.h"
#include "trackbed/common/option_error.h"

namespace trackbed::sim {

void WorldOptions::Validate() const {
  option_check::InRange("physics_step_s", physics_step_s, 1e-5, 0.01);
  option_check::InRange("gravity_mps2", gravity_mps2, 0.0, 100.0);
}

namespace {

// Lowest terrain height under an object's footprint (sampled on its bounding square).
double LowestGround(const Terrain& terrain, const StaticObject& o) {
  const double half = o.shape == StaticObject::Shape::kBox
                          ? 0.5 * std::hypot(o.size_m.x(), o.size_m.y())
                          : o.radius_m;
  // From the seed: objects scattered over a large world would otherwise generate
  // every tile under them.
  double lowest = terrain.HeightFromSeed(o.center_m.x(), o.center_m.y());
  for (int i = -4; i <= 4; ++i) {
    for (int j = -4; j <= 4; ++j) {
      lowest = std::min(lowest, terrain.HeightFromSeed(o.center_m.x() + half * i / 4.0,
                                                       o.center_m.y() + half * j / 4.0));
    }
  }
  return lowest;
}

// The origin height that sets a mesh's lowest point on the lowest ground under its
// plan bounding box (sampled 9 × 9).
double MeshOnGround(const Terrain& terrain, const MeshObject& m) {
  MeshObject at_zero = m;
  at_zero.entry.base_z_m = 0.0;
  const PlacedMesh placed(*m.visual, m.entry.mesh.scale, at_zero.Pose());
  const Eigen::AlignedBox3d& box = placed.bounds();
  double lowest = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 8; ++j) {
      const Eigen::Vector2d p =
          box.min().head<2>() +
          Eigen::Vector2d(i / 8.0, j / 8.0).cwiseProduct(box.sizes().head<2>());
      lowest = std::min(lowest, terrain.HeightFromSeed(p.x(), p.y()));
    }
  }
  return lowest - box.min().z();
}

// A mesh's solid as Bullet reads it: the scaled vertices and the indices it points
// into, kept alive with the shape.
struct MeshArrays {
  std::vector<double> vertices;
  std::vector<int> indices;
  btTriangleIndexVertexArray array;
};

}  // namespace

Eigen::Isometry3d MeshObject::Pose() const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = RollPitchYaw(entry.roll_rad, entry.pitch_rad, entry.yaw_rad);
  pose.translation() = Eigen::Vector3d(entry.center_m.x(), entry.center_m.y(), entry.base_z_m);
  return pose;
}

std::shared_ptr<const TriangleMesh> MeshObject::Solid() const {
  switch (entry.mesh.collision) {
    case MeshSource::Collision::kFile:
      return collision;
    case MeshSource::Collision::kBox:
      return std::make_shared<const TriangleMesh>(BoxMesh(visual->Bounds()));
    case MeshSource::Collision::kMesh:
      break;
  }
  return visual;
}

TriangleMesh BoxMesh(const Eigen::AlignedBox3d& box) {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k) {
    m.vertices.push_back(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k)).cast<float>());
  }
  // Corner k has x from bit 0, y from bit 1, z from bit 2.
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  m.parts.push_back({0, 12, "", Eigen::Vector4f::Ones(), nullptr});
  return m;
}

// One terrain tile in Bullet: a heightfield over the tile and one cell beyond
// it on every side that has a neighbour, so that neighbouring heightfields
// overlap by two cells and a ray along a seam, or through a tile's corner, is
// inside one of them (Bullet can miss a ray exactly on a heightfield's edge).
struct GroundTile {
  int i0 = 0, j0 = 0, cols = 0, rows = 0;  // grid vertices it covers
  std::vector<double> heights;             // row-major; the shape reads them
  std::unique_ptr<btHeightfieldTerrainShape> shape;
  std::unique_ptr<btCollisionObject> body;
  std::uint64_t used = 0;
};

// The heights of tile (ti, tj) and the border around it.
void FillGround(const Terrain& terrain, int ti, int tj, GroundTile* g) {
  const std::shared_ptr<const TerrainTile> tile = terrain.Tile(ti, tj);
  g->i0 = std::max(tile->i0 - 1, 0);
  g->j0 = std::max(tile->j0 - 1, 0);
  g->cols = std::min(tile->i0 + tile->cols, terrain.cols() - 1) + 1 - g->i0;
  g->rows = std::min(tile->j0 + tile->rows, terrain.rows() - 1) + 1 - g->j0;
  g->heights.resize(static_cast<std::size_t>(g->cols) * g->rows);
  for (int b = 0; b < g->rows; ++b) {
    for (int a = 0; a < g->cols; ++a) {
      const int i = g->i0 + a, j = g->j0 + b;
      const bool inside =
          i >= tile->i0 && i < tile->i0 + tile->cols && j >= tile->j0 && j < tile->j0 + tile->rows;
      g->heights[static_cast<std::size_t>(b) * g->cols + a] =
          inside ? tile->Height(i, j) : terrain.VertexHeight(i, j);
    }
  }
}

struct World::BulletParts {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld dynamics{&dispatcher, &broadphase, &solver, &config};
  std::map<std::pair<int, int>, GroundTile> ground;
  std::uint64_t ground_clock = 0;
  std::vector<std::unique_ptr<MeshArrays>> mesh_arrays;  // declared first: outlives the shapes
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> bodies;

  ~BulletParts() {
    for (auto& [key, g] : ground) dynamics.removeCollisionObject(g.body.get());
    for (auto& body : bodies) dynamics.removeCollisionObject(body.get());
  }

  // Puts terrain tile (ti, tj) in the world if it is not.
  void AddGround(const Terrain& terrain, int ti, int tj) {
    GroundTile& g = ground[{ti, tj}];
    g.used = ++ground_clock;
    if (g.body) return;
    FillGround(terrain, ti, tj, &g);
    // Bullet centres the shape on its AABB, so the body sits at the centre of
    // the heights' square and at the middle of their range.
    const auto [lo_it, hi_it] = std::minmax_element(g.heights.begin(), g.heights.end());
    const double lo = *lo_it, hi = std::max(*hi_it, lo + 1e-3);
    const double cell = terrain.cell_size_m();
    g.shape = std::make_unique<btHeightfieldTerrainShape>(g.cols, g.rows, g.heights.data(), lo, hi,
                                                          2, /*flipQuadEdges=*/true);
    g.shape->setLocalScaling(btVector3(cell, cell, 1));
    g.body = std::make_unique<btCollisionObject>();
    g.body->setCollisionShape(g.shape.get());
    g.body->setActivationState(ISLAND_SLEEPING);
    const double x0 = terrain.x_min() + cell * g.i0,
                 x1 = terrain.x_min() + cell * (g.i0 + g.cols - 1);
    const double y0 = terrain.y_min() + cell * g.j0,
                 y1 = terrain.y_min() + cell * (g.j0 + g.rows - 1);
    g.body->setWorldTransform(btTransform(btQuaternion::getIdentity(),
                                          btVector3((x0 + x1) / 2, (y0 + y1) / 2, (lo + hi) / 2)));
    dynamics.addCollisionObject(g.body.get(), kGroupTerrain, kGroupChassis | kGroupOccluder);
    // The box a step's update would give (the shape's, widened by the contact
    // threshold), which rays are culled against.
    dynamics.updateSingleAabb(g.body.get());
  }

  // A static obstacle of `shape` at `pose`.
  void AddObstacle(std::unique_ptr<btCollisionShape> shape, const btTransform& pose) {
    auto body = std::make_unique<btCollisionObject>();
    body->setCollisionShape(shape.get());
    body->setWorldTransform(pose);
    body->setFriction(0.6);
    body->setActivationState(ISLAND_SLEEPING);
    dynamics.addCollisionObject(body.get(), kGroupObstacle, kGroupChassis | kGroupOccluder);
    dynamics.updateSingleAabb(body.get());
    shapes.push_back(std::move(shape));
    bodies.push_back(std::move(body));
  }

  // A mesh obstacle: its solid's triangles, scaled, in a bounding volume hierarchy
  // (btBvhTriangleMeshShape), or its scaled bounding box.
  void AddMesh(const MeshObject& m) {
    const Eigen::Isometry3d pose = m.Pose();
    const Eigen::Quaterniond q(pose.linear());
    const Eigen::Vector3d& t = pose.translation();
    btTransform frame(btQuaternion(q.x(), q.y(), q.z(), q.w()), btVector3(t.x(), t.y(), t.z()));
    const Eigen::Vector3d& scale = m.entry.mesh.scale;
    if (m.entry.mesh.collision == MeshSource::Collision::kBox) {
      const Eigen::AlignedBox3d box = m.visual->Bounds();
      const Eigen::Vector3d half = 0.5 * box.sizes().cwiseProduct(scale);
      const Eigen::Vector3d c = box.center().cwiseProduct(scale);
      AddObstacle(std::make_unique<btBoxShape>(btVector3(half.x(), half.y(), half.z())),
                  frame * btTransform(btQuaternion::getIdentity(), btVector3(c.x(), c.y(), c.z())));
      return;
    }
    const TriangleMesh& solid = *m.Solid();
    auto arrays = std::make_unique<MeshArrays>();
    arrays->vertices.reserve(3 * solid.vertices.size());
    for (const Eigen::Vector3f& v : solid.vertices) {
      for (int k = 0; k < 3; ++k) arrays->vertices.push_back(v[k] * scale[k]);
    }
    arrays->indices.reserve(3 * solid.triangles.size());
    for (const auto& tri : solid.triangles) {
      for (std::uint32_t v : tri) arrays->indices.push_back(static_cast<int>(v));
    }
    btIndexedMesh part;
    part.m_numTriangles = static_cast<int>(solid.triangles.size());
    part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(arrays->indices.data());
    part.m_triangleIndexStride = 3 * sizeof(int);
    part.m_numVertices = static_cast<int>(solid.vertices.size());
    part.m_vertexBase = reinterpret_cast<const unsigned char*>(arrays->vertices.data());
    part.m_vertexStride = 3 * sizeof(double);
    part.m_indexType = PHY_INTEGER;
    part.m_vertexType = PHY_DOUBLE;
    arrays->array.addIndexedMesh(part, PHY_INTEGER);
    auto shape = std::make_unique<btBvhTriangleMeshShape>(&arrays->array,
                                                          /*useQuantizedAabbCompression=*/true);
    mesh_arrays.push_back(std::move(arrays));
    AddObstacle(std::move(shape), frame);
  }

  // Takes the least recently used tiles out beyond `keep`.
  void DropGround(std::size_t keep) {
    while (ground.size() > keep) {
      const auto oldest = LeastRecentlyUsed(ground);
      dynamics.removeCollisionObject(oldest->second.body.get());
      ground.erase(oldest);
    }
  }
};

World::World(const WorldOptions& options, Terrain terrain, std::vector<StaticObject> objects,
             std::vector<MeshObject> meshes)
    : options_(options),
      terrain_(std::move(terrain)),
      objects_(std::move(objects)),
      meshes_(std::move(meshes)),
      bullet_(std::make_unique<BulletParts>()) {
  options_.Validate();
  for (std::size_t k = 0; k < objects_.size(); ++k) {
    option_check::Nested("objects[" + std::to_string(k) + "]", objects_[k]);
    if (objects_[k].shape == StaticObject::Shape::kMesh) {
      throw OptionError("objects[" + std::to_string(k) + "]",
                        "a mesh comes with its triangles, among the meshes");
    }
    if (std::isnan(objects_[k].base_z_m))
      objects_[k].base_z_m = LowestGround(terrain_, objects_[k]);
  }
  for (std::size_t k = 0; k < meshes_.size(); ++k) {
    MeshObject& m = meshes_[k];
    option_check::Nested("meshes[" + std::to_string(k) + "]", m.entry);
    if (m.entry.shape != StaticObject::Shape::kMesh || m.entry.mesh.ground || !m.visual ||
        (m.entry.mesh.collision == MeshSource::Collision::kFile && !m.collision)) {
      throw OptionError("meshes[" + std::to_string(k) + "]",
                        "must be a mesh obstacle with its triangles");
    }
    if (std::isnan(m.entry.base_z_m)) m.entry.base_z_m = MeshOnGround(terrain_, m);
    if (m.entry.collides) {
      mesh_solids_.push_back(
          std::make_shared<const PlacedMesh>(*m.Solid(), m.entry.mesh.scale, m.Pose()));
    }
  }
  BulletParts& b = *bullet_;
  b.dynamics.setGravity(btVector3(0, 0, -options_.gravity_mps2));
  // The ground and the obstacles never move: marked asleep, their bounding
  // boxes are set once below instead of every step (for every tree and bench
  // that was 15 % of a physics-only outdoor step). Sleeping static objects
  // still collide with the awake chassis.
  b.dynamics.setForceUpdateAllAabbs(false);

  // The ground: a small world's tiles all at once, before the obstacles; a
  // larger one's as rays first reach them (CastRay).
  if (terrain_.tiles_x() * terrain_.tiles_y() <= static_cast<int>(kGroundTiles)) {
    for (int tj = 0; tj < terrain_.tiles_y(); ++tj) {
      for (int ti = 0; ti < terrain_.tiles_x(); ++ti) b.AddGround(terrain_, ti, tj);
    }
  }

  for (const MeshObject& m : meshes_) {
    if (m.entry.collides) b.AddMesh(m);
  }
  for (const StaticObject& o : objects_) {
    if (!o.collides) continue;
    std::unique_ptr<btCollisionShape> shape;
    double half_height;
    if (o.shape == StaticObject::Shape::kBox) {
      shape = std::make_unique<btBoxShape>(btVector3(o.size_m.x(), o.size_m.y(), o.size_m.z()) / 2);
      half_height = o.size_m.z() / 2;
    } else {
      shape = std::make_unique<btCylinderShapeZ>(btVector3(o.radius_m, o.radius_m, o.height_m / 2));
      half_height = o.height_m / 2;
    }
    b.AddObstacle(std::move(shape),
                  btTransform(btQuaternion(btVector3(0, 0, 1), o.yaw_rad),
                              btVector3(o.center_m.x(), o.center_m.y(), o.base_z_m + half_height)));
  }
}

World::~World() = default;

btDiscreteDynamicsWorld& World::bullet() { return bullet_->dynamics; }

std::size_t World::ground_tiles() const { return bullet_->ground.size(); }

void World::Step() {
  // maxSubSteps = 0: exactly one step of the given size, no interpolation.
  bullet_->dynamics.stepSimulation(options_.physics_step_s, 0);
}

void World::HoldGroundUnder(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
  const Terrain& t = terrain_;
  // The tiles of the cells within half a cell of the segment's box.
  auto tile = [&](double v, double v0, int n) {
    const int cell = static_cast<int>(std::clamp((v - v0) / t.cell_size_m(), 0.0, n - 2.0));
    return cell / kTileCells;
  };
  const double half = 0.5 * t.cell_size_m();
  const int ti0 = tile(std::min(from.x(), to.x()) - half, t.x_min(), t.cols());
  const int ti1 = tile(std::max(from.x(), to.x()) + half, t.x_min(), t.cols());
  const int tj0 = tile(std::min(from.y(), to.y()) - half, t.y_min(), t.rows());
  const int tj1 = tile(std::max(from.y(), to.y()) + half, t.y_min(), t.rows());
  for (int tj = tj0; tj <= tj1; ++tj) {
    for (int ti = ti0; ti <= ti1; ++ti) bullet_->AddGround(t, ti, tj);
  }
  const auto spanned = static_cast<std::size_t>((ti1 - ti0 + 1) * (tj1 - tj0 + 1));
  bullet_->DropGround(std::max(kGroundTiles, spanned));
}

std::optional<RayHit> World::CastRay(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                     int mask) const {
  if (mask & kGroupTerrain) HoldGroundUnder(from, to);
  const btVector3 a(from.x(), from.y(), from.z()), c(to.x(), to.y(), to.z());
  btCollisionWorld::ClosestRayResultCallback cb(a, c);
  cb.m_collisionFilterGroup = btBroadphaseProxy::AllFilter;
  cb.m_collisionFilterMask = mask;
  bullet_->dynamics.rayTest(a, c, cb);
  if (!cb.hasHit()) return std::nullopt;
  RayHit hit;
  hit.point_world = {cb.m_hitPointWorld.x(), cb.m_hitPointWorld.y(), cb.m_hitPointWorld.z()};
  hit.normal_world = {cb.m_hitNormalWorld.x(), cb.m_hitNormalWorld.y(), cb.m_hitNormalWorld.z()};
  hit.fraction = cb.m_closestHitFraction;
  return hit;
}

}  // namespace trackbed::sim
