// Gauss–Newton + sub-goal navigator (see gauss_newton_subgoal_navigator.h).
#include "trackbed/navigation/gauss_newton_subgoal_navigator.h"

namespace trackbed::navigation {

GaussNewtonSubgoalNavigator::GaussNewtonSubgoalNavigator(const NavigationSetup& setup,
                                                         const GaussNewtonOptions& controller,
                                                         const SubgoalOptions& subgoal,
                                                         const ProgressCheckerOptions& progress,
                                                         const Pose2& goal)
    : setup_(ValidatedOptions("setup", setup)),
      controller_(ValidatedOptions("gauss_newton", controller)),
      goal_(goal),
      switcher_(ValidatedOptions("subgoal", subgoal), goal),
      checks_(setup_, ValidatedOptions("progress", progress), goal) {}

NavigationCommand GaussNewtonSubgoalNavigator::Update(const Pose2& pose,
                                                      const std::vector<Circle>& obstacles) {
  return checks_.Update(pose, obstacles,
                        [&](NavigationCommand* command) { Drive(pose, obstacles, command); });
}

void GaussNewtonSubgoalNavigator::Drive(const Pose2& pose, const std::vector<Circle>& obstacles,
                                        NavigationCommand* command) {
  const ActiveTarget target = switcher_.Update(pose, obstacles);
  command->target = {target.pose.x, target.pose.y};
  command->subgoal_active = target.subgoal_active;
  const bool was_subgoal = last_target_subgoal_;
  last_target_subgoal_ = target.subgoal_active;
  if (target.no_way_around) {
    last_step_ = GaussNewtonStep{};  // hold still: every way is blocked
  } else {
    // The final phase holds only toward the goal itself (a sub-goal is passed through).
    const bool final_begun =
        !target.subgoal_active && !was_subgoal && last_step_.phase == GaussNewtonPhase::kFinal;
    last_step_ = ComputeGaussNewtonStep(setup_, controller_, pose, target.pose, final_begun);
    command->wheels = last_step_.wheels;
    command->twist = last_step_.twist;
  }
}

}  // namespace trackbed::navigation
