// Gauss–Newton + sub-goal navigator (see gauss_newton_subgoal_navigator.h).
#include "trackbed/navigation/gauss_newton_subgoal_navigator.h"

namespace trackbed::navigation {

GaussNewtonSubgoalNavigator::GaussNewtonSubgoalNavigator(const NavigationSetup& setup,
                                                         const GaussNewtonOptions& controller,
                                                         const SubgoalOptions& subgoal,
                                                         const ProgressOptions& progress,
                                                         const Pose2& goal)
    : setup_(ValidatedOptions("setup", setup)),
      controller_(ValidatedOptions("gauss_newton", controller)),
      goal_(goal),
      switcher_(ValidatedOptions("subgoal", subgoal), goal),
      progress_(ValidatedOptions("progress", progress)) {}

NavigationCommand GaussNewtonSubgoalNavigator::Update(const Pose2& pose,
                                                      const std::vector<Circle>& obstacles) {
  NavigationCommand command;
  command.target = {goal_.x, goal_.y};
  if (status_ == NavigationStatus::kDriving && InsideAnyObstacle(command.target, obstacles)) {
    status_ = NavigationStatus::kGoalInObstacle;
  }
  if (status_ == NavigationStatus::kDriving && AtGoal(setup_, pose, goal_)) {
    status_ = NavigationStatus::kReached;
  }
  if (status_ != NavigationStatus::kDriving) {
    command.status = status_;
    return command;
  }

  const ActiveTarget target = switcher_.Update(pose, obstacles);
  command.target = {target.pose.x, target.pose.y};
  command.subgoal_active = target.subgoal_active;
  if (target.no_way_around) {
    last_step_ = GaussNewtonStep{};  // hold still: every way is blocked
  } else {
    last_step_ = ComputeGaussNewtonStep(setup_, controller_, pose, target.pose);
    command.wheels = last_step_.wheels;
    command.twist = last_step_.twist;
  }
  const double distance = GoalErrorOf(pose, goal_).position_m;
  if (progress_.Update(distance, setup_.goal_position_tolerance_m, setup_.control_period_s)) {
    status_ = NavigationStatus::kStalled;
    command = NavigationCommand{};
    command.target = {goal_.x, goal_.y};
  }
  command.status = status_;
  return command;
}

}  // namespace trackbed::navigation
