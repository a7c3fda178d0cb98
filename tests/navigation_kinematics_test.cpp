// Differential-drive kinematics and the Gauss–Newton wheel-speed step (Jung & Kim 2014,
// eqs. 2–12): invariants and hand-checked cases, no simulation.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/QR>

#include "trackbed/common/option_error.h"
#include "trackbed/navigation/diff_drive.h"
#include "trackbed/navigation/gauss_newton_controller.h"

namespace trackbed::navigation {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(DiffDriveTest, JacobianMatchesNumericDifferentiationOfTheExactArc) {
  const DiffDriveParams params;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int trial = 0; trial < 50; ++trial) {
    const Pose2 pose{0.3 * trial, -0.1 * trial, angle(rng)};
    const Eigen::Matrix<double, 3, 2> J = WheelJacobian(params, pose.yaw);
    const double h = 1e-6;
    for (int wheel = 0; wheel < 2; ++wheel) {
      const double dl = wheel == 0 ? h : 0.0, dr = wheel == 1 ? h : 0.0;
      const Pose2 plus = IntegrateWheelAngles(params, pose, dl, dr);
      const Pose2 minus = IntegrateWheelAngles(params, pose, -dl, -dr);
      const Eigen::Vector3d numeric((plus.x - minus.x) / (2 * h), (plus.y - minus.y) / (2 * h),
                                    geometry::WrapAngle(plus.yaw - minus.yaw) / (2 * h));
      EXPECT_LT((numeric - J.col(wheel)).norm(), 1e-8) << "trial " << trial << " wheel " << wheel;
    }
  }
}

TEST(DiffDriveTest, JacobianIsTheFirstOrderTermOfTheExactArc) {
  const DiffDriveParams params;
  const Pose2 pose{1.0, 2.0, 0.7};
  const Eigen::Vector2d direction(0.3, -1.1);
  double previous = 0.0;
  for (double eps : {1e-1, 1e-2, 1e-3}) {
    const Pose2 q = IntegrateWheelAngles(params, pose, eps * direction(0), eps * direction(1));
    const Eigen::Vector3d linear = WheelJacobian(params, pose.yaw) * (eps * direction);
    const double residual =
        (Eigen::Vector3d(q.x - pose.x, q.y - pose.y, q.yaw - pose.yaw) - linear).norm();
    if (previous > 0.0) {
      EXPECT_NEAR(residual / previous, 0.01, 0.002);  // O(ε²)
    }
    previous = residual;
  }
}

TEST(DiffDriveTest, ExactArcAgreesWithFineEulerIntegration) {
  const DiffDriveParams params;
  const WheelSpeeds wheels{7.0, 19.0};
  const BodyTwist twist = TwistFromWheelSpeeds(params, wheels);
  Pose2 euler{0.5, -0.5, 0.3};
  const Pose2 exact = IntegrateTwist(euler, twist, 0.5);
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    euler.x += twist.v_mps * std::cos(euler.yaw) * 0.5 / n;
    euler.y += twist.v_mps * std::sin(euler.yaw) * 0.5 / n;
    euler.yaw += twist.yaw_rate_radps * 0.5 / n;
  }
  EXPECT_NEAR(exact.x, euler.x, 1e-4);
  EXPECT_NEAR(exact.y, euler.y, 1e-4);
  EXPECT_NEAR(exact.yaw, geometry::WrapAngle(euler.yaw), 1e-9);
  const Pose2 same = IntegrateWheelAngles(params, {0.5, -0.5, 0.3}, 3.5, 9.5);
  EXPECT_NEAR(same.x, exact.x, 1e-12);
  EXPECT_NEAR(same.y, exact.y, 1e-12);
}

TEST(DiffDriveTest, TwistAndWheelSpeedsAreInverse) {
  const DiffDriveParams params;
  const WheelSpeeds w = WheelSpeedsFromTwist(params, {1.5, -2.0});
  EXPECT_DOUBLE_EQ(w.left_radps, (1.5 + 0.25 * 2.0) / 0.2);
  EXPECT_DOUBLE_EQ(w.right_radps, (1.5 - 0.25 * 2.0) / 0.2);
  const BodyTwist back = TwistFromWheelSpeeds(params, w);
  EXPECT_NEAR(back.v_mps, 1.5, 1e-12);
  EXPECT_NEAR(back.yaw_rate_radps, -2.0, 1e-12);
}

TEST(DiffDriveTest, SaturationKeepsTheWheelSpeedRatio) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> speed(-200.0, 200.0);
  for (int trial = 0; trial < 200; ++trial) {
    const WheelSpeeds raw{speed(rng), speed(rng)};
    const WheelSpeeds s = SaturateProportionally(raw, 25.0);
    const double largest = std::max(std::abs(raw.left_radps), std::abs(raw.right_radps));
    if (largest <= 25.0) {
      EXPECT_EQ(s.left_radps, raw.left_radps);
      EXPECT_EQ(s.right_radps, raw.right_radps);
      continue;
    }
    EXPECT_NEAR(std::max(std::abs(s.left_radps), std::abs(s.right_radps)), 25.0, 1e-12);
    // Same ratio, same signs: the path's curvature is unchanged.
    EXPECT_NEAR(s.left_radps * raw.right_radps - s.right_radps * raw.left_radps, 0.0, 1e-9);
    EXPECT_GE(s.left_radps * raw.left_radps, 0.0);
    EXPECT_GE(s.right_radps * raw.right_radps, 0.0);
  }
}

TEST(DiffDriveTest, RejectsInvalidParamsNamingTheField) {
  DiffDriveParams params;
  params.wheel_separation_m = 0.0;
  try {
    params.Validate();
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "wheel_separation_m");
  }
}

TEST(GaussNewtonTest, TurnsInPlaceTowardABearingOutsideTheBand) {
  const NavigationSetup setup;
  const GaussNewtonStep step = ComputeGaussNewtonStep(setup, {}, {0, 0, 0}, {-5, 5, 90 * kDeg});
  EXPECT_EQ(step.phase, GaussNewtonPhase::kTurn);
  EXPECT_EQ(step.rho, 1.0);
  EXPECT_NEAR(step.target_heading_rad, 135 * kDeg, 1e-12);  // eq. (4): the bearing
  EXPECT_NEAR(step.twist.v_mps, 0.0, 1e-6);  // rounding at cond(JᵀWJ + λI) ~ 1e8 only
  EXPECT_NEAR(step.wheels.left_radps, -step.wheels.right_radps, 1e-6);
  EXPECT_TRUE(step.saturated);  // 135° in 0.1 s needs more than 25 rad/s
  EXPECT_NEAR(std::abs(step.wheels.right_radps), 25.0, 1e-6);
}

TEST(GaussNewtonTest, DrivesStraightAtFullSpeedOnceAligned) {
  const NavigationSetup setup;
  const Pose2 pose{0, 0, 45 * kDeg + 0.02};  // within the 5° band of the bearing
  const GaussNewtonStep step = ComputeGaussNewtonStep(setup, {}, pose, {5, 5, 90 * kDeg});
  EXPECT_EQ(step.phase, GaussNewtonPhase::kDrive);
  EXPECT_EQ(step.rho, 0.0);
  EXPECT_NEAR(step.wheels.left_radps, 25.0, 1e-6);
  EXPECT_NEAR(step.wheels.right_radps, 25.0, 1e-6);
  EXPECT_NEAR(step.twist.v_mps, 5.0, 1e-6);  // the paper's 5 m/s
}

TEST(GaussNewtonTest, AnUnsaturatedStepIsDeadbeat) {
  const NavigationSetup setup;
  const Pose2 pose{1, 1, 0.3};
  const Pose2 target{1 + 0.3 * std::cos(0.3), 1 + 0.3 * std::sin(0.3), 0.0};
  const GaussNewtonStep step = ComputeGaussNewtonStep(setup, {}, pose, target);
  ASSERT_FALSE(step.saturated);
  const Pose2 next = IntegrateWheelAngles(setup.drive, pose, step.wheels.left_radps * 0.1,
                                          step.wheels.right_radps * 0.1);
  EXPECT_NEAR(next.x, target.x, 1e-6);
  EXPECT_NEAR(next.y, target.y, 1e-6);
}

TEST(GaussNewtonTest, DampedStepEqualsThePseudoInverseStep) {
  const NavigationSetup setup;
  GaussNewtonOptions options;
  const Pose2 pose{0.2, -0.1, 0.4};
  for (const Pose2& target : {Pose2{0.4, 0.0, 0.0}, Pose2{0.22, -0.09, 1.0}}) {
    const GaussNewtonStep step = ComputeGaussNewtonStep(setup, options, pose, target);
    ASSERT_FALSE(step.saturated);
    const Eigen::Matrix<double, 3, 2> J = WheelJacobian(setup.drive, pose.yaw);
    const Eigen::Vector3d w(1.0, 1.0, step.rho);
    const Eigen::Vector3d e(target.x - pose.x, target.y - pose.y, step.heading_error_rad);
    const Eigen::Matrix<double, 3, 2> WJ = w.cwiseSqrt().asDiagonal() * J;
    const Eigen::Vector2d pinv =
        WJ.completeOrthogonalDecomposition().solve(Eigen::Vector3d(w.cwiseSqrt().asDiagonal() * e));
    EXPECT_NEAR(step.wheels.left_radps * 0.1, pinv(0), 1e-6);
    EXPECT_NEAR(step.wheels.right_radps * 0.1, pinv(1), 1e-6);
  }
}

TEST(GaussNewtonTest, WithinEpsilonItTurnsToTheGoalsOwnHeading) {
  const NavigationSetup setup;
  const GaussNewtonStep step = ComputeGaussNewtonStep(setup, {}, {5, 4.97, 0.0}, {5, 5, 90 * kDeg});
  EXPECT_EQ(step.phase, GaussNewtonPhase::kFinal);
  EXPECT_EQ(step.rho, 1.0);
  EXPECT_NEAR(step.target_heading_rad, 90 * kDeg, 1e-12);
  EXPECT_GT(step.twist.yaw_rate_radps, 0.0);
  EXPECT_FALSE(step.at_goal);
  const GaussNewtonStep done =
      ComputeGaussNewtonStep(setup, {}, {5.05, 5, 89.0 * kDeg}, {5, 5, 90 * kDeg});
  EXPECT_TRUE(done.at_goal);
  EXPECT_EQ(done.wheels.left_radps, 0.0);
  EXPECT_EQ(done.wheels.right_radps, 0.0);
}

TEST(GaussNewtonTest, WithoutTheFinalApproachANearTargetBehindIsTurnedTo) {
  // The paper's rule: 8 cm short of ε's circle behind the robot, the bearing is the
  // target heading, a turn of 180°.
  const GaussNewtonStep step =
      ComputeGaussNewtonStep({}, {}, {5.08, 5, 0.0}, {5, 5, 90 * kDeg}, true);
  EXPECT_EQ(step.phase, GaussNewtonPhase::kTurn);
  EXPECT_FALSE(step.reverse);
  EXPECT_NEAR(std::abs(step.heading_error_rad), 180 * kDeg, 1e-12);
}

TEST(GaussNewtonTest, TheFinalApproachBacksUpToANearTargetBehind) {
  GaussNewtonOptions options;
  options.final_approach_radius_m = 0.2;
  // The target 8 cm behind, 10° off the robot's axis: back up along the bearing's line.
  const Pose2 pose{5.0 + 0.08 * std::cos(10 * kDeg), 5.0 + 0.08 * std::sin(10 * kDeg), 0.0};
  const GaussNewtonStep turn = ComputeGaussNewtonStep({}, options, pose, {5, 5, 90 * kDeg});
  EXPECT_TRUE(turn.reverse);
  EXPECT_EQ(turn.phase, GaussNewtonPhase::kTurn);
  EXPECT_NEAR(turn.heading_error_rad, 10 * kDeg, 1e-9);
  // Aligned with the line: the step drives backwards onto the target (deadbeat).
  const Pose2 aligned{5.08, 5.0, 0.0};
  const GaussNewtonStep back = ComputeGaussNewtonStep({}, options, aligned, {5, 5, 90 * kDeg});
  EXPECT_TRUE(back.reverse);
  EXPECT_EQ(back.phase, GaussNewtonPhase::kDrive);
  EXPECT_LT(back.twist.v_mps, 0.0);
  EXPECT_NEAR(back.twist.v_mps * 0.1, -0.08, 1e-6);
  // Beyond the radius the paper's rule again: turn round.
  const GaussNewtonStep far = ComputeGaussNewtonStep({}, options, {5.3, 5, 0.0}, {5, 5, 0.0});
  EXPECT_FALSE(far.reverse);
  EXPECT_NEAR(std::abs(far.heading_error_rad), 180 * kDeg, 1e-12);
}

TEST(GaussNewtonTest, TheFinalPhaseHoldsWithinTheRadiusUntilItsTurnIsDone) {
  GaussNewtonOptions options;
  options.final_approach_radius_m = 0.2;
  const Pose2 target{5, 5, 90 * kDeg};
  // A skid carried the robot 8 cm off, beyond ε, in the middle of its final turn.
  const Pose2 skidded{5.08, 5.0, 30 * kDeg};
  const GaussNewtonStep held = ComputeGaussNewtonStep({}, options, skidded, target, true);
  EXPECT_EQ(held.phase, GaussNewtonPhase::kFinal);
  EXPECT_NEAR(held.target_heading_rad, 90 * kDeg, 1e-12);
  EXPECT_GT(held.twist.yaw_rate_radps, 0.0);  // on toward the goal's heading
  // Not begun (or off): the bearing's line.
  const GaussNewtonStep fresh = ComputeGaussNewtonStep({}, options, skidded, target, false);
  EXPECT_NE(fresh.phase, GaussNewtonPhase::kFinal);
  EXPECT_NE(ComputeGaussNewtonStep({}, {}, skidded, target, true).phase, GaussNewtonPhase::kFinal);
  // Beyond the radius the final phase ends.
  EXPECT_NE(ComputeGaussNewtonStep({}, options, {5.25, 5.0, 30 * kDeg}, target, true).phase,
            GaussNewtonPhase::kFinal);
  // The turn done and 8 cm of cross-track error left: a new approach along the
  // bearing's line (backwards or forwards, within 90°), not the final phase.
  NavigationSetup outdoor;  // nav_outdoor.yaml's stop tolerances
  outdoor.stop_position_tolerance_m = 0.04;
  outdoor.stop_heading_tolerance_deg = 1.0;
  const GaussNewtonStep again =
      ComputeGaussNewtonStep(outdoor, options, {5.08, 5.0, 90.5 * kDeg}, target, true);
  EXPECT_FALSE(again.at_goal);
  EXPECT_NE(again.phase, GaussNewtonPhase::kFinal);
  EXPECT_LE(std::abs(again.heading_error_rad), 90 * kDeg + 1e-9);
}

TEST(GaussNewtonTest, TheFinalApproachRadiusMustExceedEpsilon) {
  GaussNewtonOptions options;
  options.final_approach_radius_m = options.epsilon_m;
  try {
    options.Validate();
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "final_approach_radius_m");
  }
  options.final_approach_radius_m = 0.0;
  EXPECT_NO_THROW(options.Validate());
}

TEST(GaussNewtonTest, TheFinalTimeConstantSpreadsOnlyTheFinalStep) {
  GaussNewtonOptions spread;
  spread.final_time_constant_s = 0.4;
  // Within ε, 2° short of the goal's heading: deadbeat turns the 2° in one period
  // (0.1 s), the time constant over 0.4 s.
  const Pose2 near{5.0, 5.0, 88 * kDeg};
  const Pose2 target{5, 5, 90 * kDeg};
  const GaussNewtonStep deadbeat = ComputeGaussNewtonStep({}, {}, near, target);
  const GaussNewtonStep slow = ComputeGaussNewtonStep({}, spread, near, target);
  ASSERT_EQ(slow.phase, GaussNewtonPhase::kFinal);
  EXPECT_NEAR(deadbeat.twist.yaw_rate_radps, 2 * kDeg / 0.1, 1e-6);
  EXPECT_NEAR(slow.twist.yaw_rate_radps, 2 * kDeg / 0.4, 1e-6);
  // Far from the target (turn and drive phases) the step stays deadbeat.
  const Pose2 far{0.0, 0.0, 0.0};
  const Pose2 ahead{0.03, 0.0, 0.0};
  EXPECT_EQ(ComputeGaussNewtonStep({}, spread, far, {0, 1, 0}).twist.yaw_rate_radps,
            ComputeGaussNewtonStep({}, {}, far, {0, 1, 0}).twist.yaw_rate_radps);
  EXPECT_EQ(ComputeGaussNewtonStep({}, spread, far, {3, 0.01, 0}).twist.v_mps,
            ComputeGaussNewtonStep({}, {}, far, {3, 0.01, 0}).twist.v_mps);
  // A time constant shorter than the control period is the deadbeat step.
  spread.final_time_constant_s = 0.05;
  EXPECT_EQ(ComputeGaussNewtonStep({}, spread, ahead, target).twist.yaw_rate_radps,
            ComputeGaussNewtonStep({}, {}, ahead, target).twist.yaw_rate_radps);
  spread.final_time_constant_s = -0.1;
  EXPECT_THROW(spread.Validate(), OptionError);
}

TEST(GaussNewtonTest, TheLiteralUnitWeightDrivesWhileTurning) {
  // Our reading (gauss_newton_controller.h): diag(1, 1, 1) in the turn phase reverses
  // toward the target instead of turning in place.
  GaussNewtonOptions literal;
  literal.turn_position_weight = 1.0;
  const GaussNewtonStep step = ComputeGaussNewtonStep({}, literal, {0, 0, 0}, {-5, 5, 0.0});
  EXPECT_EQ(step.phase, GaussNewtonPhase::kTurn);
  EXPECT_LT(step.twist.v_mps, -4.0);
}

TEST(GaussNewtonTest, RejectsInvalidOptionsNamingTheField) {
  GaussNewtonOptions options;
  options.heading_band_rad = 0.0;
  EXPECT_THROW(options.Validate(), OptionError);
  try {
    options.Validate();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "heading_band_rad");
  }
}

}  // namespace
}  // namespace trackbed::navigation
