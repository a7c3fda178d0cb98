// Gauss–Newton wheel-speed control to a target pose (Jung & Kim 2014, §2.2–2.3).
//
// The pose error e = q_target' − q (eq. 3) uses a modified target heading (eq. 4):
// while the position error exceeds ε the target heading is the bearing from the robot
// to the target; within ε it is the target's own heading. The weighted error (eq. 5)
// uses W = diag(w_p, w_p, ρ):
//   - turn phase, far from the target and |bearing − heading| > heading band:
//     ρ = 1 ("turn in place first");
//   - drive phase, heading within the band of the bearing: ρ = 0, w_p = 1 (position only);
//   - final phase, within ε: the target's heading with ρ = 1, w_p = 1 (turn to the goal
//     heading at the end).
// One Gauss–Newton step on the wheel angles minimises ½ eᵀWe (eqs. 6–12) with the
// Jacobian of eq. (2) (WheelJacobian); wheel speeds = Δφ / Δt, then proportional
// saturation (SaturateProportionally).
//
// Two readings of ours, both options:
//
// * Damping, not a pseudo-inverse. In the drive phase JᵀWJ = (r/2)²[1 1; 1 1] has rank 1
//   (a position error across the heading cannot be removed by any wheel motion), and in
//   the turn phase (with w_p = 0, below) JᵀWJ = (r/W)²[1 −1; −1 1]. We solve
//   Δφ = (JᵀWJ + λI)⁻¹ JᵀWe (Levenberg–Marquardt) with a small λ. Both reachable
//   directions ([1 1] and [−1 1]) are eigenvectors of every JᵀWJ met here, so for
//   λ → 0 the step tends to the pseudo-inverse solution (the minimum-norm least-squares
//   step); the damped form needs no rank decision or singular-value threshold, is
//   continuous in the weights, and λ = 1e-9 against eigenvalues of 2(r/2)² = 0.02
//   and 2(r/W)² = 0.32 shortens the step by less than 1e-7 (relative).
//
// * The position weight while turning. Taken literally, W = diag(1, 1, 1) in the turn
//   phase gives the least-squares step "drive by the along-heading position error and
//   turn by the heading error" at once; after proportional saturation the position term
//   dominates (at the start of the paper's left scene the robot would reverse at almost
//   5 m/s while turning slowly). That contradicts the paper's description and figs. 5–6
//   (the robot turns in place before moving; the 0.5–1.5 s stalls of fig. 8 are turns in
//   place). We therefore weight position by `turn_position_weight` in the turn phase:
//   0 (default) turns in place exactly; 1 is the literal diag(1, 1, 1).
//
// Equation numbers are those the paper's text refers to (the typeset equations are lost
// in our copy of Jung & Kim 2014); docs/navigation.md maps them to code.
//
// The step is deadbeat: an unsaturated step removes the weighted error in one control
// period (the robot stops on the point of its heading line nearest the target, or
// finishes a turn), which is why no further gain appears.
//
// * A final approach (`final_approach_radius_m` > 0; off at 0, the paper's rule). On a
//   robot that skids, each turn in place near the target moves it by centimetres, so
//   the position error crosses ε back and forth: eq. (4)'s target heading then flips
//   between the target's own and the bearing to the target, which near the target can
//   point anywhere (behind the robot: a turn of up to 180°, then a turn back). Within
//   the radius the approach takes the bearing's line in the direction nearer the
//   robot's heading (it backs up to a target behind it, turning by at most 90°), and
//   the final phase, once begun, holds while the position error stays within the
//   radius (a hysteresis on ε), ending early only when its turn is done (heading
//   within the stop tolerance) and the position is not: a cross-track error the final
//   phase cannot remove, which a new approach along the bearing's line does.
//
// * A final-phase time constant (`final_time_constant_s` > 0; off at 0, the deadbeat
//   step). On a tracked robot the deadbeat final turn, saturated at the yaw-rate limit,
//   reverses at full rate each time it passes the goal's heading, and the chassis goes
//   on turning the old way for a tenth of a second or more (the tracks' lag and their
//   shear against the ground): a limit cycle about the goal's heading. With the time
//   constant the final phase's step is spread over max(Δt, τ) instead of Δt: a
//   proportional law of gain 1/τ, so the rate falls as the heading nears the goal's and
//   the turn ends without a reversal when τ is long enough against the lag.
#pragma once

#include "trackbed/common/units.h"
#include "trackbed/navigation/diff_drive.h"
#include "trackbed/navigation/navigation_setup.h"

namespace trackbed::navigation {

struct GaussNewtonOptions {
  /// ε of eq. (4) [m], > 0: beyond it the target heading is the bearing to the target;
  /// within it, the target's own heading (final turn). Keep it below the goal position
  /// tolerance so the final turn starts inside the success radius.
  double epsilon_m = 0.05;
  /// Heading band [rad], in (0, π): ρ = 1 (turn) until |bearing − heading| is within it,
  /// then ρ = 0 (drive). The paper calls it "the set range" without a value.
  double heading_band_rad = units::Radians(5.0);
  /// Levenberg–Marquardt damping λ [m²/rad² — the units of JᵀWJ], > 0.
  double damping = 1e-9;
  /// Weight of the position error during the turn phase, in [0, 1]; see the file
  /// comment (0 = turn in place, the paper's behaviour; 1 = literal diag(1, 1, 1)).
  double turn_position_weight = 0.0;
  /// Final-approach radius [m], >= 0; 0 = off (eq. (4) as the paper has it). Within
  /// it a target behind the robot is backed up to, and the final phase holds once
  /// begun (see the file comment). Larger than `epsilon_m` when set.
  double final_approach_radius_m = 0.0;
  /// Final-phase time constant τ [s], >= 0; 0 = off (the deadbeat step over one control
  /// period). When larger than the control period, the final phase's wheel speeds are
  /// its step over τ (see the file comment).
  double final_time_constant_s = 0.0;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `navigation.gauss_newton`), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("epsilon_m", &epsilon_m);
    a->Visit("heading_band_rad", &heading_band_rad);
    a->Visit("damping", &damping);
    a->Visit("turn_position_weight", &turn_position_weight);
    a->Visit("final_approach_radius_m", &final_approach_radius_m);
    a->Visit("final_time_constant_s", &final_time_constant_s);
  }
};

/// Which weight phase a step was in (see the file comment).
enum class GaussNewtonPhase { kTurn, kDrive, kFinal };

/// One control step: the command and why.
struct GaussNewtonStep {
  WheelSpeeds wheels;  ///< After proportional saturation [rad/s].
  BodyTwist twist;     ///< The body twist of `wheels`.
  GaussNewtonPhase phase = GaussNewtonPhase::kTurn;
  double rho = 1.0;                 ///< Heading weight ρ used (1 or 0).
  double target_heading_rad = 0.0;  ///< Modified target heading of eq. (4).
  double position_error_m = 0.0;    ///< Distance to the target.
  double heading_error_rad = 0.0;   ///< target_heading − yaw, wrapped.
  bool reverse = false;             ///< The final approach backs up to the target (file comment).
  /// Distance within the goal position tolerance and the heading within the goal
  /// heading tolerance *of the target's own heading* (the run's success criterion).
  bool at_goal = false;
  bool saturated = false;  ///< The raw Gauss–Newton wheel speeds exceeded the limit.
};

/// One Gauss–Newton step from `pose` toward `target` (a pose: position and heading).
/// Pure; `setup` and `options` are assumed validated. Returns zero wheel speeds when
/// at_goal. `final_begun`: the previous step toward the same target was in the final
/// phase (read only with `final_approach_radius_m` > 0).
GaussNewtonStep ComputeGaussNewtonStep(const NavigationSetup& setup,
                                       const GaussNewtonOptions& options, const Pose2& pose,
                                       const Pose2& target, bool final_begun = false);

}  // namespace trackbed::navigation
