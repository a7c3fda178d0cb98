// The path-following scores of a repeat, as the repeat goes: each repeated ground-truth
// position is projected onto the taught path when it is given (the progressive
// projection of teach_repeat_metrics.h) and only sums, the largest values and the
// positions of the end window are held, so that an hour's repeat does not keep its
// 360 000 positions. The figures are the batch function's bit for bit: the same sums
// in the same order (EvaluateRepeatPath, below, is this class given every position).
//
// The taught path is held whole (its positions and their arc lengths, 24 B a point): it
// is the reference every position is scored against, and grows with the route taught,
// not with the time the repeat takes. The end window holds the positions projected within
// RepeatPathMetrics::kEndWindowM of the farthest arc length reached so far: about a
// metre of repeat, more while the robot stands still inside that metre.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "trackbed/teach_repeat/teach_repeat_metrics.h"

namespace trackbed::teach_repeat {

class RunningRepeatScore {
 public:
  /// Throws std::invalid_argument for an empty taught path; OptionError for bad options.
  explicit RunningRepeatScore(std::vector<Eigen::Vector2d> taught,
                              const PathProjectionOptions& options = {});

  /// Projects the next repeated position (in time order) and adds it to the scores.
  PathProjection Add(const Eigen::Vector2d& position);

  /// The scores of the positions given so far. Throws std::invalid_argument if none was.
  RepeatPathMetrics Metrics(bool completed) const;

  std::size_t samples() const { return samples_; }
  const std::vector<Eigen::Vector2d>& taught() const { return taught_; }
  /// Projections held for the end window (bounded on a repeat that moves on).
  std::size_t end_window_size() const { return end_.size(); }

 private:
  PathProjection Project(const Eigen::Vector2d& position) const;
  void DropBehindEndWindow();

  std::vector<Eigen::Vector2d> taught_;
  std::vector<double> arc_;  // arc length of each taught point [m]
  PathProjectionOptions options_;
  double taught_length_m_ = 0.0;
  double previous_arc_m_ = 0.0;
  std::size_t samples_ = 0;
  double sum_sq_ = 0.0, lateral_max_m_ = 0.0, covered_m_ = 0.0, lateral_start_m_ = 0.0;
  Eigen::Vector2d last_ = Eigen::Vector2d::Zero();
  std::vector<PathProjection> end_;  // in time order; some may have fallen behind
  std::size_t end_compacted_size_ = 0;
};

/// Progressive projection of `repeated` onto `taught` (see the file comment). Throws
/// std::invalid_argument for an empty taught path; OptionError for bad options.
std::vector<PathProjection> ProjectOntoPath(const std::vector<Eigen::Vector2d>& taught,
                                            const std::vector<Eigen::Vector2d>& repeated,
                                            const PathProjectionOptions& options = {});

/// Scores `repeated` (ground-truth positions of the repeat up to its end or failure, in
/// time order) against `taught`. Throws std::invalid_argument if either is empty.
RepeatPathMetrics EvaluateRepeatPath(const std::vector<Eigen::Vector2d>& taught,
                                     const std::vector<Eigen::Vector2d>& repeated, bool completed,
                                     const PathProjectionOptions& options = {});

}  // namespace trackbed::teach_repeat
