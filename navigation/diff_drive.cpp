// Differential-drive kinematics (see diff_drive.h).
#include "trackbed/navigation/diff_drive.h"

#include <algorithm>
#include <cmath>

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {

void DiffDriveParams::Validate() const {
  option_check::Positive("wheel_radius_m", wheel_radius_m);
  option_check::Positive("wheel_separation_m", wheel_separation_m);
  option_check::Positive("max_wheel_speed_radps", max_wheel_speed_radps);
}

BodyTwist TwistFromWheelSpeeds(const DiffDriveParams& params, const WheelSpeeds& wheels) {
  const double r = params.wheel_radius_m;
  return {r / 2.0 * (wheels.right_radps + wheels.left_radps),
          r / params.wheel_separation_m * (wheels.right_radps - wheels.left_radps)};
}

WheelSpeeds WheelSpeedsFromTwist(const DiffDriveParams& params, const BodyTwist& twist) {
  const double r = params.wheel_radius_m;
  const double half_w = params.wheel_separation_m / 2.0;
  return {(twist.v_mps - half_w * twist.yaw_rate_radps) / r,
          (twist.v_mps + half_w * twist.yaw_rate_radps) / r};
}

Eigen::Matrix<double, 3, 2> WheelJacobian(const DiffDriveParams& params, double yaw_rad) {
  const double r = params.wheel_radius_m;
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  const double turn = r / params.wheel_separation_m;
  Eigen::Matrix<double, 3, 2> J;
  J << r / 2.0 * c, r / 2.0 * c,  //
      r / 2.0 * s, r / 2.0 * s,   //
      -turn, turn;
  return J;
}

namespace {

// sin(a)/a, accurate near 0.
double Sinc(double a) {
  if (std::abs(a) < 1e-4) return 1.0 - a * a / 6.0;
  return std::sin(a) / a;
}

// Moves along an arc of length `ds` [m] turning by `dyaw` [rad]: the chord has length
// ds·sinc(dyaw/2) and points along the mean heading θ + dyaw/2.
Pose2 Arc(const Pose2& pose, double ds, double dyaw) {
  const double chord = ds * Sinc(dyaw / 2.0);
  const double mid = pose.yaw + dyaw / 2.0;
  return {pose.x + chord * std::cos(mid), pose.y + chord * std::sin(mid),
          geometry::WrapAngle(pose.yaw + dyaw)};
}

}  // namespace

Pose2 IntegrateWheelAngles(const DiffDriveParams& params, const Pose2& pose, double delta_left_rad,
                           double delta_right_rad) {
  const double r = params.wheel_radius_m;
  return Arc(pose, r / 2.0 * (delta_right_rad + delta_left_rad),
             r / params.wheel_separation_m * (delta_right_rad - delta_left_rad));
}

Pose2 IntegrateTwist(const Pose2& pose, const BodyTwist& twist, double dt_s) {
  return Arc(pose, twist.v_mps * dt_s, twist.yaw_rate_radps * dt_s);
}

WheelSpeeds SaturateProportionally(const WheelSpeeds& wheels, double max_wheel_speed_radps) {
  const double largest = std::max(std::abs(wheels.left_radps), std::abs(wheels.right_radps));
  if (!(largest > max_wheel_speed_radps)) return wheels;
  const double scale = max_wheel_speed_radps / largest;
  return {wheels.left_radps * scale, wheels.right_radps * scale};
}

}  // namespace trackbed::navigation
