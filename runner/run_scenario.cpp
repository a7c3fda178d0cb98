// One scenario into its run folder (see run_scenario.h).
#include "trackbed/runner/run_scenario.h"

#include <exception>
#include <string>

#include "trackbed/common/durable_file.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/runner/input_files.h"
#include "trackbed/runner/kinematic_navigation_run.h"
#include "trackbed/runner/log_file.h"
#include "trackbed/runner/run_bag.h"
#include "trackbed/runner/run_folder.h"
#include "trackbed/runner/teach_repeat_run.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {
namespace {

namespace fs = std::filesystem;

// The kinematic simulation's folder: the resolved scenario, its logs and
// metrics.json (saying why when it fails).
RunMetrics RunKinematicToFolder(const scenario::Scenario& scenario, const fs::path& dir,
                                const RunObservers& observers) {
  scenario.Validate();
  fs::create_directories(dir);
  fs::remove(dir / "metrics.json");  // no stale result may pass for this run's
  WriteFileAtomically(dir / "scenario.yaml",
                      scenario::ScenarioToYaml(scenario::WithBuiltinMaterialsResolved(
                          scenario::WithRealismResolved(scenario))));
  WriteInputsJson(scenario, dir);
  WriteUnmapped(scenario, dir);
  RunMetrics metrics;
  try {
    metrics = RunKinematicNavigation(scenario, dir, observers);
    if (scenario.outputs.mcap) WriteRunBag(dir);
  } catch (const std::exception& e) {
    metrics.completed = false;
    metrics.stop_reason = std::string("failed: ") + e.what();
    WriteMetricsJson(metrics, dir);
    throw;
  }
  WriteMetricsJson(metrics, dir);
  return metrics;
}

}  // namespace

RunMetrics RunToFolder(const scenario::Scenario& scenario, const fs::path& dir,
                       const RunObservers& observers) {
  if (scenario.teach_repeat.enabled) return RunTeachRepeat(scenario, dir, observers);
  if (scenario.navigation.enabled &&
      scenario.navigation.mode == scenario::NavigationSpec::Mode::kKinematic) {
    return RunKinematicToFolder(scenario, dir, observers);
  }
  ClosedLoopOptions options;
  options.dir = dir;
  options.observers = observers;
  return ClosedLoop(scenario, std::move(options)).Run();
}

}  // namespace trackbed::runner
