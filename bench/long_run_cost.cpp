// A long run's cost along the way: the park (or any scenario) run for hours in closed
// loop into a run folder, the process's CPU time per simulated second in each tenth of
// the run, the held sizes (ClosedLoop::held_sizes) and the peak resident memory at each
// tenth, and the run folder's bytes per simulated hour. A run whose cost per simulated
// second grows along the way has something that grows with its length
// (docs/results/2026-12-06-runs-of-hours.md).
//
//   build/bench/long_run_cost [--hours H] [--set KEY=VALUE ...] [--out DIR] [SCENARIO]
//
// Default: scenes/outdoor.yaml for 8 hours without the camera (280+ laps of the park).
#include <sys/resource.h>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_args.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace {

namespace fs = std::filesystem;

double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

std::uintmax_t FolderBytes(const fs::path& dir) {
  std::uintmax_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) n += e.file_size();
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"CPU per simulated second along a long run, its held sizes and memory"};
  double hours = 8.0;
  std::string scenario_file = TRACKBED_SOURCE_DIR "/scenes/outdoor.yaml";
  std::string out = "runs/long_run_cost";
  std::vector<std::string> sets;
  app.add_option("--hours", hours, "Simulated hours")->check(CLI::PositiveNumber);
  app.add_option("--out", out, "Run folder");
  app.add_option("scenario", scenario_file, "Scenario file (default: the park)");
  trackbed::bench::AddSetOption(app, &sets);
  if (const auto status = trackbed::bench::Parse(app, argc, argv)) return *status;

  using namespace trackbed;
  std::vector<scenario::Override> overrides = {{"drive.laps", "1000"},
                                               {"robot.stereo.enabled", "false"}};
  for (const std::string& s : sets) overrides.push_back(scenario::ParseOverride(s));
  overrides.push_back({"duration_s", std::to_string(hours * 3600.0)});
  const scenario::Scenario s = scenario::LoadScenario(scenario_file, overrides);
  runner::ClosedLoopOptions options;
  options.dir = out;
  runner::ClosedLoop loop(s, std::move(options));
  loop.Start();
  std::printf("%-7s %12s %14s %13s %12s %11s\n", "tenth", "sim [s]", "CPU/sim [ms/s]",
              "window poses", "plot points", "peak [MB]");
  std::vector<double> cost;
  double t_last = 0.0, cpu_last = CpuSeconds();
  int tenth = 1;
  while (!loop.done()) {
    const double t = loop.Step().t_s;
    if (t + 1e-9 < tenth * s.duration_s / 10.0 && !loop.done()) continue;
    const double cpu = CpuSeconds();
    cost.push_back(1000.0 * (cpu - cpu_last) / (t - t_last));
    const runner::HeldSizes h = loop.held_sizes();
    std::printf("%-7d %12.1f %14.3f %13zu %12zu %11.1f\n", tenth, t, cost.back(),
                h.scoring_window_poses, h.plot_points, PeakRssMb());
    std::fflush(stdout);
    t_last = t;
    cpu_last = cpu;
    ++tenth;
  }
  const runner::RunMetrics m = loop.Finish();
  const double bytes = static_cast<double>(FolderBytes(out));
  std::printf("%s after %.1f s, %.1f m; memory.peak_rss_mb %.1f, process peak %.1f MB\n",
              m.stop_reason.c_str(), m.sim_time_s, m.distance_m, m.peak_rss_mb, PeakRssMb());
  std::printf("CPU per simulated second, last tenth / first: %.3f\n",
              cost.size() > 1 ? cost.back() / cost.front() : 0.0);
  std::printf("run folder: %.1f MB, %.1f MB per simulated hour\n", bytes / 1e6,
              bytes / 1e6 / (m.sim_time_s / 3600.0));
  return m.completed ? 0 : 1;
}
