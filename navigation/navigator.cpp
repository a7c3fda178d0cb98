// Navigation status names and the checks that end a run (see navigator.h).
#include "trackbed/navigation/navigator.h"

namespace trackbed::navigation {

const char* NavigationStatusName(NavigationStatus status) {
  switch (status) {
    case NavigationStatus::kDriving:
      return "driving";
    case NavigationStatus::kReached:
      return "reached";
    case NavigationStatus::kGoalInObstacle:
      return "goal_in_obstacle";
    case NavigationStatus::kStalled:
      return "stalled";
  }
  return "unknown";
}

NavigationChecks::NavigationChecks(const NavigationSetup& setup,
                                   const ProgressCheckerOptions& progress, const Pose2& goal)
    : goal_checker_(GoalCheckerOptionsOf(setup), goal),
      progress_checker_(progress),
      control_period_s_(setup.control_period_s) {}

NavigationCommand NavigationChecks::CheckGoal(const Pose2& pose,
                                              const std::vector<Circle>& obstacles) {
  NavigationCommand command;
  command.target = {goal_checker_.goal().x, goal_checker_.goal().y};
  if (status_ == NavigationStatus::kDriving && goal_checker_.GoalInObstacle(obstacles)) {
    status_ = NavigationStatus::kGoalInObstacle;
  }
  if (status_ == NavigationStatus::kDriving && goal_checker_.Reached(pose)) {
    status_ = NavigationStatus::kReached;
  }
  command.status = status_;
  return command;
}

void NavigationChecks::CheckProgress(const Pose2& pose, NavigationCommand* command) {
  const double distance = GoalErrorOf(pose, goal_checker_.goal()).position_m;
  if (progress_checker_.Update(distance, goal_checker_.options().position_tolerance_m,
                               control_period_s_)) {
    status_ = NavigationStatus::kStalled;
    *command = NavigationCommand{};
    command->target = {goal_checker_.goal().x, goal_checker_.goal().y};
  }
  command->status = status_;
}

}  // namespace trackbed::navigation
