// Sprocket drive (see sprocket_motor.h).
#include "trackbed/robot/sprocket_motor.h"

#include <algorithm>
#include <cmath>

#include "trackbed/common/option_error.h"

namespace trackbed::robot {

void SprocketMotorOptions::Validate() const {
  option_check::Positive("time_constant_s", time_constant_s);
  option_check::Positive("velocity_gain_nm_per_radps", velocity_gain_nm_per_radps);
  option_check::NonNegative("integral_gain_nm_per_rad", integral_gain_nm_per_rad);
  option_check::Positive("max_torque_nm", max_torque_nm);
  option_check::Positive("max_speed_radps", max_speed_radps);
  option_check::Positive("inertia_kgm2", inertia_kgm2);
  option_check::NonNegative("viscous_friction_nm_per_radps", viscous_friction_nm_per_radps);
}

SprocketMotor::SprocketMotor(const SprocketMotorOptions& options) : options_(options) {
  options_.Validate();
}

void SprocketMotor::Command(double speed_radps) {
  command_radps_ = std::clamp(speed_radps, -options_.max_speed_radps, options_.max_speed_radps);
}

void SprocketMotor::Step(double dt_s, double load_torque_nm) {
  // Exact discretisation of the first-order reference lag.
  reference_radps_ +=
      (command_radps_ - reference_radps_) * (1.0 - std::exp(-dt_s / options_.time_constant_s));
  const double j = options_.inertia_kgm2, kv = options_.velocity_gain_nm_per_radps;
  const double b = options_.viscous_friction_nm_per_radps;
  // Implicit Euler on J ω' = kv (ω_ref − ω) + I − b ω − load.
  double next =
      (j * speed_radps_ + dt_s * (kv * reference_radps_ + integral_nm_ - load_torque_nm)) /
      (j + dt_s * (kv + b));
  torque_nm_ = kv * (reference_radps_ - next) + integral_nm_;
  saturated_ = std::abs(torque_nm_) > options_.max_torque_nm;
  if (saturated_) {
    // Saturated: the torque is the limit, the rest explicit in the load.
    torque_nm_ = std::copysign(options_.max_torque_nm, torque_nm_);
    next = (j * speed_radps_ + dt_s * (torque_nm_ - load_torque_nm)) / (j + dt_s * b);
  } else {
    // Integrate only while not saturated (anti-windup).
    integral_nm_ += options_.integral_gain_nm_per_rad * (reference_radps_ - next) * dt_s;
    integral_nm_ = std::clamp(integral_nm_, -options_.max_torque_nm, options_.max_torque_nm);
  }
  speed_radps_ = next;
  angle_rad_ += speed_radps_ * dt_s;
}

}  // namespace trackbed::robot
