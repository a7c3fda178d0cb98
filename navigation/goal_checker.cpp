// Goal checker (see goal_checker.h).
#include "trackbed/navigation/goal_checker.h"

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {

void GoalCheckerOptions::Validate() const {
  // The bounds of NavigationSetup's stop tolerances, so options taken from a valid
  // setup are always valid.
  option_check::Positive("position_tolerance_m", position_tolerance_m);
  option_check::InRange("heading_tolerance_rad", heading_tolerance_rad, 1e-9, M_PI);
}

GoalCheckerOptions GoalCheckerOptionsOf(const NavigationSetup& setup) {
  GoalCheckerOptions options;
  options.position_tolerance_m = setup.stop_position_tolerance_m;
  options.heading_tolerance_rad = units::Radians(setup.stop_heading_tolerance_deg);
  return options;
}

GoalChecker::GoalChecker(const GoalCheckerOptions& options, const Pose2& goal)
    : options_(options), goal_(goal) {
  options_.Validate();
}

bool GoalChecker::GoalInObstacle(const std::vector<Circle>& obstacles) const {
  return InsideAnyObstacle({goal_.x, goal_.y}, obstacles);
}

bool GoalChecker::Reached(const Pose2& pose) const {
  const GoalError e = GoalErrorOf(pose, goal_);
  return e.position_m <= options_.position_tolerance_m &&
         std::abs(e.heading_rad) <= options_.heading_tolerance_rad;
}

}  // namespace trackbed::navigation
