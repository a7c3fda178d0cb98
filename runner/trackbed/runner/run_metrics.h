// Per-run figures scored against ground truth, accumulated sample by sample.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/estimation/icr_calibration.h"
#include "trackbed/navigation/navigation_metrics.h"
#include "trackbed/navigation/subgoal_planner.h"
#include "trackbed/robot/tracked_vehicle.h"
#include "trackbed/runner/estimator_scoring.h"
#include "trackbed/runner/run_sample.h"

namespace trackbed::runner {

/// Slip statistics of the samples where a track moved (|track speed| > 0.05 m/s).
struct SlipStats {
  double sum_abs_ratio = 0.0;
  double sum_ratio = 0.0;
  double sum_abs_velocity_mps = 0.0;
  long long samples = 0;

  double mean_abs_ratio() const { return samples ? sum_abs_ratio / samples : 0.0; }
  double mean_ratio() const { return samples ? sum_ratio / samples : 0.0; }
  double mean_abs_velocity_mps() const { return samples ? sum_abs_velocity_mps / samples : 0.0; }
};

/// How a teach & repeat run did (metrics.json `teach_repeat`): the repeat's ground
/// truth against the taught route's.
struct TeachRepeatMetrics {
  std::string method;
  /// How the repeat ended: finished, lost, or the run's stop reason.
  std::string status;
  bool completed = false;
  double autonomy = 0.0;  ///< fraction of the taught route covered before a failure
  double end_point_error_m = 0.0;
  double lateral_rms_m = 0.0, lateral_max_m = 0.0;
  /// The first repeated position's |lateral error|, and the RMS lateral error over the
  /// last metre reached [m]: an initial offset that shrinks (convergence).
  double lateral_start_m = 0.0, lateral_end_rms_m = 0.0;
  double taught_length_m = 0.0;
  std::int64_t features_lost = 0, features_recovered = 0;
  /// With crossing places (teach_repeat.occluders): the mean of the per-place rates
  /// recovered / lost over places with losses (Choi & Ha's 86.18 %); without, the
  /// pooled rate over the whole repeat. NaN when nothing was lost.
  double recovery_rate = 0.0;
  /// Σ recovered / Σ lost over the places (without places: over the repeat); NaN when
  /// nothing was lost.
  double recovery_rate_pooled = 0.0;
  /// One crossing place: its time window in the repeat [s] and what it lost and
  /// recovered (rate NaN when it lost nothing).
  struct Place {
    double start_s = 0.0, end_s = 0.0;
    std::int64_t lost = 0, recovered = 0;
    double rate = 0.0;
  };
  std::vector<Place> places;
  int milestones = 0;
  int teach_images = 0;
  /// 2D: milestone switches made by the distance bound, not by the images.
  int switches_by_distance = 0;
  /// The teach map's folder on disk [MB] (10^6 bytes), and per 100 m of taught path.
  double map_size_mb = 0.0;
  double map_mb_per_100m = 0.0;
};

struct RunMetrics {
  bool completed = false;
  /// Why the run ended: "duration reached", "path finished", or the failure.
  std::string stop_reason;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  /// Length of the ground-truth polyline sampled at the encoder rate [m].
  double distance_m = 0.0;
  /// Σ |r (Δφ_l + Δφ_r) / 2| over encoder samples [m].
  double encoder_distance_m = 0.0;
  SlipStats slip[2];                                  ///< Per track.
  std::map<std::string, SlipStats> slip_by_material;  ///< Both tracks pooled.
  /// χ fitted on this run against the true yaw rate; meaningful where `icr.identified`.
  estimation::IcrFit icr;
  /// Lowest clearance of the centre of mass above the terrain [m].
  double min_com_height_m = 0.0;
  /// Stereo pairs rendered, and the wall-clock time spent rendering them [s] (on the
  /// main thread).
  long long stereo_frames = 0;
  double render_wall_s = 0.0;
  /// Wall-clock time of the cameras' sensor model (exposure, noise, blackouts) [s]: on
  /// the localization thread when nothing on the main thread looks at the images (an
  /// image export or teach & repeat does), else on the main thread.
  double sensor_model_wall_s = 0.0;
  /// Wall-clock time spent in the localization stack [s] (on its own thread when the
  /// camera is on).
  double estimation_wall_s = 0.0;
  /// Wall-clock time of the main thread's other stages [s]: physics (forces and the
  /// Bullet step), control (driver or navigator), sensing (the range sensor) and the
  /// observers' file output.
  double physics_wall_s = 0.0, control_wall_s = 0.0, sensing_wall_s = 0.0, io_wall_s = 0.0;
  /// Wall-clock time building the world, the renderer and the robot software before
  /// the first step [s]: terrain, objects, Bullet shapes, textures, the stack.
  double setup_wall_s = 0.0;
  /// Peak resident memory of the process at the end of the run [MB].
  double peak_rss_mb = 0.0;
  /// The robot's track marks (`scene.appearance.track_marks`): points held and recorded
  /// over both tracks, and the most their record holds however long the run [MB].
  struct TrackMarkCounts {
    std::uint64_t points_held = 0, points_recorded = 0;
    double bound_mb = 0.0;
  };
  std::optional<TrackMarkCounts> track_marks;
  /// Per estimator (wheel_odometry, wheel_odometry_noslip, visual_odometry, fused).
  std::map<std::string, EstimatorMetrics> estimators;
  LocalizationSummary localization;
  /// Point-to-point navigation runs (scenario `navigation.enabled`): the method and how
  /// it did (metrics.json `navigation`).
  std::string navigation_method;
  std::optional<navigation::NavigationMetrics> navigation;
  /// The sub-goals the navigator created (for the map plot).
  std::vector<navigation::SubgoalRecord> navigation_subgoals;
  /// Teach & repeat runs (scenario `teach_repeat.enabled`).
  std::optional<TeachRepeatMetrics> teach_repeat;
  /// A repeat pass: features its repeater lost and recovered, in all.
  std::int64_t repeat_features_lost = 0, repeat_features_recovered = 0;

  double real_time_factor() const { return wall_time_s > 0 ? sim_time_s / wall_time_s : 0.0; }
};

/// Accumulates RunMetrics from consecutive samples.
class MetricsAccumulator {
 public:
  MetricsAccumulator(double sprocket_radius_m, double track_gauge_m, int ticks_per_rev);
  void Add(const RunSample& sample, double terrain_height_m);
  /// The metrics so far (wall time, completion and reason left to the caller).
  RunMetrics Metrics() const;
  /// The ICR fit's jackknife groups held (estimation::RunningIcrFit::groups).
  std::size_t icr_fit_groups() const { return icr_ ? icr_->groups() : 0; }

 private:
  double r_, gauge_;
  int ticks_per_rev_;
  bool has_previous_ = false;
  RunSample previous_;
  RunMetrics m_;
  // χ from running sums, its windows 1 s long at the first sample interval's rate
  // (docs/physics.md, "ICR calibration").
  std::optional<estimation::RunningIcrFit> icr_;
};

}  // namespace trackbed::runner
