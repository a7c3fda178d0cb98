// Teach & repeat's repeat pass as a commander (see repeat_commander.h).
#include "trackbed/runner/repeat_commander.h"

#include <chrono>
#include <stdexcept>
#include <string>

#include "trackbed/runner/run_metrics.h"

namespace trackbed::runner {

RepeatCommander::RepeatCommander(teach_repeat::Repeater* repeater, double effective_gauge_m,
                                 StepObserver on_step,
                                 std::shared_ptr<const perception::LensUndistorter> undistorter)
    : repeater_(repeater),
      gauge_eff_m_(effective_gauge_m),
      on_step_(std::move(on_step)),
      undistorter_(std::move(undistorter)) {
  if (!repeater_) throw std::invalid_argument("RepeatCommander: no repeater");
}

ControlOutput RepeatCommander::Update(const ControlInput& input) {
  if (!input.left_image) throw std::invalid_argument("RepeatCommander: no image");
  const cv::Mat* image = input.left_image;
  if (undistorter_ && !undistorter_->identity()) {
    undistorter_->Undistort(*input.left_image, &undistorted_);
    image = &undistorted_;
  }
  const auto start = std::chrono::steady_clock::now();
  const teach_repeat::RepeatCommand c = repeater_->Update(*image, input.t_s);
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  if (on_step_) on_step_({input.t_s, c, took.count()});
  features_lost_ = c.features_lost;
  features_recovered_ = c.features_recovered;
  ControlOutput out;
  out.tracks = kinematics::TrackSpeedsFromTwist(c.twist, gauge_eff_m_);
  if (c.status != teach_repeat::RepeatStatus::kDriving) {
    out.stop_reason = std::string("repeat ") + teach_repeat::ToString(c.status);
  }
  return out;
}

void RepeatCommander::AddMetrics(bool /*time_ran_out*/, RunMetrics* metrics) const {
  metrics->repeat_features_lost = features_lost_;
  metrics->repeat_features_recovered = features_recovered_;
}

}  // namespace trackbed::runner
