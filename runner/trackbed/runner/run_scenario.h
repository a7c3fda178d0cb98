// One scenario, whatever its mode, into its run folder: the closed loop (the drive
// or closed-loop navigation), the kinematic navigation simulation, or the two passes
// of teach & repeat. What `trackbed run` does.
#pragma once

#include <filesystem>

#include "trackbed/runner/run_metrics.h"
#include "trackbed/runner/run_observers.h"
#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

/// Runs `scenario` and writes the run folder `dir` (created if needed; files of an
/// earlier run there are replaced). Throws std::runtime_error when a file cannot be
/// written (metrics.json then still records the failure when it can). `observers` are
/// called after the folder's own in a closed-loop run (the drive, closed-loop navigation,
/// both passes of teach & repeat; not in kinematic navigation).
RunMetrics RunToFolder(const scenario::Scenario& scenario, const std::filesystem::path& dir,
                       const RunObservers& observers = {});

}  // namespace trackbed::runner
