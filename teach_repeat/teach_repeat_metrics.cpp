// Teach & repeat scores (see teach_repeat_metrics.h).
#include "trackbed/teach_repeat/teach_repeat_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "trackbed/common/option_error.h"

namespace trackbed::teach_repeat {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

void PathProjectionOptions::Validate() const { option_check::Positive("window_m", window_m); }

double PolylineLength(const std::vector<Eigen::Vector2d>& path) {
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  return length;
}

RecoveryMetrics EvaluateRecovery(const std::vector<RecoveryCounts>& places) {
  RecoveryMetrics r;
  double rate_sum = 0.0;
  for (std::size_t i = 0; i < places.size(); ++i) {
    const RecoveryCounts& c = places[i];
    if (c.lost < 0 || c.recovered < 0 || c.recovered > c.lost) {
      throw std::invalid_argument("EvaluateRecovery: place " + std::to_string(i) +
                                  ": needs 0 <= recovered (" + std::to_string(c.recovered) +
                                  ") <= lost (" + std::to_string(c.lost) + ")");
    }
    r.lost += c.lost;
    r.recovered += c.recovered;
    if (c.lost == 0) {
      r.per_place_rate.push_back(kNaN);
      continue;
    }
    const double rate = static_cast<double>(c.recovered) / static_cast<double>(c.lost);
    r.per_place_rate.push_back(rate);
    rate_sum += rate;
    ++r.places_with_losses;
  }
  r.mean_rate = r.places_with_losses > 0 ? rate_sum / r.places_with_losses : kNaN;
  r.pooled_rate =
      r.lost > 0 ? static_cast<double>(r.recovered) / static_cast<double>(r.lost) : kNaN;
  return r;
}

}  // namespace trackbed::teach_repeat
