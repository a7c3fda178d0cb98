// The carrier of `drive.mode: pose_path`: a body moved along the drive's waypoints at a
// set speed, without physics — a scripted camera path, as a data set's vehicle drives
// (the KITTI twin, scenes/kitti_twin.yaml). The path is a centripetal Catmull–Rom curve
// through the waypoints (Yuksel et al. 2011: no cusps or self-intersections within a
// segment); the body's heading follows its tangent, and it rests on the ground at four
// points (its footprint's front, back, left and right: pitch, roll and height follow the
// ground smoothly); its speed over the ground is constant from t = 0 to the end of the
// path, where it stops. Its two virtual tracks roll without slip, so the encoders count what it
// drove.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "trackbed/common/robot_calibration.h"
#include "trackbed/robot/platform.h"
#include "trackbed/sim/terrain.h"

namespace trackbed::robot {

/// Where and how the carrier goes.
struct PosePathOptions {
  std::vector<Eigen::Vector2d> waypoints;  ///< >= 2, finite; world frame [m]
  bool closed = false;                     ///< the curve closes back on its first waypoint
  int laps = 1;                            ///< laps of a closed curve, >= 1
  double speed_mps = 1.0;                  ///< horizontal speed over the ground, > 0
  /// The body's origin rides this high above the ground [m] (the centre of mass of
  /// robot.vehicle, which the camera mount is measured from).
  double body_height_m = 0.2;
  /// Where it rests on the ground [m]: the footprint's length (front and back points)
  /// and width (left and right points), > 0.
  double footprint_length_m = 0.55;
  double footprint_width_m = 0.5;
  double mass_kg = 40.0;  ///< the tracks' normal load is its weight, halved
  int stations_per_track = 6;
};

/// A body on a scripted path (see the file comment). Construction throws
/// std::invalid_argument for fewer than 2 waypoints, coincident consecutive waypoints,
/// a non-positive speed or laps < 1.
class PosePathCarrier : public Platform {
 public:
  /// `terrain` must outlive the carrier; `tracks`: the gauge and each track's sprocket
  /// radius as built (the encoders count those sprockets' turns).
  PosePathCarrier(const PosePathOptions& options, const sim::Terrain* terrain,
                  const calibration::VehicleCalibration& tracks, double gravity_mps2);

  /// Ignored: the path sets the motion.
  void CommandTrackSpeeds(double /*left_mps*/, double /*right_mps*/) override {}
  /// Moves the body dt_s further along the path and turns the sprockets with it.
  void ApplyForces(double dt_s) override;
  bool needs_physics() const override { return false; }
  ChassisState chassis() const override { return state_; }
  const TrackState& track(Side side) const override { return tracks_[side]; }
  bool stalled() const override { return false; }

  /// Length of the whole drive, every lap [m] (horizontal).
  double length_m() const { return lap_length_m_ * laps_; }
  /// When the body reaches the end of the path [s].
  double end_time_s() const { return length_m() / speed_mps_; }
  /// The body's pose and velocities at arc length s [m] along the drive (clamped to
  /// [0, length_m()]; at the end the body stands still).
  ChassisState StateAt(double s_m) const;

 private:
  struct Sample {
    double s_m;          // arc length from the first waypoint
    Eigen::Vector2d p;   // position
    double heading_rad;  // tangent direction, unwrapped along the curve
  };
  /// Position and heading at lap arc length s ∈ [0, lap_length_m_].
  void Interpolate(double s_m, Eigen::Vector2d* p, double* heading_rad) const;
  /// The body's pose at (p, heading), resting on the ground.
  Eigen::Isometry3d PoseOnGround(const Eigen::Vector2d& p, double heading_rad) const;
  /// The pose at drive arc length s ∈ [0, length_m()].
  Eigen::Isometry3d PoseAt(double s_m) const;

  const sim::Terrain* terrain_;
  std::vector<Sample> samples_;
  double lap_length_m_ = 0.0;
  bool closed_ = false;
  int laps_ = 1;
  double speed_mps_ = 1.0;
  double body_height_m_ = 0.2;
  double half_length_m_ = 0.275, half_width_m_ = 0.25;
  double load_n_ = 0.0;
  int stations_ = 6;
  double gauge_m_ = 0.5;
  double sprocket_radius_m_[2] = {0.1, 0.1};
  double t_s_ = 0.0;
  ChassisState state_;
  TrackState tracks_[2];
};

}  // namespace trackbed::robot
