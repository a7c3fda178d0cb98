// Tracked vehicle on terramechanical ground contact (see tracked_vehicle.h).
#include "trackbed/robot/tracked_vehicle.h"

#include <algorithm>
#include <cmath>

#include <btBulletDynamicsCommon.h>

#include "trackbed/common/option_error.h"
#include "trackbed/robot/terramechanics.h"

namespace trackbed::robot {
namespace {

Eigen::Vector3d ToEigen(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
btVector3 ToBullet(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

constexpr double kGravity = 9.81;

}  // namespace

void TrackedVehicleOptions::Validate() const {
  option_check::Positive("mass_kg", mass_kg);
  option_check::Positive("hull_size_m[0]", hull_size_m.x());
  option_check::Positive("hull_size_m[1]", hull_size_m.y());
  option_check::Positive("hull_size_m[2]", hull_size_m.z());
  option_check::Positive("com_height_m", com_height_m);
  option_check::Positive("ground_clearance_m", ground_clearance_m);
  if (ground_clearance_m >= com_height_m) {
    throw OptionError("ground_clearance_m", "must be below com_height_m");
  }
  option_check::Positive("track_gauge_m", track_gauge_m);
  option_check::Positive("track_width_m", track_width_m);
  if (track_width_m >= track_gauge_m) {
    throw OptionError("track_width_m", "must be smaller than track_gauge_m");
  }
  option_check::Positive("track_contact_length_m", track_contact_length_m);
  option_check::Positive("sprocket_radius_m", sprocket_radius_m);
  if (road_wheels_per_track < 2 || road_wheels_per_track > 32) {
    throw OptionError("road_wheels_per_track",
                      "must be in [2, 32] (got " + std::to_string(road_wheels_per_track) + ")");
  }
  option_check::Positive("road_wheel_contact_length_m", road_wheel_contact_length_m);
  if (road_wheel_contact_length_m > track_contact_length_m / road_wheels_per_track) {
    throw OptionError("road_wheel_contact_length_m",
                      "must not exceed track_contact_length_m / road_wheels_per_track");
  }
  option_check::Positive("suspension_stiffness_npm", suspension_stiffness_npm);
  option_check::NonNegative("suspension_damping_nspm", suspension_damping_nspm);
  option_check::Positive("suspension_travel_m", suspension_travel_m);
  option_check::NonNegative("shear_damping_s", shear_damping_s);
  option_check::Positive("hull_contact_stiffness_npm", hull_contact_stiffness_npm);
  option_check::NonNegative("hull_friction", hull_friction);
  option_check::Nested("motor", motor);
  const double deflection =
      mass_kg * kGravity / (2.0 * road_wheels_per_track * suspension_stiffness_npm);
  if (deflection >= suspension_travel_m) {
    throw OptionError("suspension_stiffness_npm",
                      "too soft: the static deflection exceeds suspension_travel_m");
  }
}

TrackedVehicle::TrackedVehicle(const TrackedVehicleOptions& options, sim::World* world, double x,
                               double y, double yaw_rad)
    : options_(options), world_(world), tracks_{Track(options.motor), Track(options.motor)} {
  options_.Validate();
  const TrackedVehicleOptions& o = options_;
  const int n = o.road_wheels_per_track;
  const double l = o.track_contact_length_m;
  const double contact_z = -(o.com_height_m + static_deflection_m());
  for (int side = 0; side < 2; ++side) {
    const double y_side = (side == kLeft ? 0.5 : -0.5) * o.track_gauge_m;
    for (int i = 0; i < n; ++i) {
      Station st;
      const double x_i = -l / 2 + (i + 0.5) * l / n;
      st.p_body = {x_i, y_side, contact_z};
      st.offset_from_front_m = l / 2 - x_i;
      tracks_[side].stations.push_back(st);
    }
  }
  // Hull underside: a 3 x 3 grid of contact points, used only if it touches ground.
  const double hull_bottom = -(o.com_height_m - o.ground_clearance_m);
  for (double fx : {-0.5, 0.0, 0.5}) {
    for (double fy : {-0.5, 0.0, 0.5}) {
      hull_points_body_.emplace_back(fx * o.hull_size_m.x(), fy * o.hull_size_m.y(), hull_bottom);
    }
  }

  // Chassis: a compound holding the hull box offset from the centre of mass.
  auto compound = std::make_unique<btCompoundShape>();
  auto* box = new btBoxShape(ToBullet(o.hull_size_m / 2));
  compound->addChildShape(btTransform(btQuaternion::getIdentity(),
                                      btVector3(0, 0, hull_bottom + o.hull_size_m.z() / 2)),
                          box);
  btVector3 inertia;
  box->calculateLocalInertia(o.mass_kg, inertia);
  shape_ = std::move(compound);

  // Pose: on the ground at (x, y), z axis along the terrain normal.
  const sim::GroundSample g = world_->terrain().Sample(x, y);
  const Eigen::Vector3d heading(std::cos(yaw_rad), std::sin(yaw_rad), 0.0);
  const Eigen::Vector3d z_axis = g.normal;
  const Eigen::Vector3d x_axis = (heading - heading.dot(z_axis) * z_axis).normalized();
  Eigen::Matrix3d R;
  R.col(0) = x_axis;
  R.col(1) = z_axis.cross(x_axis);
  R.col(2) = z_axis;
  const Eigen::Quaterniond q(R);
  const Eigen::Vector3d origin = Eigen::Vector3d(x, y, g.height_m) + z_axis * o.com_height_m;
  motion_state_ = std::make_unique<btDefaultMotionState>(
      btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), ToBullet(origin)));
  btRigidBody::btRigidBodyConstructionInfo info(o.mass_kg, motion_state_.get(), shape_.get(),
                                                inertia);
  info.m_friction = 0.5;
  body_ = std::make_unique<btRigidBody>(info);
  body_->setActivationState(DISABLE_DEACTIVATION);
  world_->bullet().addRigidBody(body_.get(), sim::kGroupChassis, sim::kGroupObstacle);
}

TrackedVehicle::~TrackedVehicle() {
  world_->bullet().removeRigidBody(body_.get());
  auto* compound = static_cast<btCompoundShape*>(shape_.get());
  for (int i = compound->getNumChildShapes() - 1; i >= 0; --i) {
    btCollisionShape* child = compound->getChildShape(i);
    compound->removeChildShapeByIndex(i);
    delete child;
  }
}

double TrackedVehicle::static_deflection_m() const {
  return options_.mass_kg * kGravity /
         (2.0 * options_.road_wheels_per_track * options_.suspension_stiffness_npm);
}

void TrackedVehicle::CommandTrackSpeeds(double left_mps, double right_mps) {
  tracks_[kLeft].motor.Command(left_mps / options_.sprocket_radius_m);
  tracks_[kRight].motor.Command(right_mps / options_.sprocket_radius_m);
}

ChassisState TrackedVehicle::chassis() const {
  ChassisState s;
  const btTransform& tf = body_->getCenterOfMassTransform();
  const btQuaternion q = tf.getRotation();
  s.T_world_body.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).toRotationMatrix();
  s.T_world_body.translation() = ToEigen(tf.getOrigin());
  s.v_world = ToEigen(body_->getLinearVelocity());
  s.omega_world = ToEigen(body_->getAngularVelocity());
  return s;
}

void TrackedVehicle::ApplyForces(double dt_s) {
  const TrackedVehicleOptions& o = options_;
  const ChassisState s = chassis();
  const Eigen::Matrix3d& R = s.T_world_body.linear();
  const Eigen::Vector3d com = s.T_world_body.translation();
  const Eigen::Vector3d body_x = R.col(0);
  const sim::Terrain& terrain = world_->terrain();
  const int n = o.road_wheels_per_track;
  const double patch_length = o.track_contact_length_m / n;
  const double patch_area = patch_length * o.track_width_m;
  const double r = o.sprocket_radius_m;

  for (int side = 0; side < 2; ++side) {
    Track& track = tracks_[side];
    const double u = r * track.motor.speed_radps();  // track surface speed
    double traction_along = 0.0, load = 0.0, compaction = 0.0;
    int contacts = 0;
    for (Station& st : track.stations) {
      const Eigen::Vector3d p = s.T_world_body * st.p_body;
      const sim::GroundSample g = terrain.Sample(p.x(), p.y());
      // Penetration of the unloaded contact point below the (sunk) surface, along the normal.
      const double depth = (g.height_m - st.sinkage_m - p.z()) * g.normal.z();
      if (depth <= 0.0) {
        st.shear_m.setZero();  // a pad that leaves the ground unloads the soil
        st.sinkage_m = 0.0;
        continue;
      }
      const Eigen::Vector3d v_point = s.v_world + s.omega_world.cross(p - com);
      const double approach = -v_point.dot(g.normal);
      double normal = o.suspension_stiffness_npm * std::min(depth, o.suspension_travel_m) +
                      o.suspension_damping_nspm * approach;
      if (depth > o.suspension_travel_m) {  // bump stop: twenty times stiffer
        normal += 20.0 * o.suspension_stiffness_npm * (depth - o.suspension_travel_m);
      }
      normal = std::max(normal, 0.0);
      ++contacts;
      load += normal;

      // Contact frame on the ground: t along the track, l across (to the left).
      const Eigen::Vector3d t = (body_x - body_x.dot(g.normal) * g.normal).normalized();
      const Eigen::Vector3d lat = g.normal.cross(t);
      const Eigen::Vector3d v_pad = v_point - u * t;
      const Eigen::Vector2d v_rel(v_pad.dot(t), v_pad.dot(lat));

      // Shear displacement with pad renewal, implicit in the relaxation term.
      const double lead =
          u >= 0.0 ? st.offset_from_front_m : o.track_contact_length_m - st.offset_from_front_m;
      const double relax_rate = std::abs(u) / lead;
      st.shear_m = (st.shear_m + v_rel * dt_s) / (1.0 + relax_rate * dt_s);

      // Janosi–Hanamoto on the shear-displacement vector, plus elastic-range damping.
      const sim::TerrainMaterial& m = *g.material;
      const double strength = ShearStrength(m, normal, patch_area);
      const double j = st.shear_m.norm();
      Eigen::Vector2d shear_force = Eigen::Vector2d::Zero();
      if (j > 1e-12) shear_force = -strength * JanosiHanamotoFraction(m, j) * st.shear_m / j;
      const double elastic = strength / m.shear_modulus_m * std::exp(-j / m.shear_modulus_m);
      shear_force -= o.shear_damping_s * elastic * v_rel;
      const double f_norm = shear_force.norm();
      if (f_norm > strength) shear_force *= strength / f_norm;

      // Bekker sinkage and compaction resistance (soft ground only).
      const double peak_pressure = normal / (o.road_wheel_contact_length_m * o.track_width_m);
      st.sinkage_m = BekkerSinkage(m, peak_pressure, o.track_width_m);
      const double resistance = CompactionResistance(m, st.sinkage_m, o.track_width_m) / n;
      const double v_ground = v_point.dot(t);
      const double r_force = -resistance * std::tanh(v_ground / 0.01);
      compaction += resistance;

      const Eigen::Vector3d f =
          normal * g.normal + (shear_force.x() + r_force) * t + shear_force.y() * lat;
      body_->applyForce(ToBullet(f), ToBullet(p - com));
      traction_along += shear_force.x();
    }
    // The ground pushes the track forward by traction_along: that load opposes the sprocket.
    track.motor.Step(dt_s, r * traction_along);

    // Ground truth of this track, at its centreline under the centre of mass.
    const Eigen::Vector3d p_c =
        s.T_world_body * Eigen::Vector3d(0, track.stations[0].p_body.y(), 0);
    const Eigen::Vector3d v_c = s.v_world + s.omega_world.cross(p_c - com);
    TrackState& ts = track.state;
    ts.sprocket_angle_rad = track.motor.angle_rad();
    ts.sprocket_speed_radps = track.motor.speed_radps();
    ts.motor_torque_nm = track.motor.torque_nm();
    ts.track_speed_mps = r * track.motor.speed_radps();
    ts.ground_speed_mps = v_c.dot(body_x);
    ts.slip_velocity_mps = ts.ground_speed_mps - ts.track_speed_mps;
    ts.normal_load_n = load;
    ts.traction_n = traction_along;
    ts.compaction_resistance_n = compaction;
    ts.stations_in_contact = contacts;
  }
  ApplyHullContacts(s);
}

void TrackedVehicle::ApplyHullContacts(const ChassisState& s) {
  const Eigen::Vector3d com = s.T_world_body.translation();
  const double k = options_.hull_contact_stiffness_npm;
  // Critically damped for a quarter of the mass on one point.
  const double c = 2.0 * std::sqrt(k * options_.mass_kg / 4.0);
  for (const Eigen::Vector3d& pb : hull_points_body_) {
    const Eigen::Vector3d p = s.T_world_body * pb;
    const sim::GroundSample g = world_->terrain().Sample(p.x(), p.y());
    const double depth = (g.height_m - p.z()) * g.normal.z();
    if (depth <= 0.0) continue;
    const Eigen::Vector3d v = s.v_world + s.omega_world.cross(p - com);
    const double normal = std::max(0.0, k * depth - c * v.dot(g.normal));
    const Eigen::Vector3d v_tan = v - v.dot(g.normal) * g.normal;
    const double speed = v_tan.norm();
    Eigen::Vector3d friction = Eigen::Vector3d::Zero();
    if (speed > 1e-9) {
      friction = -options_.hull_friction * normal * std::tanh(speed / 0.02) * v_tan / speed;
    }
    body_->applyForce(ToBullet(normal * g.normal + friction), ToBullet(p - com));
  }
}

}  // namespace trackbed::robot
