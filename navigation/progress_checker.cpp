// Progress checker (see progress_checker.h).
#include "trackbed/navigation/progress_checker.h"

#include <algorithm>

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {

void ProgressCheckerOptions::Validate() const {
  option_check::Positive("stall_time_s", stall_time_s);
  option_check::Positive("min_progress_m", min_progress_m);
}

ProgressChecker::ProgressChecker(const ProgressCheckerOptions& options) : options_(options) {
  options_.Validate();
}

bool ProgressChecker::Update(double distance_m, double tolerance_m, double dt_s) {
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
