// The dynamic window approach (Fox, Burgard & Thrun 1997, "The dynamic window
// approach to collision avoidance", IEEE RAM 4(1)). Method name "dwa".
//
// Search space: velocities (v, ω) with 0 ≤ v ≤ v_max, |ω| ≤ ω_max and both wheels
// within the wheel-speed limit, restricted to the dynamic window reachable from the
// current velocity within one control period under the acceleration limits, sampled on a
// regular grid. Each sample is a circular arc. Admissible: the robot can stop before the
// first obstacle on its arc (the paper's V_a, v ≤ √(2·dist·a_v)), here with the period
// of delay before braking can start: v·Δt + v²/(2·a_v) ≤ dist. Objective
//   G(v, ω) = α·heading + β·dist + γ·velocity,
// each term normalised to [0, 1] by its largest value over the admissible samples:
//   heading  = 1 − |angle to the goal| / π at the pose reached after one control period
//              followed by a full stop (Fox et al.'s predicted position);
//   dist     = arc length to the first collision on the arc, capped at clearance_cap_m
//              (a collision = the footprint's clearance below safety_margin_m, or below
//              its present clearance if that is smaller, so a robot inside the margin can
//              still move away);
//   velocity = v / v_max.
// Two usual additions so the robot can finish: v is also capped by √(2·a_v·ρ_g) and
// ρ_g/Δt (it can stop at the goal, ρ_g the goal distance), and within final_distance_m
// of the goal it brakes and turns to the goal heading within the window.
//
// Tuned once on the paper's two scenes and then fixed (`navigation_study --tune`: grid
// α = 1, β ∈ {0.2, 0.5, 1, 2}, γ ∈ {0.2, 0.5, 1}, cap ∈ {1.5, 3} m, a_v ∈ {2.5, 5} m/s²,
// with the safety margin set to the clearance the sub-goal method keeps, d_max −
// footprint = 0.65 m, and the potential field's rule): α = 1, β = 2, γ = 1, cap 1.5 m,
// a_v = 2.5 m/s², with a_ω = 20 rad/s², ω_max = 5 rad/s and 11 × 21 samples fixed
// beforehand. Fox et al.'s own α = 2, β = γ = 0.2 (with our normalisation) stop facing the
// point obstacle of the paper's right-hand scene: the heading term holds the robot there.
#pragma once

#include <vector>

#include "trackbed/navigation/circle_obstacle.h"
#include "trackbed/navigation/navigation_setup.h"
#include "trackbed/navigation/navigator.h"

namespace trackbed::navigation {

struct DynamicWindowOptions {
  /// v_max [m/s], > 0 (the wheel-speed limit applies as well).
  double max_speed_mps = 5.0;
  /// ω_max [rad/s], > 0.
  double max_yaw_rate_radps = 5.0;
  /// Linear acceleration and braking limit a_v [m/s²], > 0.
  double max_accel_mps2 = 2.5;
  /// Angular acceleration limit a_ω [rad/s²], > 0.
  double max_yaw_accel_radps2 = 20.0;
  /// Grid samples over the window in v and in ω, >= 2 each.
  int speed_samples = 11;
  int yaw_rate_samples = 21;
  /// Objective weights α (heading), β (dist), γ (velocity), >= 0, not all 0.
  double heading_weight = 1.0;
  double clearance_weight = 2.0;
  double velocity_weight = 1.0;
  /// Arc length beyond which an arc counts as free [m], > 0.
  double clearance_cap_m = 1.5;
  /// Arcs are checked for collisions every this many metres, > 0.
  double arc_step_m = 0.05;
  /// Footprint radius [m], >= 0. Not a key of this struct: a run sets it from the
  /// scenario's footprint (`navigation.footprint_radius_m`; closed loop: at least the
  /// hull's half diagonal).
  double robot_radius_m = 0.35;
  /// The clearance below which an arc counts as blocked [m], >= 0 (0.65 = d_max −
  /// footprint, the sub-goal method's clearance).
  double safety_margin_m = 0.65;
  /// Within this distance of the goal [m], > 0, brake and turn to the goal heading.
  double final_distance_m = 0.05;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `navigation.dwa`), read and written by the config archive
  /// (trackbed/common/archive.h); robot_radius_m is set by the run (above).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("max_speed_mps", &max_speed_mps);
    a->Visit("max_yaw_rate_radps", &max_yaw_rate_radps);
    a->Visit("max_accel_mps2", &max_accel_mps2);
    a->Visit("max_yaw_accel_radps2", &max_yaw_accel_radps2);
    a->Visit("speed_samples", &speed_samples);
    a->Visit("yaw_rate_samples", &yaw_rate_samples);
    a->Visit("heading_weight", &heading_weight);
    a->Visit("clearance_weight", &clearance_weight);
    a->Visit("velocity_weight", &velocity_weight);
    a->Visit("clearance_cap_m", &clearance_cap_m);
    a->Visit("arc_step_m", &arc_step_m);
    a->Visit("safety_margin_m", &safety_margin_m);
    a->Visit("final_distance_m", &final_distance_m);
  }
};

/// The chosen velocity and why.
struct DynamicWindowChoice {
  BodyTwist twist;
  int admissible = 0;      ///< Admissible samples in the window.
  double objective = 0.0;  ///< G of the chosen sample (normalised terms).
  bool braking = false;    ///< No sample was admissible: maximal braking.
};

/// One DWA decision from `pose` moving at `current` toward `goal_world`. Pure.
DynamicWindowChoice ChooseDynamicWindowVelocity(const NavigationSetup& setup,
                                                const DynamicWindowOptions& options,
                                                const Pose2& pose, const BodyTwist& current,
                                                const Eigen::Vector2d& goal_world,
                                                const std::vector<Circle>& obstacles);

/// The dynamic window as a Navigator. Its window is centred on the twist measured
/// before each decision (SetMeasuredTwist) where one is given, else on its previous
/// command.
class DynamicWindowNavigator final : public Navigator {
 public:
  /// Validates all options (throws OptionError naming the field).
  DynamicWindowNavigator(const NavigationSetup& setup, const DynamicWindowOptions& options,
                         const ProgressCheckerOptions& progress, const Pose2& goal);

  /// Its run ends by NavigationChecks (navigator.h); an ended run's velocity is zero.
  NavigationCommand Update(const Pose2& pose, const std::vector<Circle>& obstacles) override;
  const char* method() const override { return "dwa"; }
  const Pose2& goal() const override { return goal_; }
  /// The next decision's window starts from `twist` (the robot's, measured).
  void SetMeasuredTwist(const BodyTwist& twist) override { current_ = twist; }

 private:
  /// The method's own part of Update: the window's choice (or the final turn) into
  /// `command`, which becomes the current velocity.
  void Drive(const Pose2& pose, const std::vector<Circle>& obstacles, NavigationCommand* command);

  NavigationSetup setup_;
  DynamicWindowOptions options_;
  Pose2 goal_;
  NavigationChecks checks_;
  BodyTwist current_;
};

}  // namespace trackbed::navigation
