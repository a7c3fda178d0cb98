// The `trackbed` command line (README.md, "Commands"; docs/scenario_format.md).
//
//   trackbed run SCENARIO.yaml --out DIR [--seed N] [--set key=value ...]
//
// Exit status 0 on success; otherwise non-zero with a one-line reason on stderr.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "eval_command.h"
#include "export_mcap_command.h"
#include "image_stats_command.h"
#include "report_command.h"
#include "sweep_command.h"
#include "trackbed/estimation/per_distance.h"
#include "trackbed/runner/run_progress.h"
#include "trackbed/runner/run_scenario.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "transfer_command.h"
#include "unknown_arguments.h"
#include "vo_command.h"

namespace {

// "12.34", or "n/a (<why>)" for a figure that is n/a (NaN).
std::string FigureOr(double value, const char* format, const char* why) {
  if (!std::isfinite(value)) return std::string("n/a (") + why + ")";
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, value);
  return buf;
}

// The physics run's summary: distances, every estimator against ground truth, teach &
// repeat, χ (README.md, "Commands"; per-distance figures and χ only where they mean
// something: docs/run_folder.md).
void PrintRunSummary(const trackbed::runner::RunMetrics& m, const std::string& out_dir) {
  using trackbed::estimation::PercentOfPath;
  char too_short[32];  // why a per-distance figure is n/a
  std::snprintf(too_short, sizeof(too_short), "< %g m",
                trackbed::estimation::kMinPathForPerDistanceM);
  const double encoder_pct = PercentOfPath(m.encoder_distance_m - m.distance_m, m.distance_m);
  const std::string encoder_error = std::isfinite(encoder_pct)
                                        ? FigureOr(encoder_pct, "%+.2f %%", "")
                                        : std::string("error n/a: path ") + too_short;
  std::printf(
      "%s: %.1f s simulated in %.2f s wall (%.3gx real time); distance %.2f m, encoder "
      "distance %.2f m (%s); outputs in %s\n",
      m.stop_reason.c_str(), m.sim_time_s, m.wall_time_s, m.real_time_factor(), m.distance_m,
      m.encoder_distance_m, encoder_error.c_str(), out_dir.c_str());
  if (!m.estimators.empty()) {
    // The run's report: every estimator against ground truth (README.md, "Run folder").
    std::printf("%-22s %10s %12s %12s %14s\n", "estimator", "ATE [m]", "final [m]", "final [%]",
                "drift/10 m [%]");
    for (const auto& [name, e] : m.estimators) {
      std::printf("%-22s %10.3f %12.3f %12s %14s\n", name.c_str(), e.ate_rmse_m, e.final_error_m,
                  FigureOr(e.final_error_pct, "%.2f", too_short).c_str(),
                  FigureOr(e.rpe_trans_pct, "%.2f", "< 10 m").c_str());
    }
  }
  if (m.teach_repeat) {
    const trackbed::runner::TeachRepeatMetrics& t = *m.teach_repeat;
    std::printf(
        "teach & repeat (%s): %s; %d milestones from %d teach images; lateral error RMS %.3f m, "
        "max %.3f m; end point %.3f m; autonomy %.2f; features lost %lld, recovered %lld\n",
        t.method.c_str(), t.status.c_str(), t.milestones, t.teach_images, t.lateral_rms_m,
        t.lateral_max_m, t.end_point_error_m, t.autonomy, static_cast<long long>(t.features_lost),
        static_cast<long long>(t.features_recovered));
  }
  const trackbed::estimation::IcrFit& icr = m.icr;
  if (icr.identified) {
    // Turning runs (scenes/calibration/icr_turns.yaml) calibrate the effective gauge.
    std::printf(
        "ICR expansion chi = %.3f +- %.3f (B_eff = chi * B, fitted on %d turning samples)\n",
        icr.chi, icr.chi_stderr, icr.samples_used);
  } else if (icr.samples_used > 0) {
    std::printf("ICR expansion chi: n/a, not identified by this run (%s)\n", icr.reason.c_str());
  }
}

// The progress mode of `--progress` (auto: a bar on a terminal, else lines).
trackbed::runner::ProgressMode ProgressModeOf(const std::string& name) {
  if (name != "auto") return trackbed::runner::ParseProgressMode(name);
  return ::isatty(STDERR_FILENO) ? trackbed::runner::ProgressMode::kBar
                                 : trackbed::runner::ProgressMode::kLines;
}

int Run(const std::string& scenario_path, const std::string& out_dir,
        const std::vector<std::string>& sets, const std::optional<std::uint64_t>& seed,
        const std::string& progress_mode) {
  using namespace trackbed::scenario;
  using namespace trackbed::runner;
  std::vector<Override> overrides;
  for (const std::string& s : sets) overrides.push_back(ParseOverride(s));
  if (seed) overrides.push_back({"seed", std::to_string(*seed)});
  const Scenario scenario = LoadScenario(scenario_path, overrides);
  std::cerr << "trackbed run: " << scenario_path << " (scene " << scenario.scene.name << ", seed "
            << scenario.seed << ") -> " << out_dir << "\n";
  // Progress on stderr, beside the run's messages (the report goes to stdout).
  RunProgress progress(ProgressModeOf(progress_mode), scenario.RunDuration(DriveSource::kScenario),
                       stderr);
  const auto start = std::chrono::steady_clock::now();
  RunObservers observers;
  observers.on_sample = [&progress, start](const RunSample& s) {
    const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;
    progress.Sample(s.t_s, s.chassis.T_world_body.translation(), wall.count());
  };
  RunMetrics m;
  try {
    m = RunToFolder(scenario, out_dir, observers);
  } catch (...) {
    progress.Finish();
    throw;
  }
  progress.Finish();
  if (!m.completed) {
    std::cerr << "trackbed run: stopped early: " << m.stop_reason << " (files so far in " << out_dir
              << ")\n";
    return 3;
  }
  if (m.stop_reason == "stalled") {
    std::cerr << "trackbed run: the robot stalled at t = " << m.sim_time_s
              << " s: a track's motor held its torque limit (robot.vehicle.motor.max_torque_nm) "
                 "without turning for robot.vehicle.stall_time_s\n";
  }
  if (m.navigation) {
    const trackbed::navigation::NavigationMetrics& n = *m.navigation;
    std::printf(
        "navigation (%s): %s%s; path %.2f m in %.1f s; final error %.3f m, %.2f deg; min "
        "clearance %s; %d collision(s); %d sub-goal(s); outputs in %s\n",
        m.navigation_method.c_str(), n.status.c_str(), n.success ? " (success)" : " (no success)",
        n.path_length_m, n.duration_s, n.final_position_error_m, n.final_heading_error_deg,
        FigureOr(n.min_clearance_m, "%.2f m", "no obstacles").c_str(), n.collisions, n.subgoals,
        out_dir.c_str());
    return 0;
  }
  PrintRunSummary(m, out_dir);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"trackbed: a closed-loop testbed for a tracked robot"};
  app.require_subcommand(1);

  CLI::App* run =
      app.add_subcommand("run", "Run one scenario in closed loop and write its run folder");
  std::string scenario_path, out_dir;
  std::vector<std::string> sets;
  std::optional<std::uint64_t> seed;
  run->add_option("scenario", scenario_path, "Scenario file (YAML)")->required();
  run->add_option("--out", out_dir, "Run folder to write")->required();
  run->add_option("--seed", seed, "Seed (overrides the scenario's `seed`)");
  run->add_option("--set", sets, "Override a scenario key: --set dotted.key=value (repeatable)");
  std::string progress = "auto";
  run->add_option("--progress", progress,
                  "Progress on stderr: bar (one line rewritten in place), lines (one line per "
                  "10 % of duration_s), none, or auto (bar on a terminal, else lines)")
      ->check(CLI::IsMember({"auto", "bar", "lines", "none"}));
  run->add_flag_callback(
      "--no-progress", [&progress] { progress = "none"; }, "The same as --progress none");

  trackbed::apps::AddEvalCommand(app);
  trackbed::apps::AddSweepCommand(app);
  trackbed::apps::AddReportCommand(app);
  trackbed::apps::AddVoCommand(app);
  trackbed::apps::AddTransferCommand(app);
  trackbed::apps::AddImageStatsCommand(app);
  trackbed::apps::AddExportMcapCommand(app);

  if (const std::optional<std::string> unknown = trackbed::apps::UnknownArgument(app, argc, argv)) {
    std::cerr << *unknown << "\nRun with --help for more information.\n";
    return static_cast<int>(CLI::ExitCodes::ExtrasError);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (*run) {
      trackbed::apps::DieWithSweepIfCell();
      return Run(scenario_path, out_dir, sets, seed, progress);
    }
  } catch (const std::exception& e) {
    std::cerr << "trackbed: " << e.what() << "\n";
    return 2;
  }
  return 1;
}
