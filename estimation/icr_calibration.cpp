// ICR expansion factor fit (see icr_calibration.h).
#include "trackbed/estimation/icr_calibration.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

void RunningIcrFit::Add(const IcrSample& s) {
  if (std::abs(s.reference_yaw_rate_radps) < min_yaw_rate_radps_) return;
  sxy_ += s.reference_yaw_rate_radps * s.encoder_yaw_rate_radps;
  sxx_ += s.reference_yaw_rate_radps * s.reference_yaw_rate_radps;
  syy_ += s.encoder_yaw_rate_radps * s.encoder_yaw_rate_radps;
  ++used_;
}

IcrFit RunningIcrFit::Fit() const {
  IcrFit fit;
  fit.samples_used = used_;
  if (used_ == 0) return fit;
  fit.chi = sxy_ / sxx_;
  // Σ (y − χx)² = Σy² − 2χΣxy + χ²Σx² = Σy² − χΣxy at χ = Σxy / Σx².
  fit.rms_residual_radps = std::sqrt(std::max(syy_ - fit.chi * sxy_, 0.0) / used_);
  return fit;
}

double RigidPlasticIcrExpansion(const std::vector<double>& station_x_m, double half_track_m) {
  const double c = half_track_m;
  if (!(c > 0.0)) throw std::invalid_argument("RigidPlasticIcrExpansion: half_track_m must be > 0");
  double max_x = 0.0;
  for (double x : station_x_m) max_x = std::max(max_x, std::abs(x));
  if (max_x == 0.0) {
    throw std::invalid_argument("RigidPlasticIcrExpansion: needs a station off the axle");
  }
  // The moment Σ (c e − x²)/√(e² + x²) rises monotonically in e from −Σ|x| at 0
  // to +Σ c at infinity; its root lies in (0, max x² / c]. Bisection to 1e-15.
  auto moment = [&](double e) {
    double m = 0.0;
    for (double x : station_x_m) m += (c * e - x * x) / std::hypot(e, x);
    return m;
  };
  double lo = 0.0, hi = max_x * max_x / c;
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (moment(mid) > 0.0 ? hi : lo) = mid;
  }
  return (c + 0.5 * (lo + hi)) / c;
}

}  // namespace trackbed::estimation
