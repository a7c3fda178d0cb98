// Figures per distance travelled (a percentage of the path, megabytes per 100 m) and
// the shortest path they are given over (docs/run_folder.md, "Figures per distance").
#pragma once

#include <limits>

namespace trackbed::estimation {

/// The shortest path [m] a figure per distance is given over. Over less, what does not
/// grow with the distance (the start, the encoders' last tick, a few millimetres of
/// settling) outweighs what does, and the ratio grows without bound as the path
/// shrinks: a stationary run's final error of 0.15 mm over 3·10⁻¹⁶ m of jitter is 5·10¹³ %.
inline constexpr double kMinPathForPerDistanceM = 1.0;

/// 100 · `value` / `path_m` [% of the path], or NaN (n/a; null in JSON) when `path_m` is
/// below kMinPathForPerDistanceM.
inline double PercentOfPath(double value, double path_m) {
  return path_m >= kMinPathForPerDistanceM ? 100.0 * value / path_m
                                           : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace trackbed::estimation
