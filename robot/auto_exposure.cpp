// Auto-exposure and gain (see auto_exposure.h).
#include "trackbed/robot/auto_exposure.h"

#include <algorithm>
#include <cmath>

#include "trackbed/common/option_error.h"

namespace trackbed::robot {

void AutoExposureOptions::Validate() const {
  option_check::InRange("auto_exposure.target_grey", target_grey, 1.0, 254.0);
  option_check::Positive("auto_exposure.time_constant_s", time_constant_s);
  option_check::Positive("auto_exposure.min_exposure_s", min_exposure_s);
  if (!(max_exposure_s >= min_exposure_s) || !std::isfinite(max_exposure_s)) {
    throw OptionError("auto_exposure.max_exposure_s", "must be >= min_exposure_s");
  }
  option_check::InRange("auto_exposure.max_gain", max_gain, 1.0, 1000.0);
}

AutoExposure::AutoExposure(const AutoExposureOptions& options, double initial_exposure_s)
    : o_(options) {
  o_.Validate();
  exposure_s_ = std::min(std::max(initial_exposure_s, o_.min_exposure_s), o_.max_exposure_s);
}

void AutoExposure::Update(double mean_grey, double dt_s) {
  const double total = exposure_s_ * gain_;
  const double wanted = total * o_.target_grey / std::max(mean_grey, 0.5);
  const double alpha = 1.0 - std::exp(-std::max(dt_s, 0.0) / o_.time_constant_s);
  const double next = std::exp(std::log(total) + alpha * (std::log(wanted) - std::log(total)));
  exposure_s_ = std::min(std::max(next, o_.min_exposure_s), o_.max_exposure_s);
  gain_ = std::min(std::max(next / exposure_s_, 1.0), o_.max_gain);
}

}  // namespace trackbed::robot
