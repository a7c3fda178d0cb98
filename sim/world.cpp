// The Bullet world (see world.h).
#include "trackbed/sim/world.h"

#include <algorithm>
#include <cmath>

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <btBulletDynamicsCommon.h>

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
  double lowest = terrain.Height(o.center_m.x(), o.center_m.y());
  for (int i = -4; i <= 4; ++i) {
    for (int j = -4; j <= 4; ++j) {
      lowest = std::min(
          lowest, terrain.Height(o.center_m.x() + half * i / 4.0, o.center_m.y() + half * j / 4.0));
    }
  }
  return lowest;
}

}  // namespace

struct World::BulletParts {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld dynamics{&dispatcher, &broadphase, &solver, &config};
  std::unique_ptr<btHeightfieldTerrainShape> terrain_shape;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> bodies;

  ~BulletParts() {
    for (auto& body : bodies) dynamics.removeCollisionObject(body.get());
  }
};

World::World(const WorldOptions& options, Terrain terrain, std::vector<StaticObject> objects)
    : options_(options),
      terrain_(std::move(terrain)),
      objects_(std::move(objects)),
      bullet_(std::make_unique<BulletParts>()) {
  options_.Validate();
  for (std::size_t k = 0; k < objects_.size(); ++k) {
    option_check::Nested("objects[" + std::to_string(k) + "]", objects_[k]);
    if (std::isnan(objects_[k].base_z_m))
      objects_[k].base_z_m = LowestGround(terrain_, objects_[k]);
  }
  BulletParts& b = *bullet_;
  b.dynamics.setGravity(btVector3(0, 0, -options_.gravity_mps2));
  // The ground and the obstacles never move: marked asleep, their bounding
  // boxes are set once below instead of every step (for every tree and bench
  // that was 15 % of a physics-only outdoor step). Sleeping static objects
  // still collide with the awake chassis.
  b.dynamics.setForceUpdateAllAabbs(false);

  // Terrain. Bullet centres the shape on its AABB, so the body sits at the
  // centre of the grid and at the middle of the height range.
  const double lo = terrain_.min_height_m(), hi = std::max(terrain_.max_height_m(), lo + 1e-3);
  b.terrain_shape = std::make_unique<btHeightfieldTerrainShape>(
      terrain_.cols(), terrain_.rows(), terrain_.heights().data(), lo, hi, 2,
      /*flipQuadEdges=*/true);
  b.terrain_shape->setLocalScaling(btVector3(terrain_.cell_size_m(), terrain_.cell_size_m(), 1));
  auto ground = std::make_unique<btCollisionObject>();
  ground->setCollisionShape(b.terrain_shape.get());
  ground->setActivationState(ISLAND_SLEEPING);
  ground->setWorldTransform(
      btTransform(btQuaternion::getIdentity(),
                  btVector3((terrain_.x_min() + terrain_.x_max()) / 2,
                            (terrain_.y_min() + terrain_.y_max()) / 2, (lo + hi) / 2)));
  b.dynamics.addCollisionObject(ground.get(), kGroupTerrain, kGroupChassis | kGroupOccluder);
  // The box a step's update would give (the shape's, widened by the contact
  // threshold), which the range sensor's rays are culled against.
  b.dynamics.updateSingleAabb(ground.get());
  b.bodies.push_back(std::move(ground));

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
    auto body = std::make_unique<btCollisionObject>();
    body->setCollisionShape(shape.get());
    body->setWorldTransform(
        btTransform(btQuaternion(btVector3(0, 0, 1), o.yaw_rad),
                    btVector3(o.center_m.x(), o.center_m.y(), o.base_z_m + half_height)));
    body->setFriction(0.6);
    body->setActivationState(ISLAND_SLEEPING);
    b.dynamics.addCollisionObject(body.get(), kGroupObstacle, kGroupChassis | kGroupOccluder);
    b.dynamics.updateSingleAabb(body.get());
    b.shapes.push_back(std::move(shape));
    b.bodies.push_back(std::move(body));
  }
}

World::~World() = default;

btDiscreteDynamicsWorld& World::bullet() { return bullet_->dynamics; }

void World::Step() {
  // maxSubSteps = 0: exactly one step of the given size, no interpolation.
  bullet_->dynamics.stepSimulation(options_.physics_step_s, 0);
}

std::optional<RayHit> World::CastRay(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                     int mask) const {
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
