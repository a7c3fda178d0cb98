// Gauss–Newton wheel-speed control (see gauss_newton_controller.h).
#include "trackbed/navigation/gauss_newton_controller.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {

void GaussNewtonOptions::Validate() const {
  option_check::Positive("epsilon_m", epsilon_m);
  option_check::InRange("heading_band_rad", heading_band_rad, 1e-6, M_PI - 1e-6);
  option_check::Positive("damping", damping);
  option_check::InRange("turn_position_weight", turn_position_weight, 0.0, 1.0);
  option_check::NonNegative("final_approach_radius_m", final_approach_radius_m);
  option_check::NonNegative("final_time_constant_s", final_time_constant_s);
  if (final_approach_radius_m > 0.0 && !(final_approach_radius_m > epsilon_m)) {
    throw OptionError("final_approach_radius_m", "must be 0 (off) or larger than epsilon_m");
  }
}

namespace {

/// Whether the step is in the final phase: within ε, or, with the final approach, the
/// final phase begun and held within its radius until its turn is done (the file
/// comment of the header).
bool InFinalPhase(const NavigationSetup& setup, const GaussNewtonOptions& options,
                  double position_error_m, const GoalError& own, bool final_begun) {
  if (!(position_error_m > options.epsilon_m)) return true;  // eq. (4)
  if (!(options.final_approach_radius_m > 0.0) || !final_begun) return false;
  if (position_error_m > options.final_approach_radius_m) return false;
  const bool turned = std::abs(own.heading_rad) <= units::Radians(setup.stop_heading_tolerance_deg);
  return !turned;
}

}  // namespace

GaussNewtonStep ComputeGaussNewtonStep(const NavigationSetup& setup,
                                       const GaussNewtonOptions& options, const Pose2& pose,
                                       const Pose2& target, bool final_begun) {
  GaussNewtonStep step;
  const Eigen::Vector2d delta(target.x - pose.x, target.y - pose.y);
  step.position_error_m = delta.norm();

  const GoalError own = GoalErrorOf(pose, target);
  step.at_goal = own.position_m <= setup.stop_position_tolerance_m &&
                 std::abs(own.heading_rad) <= units::Radians(setup.stop_heading_tolerance_deg);
  if (step.at_goal) {
    step.phase = GaussNewtonPhase::kFinal;
    step.target_heading_rad = target.yaw;
    step.heading_error_rad = own.heading_rad;
    return step;
  }

  // Eq. (4): the bearing replaces the target heading while far from the target.
  double position_weight = 1.0;
  if (!InFinalPhase(setup, options, step.position_error_m, own, final_begun)) {
    step.target_heading_rad = std::atan2(delta.y(), delta.x());
    double off = geometry::WrapAngle(step.target_heading_rad - pose.yaw);
    if (options.final_approach_radius_m > 0.0 &&
        step.position_error_m <= options.final_approach_radius_m && std::abs(off) > M_PI / 2) {
      // The target is behind and near: back up along the bearing's line.
      step.reverse = true;
      step.target_heading_rad = geometry::WrapAngle(step.target_heading_rad + M_PI);
      off = geometry::WrapAngle(step.target_heading_rad - pose.yaw);
    }
    if (std::abs(off) > options.heading_band_rad) {
      step.phase = GaussNewtonPhase::kTurn;
      step.rho = 1.0;
      position_weight = options.turn_position_weight;
    } else {
      step.phase = GaussNewtonPhase::kDrive;
      step.rho = 0.0;
    }
  } else {
    step.phase = GaussNewtonPhase::kFinal;
    step.target_heading_rad = target.yaw;
    step.rho = 1.0;
  }
  step.heading_error_rad = geometry::WrapAngle(step.target_heading_rad - pose.yaw);

  // Eqs. (5)–(12): Δφ = (JᵀWJ + λI)⁻¹ JᵀW e, damped (see the header).
  const Eigen::Vector3d e(delta.x(), delta.y(), step.heading_error_rad);
  const Eigen::Vector3d w(position_weight, position_weight, step.rho);
  const Eigen::Matrix<double, 3, 2> J = WheelJacobian(setup.drive, pose.yaw);
  const Eigen::Matrix2d H =
      J.transpose() * w.asDiagonal() * J + options.damping * Eigen::Matrix2d::Identity();
  const Eigen::Vector2d g = J.transpose() * (w.asDiagonal() * e);
  const Eigen::Vector2d delta_phi = H.ldlt().solve(g);

  // Deadbeat over one control period, or, in the final phase with a time constant,
  // spread over it (the file comment).
  const double spread_s = step.phase == GaussNewtonPhase::kFinal
                              ? std::max(setup.control_period_s, options.final_time_constant_s)
                              : setup.control_period_s;
  const WheelSpeeds raw{delta_phi(0) / spread_s, delta_phi(1) / spread_s};
  step.wheels = SaturateProportionally(raw, setup.drive.max_wheel_speed_radps);
  step.saturated =
      step.wheels.left_radps != raw.left_radps || step.wheels.right_radps != raw.right_radps;
  step.twist = TwistFromWheelSpeeds(setup.drive, step.wheels);
  return step;
}

}  // namespace trackbed::navigation
