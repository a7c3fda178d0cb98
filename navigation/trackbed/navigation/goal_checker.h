// When a point-to-point run has ended at the goal's side: the goal is reached within
// both tolerances, or it lies inside an obstacle and can never be reached. Kept apart
// from the navigation methods, as nav2 keeps its goal checker apart from its
// controllers, so that every method ends a run by one rule (navigator.h).
#pragma once

#include <cmath>
#include <vector>

#include "trackbed/common/units.h"
#include "trackbed/navigation/circle_obstacle.h"
#include "trackbed/navigation/diff_drive.h"
#include "trackbed/navigation/navigation_setup.h"

namespace trackbed::navigation {

struct GoalCheckerOptions {
  /// The goal is reached within this distance [m], > 0.
  double position_tolerance_m = 0.1;
  /// ... and with the heading within this angle of the goal heading [rad], in (0, π].
  double heading_tolerance_rad = units::Radians(2.0);

  /// Throws OptionError naming the first invalid field.
  void Validate() const;
};

/// The goal tolerances of `setup`, which every navigator takes from there.
GoalCheckerOptions GoalCheckerOptionsOf(const NavigationSetup& setup);

/// Checks one goal pose. Holds no state beyond its options and goal: each check depends
/// only on the pose and the obstacles passed in.
class GoalChecker {
 public:
  /// Throws OptionError naming the first invalid field.
  GoalChecker(const GoalCheckerOptions& options, const Pose2& goal);

  /// True when the goal's position lies strictly inside some obstacle's physical circle
  /// (on its edge it can still be reached).
  bool GoalInObstacle(const std::vector<Circle>& obstacles) const;
  /// True when `pose` is within both tolerances of the goal.
  bool Reached(const Pose2& pose) const;

  const GoalCheckerOptions& options() const { return options_; }
  const Pose2& goal() const { return goal_; }

 private:
  GoalCheckerOptions options_;
  Pose2 goal_;
};

}  // namespace trackbed::navigation
