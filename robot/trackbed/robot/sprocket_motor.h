// A sprocket drive: velocity command → first-order reference → torque-limited
// PI velocity servo (as in a motor driver's speed loop) driving the sprocket,
// track and rotor inertia.
#pragma once

namespace trackbed::robot {

struct SprocketMotorOptions {
  /// Time constant of the first-order lag between command and reference [s], > 0.
  double time_constant_s = 0.05;
  /// Proportional gain of the drive's velocity loop [N·m/(rad/s)], > 0.
  double velocity_gain_nm_per_radps = 30.0;
  /// Integral gain of the velocity loop [N·m/rad], >= 0 (0: P only, droops under load).
  double integral_gain_nm_per_rad = 600.0;
  /// Torque limit at the sprocket [N·m], > 0.
  double max_torque_nm = 20.0;
  /// Commands are clamped to ±this sprocket speed [rad/s], > 0.
  double max_speed_radps = 15.0;
  /// Sprocket + track + reflected rotor inertia about the sprocket axis [kg·m²], > 0.
  double inertia_kgm2 = 0.05;
  /// Viscous loss in the drivetrain and track [N·m/(rad/s)], >= 0.
  double viscous_friction_nm_per_radps = 0.3;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h). integral_gain_nm_per_rad
  /// is not a scenario key.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("time_constant_s", &time_constant_s);
    a->Visit("velocity_gain_nm_per_radps", &velocity_gain_nm_per_radps);
    a->Visit("max_torque_nm", &max_torque_nm);
    a->Visit("max_speed_radps", &max_speed_radps);
    a->Visit("inertia_kgm2", &inertia_kgm2);
    a->Visit("viscous_friction_nm_per_radps", &viscous_friction_nm_per_radps);
  }
};

/// State of one sprocket drive. Angle and speed are of the sprocket shaft, which
/// is what the encoder sees.
class SprocketMotor {
 public:
  explicit SprocketMotor(const SprocketMotorOptions& options);

  /// Sets the commanded sprocket speed [rad/s] (clamped to the limit).
  void Command(double speed_radps);
  /// Advances by `dt_s` with the ground's reaction torque `load_torque_nm`
  /// (opposing positive rotation when positive). The velocity loop is
  /// integrated implicitly, so a stiff gain is stable at a 1 ms step.
  void Step(double dt_s, double load_torque_nm);

  double angle_rad() const { return angle_rad_; }
  double speed_radps() const { return speed_radps_; }
  double torque_nm() const { return torque_nm_; }
  double command_radps() const { return command_radps_; }
  /// True when the last step's torque was at the limit.
  bool saturated() const { return saturated_; }

 private:
  SprocketMotorOptions options_;
  double command_radps_ = 0.0;
  double reference_radps_ = 0.0;
  double speed_radps_ = 0.0;
  double angle_rad_ = 0.0;
  double torque_nm_ = 0.0;
  double integral_nm_ = 0.0;
  bool saturated_ = false;
};

}  // namespace trackbed::robot
