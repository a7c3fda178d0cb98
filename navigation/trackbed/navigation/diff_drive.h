// Differential-drive kinematics on wheel angles (Jung & Kim 2014, eq. 2):
//
//   ẋ = r/2 (φ̇_r + φ̇_l) cos θ,   ẏ = r/2 (φ̇_r + φ̇_l) sin θ,   θ̇ = r/W (φ̇_r − φ̇_l),
//
// with wheel radius r and wheel separation W. Pure functions on value types. Wheel
// quantities are ordered (left, right) everywhere, in vectors and Jacobian columns.
#pragma once

#include <Eigen/Core>

#include "trackbed/common/pose2.h"
#include "trackbed/common/skid_steer.h"

namespace trackbed::navigation {

using Pose2 = geometry::Pose2;
using BodyTwist = kinematics::BodyTwist;

/// The differential-drive robot of Jung & Kim 2014 (§3): its defaults are the paper's.
struct DiffDriveParams {
  /// Wheel radius r [m], > 0.
  double wheel_radius_m = 0.2;
  /// Wheel separation W (distance between the wheels' contact points) [m], > 0.
  double wheel_separation_m = 0.5;
  /// Largest |wheel angular speed| [rad/s], > 0 (25 rad/s · 0.2 m = the paper's 5 m/s).
  double max_wheel_speed_radps = 25.0;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md, `navigation`),
  /// read and written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("wheel_radius_m", &wheel_radius_m);
    a->Visit("wheel_separation_m", &wheel_separation_m);
    a->Visit("max_wheel_speed_radps", &max_wheel_speed_radps);
  }
};

/// Wheel angular speeds [rad/s]; positive drives the robot forward.
struct WheelSpeeds {
  double left_radps = 0.0;
  double right_radps = 0.0;
};

/// Body twist (forward speed [m/s], yaw rate [rad/s]) of the given wheel speeds.
BodyTwist TwistFromWheelSpeeds(const DiffDriveParams& params, const WheelSpeeds& wheels);

/// Wheel speeds that realise a body twist (inverse of TwistFromWheelSpeeds).
WheelSpeeds WheelSpeedsFromTwist(const DiffDriveParams& params, const BodyTwist& twist);

/// The 3×2 Jacobian ∂(x, y, θ)/∂(φ_l, φ_r) of eq. (2) at heading `yaw_rad`: the pose
/// change per radian of each wheel, to first order. Columns: left, right.
Eigen::Matrix<double, 3, 2> WheelJacobian(const DiffDriveParams& params, double yaw_rad);

/// The pose reached from `pose` when the wheels turn by (Δφ_l, Δφ_r) [rad] at a constant
/// ratio: the exact arc (a straight line when Δφ_l = Δφ_r), not a first-order step.
Pose2 IntegrateWheelAngles(const DiffDriveParams& params, const Pose2& pose, double delta_left_rad,
                           double delta_right_rad);

/// The pose reached from `pose` after driving the body twist for `dt_s` seconds:
/// the exact arc of radius v/ω.
Pose2 IntegrateTwist(const Pose2& pose, const BodyTwist& twist, double dt_s);

/// Scales both wheel speeds by the same factor so that neither exceeds
/// `max_wheel_speed_radps` (> 0) in magnitude; speeds within the limit are returned
/// unchanged. Keeps the ratio φ̇_l : φ̇_r, hence the path's curvature — the paper's
/// proportional saturation (Jung & Kim 2014, §2.3), which does not disturb turning.
WheelSpeeds SaturateProportionally(const WheelSpeeds& wheels, double max_wheel_speed_radps);

}  // namespace trackbed::navigation
