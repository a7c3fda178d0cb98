// What every navigation method shares: the robot's drive, the control period and
// the goal tolerance that defines "reached" (docs/navigation.md: within 0.1 m and 2°).
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
  /// The goal is reached within this distance [m], > 0.
  double goal_position_tolerance_m = 0.1;
  /// ... and with the heading within this angle of the goal heading [rad], in (0, π].
  double goal_heading_tolerance_rad = units::Radians(2.0);

  /// Throws OptionError naming the first invalid field (nested as `drive.…`).
  void Validate() const;
};

/// How far a pose is from a goal pose.
struct GoalError {
  double position_m = 0.0;   ///< Euclidean distance of the positions.
  double heading_rad = 0.0;  ///< goal yaw − pose yaw, wrapped to (−π, π].
};

/// The error of `pose` with respect to `goal`.
GoalError GoalErrorOf(const Pose2& pose, const Pose2& goal);

/// True when `pose` is within both goal tolerances of `goal`.
bool AtGoal(const NavigationSetup& setup, const Pose2& pose, const Pose2& goal);

}  // namespace trackbed::navigation
