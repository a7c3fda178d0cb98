// The fusion's applied wheel weight w over time: it falls to the rule base's weight
// at once and rises toward it with a time constant. The slip estimate lags the ground
// by its filter and hold times, so the wheels' errors outlast the slip episode that
// caused them; a weight that returned to the wheels as fast as the estimated slip
// fades would keep one half of each such error pair (docs/localization.md).
#pragma once

#include <cmath>

namespace trackbed::estimation {

class FusionWeightRise {
 public:
  /// `rise_time_s` >= 0 (FusionOptions::weight_rise_time_s); 0: the rule
  /// base's weight each frame as it is. The weight starts at 1 (the wheels).
  explicit FusionWeightRise(double rise_time_s) : rise_time_s_(rise_time_s) {}

  /// The weight after a frame `dt_s` after the previous one whose rule weight is
  /// `w_rule`: w_rule when it is lower (or dt_s is not positive, or no rise time),
  /// else w + (1 − exp(−dt/τ))·(w_rule − w).
  double Update(double w_rule, double dt_s) {
    if (w_rule <= w_ || rise_time_s_ <= 0.0 || !(dt_s > 0.0)) {
      w_ = w_rule;
    } else {
      w_ += (1.0 - std::exp(-dt_s / rise_time_s_)) * (w_rule - w_);
    }
    return w_;
  }
  double weight() const { return w_; }

 private:
  double rise_time_s_;
  double w_ = 1.0;
};

}  // namespace trackbed::estimation
