// What the run folder's plots keep of a run, in memory that does not grow with its
// length (docs/run_folder.md, "Plots of long runs"): a planar path decimated by distance
// and turn, and a time series decimated by a stride, each held under a fixed number of
// points. A run whose series stay under that number keeps every point it was given.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "trackbed/estimation/trajectory.h"

namespace trackbed::runner {

/// Points a path or a series holds at most: 20000, 33 min of 10 Hz samples.
inline constexpr std::size_t kPlotCapacity = 20000;

/// A planar path (x, y and heading of each pose) for the plots. Every pose given is kept
/// until the path holds `capacity` points; then it is thinned to a polyline whose
/// consecutive points are at least `step_m` of path apart or turn by at least `turn_rad`
/// in all (path and turning summed over the poses given between them; first 0.05 m and
/// 2°, both doubled at each further thinning until at most half the capacity is left),
/// and later poses are kept on the same rule. The first and the latest pose are always in
/// the path. A path of length L then holds about L / step_m points: on a long run the
/// spacing grows with L (L / capacity at least).
class DecimatedPath {
 public:
  explicit DecimatedPath(std::size_t capacity = kPlotCapacity);
  void Add(double t_s, const Eigen::Isometry3d& T_world_body);
  /// The kept poses and the latest one, in order, as planar poses (z = 0, rotation about
  /// z only).
  estimation::Trajectory Poses() const;
  std::vector<Eigen::Vector2d> Points() const;
  std::size_t size() const { return points_.size(); }
  double step_m() const { return step_m_; }
  double turn_rad() const { return turn_rad_; }

 private:
  struct Point {
    double t_s;
    Eigen::Vector2d xy;
    double yaw_rad;
    double path_m;    // planar path length from the first pose
    double turn_rad;  // Σ |heading change| from the first pose
  };
  bool Far(const Point& kept, const Point& p) const;
  void Thin();
  std::size_t capacity_;
  double step_m_ = 0.0, turn_rad_ = 0.0;  // 0 until the first thinning: keep every pose
  std::vector<Point> points_;
  Point latest_{};
  long long added_ = 0;
  bool latest_kept_ = true;
};

/// Items given in order, for a plot: every item until `capacity`, then every second of
/// those kept, the stride doubling each time the capacity is reached again (kept: the
/// items whose index is a multiple of the stride).
template <class T>
class StrideDecimated {
 public:
  explicit StrideDecimated(std::size_t capacity = kPlotCapacity) : capacity_(capacity) {
    if (capacity < 2) throw std::invalid_argument("StrideDecimated: capacity must be >= 2");
  }
  void Add(const T& item) {
    const bool keep = index_ % stride_ == 0;
    ++index_;
    if (!keep) return;
    items_.push_back(item);
    if (items_.size() < capacity_) return;
    // Every second kept item: those whose index is a multiple of the doubled stride.
    std::size_t n = 0;
    for (std::size_t k = 0; k < items_.size(); k += 2) items_[n++] = items_[k];
    items_.resize(n);
    stride_ *= 2;
  }
  const std::vector<T>& items() const { return items_; }
  std::size_t size() const { return items_.size(); }

 private:
  std::size_t capacity_;
  long long index_ = 0, stride_ = 1;
  std::vector<T> items_;
};

/// A time series (t, value) for the plots, stride-decimated (StrideDecimated).
class DecimatedSeries {
 public:
  explicit DecimatedSeries(std::size_t capacity = kPlotCapacity) : points_(capacity) {}
  void Add(double t, double value) { points_.Add(Eigen::Vector2d(t, value)); }
  const std::vector<Eigen::Vector2d>& points() const { return points_.items(); }
  bool empty() const { return points_.size() == 0; }
  std::size_t size() const { return points_.size(); }

 private:
  StrideDecimated<Eigen::Vector2d> points_;
};

}  // namespace trackbed::runner
