// `navigation.mode: kinematic`: the paper's differential-drive simulation (Jung & Kim
// 2014), no physics and no camera, as a run folder: ground_truth.tum (the simulated
// pose), navigation.csv, navigation.png and the run's metrics.
#pragma once

#include <filesystem>

#include "trackbed/runner/run_metrics.h"
#include "trackbed/runner/run_observers.h"
#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

/// Runs the kinematic simulation of `scenario` and writes its files into `dir` (which
/// must exist); metrics.json is left to the caller. `observers.on_sample` sees every
/// control step's pose (time and `chassis.T_world_body` only: there is no physics).
RunMetrics RunKinematicNavigation(const scenario::Scenario& scenario,
                                  const std::filesystem::path& dir,
                                  const RunObservers& observers = {});

}  // namespace trackbed::runner
