// Shared navigation settings and goal errors (see navigation_setup.h).
#include "trackbed/navigation/navigation_setup.h"

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {

void NavigationSetup::Validate() const {
  drive.Validate();
  option_check::Positive("control_period_s", control_period_s);
  option_check::Positive("stop_position_tolerance_m", stop_position_tolerance_m);
  option_check::InRange("stop_heading_tolerance_deg", stop_heading_tolerance_deg, 1e-3, 180.0);
}

GoalError GoalErrorOf(const Pose2& pose, const Pose2& goal) {
  return {std::hypot(goal.x - pose.x, goal.y - pose.y), geometry::WrapAngle(goal.yaw - pose.yaw)};
}

bool AtGoal(const NavigationSetup& setup, const Pose2& pose, const Pose2& goal) {
  const GoalError e = GoalErrorOf(pose, goal);
  return e.position_m <= setup.stop_position_tolerance_m &&
         std::abs(e.heading_rad) <= units::Radians(setup.stop_heading_tolerance_deg);
}

}  // namespace trackbed::navigation
