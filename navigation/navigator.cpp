// Navigation status names and the progress monitor (see navigator.h).
#include "trackbed/navigation/navigator.h"

#include <algorithm>

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {

const char* NavigationStatusName(NavigationStatus status) {
  switch (status) {
    case NavigationStatus::kDriving:
      return "driving";
    case NavigationStatus::kReached:
      return "reached";
    case NavigationStatus::kGoalInObstacle:
      return "goal_in_obstacle";
    case NavigationStatus::kStalled:
      return "stalled";
  }
  return "unknown";
}

void ProgressOptions::Validate() const {
  option_check::Positive("stall_time_s", stall_time_s);
  option_check::Positive("min_progress_m", min_progress_m);
}

ProgressMonitor::ProgressMonitor(const ProgressOptions& options) : options_(options) {
  options_.Validate();
}

bool ProgressMonitor::Update(double distance_m, double tolerance_m, double dt_s) {
  if (stalled_) return true;
  if (best_m_ < 0.0 || distance_m <= best_m_ - options_.min_progress_m ||
      distance_m <= tolerance_m) {
    best_m_ = best_m_ < 0.0 ? distance_m : std::min(best_m_, distance_m);
    since_s_ = 0.0;
    return false;
  }
  since_s_ += dt_s;
  stalled_ = since_s_ >= options_.stall_time_s;
  return stalled_;
}

}  // namespace trackbed::navigation
