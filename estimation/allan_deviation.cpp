// Overlapping Allan deviation (see allan_deviation.h).
#include "trackbed/estimation/allan_deviation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace trackbed::estimation {

std::vector<double> OverlappingAllanDeviation(const std::vector<double>& rate, double dt_s,
                                              const std::vector<double>& taus_s) {
  // The integral of the rate less its mean: the second differences are the same, and
  // the sums stay small enough to keep their digits over millions of samples.
  double mean = 0.0;
  for (const double x : rate) mean += x;
  mean /= rate.empty() ? 1.0 : static_cast<double>(rate.size());
  std::vector<double> theta(rate.size() + 1, 0.0);
  for (std::size_t k = 0; k < rate.size(); ++k) theta[k + 1] = theta[k] + (rate[k] - mean) * dt_s;
  return OverlappingAllanDeviationOfIntegral(theta, dt_s, taus_s);
}

std::vector<double> OverlappingAllanDeviationOfIntegral(const std::vector<double>& theta,
                                                        double dt_s,
                                                        const std::vector<double>& taus_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("Allan deviation: dt must be > 0");
  std::vector<double> out;
  for (const double tau : taus_s) {
    const auto m = static_cast<std::size_t>(std::max(1.0, std::round(tau / dt_s)));
    if (theta.size() < 2 * m + 1) {
      throw std::invalid_argument("Allan deviation: " + std::to_string(theta.size()) +
                                  " points are too few for tau " + std::to_string(tau) + " s");
    }
    const std::size_t terms = theta.size() - 2 * m;
    double sum = 0.0;
    for (std::size_t k = 0; k < terms; ++k) {
      const double d = theta[k + 2 * m] - 2.0 * theta[k + m] + theta[k];
      sum += d * d;
    }
    const double t = static_cast<double>(m) * dt_s;
    out.push_back(std::sqrt(sum / (2.0 * t * t * static_cast<double>(terms))));
  }
  return out;
}

}  // namespace trackbed::estimation
