// Pure-pursuit path following (Coulter 1992): steer along the arc through a
// look-ahead point on the path. Used as the "human driver" that drives a
// reference route on ground truth, and as a plain path follower.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "trackbed/common/pose2.h"
#include "trackbed/common/skid_steer.h"

namespace trackbed::navigation {

struct PurePursuitOptions {
  /// Cruise speed [m/s], > 0.
  double speed_mps = 0.4;
  /// Look-ahead distance [m], > 0.
  double lookahead_m = 0.8;
  /// Distance to the end of an open path at which the follower stops [m], > 0.
  double goal_tolerance_m = 0.1;
  /// Yaw-rate limit [rad/s], > 0.
  double max_yaw_rate_radps = 1.0;
  /// Heading error beyond which the robot turns in place first [rad], in (0, π].
  double turn_in_place_rad = 1.2;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md, `drive`), read
  /// and written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("speed_mps", &speed_mps);
    a->Visit("lookahead_m", &lookahead_m);
    a->Visit("goal_tolerance_m", &goal_tolerance_m);
    a->Visit("max_yaw_rate_radps", &max_yaw_rate_radps);
    a->Visit("turn_in_place_rad", &turn_in_place_rad);
  }
};

/// Planar pose of the robot: position [m] and heading [rad].
using Pose2 = geometry::Pose2;

/// Output of one control step.
struct PurePursuitCommand {
  kinematics::BodyTwist twist;
  bool finished = false;       ///< The end of an open path (or one lap) is reached.
  double progress_m = 0.0;     ///< Arc length of the path's closest point, cumulative over laps.
  double cross_track_m = 0.0;  ///< Signed distance to the path (left positive).
};

/// Follows a polyline; keeps the progress along it so that a closed loop or a
/// path that crosses itself is followed in order. Stateful: not copyable.
class PurePursuit {
 public:
  /// `waypoints` needs at least two distinct points; `closed` joins the last to the first
  /// and the follower stops after `laps` laps (>= 1; ignored for open paths).
  PurePursuit(const PurePursuitOptions& options, std::vector<Eigen::Vector2d> waypoints,
              bool closed, int laps = 1);
  PurePursuit(const PurePursuit&) = delete;
  PurePursuit& operator=(const PurePursuit&) = delete;

  PurePursuitCommand Update(const Pose2& pose);

  /// Total length of the path [m] (one lap for a closed path).
  double length_m() const { return cumulative_.back(); }

 private:
  Eigen::Vector2d PointAt(double s) const;
  /// Closest arc length within a window ahead of the current progress.
  double Project(const Eigen::Vector2d& p, double* distance, double* side) const;

  PurePursuitOptions options_;
  std::vector<Eigen::Vector2d> points_;  // closed paths repeat the first point at the end
  std::vector<double> cumulative_;
  bool closed_;
  int laps_;
  double progress_m_ = 0.0;
};

}  // namespace trackbed::navigation
