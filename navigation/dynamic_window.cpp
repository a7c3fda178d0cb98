// The dynamic window approach (see dynamic_window.h).
#include "trackbed/navigation/dynamic_window.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {
namespace {

// Arc length [m] along the arc of (v, ω) from `pose` to the first point where the
// footprint's clearance drops below `margin_m` — or below its clearance now, if that is
// already smaller (a robot inside the margin may still move away) — at most `cap_m`.
double FreeArcLength(const Pose2& pose, const BodyTwist& twist, double cap_m, double step_m,
                     double footprint_m, double margin_m, const std::vector<Circle>& obstacles) {
  if (twist.v_mps <= 0.0) return cap_m;  // turning in place does not move a disk
  const double threshold =
      std::min(margin_m, FootprintClearance({pose.x, pose.y}, footprint_m, obstacles));
  for (double s = step_m; s < cap_m + step_m; s += step_m) {
    const double arc = std::min(s, cap_m);
    const Pose2 q = IntegrateTwist(pose, twist, arc / twist.v_mps);
    if (FootprintClearance({q.x, q.y}, footprint_m, obstacles) < threshold) {
      return std::max(0.0, arc - step_m);
    }
  }
  return cap_m;
}

}  // namespace

void DynamicWindowOptions::Validate() const {
  option_check::Positive("max_speed_mps", max_speed_mps);
  option_check::Positive("max_yaw_rate_radps", max_yaw_rate_radps);
  option_check::Positive("max_accel_mps2", max_accel_mps2);
  option_check::Positive("max_yaw_accel_radps2", max_yaw_accel_radps2);
  if (speed_samples < 2) throw OptionError("speed_samples", "must be >= 2");
  if (yaw_rate_samples < 2) throw OptionError("yaw_rate_samples", "must be >= 2");
  option_check::NonNegative("heading_weight", heading_weight);
  option_check::NonNegative("clearance_weight", clearance_weight);
  option_check::NonNegative("velocity_weight", velocity_weight);
  if (heading_weight + clearance_weight + velocity_weight <= 0.0) {
    throw OptionError("heading_weight", "the three objective weights must not all be 0");
  }
  option_check::Positive("clearance_cap_m", clearance_cap_m);
  option_check::Positive("arc_step_m", arc_step_m);
  option_check::NonNegative("robot_radius_m", robot_radius_m);
  option_check::NonNegative("safety_margin_m", safety_margin_m);
  option_check::Positive("final_distance_m", final_distance_m);
}

DynamicWindowChoice ChooseDynamicWindowVelocity(const NavigationSetup& setup,
                                                const DynamicWindowOptions& options,
                                                const Pose2& pose, const BodyTwist& current,
                                                const Eigen::Vector2d& goal_world,
                                                const std::vector<Circle>& obstacles) {
  const double dt = setup.control_period_s;
  const double a_v = options.max_accel_mps2, a_w = options.max_yaw_accel_radps2;
  const Eigen::Vector2d p(pose.x, pose.y);
  const double goal_distance = (goal_world - p).norm();

  // The dynamic window: velocities reachable within one period.
  const double v_lo = std::max(0.0, current.v_mps - a_v * dt);
  double v_hi = std::min(options.max_speed_mps, current.v_mps + a_v * dt);
  const double w_lo = std::max(-options.max_yaw_rate_radps, current.yaw_rate_radps - a_w * dt);
  const double w_hi = std::min(options.max_yaw_rate_radps, current.yaw_rate_radps + a_w * dt);
  const double goal_cap = std::min(std::sqrt(2.0 * a_v * goal_distance), goal_distance / dt);
  v_hi = std::max(v_lo, std::min(v_hi, goal_cap));

  DynamicWindowChoice choice;
  // Only obstacles the footprint could meet within the cap matter.
  const double reach = options.clearance_cap_m + options.robot_radius_m + options.safety_margin_m;
  std::vector<Circle> near;
  for (const Circle& o : obstacles) {
    if (SurfaceDistance(p, o) <= reach) near.push_back(o);
  }
  const double wheel_limit = setup.drive.max_wheel_speed_radps * setup.drive.wheel_radius_m;
  const double half_w = setup.drive.wheel_separation_m / 2.0;

  struct Sample {
    BodyTwist twist;
    double heading, dist, velocity;
  };
  std::vector<Sample> samples;
  double max_heading = 0.0, max_dist = 0.0, max_velocity = 0.0;
  for (int i = 0; i < options.speed_samples; ++i) {
    const double v = v_lo + (v_hi - v_lo) * i / (options.speed_samples - 1);
    for (int j = 0; j < options.yaw_rate_samples; ++j) {
      const double w = w_lo + (w_hi - w_lo) * j / (options.yaw_rate_samples - 1);
      if (std::abs(v) + std::abs(w) * half_w > wheel_limit * (1.0 + 1e-12)) continue;
      const BodyTwist twist{v, w};
      const double dist = FreeArcLength(pose, twist, options.clearance_cap_m, options.arc_step_m,
                                        options.robot_radius_m, options.safety_margin_m, near);
      // Admissible: the robot can stop before the obstacle, braking one period late (the
      // command is held for a period before the next decision can brake).
      if (v * dt + v * v / (2.0 * a_v) > dist) continue;
      // Fox et al.: heading at the pose after one period and a full stop on the same arc.
      const Pose2 after = IntegrateTwist(pose, twist, dt);
      const Pose2 stop = IntegrateTwist(after, twist, v / (2.0 * a_v));
      const double bearing = std::atan2(goal_world.y() - stop.y, goal_world.x() - stop.x);
      Sample s{twist, 1.0 - std::abs(geometry::WrapAngle(bearing - stop.yaw)) / M_PI,
               std::min(dist, options.clearance_cap_m) / options.clearance_cap_m,
               v / options.max_speed_mps};
      max_heading = std::max(max_heading, s.heading);
      max_dist = std::max(max_dist, s.dist);
      max_velocity = std::max(max_velocity, s.velocity);
      samples.push_back(s);
    }
  }
  choice.admissible = static_cast<int>(samples.size());
  if (samples.empty()) {
    choice.braking = true;
    choice.twist = {v_lo, std::clamp(0.0, w_lo, w_hi)};
    return choice;
  }
  auto normalised = [](double x, double max) { return max > 0.0 ? x / max : 0.0; };
  double best = -std::numeric_limits<double>::infinity();
  for (const Sample& s : samples) {
    const double g = options.heading_weight * normalised(s.heading, max_heading) +
                     options.clearance_weight * normalised(s.dist, max_dist) +
                     options.velocity_weight * normalised(s.velocity, max_velocity);
    if (g > best) {
      best = g;
      choice.twist = s.twist;
    }
  }
  choice.objective = best;
  return choice;
}

DynamicWindowNavigator::DynamicWindowNavigator(const NavigationSetup& setup,
                                               const DynamicWindowOptions& options,
                                               const ProgressCheckerOptions& progress,
                                               const Pose2& goal)
    : setup_(ValidatedOptions("setup", setup)),
      options_(ValidatedOptions("dwa", options)),
      goal_(goal),
      checks_(setup_, ValidatedOptions("progress", progress), goal) {}

NavigationCommand DynamicWindowNavigator::Update(const Pose2& pose,
                                                 const std::vector<Circle>& obstacles) {
  const NavigationCommand command =
      checks_.Update(pose, obstacles, [&](NavigationCommand* c) { Drive(pose, obstacles, c); });
  // An ended run's command is zero: the robot is taken to stand still from then on.
  if (command.status != NavigationStatus::kDriving) current_ = {};
  return command;
}

void DynamicWindowNavigator::Drive(const Pose2& pose, const std::vector<Circle>& obstacles,
                                   NavigationCommand* command) {
  const Eigen::Vector2d goal(goal_.x, goal_.y);
  const GoalError error = GoalErrorOf(pose, goal_);
  const double dt = setup_.control_period_s;
  BodyTwist twist;
  if (error.position_m <= options_.final_distance_m) {
    // Brake and turn to the goal heading within the window, never faster than one can
    // stop at the goal heading (ω ≤ √(2 a_ω |e|)) or reach it in one period.
    const double a_w = options_.max_yaw_accel_radps2;
    twist.v_mps = std::max(0.0, current_.v_mps - options_.max_accel_mps2 * dt);
    const double magnitude =
        std::min({options_.max_yaw_rate_radps, std::sqrt(2.0 * a_w * std::abs(error.heading_rad)),
                  std::abs(error.heading_rad) / dt});
    twist.yaw_rate_radps =
        std::clamp(std::copysign(magnitude, error.heading_rad), current_.yaw_rate_radps - a_w * dt,
                   current_.yaw_rate_radps + a_w * dt);
  } else {
    twist = ChooseDynamicWindowVelocity(setup_, options_, pose, current_, goal, obstacles).twist;
  }
  command->wheels = SaturateProportionally(WheelSpeedsFromTwist(setup_.drive, twist),
                                           setup_.drive.max_wheel_speed_radps);
  command->twist = TwistFromWheelSpeeds(setup_.drive, command->wheels);
  current_ = command->twist;
}

}  // namespace trackbed::navigation
