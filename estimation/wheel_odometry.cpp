// Wheel odometry with slip estimation (see wheel_odometry.h).
#include "trackbed/estimation/wheel_odometry.h"

#include <algorithm>
#include <cmath>

#include "trackbed/common/option_error.h"

namespace trackbed::estimation {

void WheelOdometryOptions::Validate() const {
  option_check::Positive("sprocket_radius_m", sprocket_radius_m);
  if (right_sprocket_radius_m) {
    option_check::Positive("right_sprocket_radius_m", *right_sprocket_radius_m);
  }
  option_check::Positive("track_gauge_m", track_gauge_m);
  option_check::InRange("icr_expansion", icr_expansion, 0.2, 5.0);
  if (ticks_per_rev < 1) throw OptionError("ticks_per_rev", "must be >= 1");
  option_check::Finite("icr_offset_m", icr_offset_m);
  option_check::Positive("slip_decay_time_s", slip_decay_time_s);
  option_check::NonNegative("slip_filter_time_s", slip_filter_time_s);
  option_check::NonNegative("slip_hold_s", slip_hold_s);
}

double TrackSlip::max_abs_mps() const { return std::max(std::abs(left_mps), std::abs(right_mps)); }

WheelOdometry::WheelOdometry(const WheelOdometryOptions& options,
                             const geometry::Pose2& initial_pose)
    : options_(options), pose_(initial_pose) {
  options_.Validate();
}

double WheelOdometry::Angle(std::int64_t ticks) const {
  return static_cast<double>(ticks) * 2.0 * M_PI / options_.ticks_per_rev;
}

void WheelOdometry::AddEncoderSample(double t_s, std::int64_t left_ticks, std::int64_t right_ticks,
                                     std::optional<double> yaw_increment_rad) {
  const double left = Angle(left_ticks), right = Angle(right_ticks);
  hist_t_[hist_next_] = t_s;
  hist_l_[hist_next_] = left;
  hist_r_[hist_next_] = right;
  hist_next_ = (hist_next_ + 1) % kHistory;
  hist_count_ = std::min(hist_count_ + 1, kHistory);
  if (!has_sample_ || t_s <= last_t_) {
    has_sample_ = true;
    last_t_ = t_s;
    last_left_ = left;
    last_right_ = right;
    return;
  }
  const double dt = t_s - last_t_;
  const double r_l = options_.sprocket_radius_m;
  const double r_r = options_.right_sprocket_radius_m.value_or(r_l);
  const double gauge = options_.icr_expansion * options_.track_gauge_m;  // B_eff
  const double w_l = (left - last_left_) / dt, w_r = (right - last_right_) / dt;
  if (options_.estimate_slip && t_s - last_measurement_t_ > options_.slip_hold_s) {
    // Held slip decays toward zero while no new measurement arrives.
    const double decay = std::exp(-dt / options_.slip_decay_time_s);
    slip_.left_mps *= decay;
    slip_.right_mps *= decay;
  }
  // Ham et al. eqs. 3–5 in the body frame: forward speed, yaw rate, and the
  // lateral speed −d·ω from the ICR's longitudinal offset d.
  const double v_l = r_l * w_l + slip_.left_mps, v_r = r_r * w_r + slip_.right_mps;
  forward_mps_ = 0.5 * (v_r + v_l);
  yaw_rate_radps_ = yaw_increment_rad ? *yaw_increment_rad / dt : (v_r - v_l) / gauge;
  const double lateral = -options_.icr_offset_m * yaw_rate_radps_;
  // Eq. 6, integrated exactly for constant body velocities over the step.
  const double dyaw = yaw_rate_radps_ * dt;
  double dx, dy;
  if (std::abs(dyaw) < 1e-9) {
    dx = forward_mps_ * dt;
    dy = lateral * dt;
  } else {
    const double s = std::sin(dyaw) / yaw_rate_radps_, c = (1.0 - std::cos(dyaw)) / yaw_rate_radps_;
    dx = forward_mps_ * s - lateral * c;
    dy = forward_mps_ * c + lateral * s;
  }
  pose_ = Compose(pose_, {dx, dy, dyaw});
  last_t_ = t_s;
  last_left_ = left;
  last_right_ = right;
}

bool WheelOdometry::AnglesAt(double t_s, double* left_rad, double* right_rad) const {
  // Newest first: find the two samples bracketing t.
  for (int k = 0; k + 1 < hist_count_; ++k) {
    const int i1 = (hist_next_ - 1 - k + 2 * kHistory) % kHistory;
    const int i0 = (i1 - 1 + kHistory) % kHistory;
    if (hist_t_[i0] <= t_s && t_s <= hist_t_[i1]) {
      const double span = hist_t_[i1] - hist_t_[i0];
      const double a = span > 0 ? (t_s - hist_t_[i0]) / span : 1.0;
      *left_rad = hist_l_[i0] + a * (hist_l_[i1] - hist_l_[i0]);
      *right_rad = hist_r_[i0] + a * (hist_r_[i1] - hist_r_[i0]);
      return true;
    }
  }
  return false;
}

void WheelOdometry::AddMeasuredVelocity(double t0_s, double t1_s, double forward_mps,
                                        double yaw_rate_radps) {
  if (!options_.estimate_slip || !(t1_s > t0_s)) return;
  double l0, r0, l1, r1;
  if (!AnglesAt(t0_s, &l0, &r0) || !AnglesAt(t1_s, &l1, &r1)) return;
  const double dt = t1_s - t0_s, r_l = options_.sprocket_radius_m;
  const double r_r = options_.right_sprocket_radius_m.value_or(r_l);
  const double gauge = options_.icr_expansion * options_.track_gauge_m;
  // Ham et al. eqs. 1–2 with the body-frame forward speed cosθ·v_x + sinθ·v_y
  // measured by visual odometry, low-pass filtered over the measurement interval.
  const double left = forward_mps - gauge * yaw_rate_radps / 2.0 - r_l * (l1 - l0) / dt;
  const double right = forward_mps + gauge * yaw_rate_radps / 2.0 - r_r * (r1 - r0) / dt;
  const double gain =
      options_.slip_filter_time_s > 0.0 ? 1.0 - std::exp(-dt / options_.slip_filter_time_s) : 1.0;
  slip_.left_mps += gain * (left - slip_.left_mps);
  slip_.right_mps += gain * (right - slip_.right_mps);
  last_measurement_t_ = t1_s;
}

}  // namespace trackbed::estimation
