// ICR expansion factor fit (see icr_calibration.h).
#include "trackbed/estimation/icr_calibration.h"

#include <cmath>

namespace trackbed::estimation {

IcrFit FitIcrExpansion(const std::vector<IcrSample>& samples, double min_yaw_rate_radps) {
  double sxy = 0.0, sxx = 0.0;
  IcrFit fit;
  for (const IcrSample& s : samples) {
    if (std::abs(s.reference_yaw_rate_radps) < min_yaw_rate_radps) continue;
    sxy += s.reference_yaw_rate_radps * s.encoder_yaw_rate_radps;
    sxx += s.reference_yaw_rate_radps * s.reference_yaw_rate_radps;
    ++fit.samples_used;
  }
  if (fit.samples_used == 0) return fit;
  fit.chi = sxy / sxx;
  double sse = 0.0;
  for (const IcrSample& s : samples) {
    if (std::abs(s.reference_yaw_rate_radps) < min_yaw_rate_radps) continue;
    const double e = s.encoder_yaw_rate_radps - fit.chi * s.reference_yaw_rate_radps;
    sse += e * e;
  }
  fit.rms_residual_radps = std::sqrt(sse / fit.samples_used);
  return fit;
}

}  // namespace trackbed::estimation
