// The kinematic navigation run (see kinematic_navigation_run.h).
#include "trackbed/runner/kinematic_navigation_run.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "trackbed/common/pose2.h"
#include "trackbed/estimation/trajectory.h"
#include "trackbed/navigation/kinematic_simulation.h"
#include "trackbed/navigation/navigator_factory.h"
#include "trackbed/runner/log_file.h"
#include "trackbed/runner/navigation_log.h"
#include "trackbed/runner/navigation_scenario.h"

namespace trackbed::runner {

RunMetrics RunKinematicNavigation(const scenario::Scenario& scenario,
                                  const std::filesystem::path& dir, const RunObservers& observers) {
  const auto wall_start = std::chrono::steady_clock::now();
  const navigation::NavigationScene scene = NavigationSceneOf(scenario);
  const std::unique_ptr<navigation::Navigator> navigator = navigation::MakeNavigator(
      scenario.navigation.method, NavigatorOptionsOf(scenario), scene.goal);
  navigation::KinematicSimulationOptions options = KinematicOptionsOf(scenario);
  if (observers.on_sample) {
    options.on_row = [&observers](const navigation::NavigationLogEntry& e) {
      RunSample s;
      s.t_s = e.t_s;
      s.chassis.T_world_body = geometry::ToIsometry({e.x_m, e.y_m, e.yaw_rad}, 0.0);
      observers.on_sample(s);
    };
  }
  const navigation::KinematicRun run =
      navigation::RunKinematicSimulation(scene, *navigator, options);

  LogFile truth(dir / "ground_truth.tum", "");
  LogFile csv(dir / "navigation.csv", kNavigationCsvHeader);
  RunMetrics m;
  for (std::size_t k = 0; k < run.log.size(); ++k) {
    const navigation::NavigationLogEntry& e = run.log[k];
    truth.Line(
        estimation::FormatTumLine({e.t_s, geometry::ToIsometry({e.x_m, e.y_m, e.yaw_rad}, 0.0)})
            .c_str());
    csv.Line(NavigationCsvRow(e).c_str());
    if (k > 0) {
      // The commanded wheel travel of the step: what encoders on this robot would count.
      m.encoder_distance_m += std::abs(run.log[k - 1].v_mps) * (e.t_s - run.log[k - 1].t_s);
    }
  }
  truth.Close();
  csv.Close();

  WriteNavigationMap(dir / "navigation.png",
                     scenario.scene.name + ": " + navigation::ToString(scenario.navigation.method) +
                         " (" + run.metrics.status + ")",
                     run.log, scene.obstacles, scenario.navigation.safety_radius_m, scene.start,
                     scene.goal, run.subgoals);

  m.completed = true;
  m.stop_reason = "navigation " + run.metrics.status;
  m.sim_time_s = run.metrics.duration_s;
  m.distance_m = run.metrics.path_length_m;
  m.navigation_method = navigation::ToString(scenario.navigation.method);
  m.navigation = run.metrics;
  m.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return m;
}

}  // namespace trackbed::runner
