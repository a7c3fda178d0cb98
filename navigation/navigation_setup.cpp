// Shared navigation settings and goal errors (see navigation_setup.h).
#include "trackbed/navigation/navigation_setup.h"

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {

void NavigationSetup::Validate() const {
  option_check::Nested("drive", drive);
  option_check::Positive("control_period_s", control_period_s);
  option_check::Positive("goal_position_tolerance_m", goal_position_tolerance_m);
  option_check::InRange("goal_heading_tolerance_rad", goal_heading_tolerance_rad, 1e-9, M_PI);
}

GoalError GoalErrorOf(const Pose2& pose, const Pose2& goal) {
  return {std::hypot(goal.x - pose.x, goal.y - pose.y), geometry::WrapAngle(goal.yaw - pose.yaw)};
}

bool AtGoal(const NavigationSetup& setup, const Pose2& pose, const Pose2& goal) {
  const GoalError e = GoalErrorOf(pose, goal);
  return e.position_m <= setup.goal_position_tolerance_m &&
         std::abs(e.heading_rad) <= setup.goal_heading_tolerance_rad;
}

}  // namespace trackbed::navigation
