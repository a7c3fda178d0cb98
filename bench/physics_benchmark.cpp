// Physics-only real-time factor of the shipped scenes: the closed loop with
// the ground-truth driver, the cameras switched off, no vision, no file output.
//
//   physics_benchmark [--seconds S] [SCENARIO.yaml ...]
//
// Defaults: scenes/corridor.yaml and scenes/outdoor.yaml, each for its own
// duration. Prints one line per scene; the figure to compare is the ratio of
// simulated to wall-clock time on one core.
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "bench_args.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Physics-only real-time factor of scenarios: the closed loop with the "
      "ground-truth driver, cameras off, no vision, no file output"};
  double seconds = 0.0;
  std::vector<std::string> files;
  app.add_option("--seconds", seconds, "Simulated time per scene [s] (0: the scene's own duration)")
      ->capture_default_str()
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  trackbed::bench::AddScenarioFiles(app, &files);
  if (const std::optional<int> status = trackbed::bench::Parse(app, argc, argv)) return *status;
  files = trackbed::bench::ScenarioFilesOrDefault(files);
  try {
    for (const std::string& f : files) {
      std::vector<trackbed::scenario::Override> overrides = {{"robot.stereo.enabled", "false"}};
      if (seconds > 0) overrides.push_back({"duration_s", std::to_string(seconds)});
      const trackbed::scenario::Scenario s = trackbed::scenario::LoadScenario(f, overrides);
      const trackbed::runner::RunMetrics m = trackbed::runner::RunClosedLoop(s);
      std::printf("%-10s sim %7.1f s  wall %6.2f s  physics-only real-time factor %6.1fx  (%s)\n",
                  s.scene.name.c_str(), m.sim_time_s, m.wall_time_s, m.real_time_factor(),
                  m.stop_reason.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "physics_benchmark: %s\n", e.what());
    return 1;
  }
  return 0;
}
