// One closed-loop expectation of a sweep (see sweep_expectation.h).
#include "trackbed/experiments/sweep_expectation.h"

#include <cmath>
#include <cstdio>

namespace trackbed::experiments {

std::string FormatMeasured(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

std::string SweepExpectation::Problem() const {
  if (metric.empty()) return "metric: must not be empty";
  if (over != "cell" && over != "mean") return "over: must be cell or mean (got '" + over + "')";
  for (const std::optional<double>* b : {&min, &max}) {
    if (*b && !std::isfinite(**b)) return std::string(b == &min ? "min" : "max") + ": not finite";
  }
  if (order.empty()) {
    if (!min && !max) return "min, max: a bound needs at least one (or give `order`)";
    if (min && max && *max < *min) return "max: must be >= min";
    return "";
  }
  if (min || max) return "order: an ordering takes no min or max";
  if (order.size() < 2) return "order: name at least two estimators";
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (order[i].empty()) return "order: an empty estimator name";
    for (std::size_t j = 0; j < i; ++j) {
      if (order[j] == order[i]) return "order: '" + order[i] + "' named twice";
    }
  }
  return "";
}

std::string SweepExpectation::Text() const {
  std::string s;
  if (order.empty()) {
    if (min) s += FormatMeasured(*min) + " <= ";
    s += metric;
    if (max) s += " <= " + FormatMeasured(*max);
  } else {
    for (std::size_t i = 0; i < order.size(); ++i) s += (i ? " < " : "") + order[i];
    s += " by " + metric;
  }
  s += over == "mean" ? " on each group's mean" : " in every cell";
  return scenario.empty() ? s : s + " of " + scenario;
}

}  // namespace trackbed::experiments
