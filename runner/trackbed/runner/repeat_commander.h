// The repeat pass of visual teach & repeat (Choi & Ha 2011) as a commander: on every
// stereo frame the repeater steers from the left image alone; its twist becomes
// track speeds through the effective gauge χ·B, held until the next frame.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <utility>

#include "trackbed/perception/lens_undistorter.h"
#include "trackbed/runner/commander.h"
#include "trackbed/teach_repeat/teach_repeat.h"

namespace trackbed::runner {

/// One repeat frame, as RepeatCommander's observer sees it.
struct RepeatStep {
  double t_s = 0.0;  ///< the frame's time [s]
  teach_repeat::RepeatCommand command;
  /// Wall-clock time the repeater took on the frame [s] (machine-dependent).
  double repeater_s = 0.0;
};

class RepeatCommander : public Commander {
 public:
  /// `repeater` must outlive this. `on_step` (may be empty) sees every frame's time,
  /// command and the repeater's time. `undistorter` (may be null: the images are a
  /// pinhole's) undistorts each left image as the map's images were.
  using StepObserver = std::function<void(const RepeatStep&)>;
  RepeatCommander(teach_repeat::Repeater* repeater, double effective_gauge_m, StepObserver on_step,
                  std::shared_ptr<const perception::LensUndistorter> undistorter = nullptr);

  Trigger trigger() const override { return Trigger::kStereoFrame; }
  double period_s() const override { return 0.0; }
  /// Ends the run with "repeat <status>" once the repeater stops driving.
  ControlOutput Update(const ControlInput& input) override;
  /// The features the repeater lost and recovered, in all.
  void AddMetrics(bool time_ran_out, RunMetrics* metrics) const override;

 private:
  teach_repeat::Repeater* repeater_;
  double gauge_eff_m_;
  StepObserver on_step_;
  std::shared_ptr<const perception::LensUndistorter> undistorter_;
  cv::Mat undistorted_;
  std::int64_t features_lost_ = 0, features_recovered_ = 0;
};

}  // namespace trackbed::runner
