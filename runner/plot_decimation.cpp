// Decimated paths and series for the plots (see plot_decimation.h).
#include "trackbed/runner/plot_decimation.h"

#include <cmath>
#include <stdexcept>

namespace trackbed::runner {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFirstStepM = 0.05;
constexpr double kFirstTurnRad = 2.0 * kPi / 180.0;

}  // namespace

DecimatedPath::DecimatedPath(std::size_t capacity) : capacity_(capacity) {
  if (capacity < 4) throw std::invalid_argument("DecimatedPath: capacity must be >= 4");
}

bool DecimatedPath::Far(const Point& kept, const Point& p) const {
  if (step_m_ == 0.0) return true;
  return p.path_m - kept.path_m >= step_m_ || p.turn_rad - kept.turn_rad >= turn_rad_;
}

void DecimatedPath::Add(double t_s, const Eigen::Isometry3d& T_world_body) {
  const Eigen::Matrix3d& R = T_world_body.linear();
  Point p{t_s, T_world_body.translation().head<2>(), std::atan2(R(1, 0), R(0, 0)), 0.0, 0.0};
  if (added_ > 0) {
    p.path_m = latest_.path_m + (p.xy - latest_.xy).norm();
    p.turn_rad =
        latest_.turn_rad + std::abs(std::remainder(p.yaw_rad - latest_.yaw_rad, 2.0 * kPi));
  }
  ++added_;
  latest_ = p;
  latest_kept_ = points_.empty() || Far(points_.back(), latest_);
  if (!latest_kept_) return;
  points_.push_back(latest_);
  if (points_.size() >= capacity_) Thin();
}

void DecimatedPath::Thin() {
  while (points_.size() > capacity_ / 2) {
    step_m_ = step_m_ == 0.0 ? kFirstStepM : 2.0 * step_m_;
    turn_rad_ = turn_rad_ == 0.0 ? kFirstTurnRad : 2.0 * turn_rad_;
    std::vector<Point> kept{points_.front()};
    for (std::size_t k = 1; k < points_.size(); ++k) {
      if (Far(kept.back(), points_[k])) kept.push_back(points_[k]);
    }
    points_ = std::move(kept);
  }
  // The latest pose may have been thinned out; Poses() adds it back.
  latest_kept_ = points_.back().t_s == latest_.t_s;
}

estimation::Trajectory DecimatedPath::Poses() const {
  estimation::Trajectory out;
  out.reserve(points_.size() + 1);
  auto add = [&out](const Point& p) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(p.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() << p.xy, 0.0;
    out.push_back({p.t_s, T});
  };
  for (const Point& p : points_) add(p);
  if (!latest_kept_) add(latest_);
  return out;
}

std::vector<Eigen::Vector2d> DecimatedPath::Points() const {
  std::vector<Eigen::Vector2d> out;
  out.reserve(points_.size() + 1);
  for (const Point& p : points_) out.push_back(p.xy);
  if (!latest_kept_) out.push_back(latest_.xy);
  return out;
}

}  // namespace trackbed::runner
