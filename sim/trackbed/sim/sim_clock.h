// The one simulation clock: an integer count of fixed physics steps, so that
// sensor and controller rates never drift against each other.
#pragma once

#include <cmath>
#include <cstdint>

namespace trackbed::sim {

class SimClock {
 public:
  explicit SimClock(double step_s) : step_s_(step_s) {}

  void Tick() { ++steps_; }
  std::int64_t steps() const { return steps_; }
  double step_s() const { return step_s_; }
  /// Simulated time [s] since the start.
  double now_s() const { return static_cast<double>(steps_) * step_s_; }

  /// Number of physics steps in one period of a component running at `rate_hz`
  /// (at least one).
  std::int64_t StepsPerPeriod(double rate_hz) const {
    const auto n = static_cast<std::int64_t>(std::llround(1.0 / (rate_hz * step_s_)));
    return n < 1 ? 1 : n;
  }
  /// True on the steps where a component of the given period fires (step 0 included).
  bool Fires(std::int64_t period_steps) const { return steps_ % period_steps == 0; }

 private:
  double step_s_;
  std::int64_t steps_ = 0;
};

}  // namespace trackbed::sim
