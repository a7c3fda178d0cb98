// What every navigation method shares: the robot's drive, the control period and
// the goal tolerances at which a navigator stops (a run's success is judged apart from
// them, by SuccessCriteria in navigation_metrics.h).
#pragma once

#include <cmath>

#include "trackbed/common/units.h"
#include "trackbed/navigation/diff_drive.h"

namespace trackbed::navigation {

struct NavigationSetup {
  /// The robot the commands are for (wheel radius, separation, wheel-speed limit).
  DiffDriveParams drive;
  /// Control period Δt [s], > 0: commands are held this long (Jung & Kim 2014: 100 ms).
  double control_period_s = 0.1;
  /// The navigator stops (kReached) within this distance of the goal [m], > 0 …
  double stop_position_tolerance_m = 0.1;
  /// … with the heading within this angle of the goal heading [deg], in [0.001, 180].
  double stop_heading_tolerance_deg = 2.0;

  /// Throws OptionError naming the first invalid field; the drive's fields are named
  /// without a prefix, as they are keys beside this struct's (Serialize).
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md, `navigation`),
  /// read and written by the config archive (trackbed/common/archive.h). The drive's
  /// keys sit beside the others.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("control_period_s", &control_period_s);
    drive.Serialize(a);
    a->Visit("stop_position_tolerance_m", &stop_position_tolerance_m);
    a->Visit("stop_heading_tolerance_deg", &stop_heading_tolerance_deg);
  }
};

/// How far a pose is from a goal pose.
struct GoalError {
  double position_m = 0.0;   ///< Euclidean distance of the positions.
  double heading_rad = 0.0;  ///< goal yaw − pose yaw, wrapped to (−π, π].
};

/// The error of `pose` with respect to `goal`.
GoalError GoalErrorOf(const Pose2& pose, const Pose2& goal);

/// True when `pose` is within both stop tolerances of `goal`.
bool AtGoal(const NavigationSetup& setup, const Pose2& pose, const Pose2& goal);

}  // namespace trackbed::navigation
