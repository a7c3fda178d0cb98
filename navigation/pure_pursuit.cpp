// Pure-pursuit path follower (see pure_pursuit.h).
#include "trackbed/navigation/pure_pursuit.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {

void PurePursuitOptions::Validate() const {
  option_check::Positive("speed_mps", speed_mps);
  option_check::Positive("lookahead_m", lookahead_m);
  option_check::Positive("goal_tolerance_m", goal_tolerance_m);
  option_check::Positive("max_yaw_rate_radps", max_yaw_rate_radps);
  option_check::InRange("turn_in_place_rad", turn_in_place_rad, 1e-3, M_PI);
}

PurePursuit::PurePursuit(const PurePursuitOptions& options, std::vector<Eigen::Vector2d> waypoints,
                         bool closed, int laps)
    : options_(options), points_(std::move(waypoints)), closed_(closed), laps_(closed ? laps : 1) {
  options_.Validate();
  if (laps < 1) throw std::invalid_argument("PurePursuit: laps must be >= 1");
  if (points_.size() < 2) throw std::invalid_argument("PurePursuit: needs at least two waypoints");
  if (closed_) points_.push_back(points_.front());
  cumulative_.push_back(0.0);
  for (std::size_t k = 1; k < points_.size(); ++k) {
    cumulative_.push_back(cumulative_.back() + (points_[k] - points_[k - 1]).norm());
  }
  if (!(cumulative_.back() > 0.0)) {
    throw std::invalid_argument("PurePursuit: the path has zero length");
  }
}

Eigen::Vector2d PurePursuit::PointAt(double s) const {
  const double total = cumulative_.back();
  if (closed_) {
    s = std::fmod(s, total);
    if (s < 0) s += total;
  } else {
    s = std::clamp(s, 0.0, total);
  }
  auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  std::size_t k = std::clamp<std::size_t>(it - cumulative_.begin(), 1, points_.size() - 1);
  const double seg = cumulative_[k] - cumulative_[k - 1];
  const double a = seg > 0 ? (s - cumulative_[k - 1]) / seg : 0.0;
  return points_[k - 1] + a * (points_[k] - points_[k - 1]);
}

double PurePursuit::Project(const Eigen::Vector2d& p, double* distance, double* side) const {
  // Search a window of arc length around the current progress, so that a
  // crossing or the loop's start does not make the projection jump.
  const double total = cumulative_.back();
  const double lap = closed_ ? std::floor(progress_m_ / total) * total : 0.0;
  const double local = progress_m_ - lap;
  const double window_back = 0.5, window_ahead = 2.0 + 2.0 * options_.lookahead_m;
  double best_s = progress_m_, best_d = 1e300, best_side = 0.0;
  const std::size_t n = points_.size();
  for (int wrap = 0; wrap < (closed_ ? 2 : 1); ++wrap) {
    for (std::size_t k = 1; k < n; ++k) {
      const double s0 = cumulative_[k - 1] + wrap * total;
      const double s1 = cumulative_[k] + wrap * total;
      if (s1 < local - window_back || s0 > local + window_ahead) continue;
      const Eigen::Vector2d a = points_[k - 1], d = points_[k] - points_[k - 1];
      const double len2 = d.squaredNorm();
      if (len2 <= 0) continue;
      double t = std::clamp((p - a).dot(d) / len2, 0.0, 1.0);
      double s = s0 + t * (s1 - s0);
      s = std::clamp(s, local - window_back, local + window_ahead);
      const Eigen::Vector2d q = PointAt(s);
      const double dist = (p - q).norm();
      if (dist < best_d) {
        best_d = dist;
        best_s = lap + s;
        best_side = d.x() * (p - a).y() - d.y() * (p - a).x();
      }
    }
  }
  *distance = best_d;
  *side = best_side >= 0 ? 1.0 : -1.0;
  return best_s;
}

PurePursuitCommand PurePursuit::Update(const Pose2& pose) {
  PurePursuitCommand cmd;
  const Eigen::Vector2d p(pose.x, pose.y);
  double distance = 0.0, side = 1.0;
  progress_m_ = std::max(progress_m_, Project(p, &distance, &side));
  cmd.progress_m = progress_m_;
  cmd.cross_track_m = side * distance;

  const double total = cumulative_.back() * laps_;
  const double remaining = total - progress_m_;
  const Eigen::Vector2d end = closed_ ? points_.front() : points_.back();
  if (remaining <= options_.lookahead_m && (p - end).norm() <= options_.goal_tolerance_m) {
    cmd.finished = true;
    return cmd;
  }
  if (remaining <= 0.0) {  // past the end but not within tolerance: stop anyway
    cmd.finished = true;
    return cmd;
  }
  // Look-ahead point; near the end of the path it is the end itself.
  const Eigen::Vector2d target =
      remaining > options_.lookahead_m ? PointAt(progress_m_ + options_.lookahead_m) : end;
  const Eigen::Vector2d delta = target - p;
  const double bearing = std::atan2(delta.y(), delta.x());
  const double alpha = std::remainder(bearing - pose.yaw, 2.0 * M_PI);
  const double lookahead = std::max(delta.norm(), 1e-6);
  // Slow down over the last metre so the robot stops at the end.
  double speed = options_.speed_mps;
  if (!closed_ || remaining < options_.lookahead_m) {
    speed = std::min(speed, std::max(0.05, remaining));
  }
  if (std::abs(alpha) > options_.turn_in_place_rad) {
    cmd.twist.v_mps = 0.0;
    cmd.twist.yaw_rate_radps = std::copysign(options_.max_yaw_rate_radps * 0.5, alpha);
    return cmd;
  }
  const double curvature = 2.0 * std::sin(alpha) / lookahead;
  double yaw_rate = speed * curvature;
  if (std::abs(yaw_rate) > options_.max_yaw_rate_radps) {
    // Keep the arc, lower the speed.
    speed *= options_.max_yaw_rate_radps / std::abs(yaw_rate);
    yaw_rate = std::copysign(options_.max_yaw_rate_radps, yaw_rate);
  }
  cmd.twist.v_mps = speed;
  cmd.twist.yaw_rate_radps = yaw_rate;
  return cmd;
}

}  // namespace trackbed::navigation
