// Tracked vehicle on terramechanical ground contact (see tracked_vehicle.h).
#include "trackbed/robot/tracked_vehicle.h"

#include <algorithm>
#include <cmath>

#include <btBulletDynamicsCommon.h>

#include "trackbed/common/option_error.h"
#include "trackbed/robot/terramechanics.h"
#include "trackbed/robot/track_contact.h"

namespace trackbed::robot {
namespace {

Eigen::Vector3d ToEigen(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
btVector3 ToBullet(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

constexpr double kGravity = 9.81;
// Speed scale of the sign of a resistance that opposes motion [m/s]: smooths its
// switch through zero speed, where an exact sign would chatter at a 1 ms step.
constexpr double kResistanceSignSpeed_mps = 0.01;

// The station positions along body x: given, or evenly over the contact length.
std::vector<double> StationPositions(const TrackedVehicleOptions& o) {
  if (!o.station_x_m.empty()) return o.station_x_m;
  std::vector<double> xs;
  const int n = o.road_wheels_per_track;
  for (int i = 0; i < n; ++i) {
    xs.push_back(-o.track_contact_length_m / 2 + (i + 0.5) * o.track_contact_length_m / n);
  }
  return xs;
}

void ValidateStations(const TrackedVehicleOptions& o) {
  if (o.station_x_m.empty()) {
    if (o.road_wheels_per_track < 2 || o.road_wheels_per_track > 32) {
      throw OptionError("road_wheels_per_track",
                        "must be in [2, 32] (got " + std::to_string(o.road_wheels_per_track) + ")");
    }
  } else if (o.station_x_m.size() < 2 || o.station_x_m.size() > 32) {
    throw OptionError("station_x_m", "must list 2 to 32 positions (got " +
                                         std::to_string(o.station_x_m.size()) + ")");
  }
  const std::vector<double> xs = StationPositions(o);
  for (std::size_t k = 0; k < xs.size(); ++k) {
    const std::string field = "station_x_m[" + std::to_string(k) + "]";
    option_check::Finite(field.c_str(), xs[k]);
    for (std::size_t other = 0; other < k; ++other) {  // a rut travels between them
      if (std::abs(xs[k] - xs[other]) < 1e-3) {
        throw OptionError(field, "must be at least 1 mm from station_x_m[" + std::to_string(other) +
                                     "] (got " + option_check::Describe(xs[k]) + " and " +
                                     option_check::Describe(xs[other]) + ")");
      }
    }
    if (o.contact == TrackedVehicleOptions::Contact::kTracks &&
        std::abs(xs[k]) >= o.track_contact_length_m / 2) {
      throw OptionError(field, "must lie inside the track's contact length (|x| < " +
                                   option_check::Describe(o.track_contact_length_m / 2) + ")");
    }
  }
  option_check::Positive("road_wheel_contact_length_m", o.road_wheel_contact_length_m);
  if (o.contact == TrackedVehicleOptions::Contact::kTracks &&
      o.road_wheel_contact_length_m > o.track_contact_length_m / xs.size()) {
    throw OptionError("road_wheel_contact_length_m",
                      "must not exceed track_contact_length_m / stations per side");
  }
}

}  // namespace

std::vector<render::ShadowBox> ShadowBoxes(const TrackedVehicleOptions& o) {
  const double hull_bottom = -(o.com_height_m - o.ground_clearance_m);
  std::vector<render::ShadowBox> boxes;
  boxes.push_back({Eigen::Vector3d(0, 0, hull_bottom + 0.5 * o.hull_size_m.z()), o.hull_size_m});
  const double d = 2.0 * o.sprocket_radius_m;
  for (double side : {0.5, -0.5}) {
    boxes.push_back({Eigen::Vector3d(0, side * o.track_gauge_m, -o.com_height_m + 0.5 * d),
                     Eigen::Vector3d(o.track_contact_length_m + d, o.track_width_m, d)});
  }
  return boxes;
}

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
  ValidateStations(*this);
  option_check::Positive("suspension_stiffness_npm", suspension_stiffness_npm);
  option_check::NonNegative("suspension_damping_nspm", suspension_damping_nspm);
  option_check::Positive("suspension_travel_m", suspension_travel_m);
  option_check::NonNegative("shear_damping_s", shear_damping_s);
  option_check::Positive("hull_contact_stiffness_npm", hull_contact_stiffness_npm);
  option_check::NonNegative("hull_friction", hull_friction);
  option_check::NonNegative("running_gear_resistance_coeff", running_gear_resistance_coeff);
  option_check::NonNegative("running_gear_speed_coeff_s_per_m", running_gear_speed_coeff_s_per_m);
  option_check::Positive("stall_time_s", stall_time_s);
  option_check::Nested("motor", motor);
  const double n = static_cast<double>(StationPositions(*this).size());
  const double deflection = mass_kg * kGravity / (2.0 * n * suspension_stiffness_npm);
  if (deflection >= suspension_travel_m) {
    throw OptionError("suspension_stiffness_npm",
                      "too soft: the static deflection exceeds suspension_travel_m");
  }
}

TrackedVehicle::TrackedVehicle(const TrackedVehicleOptions& options, sim::World* world, double x,
                               double y, double yaw_rad,
                               const calibration::VehicleCalibration* as_built)
    : options_(options), world_(world), tracks_{Track(options.motor), Track(options.motor)} {
  options_.Validate();
  const TrackedVehicleOptions& o = options_;
  tracks_[kLeft].sprocket_radius_m =
      as_built ? as_built->sprocket_radius_left_m : o.sprocket_radius_m;
  tracks_[kRight].sprocket_radius_m =
      as_built ? as_built->sprocket_radius_right_m : o.sprocket_radius_m;
  const double gauge_m = as_built ? as_built->track_gauge_m : o.track_gauge_m;
  const double l = o.track_contact_length_m;
  const double contact_z = -(o.com_height_m + static_deflection_m());
  const bool wheels = o.contact == TrackedVehicleOptions::Contact::kWheels;
  for (int side = 0; side < 2; ++side) {
    const double y_side = (side == kLeft ? 0.5 : -0.5) * gauge_m;
    for (double x_station : StationPositions(o)) {
      Station st;
      st.p_body = {x_station, y_side, contact_z};
      st.lead_forward_m = wheels ? o.road_wheel_contact_length_m / 2 : l / 2 - x_station;
      st.lead_backward_m = wheels ? o.road_wheel_contact_length_m / 2 : l / 2 + x_station;
      tracks_[side].stations.push_back(st);
    }
    // Front to rear: the order in which stations meet new ground driving forward.
    std::sort(tracks_[side].stations.begin(), tracks_[side].stations.end(),
              [](const Station& a, const Station& b) { return a.p_body.x() > b.p_body.x(); });
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

int TrackedVehicle::stations_per_side() const {
  return options_.station_x_m.empty() ? options_.road_wheels_per_track
                                      : static_cast<int>(options_.station_x_m.size());
}

double TrackedVehicle::static_deflection_m() const {
  return options_.mass_kg * kGravity /
         (2.0 * stations_per_side() * options_.suspension_stiffness_npm);
}

bool TrackedVehicle::stalled() const {
  for (const Track& t : tracks_) {
    if (t.state.stall_time_s >= options_.stall_time_s) return true;
  }
  return false;
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
  const ChassisState s = chassis();
  for (Track& track : tracks_) ApplyTrackForces(s, &track, dt_s);
  ApplyHullContacts(s);
}

double TrackedVehicle::SuspensionLoad(double depth_m, double approach_mps) const {
  const TrackedVehicleOptions& o = options_;
  if (depth_m <= 0.0) return 0.0;
  double normal = o.suspension_stiffness_npm * std::min(depth_m, o.suspension_travel_m) +
                  o.suspension_damping_nspm * approach_mps;
  if (depth_m > o.suspension_travel_m) {  // bump stop: twenty times stiffer
    normal += 20.0 * o.suspension_stiffness_npm * (depth_m - o.suspension_travel_m);
  }
  return std::max(normal, 0.0);
}

double TrackedVehicle::SettleSinkage(const sim::SoilPoint& soil, double previous_m,
                                     double surface_depth_m, double approach_mps) const {
  if (soil.IsRigid()) return 0.0;
  // Solve g(z) = z − Z(N(z)) = 0: the load N falls as the pad sinks (the spring
  // extends), the sinkage Z rises with the load. g is increasing, so Newton from
  // the last step's sinkage tracks the root as the load changes;
  // an explicit update (z = Z(N) of the last load) is unstable where the soil is
  // softer than the suspension.
  const TrackedVehicleOptions& o = options_;
  const double b = o.track_width_m, area = o.road_wheel_contact_length_m * b;
  // One Newton step a physics step, from the last step's sinkage.
  const double z = std::clamp(previous_m, 0.0, std::max(surface_depth_m, 0.0));
  const double depth = surface_depth_m - z;
  const double normal = SuspensionLoad(depth, approach_mps);
  const double target = BekkerSinkage(soil, normal / area, b);
  // dZ/dN = Z / (n N) (Bekker); dN/dz = −spring rate (bump stop beyond travel).
  const double rate = depth > o.suspension_travel_m ? 21.0 * o.suspension_stiffness_npm
                                                    : o.suspension_stiffness_npm;
  const double slope = normal > 0.0 ? 1.0 + target / (soil.bekker_n * normal) * rate : 1.0;
  return std::clamp(z - (z - target) / slope, 0.0, std::max(surface_depth_m, 0.0));
}

double TrackedVehicle::UpdateSinkage(const sim::SoilPoint& soil, double ahead_rut_m,
                                     double spacing_m, double surface_depth_m, double approach_mps,
                                     double u_mps, double v_along_mps, double dt_s,
                                     Station* st) const {
  const TrackedVehicleOptions& o = options_;
  // Multi-pass (Wong §4.2): the rut under a station is carried from under the
  // station ahead as the ground passes, one station spacing of travel to arrive;
  // at rest nothing moves. A road wheel reloading a rut to the pressure that made
  // it sinks no further, so deepening the rut is what costs compaction work.
  const double carried = std::abs(v_along_mps) * dt_s / spacing_m;
  st->rut_m = soil.IsRigid() ? 0.0 : (st->rut_m + carried * ahead_rut_m) / (1.0 + carried);
  // Slip sinkage (Lyasko 2010): a slipping pad digs, the total reaching Bekker's
  // times (1 + i)/(1 − 0.5 i) in steady slip i, over one road-wheel contact length
  // of relative travel (ground and slip). Soil it digs out is carried back by the
  // shear, whose work the slip already pays: it deepens the rut without compaction.
  const double slip = std::abs(u_mps) > 1e-3 ? (u_mps - v_along_mps) / u_mps : 0.0;
  const double worked = (std::abs(v_along_mps) + std::abs(u_mps - v_along_mps)) * dt_s /
                        o.road_wheel_contact_length_m;
  const double dug = st->static_sinkage_m * (SlipSinkageFactor(slip) - 1.0);
  st->slip_sinkage_m = (st->slip_sinkage_m + worked * dug) / (1.0 + worked);  // implicit
  // Bekker's sinkage under the road wheel's peak pressure, consistent with its load.
  st->static_sinkage_m =
      SettleSinkage(soil, st->static_sinkage_m, surface_depth_m - st->slip_sinkage_m, approach_mps);
  double compaction_n = 0.0;
  if (st->static_sinkage_m > st->rut_m) {
    const double b = o.track_width_m;
    compaction_n = CompactionResistance(soil, st->static_sinkage_m, b) -
                   CompactionResistance(soil, st->rut_m, b);
  }
  st->sinkage_m = std::max(st->rut_m, st->static_sinkage_m) + st->slip_sinkage_m;
  return compaction_n;
}

void TrackedVehicle::ApplyTrackForces(const ChassisState& s, Track* track, double dt_s) {
  const TrackedVehicleOptions& o = options_;
  const Eigen::Vector3d com = s.T_world_body.translation();
  const Eigen::Vector3d body_x = s.T_world_body.linear().col(0);
  const sim::Terrain& terrain = world_->terrain();
  const bool wheels = o.contact == TrackedVehicleOptions::Contact::kWheels;
  const double b = o.track_width_m;
  // A station's share of the shear area and the length of its side face.
  const double patch_length =
      wheels ? o.road_wheel_contact_length_m : o.track_contact_length_m / stations_per_side();
  const double r = track->sprocket_radius_m;
  const double u = r * track->motor.speed_radps();  // track surface speed

  // Ground speed of the track's centreline under the centre of mass, along body x.
  const Eigen::Vector3d p_c = s.T_world_body * Eigen::Vector3d(0, track->stations[0].p_body.y(), 0);
  const double v_track = (s.v_world + s.omega_world.cross(p_c - com)).dot(body_x);

  TrackState& ts = track->state;
  ts.traction_n = ts.normal_load_n = ts.compaction_resistance_n = ts.bulldozing_resistance_n = 0.0;
  ts.stations_in_contact = 0;
  // Each station's compacted depth at the last step: the rut it leaves behind.
  std::array<double, 32> compacted{};
  const int count = static_cast<int>(track->stations.size());
  for (int k = 0; k < count; ++k) {
    const Station& st = track->stations[static_cast<std::size_t>(k)];
    compacted[static_cast<std::size_t>(k)] = std::max(st.rut_m, st.static_sinkage_m);
  }
  for (int k = 0; k < count; ++k) {  // front to rear
    Station& st = track->stations[static_cast<std::size_t>(k)];
    const Eigen::Vector3d p = s.T_world_body * st.p_body;
    const sim::GroundSample g = terrain.Sample(p.x(), p.y());
    // Penetration of the unloaded contact point below the undisturbed surface.
    const double surface_depth = (g.height_m - p.z()) * g.normal.z();
    if (surface_depth <= 0.0) {
      st = Station{st.p_body, st.lead_forward_m, st.lead_backward_m};  // left the ground
      continue;
    }
    const Eigen::Vector3d v_point = s.v_world + s.omega_world.cross(p - com);
    const sim::SoilPoint soil = terrain.SoilAt(*g.material, p.x(), p.y());
    // Contact frame on the ground: t along the track, lat across (to the left).
    const Eigen::Vector3d t = (body_x - body_x.dot(g.normal) * g.normal).normalized();
    const Eigen::Vector3d lat = g.normal.cross(t);
    const double v_along = v_point.dot(t);
    const double approach = -v_point.dot(g.normal);

    // The ground under the station comes from under the station ahead of it (in
    // the direction the ground passes), or fresh from ahead of the leading one.
    const int ahead = v_along >= 0.0 ? k - 1 : k + 1;
    const bool has_ahead = ahead >= 0 && ahead < count;
    const double ahead_rut_m = has_ahead ? compacted[static_cast<std::size_t>(ahead)] : 0.0;
    const double spacing_m =
        has_ahead
            ? std::abs(st.p_body.x() - track->stations[static_cast<std::size_t>(ahead)].p_body.x())
            : o.road_wheel_contact_length_m;
    const double compaction =
        UpdateSinkage(soil, ahead_rut_m, spacing_m, surface_depth, approach, u, v_along, dt_s, &st);
    const double normal = SuspensionLoad(surface_depth - st.sinkage_m, approach);
    if (normal <= 0.0) {  // in its rut but not pressed: no shear
      st.shear_m.setZero();
      continue;
    }
    StationKinematics kin;
    const Eigen::Vector3d v_pad = v_point - u * t;
    kin.v_pad_mps = {v_pad.dot(t), v_pad.dot(lat)};
    kin.track_speed_mps = u;
    kin.lead_m = u >= 0.0 ? st.lead_forward_m : st.lead_backward_m;
    StationLoad load;
    load.normal_n = normal;
    load.area_m2 = patch_length * b;
    // The station's side face bulldozes soil when it skids sideways in its rut.
    load.bulldozing_n = BulldozingResistance(soil, st.sinkage_m, patch_length);
    const Eigen::Vector2d shear =
        StepStationShear(soil, kin, load, o.shear_damping_s, dt_s, &st.shear_m);

    // Its sign follows the ground speed, smoothed over a speed wide enough that
    // all stations' slope R/v_s stays within what the explicit step integrates
    // (time constant m / (2 n R / v_s) of at least two steps).
    const double resistance_sign_speed =
        std::max(kResistanceSignSpeed_mps, 4.0 * count * compaction * dt_s / o.mass_kg);
    const double compaction_n = compaction * std::tanh(v_along / resistance_sign_speed);
    const Eigen::Vector3d f = normal * g.normal + (shear.x() - compaction_n) * t + shear.y() * lat;
    body_->applyForce(ToBullet(f), ToBullet(p - com));
    ++ts.stations_in_contact;
    ts.normal_load_n += normal;
    ts.traction_n += shear.x();
    ts.compaction_resistance_n += std::abs(compaction_n);
    ts.bulldozing_resistance_n += load.bulldozing_n;
  }

  // The ground pushes the track forward by the traction: that load opposes the
  // sprocket, as does the running gear's internal resistance (Bekker, in Wong §4.1),
  // which loads the motor and not the soil.
  const double running_gear =
      0.5 * o.mass_kg * kGravity *
      (o.running_gear_resistance_coeff + o.running_gear_speed_coeff_s_per_m * std::abs(u));
  track->motor.Step(dt_s,
                    r * (ts.traction_n + running_gear * std::tanh(u / kResistanceSignSpeed_mps)));
  UpdateStall(track, dt_s);

  ts.sprocket_angle_rad = track->motor.angle_rad();
  ts.sprocket_speed_radps = track->motor.speed_radps();
  ts.motor_torque_nm = track->motor.torque_nm();
  ts.track_speed_mps = r * track->motor.speed_radps();
  ts.ground_speed_mps = v_track;
  ts.slip_velocity_mps = ts.ground_speed_mps - ts.track_speed_mps;
  ts.running_gear_resistance_n = running_gear;
  if (marks_) RecordTrackMark(s, *track);
}

// The rut the track leaves is the deepest any of its stations runs: the ground it has
// passed was compacted, or dug by slip, that deep (the rut carried from station to station
// only deepens). Its centreline: the track's under the middle of its stations.
void TrackedVehicle::RecordTrackMark(const ChassisState& s, const Track& track) {
  double depth_m = 0.0, x_sum = 0.0;
  for (const Station& st : track.stations) {
    depth_m = std::max(depth_m, st.sinkage_m);
    x_sum += st.p_body.x();
  }
  const double x_mid = x_sum / static_cast<double>(track.stations.size());
  Eigen::Vector3d p = s.T_world_body * Eigen::Vector3d(x_mid, track.stations[0].p_body.y(), 0.0);
  p.z() = world_->terrain().Height(p.x(), p.y());
  const Eigen::Vector3d body_x = s.T_world_body.linear().col(0);
  const int side = &track == &tracks_[kLeft] ? kLeft : kRight;
  marks_->Update(side, p, std::atan2(body_x.y(), body_x.x()), depth_m, options_.track_width_m,
                 track.sprocket_radius_m * track.motor.angle_rad());
}

void TrackedVehicle::UpdateStall(Track* track, double dt_s) const {
  const SprocketMotor& m = track->motor;
  const bool held = m.saturated() && std::abs(m.command_radps()) > 0.0 &&
                    std::abs(m.speed_radps()) < 0.1 * std::abs(m.command_radps());
  track->state.stall_time_s = held ? track->state.stall_time_s + dt_s : 0.0;
}

void TrackedVehicle::ApplyHullContacts(const ChassisState& s) {
  const Eigen::Vector3d com = s.T_world_body.translation();
  const double k = options_.hull_contact_stiffness_npm;
  // Critically damped for a quarter of the mass on one point.
  const double c = 2.0 * std::sqrt(k * options_.mass_kg / 4.0);
  for (const Eigen::Vector3d& pb : hull_points_body_) {
    const Eigen::Vector3d p = s.T_world_body * pb;
    // Above the ground, as the hull nearly always is: no contact (the full
    // sample's normal and material are not needed).
    if (p.z() >= world_->terrain().Height(p.x(), p.y())) continue;
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
