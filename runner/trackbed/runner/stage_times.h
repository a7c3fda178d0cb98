// Wall-clock time of a run's stages and its peak memory (metrics.json `timing` and
// `memory`): measurements of the machine, not of the run.
#pragma once

#include <chrono>
#include <utility>

#include "trackbed/runner/run_metrics.h"
#include "trackbed/runner/run_observers.h"

namespace trackbed::runner {

/// Wall-clock seconds of a closed loop's stages (RunMetrics' `*_wall_s`).
struct StageTimes {
  double setup_s = 0.0;         ///< building the world, the robot and its software
  double physics_s = 0.0;       ///< forces and the Bullet step
  double control_s = 0.0;       ///< the commander
  double sensing_s = 0.0;       ///< the range sensor
  double io_s = 0.0;            ///< the observers (the run folder's files)
  double render_s = 0.0;        ///< the camera's renders
  double sensor_model_s = 0.0;  ///< the camera's sensor model, on whichever thread
  double estimation_s = 0.0;    ///< the localization stack

  /// Sets `m`'s wall-clock times to these and its peak memory to the process's so far.
  void WriteTo(RunMetrics* m) const;
};

/// Runs `f`, adding its wall-clock time to *seconds (also when it throws); returns
/// what `f` returns.
template <class F>
auto Timed(double* seconds, F&& f) {
  const auto start = std::chrono::steady_clock::now();
  struct Add {
    double* seconds;
    std::chrono::steady_clock::time_point start;
    ~Add() {
      *seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
  } add{seconds, start};
  return std::forward<F>(f)();
}

/// `o`, each call's wall-clock time added to *io_s.
RunObservers TimedObservers(const RunObservers& o, double* io_s);

}  // namespace trackbed::runner
