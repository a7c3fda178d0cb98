// The checks that end every navigator's run (NavigationChecks, navigator.h): their
// order, that an ended run stays ended with a zero command, and that all three methods
// end a run by them.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/navigation/navigator.h"
#include "trackbed/navigation/navigator_factory.h"

namespace trackbed::navigation {
namespace {

constexpr double kPeriod = 0.25;  // adds up exactly: the stall falls on a known update

NavigationSetup QuarterSecondPeriod() {
  NavigationSetup setup;
  setup.control_period_s = kPeriod;
  return setup;
}

ProgressCheckerOptions OneSecond() {
  ProgressCheckerOptions options;
  options.stall_time_s = 1.0;
  return options;
}

// A method's command that is easy to recognise.
void DriveForward(NavigationCommand* command) {
  command->wheels = {3.0, 3.0};
  command->twist = {0.6, 0.0};
  command->target = {7.0, 8.0};
  command->subgoal_active = true;
}

TEST(NavigationChecksTest, WhileDrivingTheMethodsCommandPassesThrough) {
  NavigationChecks checks(QuarterSecondPeriod(), OneSecond(), {5.0, 0.0, 0.0});
  bool target_was_goal = false;
  const NavigationCommand command = checks.Update({0.0, 0.0, 0.0}, {}, [&](NavigationCommand* c) {
    target_was_goal = c->target == Eigen::Vector2d(5.0, 0.0) && c->wheels.left_radps == 0.0;
    DriveForward(c);
  });
  EXPECT_TRUE(target_was_goal);  // the method starts from a zero command toward the goal
  EXPECT_EQ(command.status, NavigationStatus::kDriving);
  EXPECT_EQ(command.wheels.left_radps, 3.0);
  EXPECT_EQ(command.target, Eigen::Vector2d(7.0, 8.0));
  EXPECT_TRUE(command.subgoal_active);
}

TEST(NavigationChecksTest, AGoalInsideAnObstacleEndsTheRunBeforeTheMethodRuns) {
  NavigationChecks checks(QuarterSecondPeriod(), OneSecond(), {5.0, 0.0, 0.0});
  int drives = 0;
  const auto drive = [&](NavigationCommand* c) {
    ++drives;
    DriveForward(c);
  };
  // The robot stands at the goal as well: the obstacle check comes first.
  NavigationCommand command = checks.Update({5.0, 0.0, 0.0}, {{{5.2, 0.0}, 0.5}}, drive);
  EXPECT_EQ(command.status, NavigationStatus::kGoalInObstacle);
  EXPECT_EQ(command.wheels.left_radps, 0.0);
  EXPECT_EQ(command.target, Eigen::Vector2d(5.0, 0.0));
  // The obstacle gone, the run stays ended.
  command = checks.Update({0.0, 0.0, 0.0}, {}, drive);
  EXPECT_EQ(command.status, NavigationStatus::kGoalInObstacle);
  EXPECT_EQ(drives, 0);
  EXPECT_EQ(checks.status(), NavigationStatus::kGoalInObstacle);
}

TEST(NavigationChecksTest, ReachingTheGoalEndsTheRun) {
  NavigationChecks checks(QuarterSecondPeriod(), OneSecond(), {5.0, 0.0, 0.0});
  int drives = 0;
  const auto drive = [&](NavigationCommand* c) {
    ++drives;
    DriveForward(c);
  };
  EXPECT_EQ(checks.Update({0.0, 0.0, 0.0}, {}, drive).status, NavigationStatus::kDriving);
  const NavigationCommand command = checks.Update({4.95, 0.0, 0.01}, {}, drive);
  EXPECT_EQ(command.status, NavigationStatus::kReached);
  EXPECT_EQ(command.wheels.right_radps, 0.0);
  EXPECT_EQ(checks.Update({0.0, 0.0, 0.0}, {}, drive).status, NavigationStatus::kReached);
  EXPECT_EQ(drives, 1);
}

TEST(NavigationChecksTest, NoProgressReplacesTheCommandByZeroAndEndsTheRun) {
  NavigationChecks checks(QuarterSecondPeriod(), OneSecond(), {5.0, 0.0, 0.0});
  int drives = 0;
  const auto drive = [&](NavigationCommand* c) {
    ++drives;
    DriveForward(c);
  };
  for (int k = 0; k < 4; ++k) {  // the first sets the best distance, then 0.75 s
    EXPECT_EQ(checks.Update({0.0, 0.0, 0.0}, {}, drive).status, NavigationStatus::kDriving);
  }
  NavigationCommand command = checks.Update({0.0, 0.0, 0.0}, {}, drive);
  EXPECT_EQ(command.status, NavigationStatus::kStalled);
  EXPECT_EQ(command.wheels.left_radps, 0.0);
  EXPECT_EQ(command.twist.v_mps, 0.0);
  EXPECT_EQ(command.target, Eigen::Vector2d(5.0, 0.0));  // the goal, not the method's target
  EXPECT_FALSE(command.subgoal_active);
  command = checks.Update({4.95, 0.0, 0.0}, {}, drive);  // even at the goal
  EXPECT_EQ(command.status, NavigationStatus::kStalled);
  EXPECT_EQ(drives, 5);
}

TEST(NavigationChecksTest, EveryMethodEndsItsRunByTheSameChecks) {
  for (const std::string& method : NavigationMethodNames()) {
    SCOPED_TRACE(method);
    NavigatorOptions options;
    const std::unique_ptr<Navigator> blocked = MakeNavigator(method, options, {3.0, 0.0, 0.0});
    NavigationCommand command = blocked->Update({0.0, 0.0, 0.0}, {{{3.0, 0.0}, 0.4}});
    EXPECT_EQ(command.status, NavigationStatus::kGoalInObstacle);
    EXPECT_EQ(command.wheels.left_radps, 0.0);

    const std::unique_ptr<Navigator> there = MakeNavigator(method, options, {3.0, 0.0, 0.0});
    command = there->Update({3.0, 0.02, 0.0}, {});
    EXPECT_EQ(command.status, NavigationStatus::kReached);
    EXPECT_EQ(command.wheels.right_radps, 0.0);

    // Boxed in by obstacles all round (the goal outside): no progress, then kStalled.
    options.progress.stall_time_s = 2.0;
    const std::unique_ptr<Navigator> boxed = MakeNavigator(method, options, {10.0, 0.0, 0.0});
    std::vector<Circle> box;
    for (int k = 0; k < 16; ++k) {
      const double a = 2.0 * M_PI * k / 16.0;
      box.push_back({{1.2 * std::cos(a), 1.2 * std::sin(a)}, 0.3});
    }
    NavigationStatus status = NavigationStatus::kDriving;
    for (int step = 0; step < 100 && status == NavigationStatus::kDriving; ++step) {
      status = boxed->Update({0.0, 0.0, 0.0}, box).status;  // the robot does not move
    }
    EXPECT_EQ(status, NavigationStatus::kStalled);
  }
}

}  // namespace
}  // namespace trackbed::navigation
