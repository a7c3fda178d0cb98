// Scores of a visual teach & repeat run (Choi & Ha 2011 §IV): pure functions.
//
// * Path following, against the taught path (ground-truth positions of the teach run, a
//   polyline): the lateral error of every repeated ground-truth position (its distance
//   to the taught path, signed: > 0 left of the taught direction), its RMS and maximum;
//   the end-point error (distance between the repeat's last position and the taught
//   path's end — the paper's "measured end-point error"); and the autonomy, the
//   fraction of the taught route's length covered before a failure (1 for a completed
//   repeat).
//   The projection and these scores are computed in running_repeat_score.h, as the
//   repeat goes or from a whole path. Positions are projected progressively: each onto
//   the part of the taught path within `window_m` of arc length of the previous
//   projection (the first near the start), so that a route that passes near itself (a
//   loop, an out-and-back) does not make the projection jump to the wrong pass.
// * Feature recovery (experiment 1, Table 1): per place (a stop with a pedestrian
//   crossing the view), the features lost and recovered there; the rate per place,
//   their mean (the paper's 86.18 %) and the pooled rate Σ recovered / Σ lost (531 of
//   605, 87.8 %). A place without losses has no rate and is left out of the mean.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace trackbed::teach_repeat {

/// Options of the path projection.
struct PathProjectionOptions {
  /// Arc-length window around the previous projection [m], > 0 (see the file comment).
  double window_m = 2.0;
  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `teach_repeat.path_projection`), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("window_m", &window_m);
  }
};

/// A position relative to the taught path.
struct PathProjection {
  double arc_length_m = 0.0;  ///< along the taught path to the nearest point [m]
  double lateral_m = 0.0;     ///< signed distance to it [m], > 0 left of the path
};

/// Length of a polyline [m] (0 for fewer than two points).
double PolylineLength(const std::vector<Eigen::Vector2d>& path);

/// Path-following scores of one repeat.
struct RepeatPathMetrics {
  std::size_t samples = 0;         ///< repeated positions scored
  double taught_length_m = 0.0;    ///< length of the taught path
  double lateral_rms_m = 0.0;      ///< RMS of the lateral errors
  double lateral_max_m = 0.0;      ///< largest |lateral error|
  double end_point_error_m = 0.0;  ///< |last repeated position − last taught position|
  /// |lateral error| of the first repeated position [m]: the offset the repeat starts
  /// with. Unsigned: at the taught path's first vertex the side comes from its first
  /// segment, which on settling rough ground can be a fraction of a millimetre long
  /// in any direction.
  double lateral_start_m = 0.0;
  /// RMS lateral error over the last `kEndWindowM` of arc length reached [m]: where the
  /// repeat has got to; below |lateral_start_m| when an initial offset shrank.
  double lateral_end_rms_m = 0.0;
  static constexpr double kEndWindowM = 1.0;
  double covered_m = 0.0;  ///< largest arc length reached along the taught path
  /// completed ? 1 : covered_m / taught_length_m, in [0, 1].
  double autonomy = 0.0;
  bool completed = false;
};

/// Features lost and recovered at one place (or event).
struct RecoveryCounts {
  std::int64_t lost = 0;
  std::int64_t recovered = 0;
};

/// Recovery scores over places.
struct RecoveryMetrics {
  /// recovered / lost per place; NaN where nothing was lost.
  std::vector<double> per_place_rate;
  /// Mean of the per-place rates over places with losses (the paper's figure); NaN if
  /// no place lost anything.
  double mean_rate = 0.0;
  /// Σ recovered / Σ lost; NaN if nothing was lost.
  double pooled_rate = 0.0;
  std::int64_t lost = 0, recovered = 0;
  int places_with_losses = 0;
};

/// Throws std::invalid_argument for negative counts or more recovered than lost.
RecoveryMetrics EvaluateRecovery(const std::vector<RecoveryCounts>& places);

}  // namespace trackbed::teach_repeat
