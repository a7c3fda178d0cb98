// The tracked (skid-steer) vehicle: a Bullet chassis on two tracks whose
// traction on the ground is computed per road wheel from terramechanics.
//
// Each track touches the ground at `road_wheels_per_track` stations along its
// contact length. Per station and physics step:
//  - normal load from a spring–damper suspension against the terrain surface
//    (lowered by the Bekker sinkage of the previous step);
//  - the pad's velocity relative to the ground, v_pad = v_point − u·t (u = r ω
//    the track speed), integrated into a 2-D shear-displacement state j with
//    relaxation: pads enter the contact unsheared and travel back at u, so
//    j' = v_pad − (|u| / L) j, L the distance from the leading edge. In steady
//    slip this gives Wong's j(x) = s·x along the track.
//  - Janosi–Hanamoto traction of magnitude (cA + N tan φ)(1 − e^(−|j|/K))
//    opposing j, for the vector so that skid turning meets lateral resistance
//    (Wong & Chiang 2001); a small viscous term in the elastic range damps the
//    soil-spring oscillation (regularisation, see docs/physics.md);
//  - Bekker sinkage under the road wheel's peak pressure and the compaction
//    resistance of making that rut, opposing the motion (soft ground only).
// The longitudinal traction loads the sprocket motor; the encoder reads the
// sprocket. Slip therefore emerges from the dynamics: encoders never see the
// chassis velocity.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/robot/sprocket_motor.h"
#include "trackbed/sim/world.h"

class btRigidBody;
class btCollisionShape;
struct btDefaultMotionState;

namespace trackbed::robot {

/// Geometry, mass and running gear of the vehicle. Defaults: a ≈ 40 kg field robot.
struct TrackedVehicleOptions {
  /// Total mass [kg], > 0.
  double mass_kg = 40.0;
  /// Hull box extents [m]: length, width, height.
  Eigen::Vector3d hull_size_m{0.70, 0.42, 0.20};
  /// Height of the centre of mass above flat ground at rest [m], > 0.
  double com_height_m = 0.20;
  /// Height of the hull's underside above flat ground at rest [m], > 0.
  double ground_clearance_m = 0.08;
  /// Track gauge B: lateral distance between the track centrelines [m], > 0.
  double track_gauge_m = 0.50;
  /// Track (pad) width b [m], > 0.
  double track_width_m = 0.10;
  /// Length of each track's ground contact l [m], > 0.
  double track_contact_length_m = 0.55;
  /// Sprocket pitch radius r [m], > 0: track speed = r ω.
  double sprocket_radius_m = 0.10;
  /// Road wheels (contact stations) per track, in [2, 32].
  int road_wheels_per_track = 6;
  /// Length of track under one road wheel that carries the wheel's load into the
  /// soil [m], > 0 and <= contact length / road wheels. A flexible track's ground
  /// pressure peaks under the road wheels (Wong, ch. 4); Rowland's mean maximum
  /// pressure puts this length near √(track pitch × road-wheel diameter), here
  /// √(0.02 m × 0.08 m) ≈ 0.04 m. Sets the pressure for Bekker sinkage; shear acts
  /// over the whole contact.
  double road_wheel_contact_length_m = 0.04;
  /// Suspension spring rate per road wheel [N/m], > 0.
  double suspension_stiffness_npm = 2500.0;
  /// Suspension damping per road wheel [N·s/m], >= 0.
  double suspension_damping_nspm = 120.0;
  /// Suspension travel before the bump stop [m], > 0.
  double suspension_travel_m = 0.06;
  /// Time constant of the soil's viscous shear damping in the elastic range [s], >= 0.
  double shear_damping_s = 0.01;
  /// Hull-to-ground contact stiffness [N/m] (when the hull bottoms out), > 0.
  double hull_contact_stiffness_npm = 2.0e5;
  /// Hull-to-ground friction coefficient [-], >= 0.
  double hull_friction = 0.5;
  SprocketMotorOptions motor;

  void Validate() const;
};

/// Index of the two tracks.
enum Side { kLeft = 0, kRight = 1 };

/// Kinematic state of the chassis (body frame: x forward, y left, z up, origin
/// at the centre of mass).
struct ChassisState {
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();      ///< Linear velocity [m/s].
  Eigen::Vector3d omega_world = Eigen::Vector3d::Zero();  ///< Angular velocity [rad/s].
};

/// What one track is doing now.
struct TrackState {
  double sprocket_angle_rad = 0.0;
  double sprocket_speed_radps = 0.0;
  double motor_torque_nm = 0.0;
  double track_speed_mps = 0.0;    ///< r ω.
  double ground_speed_mps = 0.0;   ///< Chassis velocity at the track centreline, along body x.
  double slip_velocity_mps = 0.0;  ///< ground − track speed (Ham et al. sign).
  double normal_load_n = 0.0;      ///< Sum over stations.
  double traction_n = 0.0;         ///< Longitudinal shear force on the vehicle.
  double compaction_resistance_n = 0.0;
  int stations_in_contact = 0;
};

/// A tracked vehicle in a World. Not copyable; removes its body on destruction.
class TrackedVehicle {
 public:
  /// Places the vehicle at rest on the terrain at (x, y) with heading `yaw_rad`,
  /// aligned with the local ground slope.
  TrackedVehicle(const TrackedVehicleOptions& options, sim::World* world, double x, double y,
                 double yaw_rad);
  ~TrackedVehicle();
  TrackedVehicle(const TrackedVehicle&) = delete;
  TrackedVehicle& operator=(const TrackedVehicle&) = delete;

  /// Commands the track surface speeds [m/s] (sprocket speed = v / r).
  void CommandTrackSpeeds(double left_mps, double right_mps);
  /// Computes ground forces, applies them to the chassis and advances the
  /// sprockets and the soil shear state by one physics step. Call before World::Step().
  void ApplyForces(double dt_s);

  ChassisState chassis() const;
  const TrackState& track(Side side) const { return tracks_[side].state; }
  const TrackedVehicleOptions& options() const { return options_; }
  /// Static-equilibrium suspension deflection [m] on flat ground.
  double static_deflection_m() const;

 private:
  struct Station {
    Eigen::Vector3d p_body;         // unloaded contact point
    Eigen::Vector2d shear_m{0, 0};  // (along, across) shear displacement
    double sinkage_m = 0.0;
    double offset_from_front_m = 0.0;
  };
  struct Track {
    explicit Track(const SprocketMotorOptions& o) : motor(o) {}
    SprocketMotor motor;
    std::vector<Station> stations;
    TrackState state;
  };

  void ApplyHullContacts(const ChassisState& s);

  TrackedVehicleOptions options_;
  sim::World* world_;
  std::array<Track, 2> tracks_;
  std::vector<Eigen::Vector3d> hull_points_body_;
  std::unique_ptr<btCollisionShape> shape_;
  std::unique_ptr<btDefaultMotionState> motion_state_;
  std::unique_ptr<btRigidBody> body_;
};

}  // namespace trackbed::robot
