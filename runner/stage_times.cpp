// Wall-clock time of a run's stages (see stage_times.h).
#include "trackbed/runner/stage_times.h"

#include <sys/resource.h>

#include <type_traits>

namespace trackbed::runner {
namespace {

// Peak resident set size of this process so far [MB].
double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

}  // namespace

void StageTimes::WriteTo(RunMetrics* m) const {
  m->render_wall_s = render_s;
  m->sensor_model_wall_s = sensor_model_s;
  m->estimation_wall_s = estimation_s;
  m->setup_wall_s = setup_s;
  m->physics_wall_s = physics_s;
  m->control_wall_s = control_s;
  m->sensing_wall_s = sensing_s;
  m->io_wall_s = io_s;
  m->peak_rss_mb = PeakRssMb();
}

RunObservers TimedObservers(const RunObservers& o, double* io_s) {
  return CombineObservers(o, o, [io_s](const auto& f, const auto&) -> std::decay_t<decltype(f)> {
    if (!f) return {};
    return [f, io_s](const auto& x) { Timed(io_s, [&] { f(x); }); };
  });
}

}  // namespace trackbed::runner
