// A run folder (docs/run_folder.md): the resolved scenario, ground truth, sensor
// logs, estimates, plots and metrics.json, streamed while the run goes so that a
// run that stops early leaves readable files. metrics.json is written last,
// atomically, and says whether the run completed and why it stopped.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "trackbed/runner/robot_build.h"
#include "trackbed/runner/run_metrics.h"
#include "trackbed/runner/run_observers.h"
#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

/// Writes one closed-loop run's folder. Not copyable.
class RunFolderWriter {
 public:
  /// Creates `dir` (files of an earlier run there are replaced), removes a stale
  /// metrics.json, writes scenario.yaml (every key, built-in materials and the
  /// robot's realism resolved) and opens the logs. Throws std::runtime_error when a file
  /// cannot be written.
  RunFolderWriter(const scenario::Scenario& scenario, const std::filesystem::path& dir);
  RunFolderWriter(const RunFolderWriter&) = delete;
  RunFolderWriter& operator=(const RunFolderWriter&) = delete;
  ~RunFolderWriter();

  /// Writes the calibration the software was given (stereo_calibration.json,
  /// imu_calibration.json, vehicle_calibration.json) and the truth
  /// (ground_truth_calibration.json), and opens the image export. Before observers().
  void WriteCalibration(const scenario::Scenario& scenario, const RobotBuild& robot);
  /// The observers that write the logs; they refer to this writer.
  RunObservers observers();
  /// Points the plots hold so far, in all their paths and series, and in the largest.
  std::size_t plot_points() const;
  std::size_t largest_plot_series() const;
  /// Closes the logs, draws the plots and writes metrics.json.
  void Close(const scenario::Scenario& scenario, const RunMetrics& metrics);

 private:
  struct Files;
  std::filesystem::path dir_;
  std::unique_ptr<Files> files_;
};

/// The metrics.json document of a run, as text.
std::string MetricsJson(const RunMetrics& metrics);

/// Writes `dir`/metrics.json atomically (a temporary file renamed over it).
void WriteMetricsJson(const RunMetrics& metrics, const std::filesystem::path& dir);

}  // namespace trackbed::runner
