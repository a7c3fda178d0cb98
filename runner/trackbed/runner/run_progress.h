// The progress of a run as `trackbed run` shows it (README.md, "Commands"): simulated
// time of the total, real-time factor, time left and distance driven. On a terminal one
// line rewritten in place (`bar`); otherwise at most one line per tenth of the run
// (`lines`), or nothing (`none`).
#pragma once

#include <cstdio>
#include <string>

#include <Eigen/Core>

namespace trackbed::runner {

enum class ProgressMode { kNone, kLines, kBar };

/// "none", "lines", "bar" to the mode; throws std::invalid_argument for anything else.
ProgressMode ParseProgressMode(const std::string& name);

/// Where a run stands.
struct ProgressFigures {
  double sim_s = 0.0;       ///< simulated time so far [s]
  double total_s = 0.0;     ///< the scenario's duration_s [s] (a route may end sooner)
  double wall_s = 0.0;      ///< wall-clock time since the run started [s]
  double distance_m = 0.0;  ///< true path length so far [m]
};

/// One line, no newline: "  612.0 / 3600.0 s (17 %)  158x real time  0:00:19 left
/// 245.3 m" (the time left at the real-time factor so far; "?" before any time has passed;
/// kilometres from 10 km on).
std::string FormatProgress(const ProgressFigures& f);

/// Shows a run's progress on `out`. Sample() at every encoder sample, with the wall-clock
/// time since the start; Finish() at the end. A time earlier than the last starts a new
/// pass (teach & repeat's repeat): its tenths and its real-time factor are counted
/// afresh, the distance goes on.
class RunProgress {
 public:
  RunProgress(ProgressMode mode, double total_s, std::FILE* out);
  void Sample(double sim_s, const Eigen::Vector3d& true_position, double wall_s);
  /// Clears the bar's line (the run's report follows on a clean line).
  void Finish();
  /// Lines printed so far (the bar's rewrites included).
  int lines() const { return lines_; }

 private:
  ProgressMode mode_;
  double total_s_;
  std::FILE* out_;
  bool started_ = false;
  double last_sim_s_ = 0.0;
  double pass_start_wall_s_ = 0.0;  // the wall-clock time this pass began
  Eigen::Vector3d last_position_ = Eigen::Vector3d::Zero();
  double distance_m_ = 0.0;
  double last_bar_wall_s_ = -1.0;  // the bar is rewritten at most 4 times a second
  int last_tenth_ = 0;             // lines: the last tenth reported
  std::size_t bar_width_ = 0;      // characters of the line on screen
  int lines_ = 0;
};

}  // namespace trackbed::runner
