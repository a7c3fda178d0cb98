// Path-following scores as the repeat goes (see running_repeat_score.h).
#include "trackbed/teach_repeat/running_repeat_score.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace trackbed::teach_repeat {
namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

RunningRepeatScore::RunningRepeatScore(std::vector<Eigen::Vector2d> taught,
                                       const PathProjectionOptions& options)
    : taught_(std::move(taught)), options_(options) {
  options_.Validate();
  if (taught_.empty()) throw std::invalid_argument("RunningRepeatScore: the taught path is empty");
  arc_.assign(taught_.size(), 0.0);
  for (std::size_t k = 1; k < taught_.size(); ++k)
    arc_[k] = arc_[k - 1] + (taught_[k] - taught_[k - 1]).norm();
  taught_length_m_ = PolylineLength(taught_);
}

// The nearest point of the taught segments within the window around the previous
// projection, the segments taken in order: those whose arc-length span meets the
// window are consecutive (the arc lengths never decrease), so the first is found by
// bisection instead of a scan of the whole path.
PathProjection RunningRepeatScore::Project(const Eigen::Vector2d& p) const {
  if (taught_.size() == 1) return {0.0, (p - taught_[0]).norm()};
  const double lo = previous_arc_m_ - options_.window_m, hi = previous_arc_m_ + options_.window_m;
  // First segment k whose end arc_[k + 1] reaches lo.
  std::size_t k = static_cast<std::size_t>(std::lower_bound(arc_.begin() + 1, arc_.end(), lo) -
                                           (arc_.begin() + 1));
  double best_distance = std::numeric_limits<double>::infinity();
  PathProjection best;
  for (; k + 1 < taught_.size() && arc_[k] <= hi; ++k) {
    const Eigen::Vector2d d = taught_[k + 1] - taught_[k];
    const double length = d.norm();
    double t = 0.0;
    if (length > 0.0) t = std::clamp((p - taught_[k]).dot(d) / (length * length), 0.0, 1.0);
    const Eigen::Vector2d nearest = taught_[k] + t * d;
    const double distance = (p - nearest).norm();
    if (distance < best_distance) {
      best_distance = distance;
      best.arc_length_m = arc_[k] + t * length;
      // Sign by the side of the segment (at a vertex, of the segment found first).
      const double side = length > 0.0 ? Cross(d, p - taught_[k]) : 0.0;
      best.lateral_m = side < 0.0 ? -distance : distance;
    }
  }
  return best;
}

PathProjection RunningRepeatScore::Add(const Eigen::Vector2d& position) {
  const PathProjection p = Project(position);
  if (taught_.size() > 1) previous_arc_m_ = p.arc_length_m;
  if (samples_ == 0) lateral_start_m_ = std::abs(p.lateral_m);
  ++samples_;
  sum_sq_ += p.lateral_m * p.lateral_m;
  lateral_max_m_ = std::max(lateral_max_m_, std::abs(p.lateral_m));
  covered_m_ = std::max(covered_m_, p.arc_length_m);
  last_ = position;
  // A projection behind the end window now stays behind it: the farthest arc length
  // reached never decreases.
  if (p.arc_length_m >= covered_m_ - RepeatPathMetrics::kEndWindowM) end_.push_back(p);
  if (end_.size() >= 2 * std::max<std::size_t>(end_compacted_size_, 512)) DropBehindEndWindow();
  return p;
}

void RunningRepeatScore::DropBehindEndWindow() {
  const double from = covered_m_ - RepeatPathMetrics::kEndWindowM;
  end_.erase(std::remove_if(end_.begin(), end_.end(),
                            [from](const PathProjection& p) { return p.arc_length_m < from; }),
             end_.end());
  end_compacted_size_ = end_.size();
}

RepeatPathMetrics RunningRepeatScore::Metrics(bool completed) const {
  if (samples_ == 0) throw std::invalid_argument("RunningRepeatScore: no repeated position given");
  RepeatPathMetrics m;
  m.samples = samples_;
  m.completed = completed;
  m.taught_length_m = taught_length_m_;
  m.lateral_max_m = lateral_max_m_;
  m.covered_m = covered_m_;
  m.lateral_rms_m = std::sqrt(sum_sq_ / static_cast<double>(samples_));
  m.lateral_start_m = lateral_start_m_;
  double end_sq = 0.0;
  std::size_t end_n = 0;
  for (const PathProjection& p : end_) {
    if (p.arc_length_m >= covered_m_ - RepeatPathMetrics::kEndWindowM) {
      end_sq += p.lateral_m * p.lateral_m;
      ++end_n;
    }
  }
  m.lateral_end_rms_m = std::sqrt(end_sq / static_cast<double>(end_n));
  m.end_point_error_m = (last_ - taught_.back()).norm();
  if (completed) {
    m.autonomy = 1.0;
  } else {
    m.autonomy =
        m.taught_length_m > 0.0 ? std::clamp(m.covered_m / m.taught_length_m, 0.0, 1.0) : 0.0;
  }
  return m;
}

std::vector<PathProjection> ProjectOntoPath(const std::vector<Eigen::Vector2d>& taught,
                                            const std::vector<Eigen::Vector2d>& repeated,
                                            const PathProjectionOptions& options) {
  options.Validate();
  if (taught.empty()) throw std::invalid_argument("ProjectOntoPath: the taught path is empty");
  RunningRepeatScore score(taught, options);
  std::vector<PathProjection> out;
  out.reserve(repeated.size());
  for (const Eigen::Vector2d& p : repeated) out.push_back(score.Add(p));
  return out;
}

RepeatPathMetrics EvaluateRepeatPath(const std::vector<Eigen::Vector2d>& taught,
                                     const std::vector<Eigen::Vector2d>& repeated, bool completed,
                                     const PathProjectionOptions& options) {
  if (taught.empty() || repeated.empty()) {
    throw std::invalid_argument("EvaluateRepeatPath: taught and repeated paths must be non-empty");
  }
  RunningRepeatScore score(taught, options);
  for (const Eigen::Vector2d& p : repeated) score.Add(p);
  return score.Metrics(completed);
}

}  // namespace trackbed::teach_repeat
