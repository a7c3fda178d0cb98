// Observers of a closed-loop run: one handler per rate (encoder samples, stereo
// pairs, the localization stack's frames, IMU samples, range scans, navigation control
// steps, estimates reported from outside).
// Whatever consumes sensor data or results while a run goes — the run folder's
// logs, an image export, a teach pass, a test — is a set of these.
#pragma once

#include <functional>
#include <type_traits>

#include "trackbed/navigation/navigation_metrics.h"
#include "trackbed/robot/imu.h"
#include "trackbed/robot/range_sensor.h"
#include "trackbed/runner/run_sample.h"

namespace trackbed::runner {

/// Observers of a run; any may be empty.
struct RunObservers {
  /// Every stereo frame's visual odometry and fusion (when the camera is on).
  std::function<void(const LocalizationFrame&)> on_localization_frame;
  /// Every stereo pair (when robot.stereo.enabled). An observer here makes the
  /// camera's sensor model run on the main thread (the bytes are the same).
  std::function<void(const StereoFrame&)> on_stereo;
  /// Every encoder sample (ground truth and, when estimation.enabled, the estimates
  /// alongside); in kinematic navigation every control step's pose.
  std::function<void(const RunSample&)> on_sample;
  /// Every IMU sample.
  std::function<void(const robot::ImuSample&)> on_imu;
  /// Every range scan (when robot.range_sensor.enabled).
  std::function<void(const robot::RangeScanSample&)> on_scan;
  /// Every control step of closed-loop navigation (ground-truth pose, command, target).
  std::function<void(const navigation::NavigationLogEntry&)> on_navigation_step;
  /// Every estimate reported from outside the loop (ClosedLoop::ReportEstimate).
  std::function<void(const ExternalEstimate&)> on_external_estimate;
};

/// Builds observers member by member: out.X = f(a.X, b.X) for every observer X. The
/// one list of RunObservers' members, for code that wraps or combines observers.
template <class F>
RunObservers CombineObservers(const RunObservers& a, const RunObservers& b, F&& f) {
  RunObservers out;
  out.on_localization_frame = f(a.on_localization_frame, b.on_localization_frame);
  out.on_stereo = f(a.on_stereo, b.on_stereo);
  out.on_sample = f(a.on_sample, b.on_sample);
  out.on_imu = f(a.on_imu, b.on_imu);
  out.on_scan = f(a.on_scan, b.on_scan);
  out.on_navigation_step = f(a.on_navigation_step, b.on_navigation_step);
  out.on_external_estimate = f(a.on_external_estimate, b.on_external_estimate);
  return out;
}

/// Observers that call `a`'s and then `b`'s.
inline RunObservers Chained(const RunObservers& a, const RunObservers& b) {
  return CombineObservers(a, b, [](const auto& f, const auto& g) -> std::decay_t<decltype(f)> {
    if (!f) return g;
    if (!g) return f;
    return [f, g](const auto& x) {
      f(x);
      g(x);
    };
  });
}

}  // namespace trackbed::runner
