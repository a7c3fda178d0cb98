// From a 2-D range scan to obstacle circles in the world frame, for the avoiders of
// this library (`closed_loop` mode). Pure: the ray casting that produces the
// scan lives with the simulator.
//
// 1. Hits: beams with a finite range below max range, in the world frame through the
//    sensor pose.
// 2. Clusters: consecutive hits (in beam order) closer than `jump_threshold_m`; a beam
//    without a hit also ends a cluster. With `wrap_around`, the last and first clusters
//    of a full 360° scan are joined when they meet.
// 3. Circles. A cluster whose extent (largest distance of its hits from its first hit)
//    is at most `max_fit_extent_m` is one obstacle: an algebraic least-squares circle
//    (Kåsa) through its hits when it has at least `min_fit_points`, its radius is within
//    [min_radius_m, max_radius_m] and its centre lies beyond the hits (seen from the
//    sensor); otherwise the centre is the hits' mean pushed away from the sensor by the
//    radius, and the radius is half the extent (at least min_radius_m). Either way the
//    radius is then grown, if needed, until the circle covers every hit of the cluster,
//    so noise makes circles larger, never smaller.
//    A longer cluster (a wall, a large object) is chopped, in beam order, into pieces no
//    longer than half of `wall_spacing_m` (≤ d_max): each piece becomes the circle
//    centred at the mean of its hits that covers them (radius at least min_radius_m).
//    Where two consecutive piece centres are still farther apart than the spacing (the
//    hits were unevenly spread), circles are inserted evenly on the line between them —
//    the cluster has no jump there, so the wall is continuous. A wall thus becomes a
//    chain of circles whose consecutive centres are at most wall_spacing_m apart.
#pragma once

#include <vector>

#include "trackbed/navigation/circle_obstacle.h"
#include "trackbed/navigation/diff_drive.h"

namespace trackbed::navigation {

/// A planar range scan in the sensor frame (x forward, y left).
struct RangeScan {
  std::vector<double> ranges_m;    ///< One per beam; ≥ max_range_m, inf or NaN = no hit.
  std::vector<double> angles_rad;  ///< Beam angles in the sensor frame, in scan order.
  double max_range_m = 8.0;
};

struct ScanClusteringOptions {
  /// Consecutive hits farther apart than this [m] start a new cluster, > 0.
  double jump_threshold_m = 0.3;
  /// Clusters up to this extent [m] are fitted as one circle, > 0.
  double max_fit_extent_m = 1.5;
  /// Longer clusters become chains of circles at most this far apart [m], > 0 (≤ d_max;
  /// a closed-loop run uses the smaller of this and `navigation.safety_radius_m`).
  double wall_spacing_m = 1.0;
  /// Least-squares fits need at least this many hits, >= 3.
  int min_fit_points = 5;
  /// Radius bounds [m] for fitted circles; min_radius_m also floors every circle, > 0.
  double min_radius_m = 0.05;
  double max_radius_m = 1.0;
  /// Clusters with fewer hits are dropped as noise, >= 1.
  int min_cluster_points = 1;
  /// Join the last cluster to the first (a full 360° scan).
  bool wrap_around = true;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `navigation.clustering`), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("jump_threshold_m", &jump_threshold_m);
    a->Visit("max_fit_extent_m", &max_fit_extent_m);
    a->Visit("wall_spacing_m", &wall_spacing_m);
    a->Visit("min_fit_points", &min_fit_points);
    a->Visit("min_radius_m", &min_radius_m);
    a->Visit("max_radius_m", &max_radius_m);
    a->Visit("min_cluster_points", &min_cluster_points);
    a->Visit("wrap_around", &wrap_around);
  }
};

/// Obstacle circles in the world frame seen by a scan taken at `sensor_pose_world`.
/// Throws std::invalid_argument if ranges and angles differ in length, OptionError for
/// invalid options.
std::vector<Circle> ClusterScan(const RangeScan& scan, const Pose2& sensor_pose_world,
                                const ScanClusteringOptions& options = {});

}  // namespace trackbed::navigation
