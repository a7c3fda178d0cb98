// Wheel odometry of a tracked robot with slip estimation (Ham et al. 2012,
// eqs. 1–6), and the plain no-slip skid-steer odometry as its baseline.
//
// How we read the paper (docs/localization.md). Eqs. 1–2 compute each track's slip
// velocity from "the robot's velocity from the previous step" and the
// encoders; eqs. 3–5 then add the slip back to the track speeds. If the
// velocity in eqs. 1–2 were the odometry's own previous output, the two
// steps would cancel: v_k = v_{k−1} + r(ω_k − ω_{k−1}), which from rest is
// plain odometry — encoders alone cannot reveal slip. So the velocity in
// eqs. 1–2 is an independent measurement of the robot's motion: the velocity
// visual odometry measured over its last frame interval, when that frame was
// valid (enough inliers). Between valid frames the slip estimate is held,
// decaying toward zero with `slip_decay_time_s`. The fused velocity is never
// fed back: with w → 1 the slip estimate would freeze at whatever it was.
//
// Eq. 5 and eqs. 1–2 use the effective gauge B_eff = χ·B of a skid-steer
// vehicle (Martinez et al. 2005, Mandow et al. 2007), χ from a calibration run
// on the hard floor (scenes/calibration/icr_turns.yaml, docs/physics.md).
#pragma once

#include <cstdint>
#include <optional>

#include "trackbed/common/pose2.h"

namespace trackbed::estimation {

struct WheelOdometryOptions {
  // The robot's geometry (sprocket radii, gauge, χ: its given calibration; the encoders'
  // resolution) is known at run time, not set in a file of options: those fields are no
  // keys (see Serialize), and a scenario's runner sets them from the robot.
  /// Effective sprocket radius r [m] of the left track, and of the right one unless
  /// `right_sprocket_radius_m` is given (a calibration's per-track radii), > 0.
  double sprocket_radius_m = 0.10;
  std::optional<double> right_sprocket_radius_m;
  /// Nominal track gauge B [m], > 0.
  double track_gauge_m = 0.50;
  /// ICR expansion factor χ (B_eff = χ·B), >= 1 in practice, > 0.
  double icr_expansion = 1.0;
  /// Encoder counts per sprocket revolution, >= 1.
  int ticks_per_rev = 4096;
  /// Longitudinal offset d of the instantaneous centre of rotation [m] (eqs. 3–4):
  /// lateral body velocity = −d·ω.
  double icr_offset_m = 0.0;
  /// Estimate slip from measured velocities (Ham et al.); false: the no-slip baseline.
  bool estimate_slip = true;
  /// Time constant with which a held slip estimate decays toward zero [s], > 0, once
  /// no measurement has come for `slip_hold_s`.
  double slip_decay_time_s = 3.0;
  /// How long a slip measurement stays fresh [s] (a few camera periods), >= 0.
  double slip_hold_s = 0.3;
  /// Time constant of the low-pass filter on slip measurements [s], >= 0 (0: take each
  /// measurement whole). One visual-odometry interval is short and noisy, but the
  /// estimate's lag is the wheels' error: as a skid turn starts and ends the slip changes
  /// within a few frames, and each 0.1 s of lag is yaw the estimate has not caught up
  /// with. 0.2 s against 0.5 s over 30 outdoor seeds (docs/localization.md): the wheels
  /// alone 0.181 against 0.169 m ATE, the fused estimate, which takes the wheels'
  /// transients, 0.085 against 0.103 m.
  double slip_filter_time_s = 0.2;

  void Validate() const;

  /// The keys of the fields that are knobs (e.g. the scenario's `estimation.wheel.*`,
  /// docs/scenario_format.md), read and written by the config archive
  /// (trackbed/common/archive.h). Not visited: the calibration's fields (above) and
  /// estimate_slip, which the localization stack sets per estimator.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("icr_offset_m", &icr_offset_m);
    a->Visit("slip_decay_time_s", &slip_decay_time_s);
    a->Visit("slip_hold_s", &slip_hold_s);
    a->Visit("slip_filter_time_s", &slip_filter_time_s);
  }
};

/// The slip velocities of the two tracks [m/s], paper's sign (ground − track).
struct TrackSlip {
  double left_mps = 0.0;
  double right_mps = 0.0;
  double max_abs_mps() const;
};

/// Integrates encoder samples into a planar pose. Not copyable.
class WheelOdometry {
 public:
  WheelOdometry(const WheelOdometryOptions& options, const geometry::Pose2& initial_pose);
  WheelOdometry(const WheelOdometry&) = delete;
  WheelOdometry& operator=(const WheelOdometry&) = delete;

  /// One encoder sample (counts since start) at time `t_s`. The first sample
  /// only sets the reference. `yaw_increment_rad`: the heading's change since the last
  /// sample from another source (the gyro's), taken instead of the tracks' speed
  /// difference; the slip estimate still comes from both tracks (eqs. 1–2).
  void AddEncoderSample(double t_s, std::int64_t left_ticks, std::int64_t right_ticks,
                        std::optional<double> yaw_increment_rad = std::nullopt);
  /// Turns the pose's heading by `yaw_rad` in place (a correction from a measurement).
  void Rotate(double yaw_rad) { pose_.yaw = geometry::WrapAngle(pose_.yaw + yaw_rad); }

  /// An independent measurement of the body's forward speed [m/s] and yaw rate
  /// [rad/s] averaged over (t0_s, t1_s] — visual odometry over its last frame
  /// interval — updates the slip estimate with eqs. 1–2, using the encoders'
  /// mean speeds over the same interval. Ignored by the no-slip baseline.
  void AddMeasuredVelocity(double t0_s, double t1_s, double forward_mps, double yaw_rate_radps);

  const geometry::Pose2& pose() const { return pose_; }
  const TrackSlip& slip() const { return slip_; }
  /// Forward speed [m/s] and yaw rate [rad/s] of the last step (eqs. 3–5).
  double forward_mps() const { return forward_mps_; }
  double yaw_rate_radps() const { return yaw_rate_radps_; }

 private:
  double Angle(std::int64_t ticks) const;
  /// Sprocket angles at time t by linear interpolation in the sample history.
  bool AnglesAt(double t_s, double* left_rad, double* right_rad) const;

  WheelOdometryOptions options_;
  geometry::Pose2 pose_;
  TrackSlip slip_;
  double forward_mps_ = 0.0, yaw_rate_radps_ = 0.0;
  double last_measurement_t_ = -1e300;
  bool has_sample_ = false;
  double last_t_ = 0.0, last_left_ = 0.0, last_right_ = 0.0;
  // A short history of (t, left, right) sprocket angles for AddMeasuredVelocity.
  static constexpr int kHistory = 256;
  double hist_t_[kHistory] = {}, hist_l_[kHistory] = {}, hist_r_[kHistory] = {};
  int hist_count_ = 0, hist_next_ = 0;
};

}  // namespace trackbed::estimation
