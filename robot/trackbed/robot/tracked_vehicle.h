// The tracked (skid-steer) vehicle: a Bullet chassis on two tracks (or two
// rows of wheels) whose traction on the ground is computed per contact station
// from terramechanics (robot/track_contact.h; docs/physics.md).
//
// Each side touches the ground at its stations (road wheels under a track, or
// wheels). Per station and physics step: normal load from a spring–damper
// suspension; a 2-D shear displacement renewed as pads enter the contact;
// Janosi–Hanamoto shear on it, anisotropic along and across; Bekker sinkage
// with slip sinkage, the rut each station runs in, the compaction resistance of
// deepening it and the bulldozing resistance of its side in a skid. The sprocket
// carries the longitudinal traction plus the running-gear resistance; the encoder
// reads the sprocket. Slip emerges from the dynamics: encoders never see the
// chassis velocity.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/common/robot_calibration.h"
#include "trackbed/render/robot_shadow.h"
#include "trackbed/robot/platform.h"
#include "trackbed/robot/sprocket_motor.h"
#include "trackbed/sim/track_marks.h"
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
  /// Road wheels (contact stations) per track, in [2, 32]; ignored when
  /// station_x_m is given.
  int road_wheels_per_track = 6;
  /// Contact-station positions along body x [m], rear to front or any order; when
  /// not empty it replaces the even spacing over the contact length and its length
  /// replaces road_wheels_per_track. Four-wheel skid steer: two stations a side.
  std::vector<double> station_x_m;
  /// What touches the ground: a continuous track (shear grows from the track's
  /// leading edge) or wheels (shear restarts in each wheel's own contact patch).
  enum class Contact { kTracks, kWheels };
  Contact contact = Contact::kTracks;
  /// Length of track under one road wheel that carries the wheel's load into the
  /// soil [m], > 0 and <= contact length / road wheels; for wheels, the length of
  /// the tyre's contact patch. A flexible track's ground
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
  /// Running-gear (internal) resistance at rest as a fraction of the weight a side
  /// carries [-], >= 0; Bekker's R_in = W (222 + 3 V) N (W in t, V in km/h) for
  /// tracked vehicles, as Wong §4.1 gives it: 222 / 9810.
  double running_gear_resistance_coeff = 222.0 / 9810.0;
  /// Its growth with track speed [s/m], >= 0: 3 N/(t·km/h) = 3·3.6 / 9810 s/m.
  double running_gear_speed_coeff_s_per_m = 3.0 * 3.6 / 9810.0;
  /// A track whose motor holds its torque limit while its sprocket turns at less
  /// than a tenth of the command for this long has stalled [s], > 0.
  double stall_time_s = 1.0;
  /// Hull-to-ground contact stiffness [N/m] (when the hull bottoms out), > 0.
  double hull_contact_stiffness_npm = 2.0e5;
  /// Hull-to-ground friction coefficient [-], >= 0.
  double hull_friction = 0.5;
  SprocketMotorOptions motor;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("mass_kg", &mass_kg);
    a->Visit("hull_size_m", &hull_size_m);
    a->Visit("com_height_m", &com_height_m);
    a->Visit("ground_clearance_m", &ground_clearance_m);
    a->Visit("track_gauge_m", &track_gauge_m);
    a->Visit("track_width_m", &track_width_m);
    a->Visit("track_contact_length_m", &track_contact_length_m);
    a->Visit("sprocket_radius_m", &sprocket_radius_m);
    a->Visit("road_wheels_per_track", &road_wheels_per_track);
    a->Visit("station_x_m", &station_x_m);
    a->VisitEnum("contact", &contact, {{"tracks", Contact::kTracks}, {"wheels", Contact::kWheels}});
    a->Visit("road_wheel_contact_length_m", &road_wheel_contact_length_m);
    a->Visit("suspension_stiffness_npm", &suspension_stiffness_npm);
    a->Visit("suspension_damping_nspm", &suspension_damping_nspm);
    a->Visit("suspension_travel_m", &suspension_travel_m);
    a->Visit("shear_damping_s", &shear_damping_s);
    a->Visit("hull_contact_stiffness_npm", &hull_contact_stiffness_npm);
    a->Visit("hull_friction", &hull_friction);
    a->Visit("running_gear_resistance_coeff", &running_gear_resistance_coeff);
    a->Visit("running_gear_speed_coeff_s_per_m", &running_gear_speed_coeff_s_per_m);
    a->Visit("stall_time_s", &stall_time_s);
    a->Visit("motor", &motor);
  }
};

/// The boxes whose shadow the vehicle casts (render/robot_shadow.h), in its body frame:
/// the hull, and each track as a box its contact length plus a sprocket diameter long,
/// its width wide, from the ground to a sprocket diameter high (wheels drawn as tracks).
std::vector<render::ShadowBox> ShadowBoxes(const TrackedVehicleOptions& o);

/// A tracked vehicle in a World. Not copyable; removes its body on destruction.
class TrackedVehicle : public Platform {
 public:
  /// Places the vehicle at rest on the terrain at (x, y) with heading `yaw_rad`,
  /// aligned with the local ground slope. `as_built` (robot/as_built.h): each track's
  /// effective sprocket radius and the gauge of this vehicle as built; null: the
  /// design's. Track speed commands are turned into sprocket rates with the design's
  /// radius, as the motor controller knows only that.
  TrackedVehicle(const TrackedVehicleOptions& options, sim::World* world, double x, double y,
                 double yaw_rad, const calibration::VehicleCalibration* as_built = nullptr);
  ~TrackedVehicle() override;

  /// Commands the track surface speeds [m/s] (sprocket speed = v / r).
  void CommandTrackSpeeds(double left_mps, double right_mps) override;
  /// Computes ground forces, applies them to the chassis and advances the
  /// sprockets and the soil shear state by one physics step. Call before World::Step().
  void ApplyForces(double dt_s) override;
  bool needs_physics() const override { return true; }

  ChassisState chassis() const override;
  const TrackState& track(Side side) const override { return tracks_[side].state; }
  const TrackedVehicleOptions& options() const { return options_; }
  /// Static-equilibrium suspension deflection [m] on flat ground.
  double static_deflection_m() const;
  /// Contact stations per side (station_x_m's size, else road_wheels_per_track).
  int stations_per_side() const;
  /// True once a track has been stalled for stall_time_s (see TrackState).
  bool stalled() const override;
  /// Where each track's ruts go from now on (sim/track_marks.h), at every physics step;
  /// null (the default): none recorded. Drawn only: the physics never reads it.
  void SetTrackMarks(sim::TrackMarks* marks) { marks_ = marks; }

 private:
  struct Station {
    Eigen::Vector3d p_body;         // unloaded contact point
    double lead_forward_m = 0.0;    // shear length from its leading edge, driving forward
    double lead_backward_m = 0.0;   // ... and in reverse
    Eigen::Vector2d shear_m{0, 0};  // (along, across) shear displacement
    double static_sinkage_m = 0.0;  // Bekker's, under its own load
    double slip_sinkage_m = 0.0;    // dug by slip
    double rut_m = 0.0;             // compacted depth carried from the stations ahead
    double sinkage_m = 0.0;         // how deep it runs: the deeper of both, plus slip's
  };
  struct Track {
    explicit Track(const SprocketMotorOptions& o) : motor(o) {}
    SprocketMotor motor;
    double sprocket_radius_m = 0.0;  // as built
    std::vector<Station> stations;
    TrackState state;
  };

  void ApplyTrackForces(const ChassisState& s, Track* track, double dt_s);
  double SuspensionLoad(double depth_m, double approach_mps) const;
  double SettleSinkage(const sim::SoilPoint& soil, double previous_m, double surface_depth_m,
                       double approach_mps) const;
  // Advances the station's rut, slip and static sinkage; returns the compaction
  // resistance [N] of deepening its rut.
  double UpdateSinkage(const sim::SoilPoint& soil, double ahead_rut_m, double spacing_m,
                       double surface_depth_m, double approach_mps, double u_mps,
                       double v_along_mps, double dt_s, Station* st) const;
  void UpdateStall(Track* track, double dt_s) const;
  void RecordTrackMark(const ChassisState& s, const Track& track);
  void ApplyHullContacts(const ChassisState& s);

  TrackedVehicleOptions options_;
  sim::World* world_;
  std::array<Track, 2> tracks_;
  std::vector<Eigen::Vector3d> hull_points_body_;
  std::unique_ptr<btCollisionShape> shape_;
  std::unique_ptr<btDefaultMotionState> motion_state_;
  std::unique_ptr<btRigidBody> body_;
  sim::TrackMarks* marks_ = nullptr;
};

}  // namespace trackbed::robot
