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

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

void PathProjectionOptions::Validate() const { option_check::Positive("window_m", window_m); }

double PolylineLength(const std::vector<Eigen::Vector2d>& path) {
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  return length;
}

std::vector<PathProjection> ProjectOntoPath(const std::vector<Eigen::Vector2d>& taught,
                                            const std::vector<Eigen::Vector2d>& repeated,
                                            const PathProjectionOptions& options) {
  options.Validate();
  if (taught.empty()) throw std::invalid_argument("ProjectOntoPath: the taught path is empty");
  std::vector<PathProjection> out;
  out.reserve(repeated.size());
  if (taught.size() == 1) {
    for (const Eigen::Vector2d& p : repeated) out.push_back({0.0, (p - taught[0]).norm()});
    return out;
  }
  std::vector<double> arc(taught.size(), 0.0);
  for (std::size_t k = 1; k < taught.size(); ++k)
    arc[k] = arc[k - 1] + (taught[k] - taught[k - 1]).norm();

  double previous = 0.0;
  for (const Eigen::Vector2d& p : repeated) {
    const double lo = previous - options.window_m, hi = previous + options.window_m;
    double best_distance = std::numeric_limits<double>::infinity();
    PathProjection best;
    for (std::size_t k = 0; k + 1 < taught.size(); ++k) {
      if (arc[k + 1] < lo || arc[k] > hi) continue;  // segment outside the window
      const Eigen::Vector2d d = taught[k + 1] - taught[k];
      const double length = d.norm();
      double t = 0.0;
      if (length > 0.0) t = std::clamp((p - taught[k]).dot(d) / (length * length), 0.0, 1.0);
      const Eigen::Vector2d nearest = taught[k] + t * d;
      const double distance = (p - nearest).norm();
      if (distance < best_distance) {
        best_distance = distance;
        best.arc_length_m = arc[k] + t * length;
        // Sign by the side of the segment (at a vertex, of the segment found first).
        const double side = length > 0.0 ? Cross(d, p - taught[k]) : 0.0;
        best.lateral_m = side < 0.0 ? -distance : distance;
      }
    }
    out.push_back(best);
    previous = best.arc_length_m;
  }
  return out;
}

RepeatPathMetrics EvaluateRepeatPath(const std::vector<Eigen::Vector2d>& taught,
                                     const std::vector<Eigen::Vector2d>& repeated, bool completed,
                                     const PathProjectionOptions& options) {
  if (taught.empty() || repeated.empty()) {
    throw std::invalid_argument("EvaluateRepeatPath: taught and repeated paths must be non-empty");
  }
  RepeatPathMetrics m;
  m.samples = repeated.size();
  m.completed = completed;
  m.taught_length_m = PolylineLength(taught);
  double sum_sq = 0.0;
  const std::vector<PathProjection> projections = ProjectOntoPath(taught, repeated, options);
  for (const PathProjection& p : projections) {
    sum_sq += p.lateral_m * p.lateral_m;
    m.lateral_max_m = std::max(m.lateral_max_m, std::abs(p.lateral_m));
    m.covered_m = std::max(m.covered_m, p.arc_length_m);
  }
  m.lateral_rms_m = std::sqrt(sum_sq / static_cast<double>(repeated.size()));
  m.lateral_start_m = std::abs(projections.front().lateral_m);
  double end_sq = 0.0;
  std::size_t end_n = 0;
  for (const PathProjection& p : projections) {
    if (p.arc_length_m >= m.covered_m - RepeatPathMetrics::kEndWindowM) {
      end_sq += p.lateral_m * p.lateral_m;
      ++end_n;
    }
  }
  m.lateral_end_rms_m = std::sqrt(end_sq / static_cast<double>(end_n));
  m.end_point_error_m = (repeated.back() - taught.back()).norm();
  if (completed) {
    m.autonomy = 1.0;
  } else {
    m.autonomy =
        m.taught_length_m > 0.0 ? std::clamp(m.covered_m / m.taught_length_m, 0.0, 1.0) : 0.0;
  }
  return m;
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
