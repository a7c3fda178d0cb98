// What drives the tracks in a closed-loop run. A Commander is called at its own
// control rate (or on every stereo frame, for one that steers from images) with what
// the robot may know at that moment, and answers with track speeds; it may end the
// run. The scripted or path-following drive, closed-loop navigation and the repeat
// of teach & repeat are commanders; so is a user's own.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "trackbed/common/skid_steer.h"
#include "trackbed/estimation/localization.h"
#include "trackbed/robot/range_sensor.h"

namespace trackbed::runner {

struct RunMetrics;

/// What a commander sees when it is called.
struct ControlInput {
  double t_s = 0.0;  ///< simulation time [s]
  /// Ground truth of the body: what a scripted route follows; a commander standing for
  /// robot software must only log or score with it.
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  /// The localization stack, up to date at t_s; null unless the commander
  /// needs_estimates() and estimation is on.
  const estimation::LocalizationStack* estimates = nullptr;
  /// The left image (CV_8UC1) for a commander triggered by stereo frames; else null.
  const cv::Mat* left_image = nullptr;
};

/// A commander's answer.
struct ControlOutput {
  kinematics::TrackSpeeds tracks;  ///< held until the next call [m/s]
  /// Set: the run ends after this call, for this reason (metrics.json `stop_reason`).
  std::optional<std::string> stop_reason;
};

/// The interface of everything that drives a run. Not copyable.
class Commander {
 public:
  /// When Update is called: every period_s() of simulated time (the first call at
  /// t = 0), or on every stereo frame.
  enum class Trigger { kPeriodic, kStereoFrame };

  Commander() = default;
  Commander(const Commander&) = delete;
  Commander& operator=(const Commander&) = delete;
  virtual ~Commander() = default;

  virtual Trigger trigger() const { return Trigger::kPeriodic; }
  /// Control period [s] of a periodic commander (> 0).
  virtual double period_s() const = 0;
  /// Whether Update reads ControlInput::estimates (the loop then waits for the
  /// localization stack to catch up before each call).
  virtual bool needs_estimates() const { return false; }
  /// One control step.
  virtual ControlOutput Update(const ControlInput& input) = 0;
  /// Every range scan, as it is taken (robot.range_sensor.enabled).
  virtual void AddScan(const robot::RangeScanSample& /*scan*/) {}
  /// Adds this commander's own figures to the run's metrics once the run has ended;
  /// `time_ran_out` when it ended by reaching duration_s.
  virtual void AddMetrics(bool /*time_ran_out*/, RunMetrics* /*metrics*/) const {}
};

}  // namespace trackbed::runner
