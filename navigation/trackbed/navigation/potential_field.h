// Artificial potential field with the goal-nearby correction of Ge & Cui 2000
// ("New potential functions for mobile robot path planning", IEEE T-RA 16(5)): the
// baseline Jung & Kim 2014 compare with. Method name "potential_field".
//
// Attraction U_att = ½ ξ ρ_g² (ρ_g the distance to the goal) gives F_att = ξ (p_g − p).
// Repulsion of each obstacle within the influence range ρ0:
//   U_rep = ½ η (1/ρ − 1/ρ0)² ρ_g^n,
// ρ the distance from the robot's footprint edge to the obstacle's surface. The factor
// ρ_g^n is Ge & Cui's correction: the repulsion vanishes at the goal, so the goal is the
// global minimum even when an obstacle lies within ρ0 of it (the "goal non-reachable
// with obstacles nearby" problem of the plain field). Its negative gradient has two parts,
//   F_rep1 = η (1/ρ − 1/ρ0) ρ_g^n / ρ²    along n_OR (obstacle → robot),
//   F_rep2 = (n/2) η (1/ρ − 1/ρ0)² ρ_g^(n−1)  along n_RG (robot → goal).
// The total force F is read as a desired velocity [m/s]: the desired heading is its
// direction and the desired speed its magnitude (capped, and limited so that one control
// period covers at most half the clearance: a step guard); a proportional heading
// controller turns the robot toward it, slowing with cos(heading error) and turning in
// place when the error is large. Within `final_distance_m` of the goal the robot turns
// in place to the goal heading, so the success criterion (0.1 m, 2°) can be met.
//
// Exponent n = 1 (Ge & Cui allow any n > 0): with it the ratio of repulsion to attraction
// no longer depends on the goal distance — head-on, the two balance at the footprint
// distance ρ* with ξ = η (1/ρ* − 1/ρ0)/ρ*², wherever the goal is. With n = 2 the
// repulsion 8 m from the goal is 64 times that 1 m from it, and the random fields fill
// with local minima (55 of 100 stalled in our first runs).
//
// Gains tuned once on the paper's two scenes and then fixed (`navigation_study --tune`:
// grid ξ ∈ {1, 2, 4} /s, ρ0 ∈ {1, 1.5, 2, 3} m, ρ* ∈ {0.2, 0.4, 0.6, 0.8} m; rule: both
// goals reached keeping the clearance the sub-goal method keeps by construction —
// d_max − footprint = 0.65 m, floor 0.6 m ("equal safety": a path that passes closer is
// always shorter) — then the shortest path within 1 %, then the shortest time):
// ξ = 1 /s, ρ0 = 3 m, ρ* = 0.8 m, i.e. η = 0.698 m³/s (the defaults). With a 0.1 m floor
// instead the rule picks ρ* = 0.2 m, whose paper-scene paths are shorter than the
// sub-goal method's but which collides in most random fields.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "trackbed/common/units.h"
#include "trackbed/navigation/circle_obstacle.h"
#include "trackbed/navigation/navigation_setup.h"
#include "trackbed/navigation/navigator.h"

namespace trackbed::navigation {

struct PotentialFieldOptions {
  /// ξ [1/s], > 0: attraction F_att = ξ (p_goal − p).
  double attractive_gain_per_s = 1.0;
  /// η [m^(4−n)/s], >= 0: repulsion gain (ξ ρ*²/(1/ρ* − 1/ρ0) for the balance distance ρ*).
  double repulsive_gain = 0.64 / (1.0 / 0.8 - 1.0 / 3.0);  // ρ* = 0.8 m
  /// ρ0 [m], > 0: obstacles farther than this (footprint edge to surface) do not repel.
  double influence_range_m = 3.0;
  /// n, >= 0: exponent of the goal distance in Ge & Cui's repulsion; 0 is the plain,
  /// uncorrected field (Khatib 1986), kept for comparison.
  double goal_exponent = 1.0;
  /// Footprint radius [m], >= 0: distances ρ are measured from the footprint's edge. Not
  /// a key of this struct: a run sets it from the scenario's footprint
  /// (`navigation.footprint_radius_m`; closed loop: at least the hull's half diagonal).
  double robot_radius_m = 0.35;
  /// ρ is clamped below at this [m], > 0, so the force stays finite on contact.
  double min_distance_m = 0.02;
  /// Speed cap [m/s], > 0 (wheel saturation applies as well).
  double max_speed_mps = 5.0;
  /// Step guard, in (0, 1]: one control period never covers more than this fraction of
  /// the footprint's clearance to the nearest obstacle (v ≤ f·clearance/Δt). The
  /// field is followed by explicit steps of up to 0.5 m; without the guard a step
  /// overshoots the stiff 1/ρ² repulsion into the obstacle. Fixed, not tuned.
  double clearance_step_fraction = 0.5;
  /// Heading controller gain [1/s], > 0: ω = k (heading of F − yaw).
  double heading_gain_per_s = 5.0;
  /// Yaw-rate cap [rad/s], > 0.
  double max_yaw_rate_radps = 6.0;
  /// Heading error beyond which the robot turns in place [rad], in (0, π].
  double turn_in_place_rad = units::Radians(60.0);
  /// Within this distance of the goal [m], > 0, the robot stops and turns to the goal
  /// heading; keep it below the goal position tolerance.
  double final_distance_m = 0.05;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `navigation.potential_field`), read and written by the config archive
  /// (trackbed/common/archive.h); robot_radius_m is set by the run (above).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("attractive_gain_per_s", &attractive_gain_per_s);
    a->Visit("repulsive_gain", &repulsive_gain);
    a->Visit("influence_range_m", &influence_range_m);
    a->Visit("goal_exponent", &goal_exponent);
    a->Visit("min_distance_m", &min_distance_m);
    a->Visit("max_speed_mps", &max_speed_mps);
    a->Visit("clearance_step_fraction", &clearance_step_fraction);
    a->Visit("heading_gain_per_s", &heading_gain_per_s);
    a->Visit("max_yaw_rate_radps", &max_yaw_rate_radps);
    a->Visit("turn_in_place_rad", &turn_in_place_rad);
    a->Visit("final_distance_m", &final_distance_m);
  }
};

/// The field's force at one position, read as a velocity [m/s] in the world frame.
struct PotentialFieldForce {
  Eigen::Vector2d attractive = Eigen::Vector2d::Zero();
  Eigen::Vector2d repulsive = Eigen::Vector2d::Zero();  ///< Sum over obstacles.
  Eigen::Vector2d total = Eigen::Vector2d::Zero();
  int repelling_obstacles = 0;  ///< Obstacles within the influence range.
};

/// −∇(U_att + Σ U_rep) at `p_world` for a goal at `goal_world`. Pure.
PotentialFieldForce ComputePotentialFieldForce(const PotentialFieldOptions& options,
                                               const Eigen::Vector2d& p_world,
                                               const Eigen::Vector2d& goal_world,
                                               const std::vector<Circle>& obstacles);

/// The potential field as a Navigator (its run ends by NavigationChecks, navigator.h).
class PotentialFieldNavigator final : public Navigator {
 public:
  /// Validates all options (throws OptionError naming the field).
  PotentialFieldNavigator(const NavigationSetup& setup, const PotentialFieldOptions& options,
                          const ProgressCheckerOptions& progress, const Pose2& goal);

  NavigationCommand Update(const Pose2& pose, const std::vector<Circle>& obstacles) override;
  const char* method() const override { return "potential_field"; }
  const Pose2& goal() const override { return goal_; }

 private:
  /// The method's own part of Update: the field's command into `command`.
  void Drive(const Pose2& pose, const std::vector<Circle>& obstacles, NavigationCommand* command);

  NavigationSetup setup_;
  PotentialFieldOptions options_;
  Pose2 goal_;
  NavigationChecks checks_;
};

}  // namespace trackbed::navigation
