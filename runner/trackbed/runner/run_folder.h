// A run folder (docs/run_folder.md): the resolved scenario, ground truth, sensor
// logs and metrics.json, streamed while the run goes so that a run that stops
// early leaves readable files. metrics.json is written last, atomically, and
// says whether the run completed and why it stopped.
#pragma once

#include <filesystem>

#include "trackbed/runner/closed_loop_runner.h"
#include "trackbed/runner/run_metrics.h"
#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

/// Runs `scenario` in closed loop, writing the run folder `dir` (created if
/// needed; files of an earlier run there are replaced). Throws
/// std::runtime_error when a file cannot be written (metrics.json then still
/// records the failure when it can).
RunMetrics RunToFolder(const scenario::Scenario& scenario, const std::filesystem::path& dir);

/// RunToFolder's closed loop with `extra` observers called after the folder's own, and
/// an optional teach & repeat `repeater` driving (see RunClosedLoop). Used by the teach
/// & repeat run, which writes one such folder per pass.
RunMetrics RunToFolderWith(const scenario::Scenario& scenario, const std::filesystem::path& dir,
                           const RunObservers& extra, teach_repeat::Repeater* repeater);

/// The metrics.json document of a run, as text.
std::string MetricsJson(const RunMetrics& metrics);

/// Writes `dir`/metrics.json atomically (a temporary file renamed over it).
void WriteMetricsJson(const RunMetrics& metrics, const std::filesystem::path& dir);

}  // namespace trackbed::runner
