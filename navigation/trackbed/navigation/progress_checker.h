// Whether a point-to-point run still makes progress toward its goal: a run that has not
// come closer for a configurable time ends (kStalled, navigator.h) instead of hanging
// in a trap or before an unreachable goal. Kept apart from the navigation methods, as
// nav2 keeps its progress checker apart from its controllers, so that every method
// gives up by one rule.
#pragma once

namespace trackbed::navigation {

struct ProgressCheckerOptions {
  /// A run with no progress toward the goal for this long [s] ends as kStalled, > 0.
  double stall_time_s = 30.0;
  /// "Progress" = the best distance to the goal so far shrinking by at least this [m], > 0.
  double min_progress_m = 0.1;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md, `navigation`),
  /// read and written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("stall_time_s", &stall_time_s);
    a->Visit("min_progress_m", &min_progress_m);
  }
};

/// Detects lack of progress toward the goal. The clock runs only while the robot is
/// farther than the goal position tolerance (the final turn is not "no progress").
/// Stateful: one per run, not copyable.
class ProgressChecker {
 public:
  /// Throws OptionError naming the first invalid field.
  explicit ProgressChecker(const ProgressCheckerOptions& options);
  ProgressChecker(const ProgressChecker&) = delete;
  ProgressChecker& operator=(const ProgressChecker&) = delete;

  /// Adds one control period of `dt_s` [s] at distance `distance_m` from the goal, whose
  /// position tolerance is `tolerance_m`; returns true once stalled (and from then on).
  bool Update(double distance_m, double tolerance_m, double dt_s);

  bool stalled() const { return stalled_; }

 private:
  ProgressCheckerOptions options_;
  double best_m_ = -1.0;  ///< Best distance so far; < 0 before the first update.
  double since_s_ = 0.0;  ///< Time since the best distance last improved enough.
  bool stalled_ = false;
};

}  // namespace trackbed::navigation
