// Jung & Kim 2014 as one navigator: the sub-goal switcher picks the active target
// (goal or sub-goal, subgoal_planner.h) and the Gauss–Newton controller drives to it
// (gauss_newton_controller.h). Method name "gauss_newton_subgoal".
#pragma once

#include <vector>

#include "trackbed/navigation/gauss_newton_controller.h"
#include "trackbed/navigation/navigation_setup.h"
#include "trackbed/navigation/navigator.h"
#include "trackbed/navigation/subgoal_planner.h"

namespace trackbed::navigation {

class GaussNewtonSubgoalNavigator final : public Navigator {
 public:
  /// Validates all options (throws OptionError naming the field).
  GaussNewtonSubgoalNavigator(const NavigationSetup& setup, const GaussNewtonOptions& controller,
                              const SubgoalOptions& subgoal, const ProgressCheckerOptions& progress,
                              const Pose2& goal);

  /// The run-ending checks of NavigationChecks around the switcher's target and one
  /// Gauss–Newton step. When the blocking obstacles close around the robot (no way
  /// around) the robot holds still, so a run toward an enclosed goal ends as kStalled.
  NavigationCommand Update(const Pose2& pose, const std::vector<Circle>& obstacles) override;

  const char* method() const override { return "gauss_newton_subgoal"; }
  const Pose2& goal() const override { return goal_; }
  std::vector<SubgoalRecord> subgoals() const override { return switcher_.subgoals(); }

  /// The last Gauss–Newton step (phase, ρ, errors), for logs and tests.
  const GaussNewtonStep& last_step() const { return last_step_; }

 private:
  /// The method's own part of Update: target and Gauss–Newton step into `command`.
  void Drive(const Pose2& pose, const std::vector<Circle>& obstacles, NavigationCommand* command);

  NavigationSetup setup_;
  GaussNewtonOptions controller_;
  Pose2 goal_;
  SubgoalSwitcher switcher_;
  NavigationChecks checks_;
  GaussNewtonStep last_step_;
  bool last_target_subgoal_ = false;  ///< The previous step's target was a sub-goal.
};

}  // namespace trackbed::navigation
