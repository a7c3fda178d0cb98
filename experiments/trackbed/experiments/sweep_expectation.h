// One closed-loop expectation of a sweep (docs/sweeps.md, "Expectations"): a bound on
// a metric in every cell or on each group's mean, or an ordering of estimators, as a
// sweep file's `expect:` list and cells.json hold it. Checking is expectation_checks.h.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "trackbed/common/archive.h"

namespace trackbed::experiments {

/// One expectation, as a sweep file's `expect:` list has it:
///   {metric: estimators.fused.ate_rmse_m, max: 0.1}               every cell
///   {metric: estimators.fused.ate_rmse_m, max: 0.08, over: mean}  each group's mean
///   {order: [fused, visual_odometry], metric: ate_rmse_m}         per cell, smallest first
struct SweepExpectation {
  /// A bound: the dotted path of a number in metrics.json. An order: the metric of each
  /// named estimator (`estimators.<name>.<metric>`).
  std::string metric;
  std::optional<double> min, max;
  /// `cell` (each ok cell) or `mean` (each group's mean over its ok cells).
  std::string over = "cell";
  /// Estimator names whose metric must increase strictly in this order (best first for
  /// an error); empty for a bound.
  std::vector<std::string> order;
  /// Only the cells of this scenario (as the sweep file's `scenarios` writes it); empty:
  /// every cell.
  std::string scenario;

  /// The reason the expectation is malformed, with the field at fault first
  /// (`max: must be >= min`); empty when it is well formed.
  std::string Problem() const;
  /// One line, e.g. `estimators.fused.ate_rmse_m <= 0.1 in every cell`.
  std::string Text() const;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("metric", &metric, archive::kRequired);
    a->Visit("min", &min, archive::kOmitEmpty);
    a->Visit("max", &max, archive::kOmitEmpty);
    a->Visit("over", &over);
    a->Visit("order", &order, archive::kOmitEmpty);
    a->Visit("scenario", &scenario, archive::kOmitEmpty);
  }
};

/// A measured value as expectations print it (6 significant digits).
std::string FormatMeasured(double v);

}  // namespace trackbed::experiments
