// Potential field with Ge & Cui's goal-nearby correction (see potential_field.h).
#include "trackbed/navigation/potential_field.h"

#include <algorithm>
#include <cmath>

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {

void PotentialFieldOptions::Validate() const {
  option_check::Positive("attractive_gain_per_s", attractive_gain_per_s);
  option_check::NonNegative("repulsive_gain", repulsive_gain);
  option_check::Positive("influence_range_m", influence_range_m);
  option_check::NonNegative("goal_exponent", goal_exponent);
  option_check::NonNegative("robot_radius_m", robot_radius_m);
  option_check::Positive("min_distance_m", min_distance_m);
  option_check::Positive("max_speed_mps", max_speed_mps);
  option_check::InRange("clearance_step_fraction", clearance_step_fraction, 1e-6, 1.0);
  option_check::Positive("heading_gain_per_s", heading_gain_per_s);
  option_check::Positive("max_yaw_rate_radps", max_yaw_rate_radps);
  option_check::InRange("turn_in_place_rad", turn_in_place_rad, 1e-6, M_PI);
  option_check::Positive("final_distance_m", final_distance_m);
}

PotentialFieldForce ComputePotentialFieldForce(const PotentialFieldOptions& options,
                                               const Eigen::Vector2d& p_world,
                                               const Eigen::Vector2d& goal_world,
                                               const std::vector<Circle>& obstacles) {
  PotentialFieldForce force;
  const Eigen::Vector2d to_goal = goal_world - p_world;
  const double rho_g = to_goal.norm();
  force.attractive = options.attractive_gain_per_s * to_goal;
  const Eigen::Vector2d n_rg =
      rho_g > 0.0 ? Eigen::Vector2d(to_goal / rho_g) : Eigen::Vector2d::Zero();
  const double eta = options.repulsive_gain, n = options.goal_exponent;
  const double rho0 = options.influence_range_m;
  for (const Circle& o : obstacles) {
    const Eigen::Vector2d away = p_world - o.centre;
    const double centre_distance = away.norm();
    const double rho =
        std::max(options.min_distance_m, centre_distance - o.radius_m - options.robot_radius_m);
    if (rho > rho0) continue;
    ++force.repelling_obstacles;
    const Eigen::Vector2d n_or =
        centre_distance > 0.0 ? Eigen::Vector2d(away / centre_distance) : Eigen::Vector2d(-n_rg);
    const double excess = 1.0 / rho - 1.0 / rho0;
    const double f1 = eta * excess * std::pow(rho_g, n) / (rho * rho);
    const double f2 =
        n > 0.0 && rho_g > 0.0 ? n / 2.0 * eta * excess * excess * std::pow(rho_g, n - 1.0) : 0.0;
    force.repulsive += f1 * n_or + f2 * n_rg;
  }
  force.total = force.attractive + force.repulsive;
  return force;
}

PotentialFieldNavigator::PotentialFieldNavigator(const NavigationSetup& setup,
                                                 const PotentialFieldOptions& options,
                                                 const ProgressCheckerOptions& progress,
                                                 const Pose2& goal)
    : setup_(ValidatedOptions("setup", setup)),
      options_(ValidatedOptions("potential_field", options)),
      goal_(goal),
      checks_(setup_, ValidatedOptions("progress", progress), goal) {}

NavigationCommand PotentialFieldNavigator::Update(const Pose2& pose,
                                                  const std::vector<Circle>& obstacles) {
  return checks_.Update(pose, obstacles,
                        [&](NavigationCommand* command) { Drive(pose, obstacles, command); });
}

void PotentialFieldNavigator::Drive(const Pose2& pose, const std::vector<Circle>& obstacles,
                                    NavigationCommand* command) {
  const Eigen::Vector2d p(pose.x, pose.y), goal(goal_.x, goal_.y);
  const GoalError error = GoalErrorOf(pose, goal_);
  BodyTwist twist;
  if (error.position_m <= options_.final_distance_m) {
    // Final turn in place to the goal heading, at most what one period needs.
    twist.yaw_rate_radps = std::clamp(error.heading_rad / setup_.control_period_s,
                                      -options_.max_yaw_rate_radps, options_.max_yaw_rate_radps);
  } else {
    const PotentialFieldForce force = ComputePotentialFieldForce(options_, p, goal, obstacles);
    const double magnitude = force.total.norm();
    if (magnitude > 0.0) {
      const double heading = std::atan2(force.total.y(), force.total.x());
      const double off = geometry::WrapAngle(heading - pose.yaw);
      twist.yaw_rate_radps = std::clamp(options_.heading_gain_per_s * off,
                                        -options_.max_yaw_rate_radps, options_.max_yaw_rate_radps);
      if (std::abs(off) <= options_.turn_in_place_rad) {
        const double clearance = FootprintClearance(p, options_.robot_radius_m, obstacles);
        const double guard = options_.clearance_step_fraction *
                             std::max(options_.min_distance_m, clearance) / setup_.control_period_s;
        twist.v_mps = std::min({options_.max_speed_mps, magnitude, guard}) * std::cos(off);
      }
    }
  }
  command->wheels = SaturateProportionally(WheelSpeedsFromTwist(setup_.drive, twist),
                                           setup_.drive.max_wheel_speed_radps);
  command->twist = TwistFromWheelSpeeds(setup_.drive, command->wheels);
}

}  // namespace trackbed::navigation
