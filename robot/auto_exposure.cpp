// Auto-exposure and gain (see auto_exposure.h).
#include "trackbed/robot/auto_exposure.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

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
  const Eigen::Vector4d& w = metering_window;
  if (!(w.allFinite() && w[0] >= 0.0 && w[1] >= 0.0 && w[0] < w[2] && w[1] < w[3] && w[2] <= 1.0 &&
        w[3] <= 1.0)) {
    throw OptionError("auto_exposure.metering_window",
                      "must be [left, top, right, bottom] with 0 <= left < right <= 1 and "
                      "0 <= top < bottom <= 1");
  }
}

AutoExposure::AutoExposure(const AutoExposureOptions& options, double initial_exposure_s)
    : o_(options) {
  o_.Validate();
  exposure_s_ = std::min(std::max(initial_exposure_s, o_.min_exposure_s), o_.max_exposure_s);
}

double AutoExposure::Meter(const GrayImage& image) const {
  if (image.width == 0 || image.height == 0) return 0.0;
  // The window's pixel bounds, at least one pixel (a window narrower than a pixel).
  const Eigen::Vector4d& w = o_.metering_window;
  const auto span = [](double lo, double hi, int n, int* first, int* end) {
    *first = std::min(static_cast<int>(std::lround(lo * n)), n - 1);
    *end = std::clamp(static_cast<int>(std::lround(hi * n)), *first + 1, n);
  };
  int u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  span(w[0], w[2], image.width, &u0, &u1);
  span(w[1], w[3], image.height, &v0, &v1);
  std::uint64_t sum = 0;
  for (int v = v0; v < v1; ++v) {
    const std::uint8_t* row = &image.pixels[static_cast<std::size_t>(v) * image.width];
    for (int u = u0; u < u1; ++u) sum += row[u];
  }
  return static_cast<double>(sum) / (static_cast<double>(u1 - u0) * (v1 - v0));
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
