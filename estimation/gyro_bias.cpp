// The gyro's bias from zero-velocity intervals (see gyro_bias.h).
#include "trackbed/estimation/gyro_bias.h"

#include <cmath>
#include <cstdlib>

#include "trackbed/common/option_error.h"

namespace trackbed::estimation {

void GyroModel::Validate() const {
  option_check::NonNegative("noise_density", noise_density);
  option_check::NonNegative("bias_random_walk", bias_random_walk);
  option_check::NonNegative("bias_instability_std", bias_instability_std);
  option_check::NonNegative("turn_on_bias_std", turn_on_bias_std);
}

double GyroModel::RotationVariance(double dt_s, double bias_variance) const {
  const double bias_var = bias_variance + bias_instability_std * bias_instability_std;
  return bias_var * dt_s * dt_s + noise_density * noise_density * dt_s;
}

void GyroHeadingOptions::Validate() const {
  option_check::Positive("standstill_window_s", standstill_window_s);
  option_check::Positive("vertical_filter_time_s", vertical_filter_time_s);
}

ZeroVelocityGyroBias::ZeroVelocityGyroBias(const GyroModel& model, double standstill_window_s)
    : model_(model), window_s_(standstill_window_s) {
  model_.Validate();
  option_check::Positive("standstill_window_s", window_s_);
  variance_.setConstant(model_.turn_on_bias_std * model_.turn_on_bias_std);
}

void ZeroVelocityGyroBias::AddEncoderSample(double t_s, long long left_ticks,
                                            long long right_ticks) {
  // A count may toggle by one at a tick's edge while the robot stands (the chassis
  // rocks on its suspension): only a departure of more than a tick from the counts the
  // standstill began at counts as motion.
  if (!has_encoder_ || std::llabs(left_ticks - left_) > kStandstillTicks ||
      std::llabs(right_ticks - right_) > kStandstillTicks) {
    t_counts_changed_ = t_s;
    left_ = left_ticks;
    right_ = right_ticks;
  }
  has_encoder_ = true;
  standstill_ = t_s - t_counts_changed_ >= window_s_;
  // The samples up to this one are settled: measurements when the robot still stands,
  // else (counts changed since, the motion may have begun before) only time.
  while (!pending_.empty() && pending_.front().t1_s <= t_s) {
    Use(pending_.front());
    pending_.pop_front();
  }
}

void ZeroVelocityGyroBias::AddGyroSample(double t_s, const Eigen::Vector3d& rate_radps) {
  const bool first = !has_gyro_;
  const double t0 = t_gyro_;
  has_gyro_ = true;
  t_gyro_ = t_s;
  if (first || !(t_s > t0)) return;
  pending_.push_back({t0, t_s, rate_radps});
}

void ZeroVelocityGyroBias::Use(const GyroInterval& sample) {
  const double dt = sample.t1_s - sample.t0_s;
  const double walk = model_.bias_random_walk * model_.bias_random_walk * dt;
  variance_.array() += walk;
  // The sample's white noise, averaged over its interval: variance N²/Δt. A rate beyond
  // five of its σ and three turn-on σ is motion the encoders do not see (the chassis
  // settling on its suspension), not the bias.
  const double noise = model_.noise_density * model_.noise_density / dt;
  const double limit = 5.0 * std::sqrt(noise) + 3.0 * model_.turn_on_bias_std;
  if (!standstill_ || sample.rate_radps.cwiseAbs().maxCoeff() > limit) return;
  for (int i = 0; i < 3; ++i) {
    const double total = variance_(i) + noise;
    const double gain = total > 0.0 ? variance_(i) / total : 0.0;
    bias_(i) += gain * (sample.rate_radps(i) - bias_(i));
    variance_(i) *= 1.0 - gain;
  }
  standstill_s_ += dt;
}

}  // namespace trackbed::estimation
