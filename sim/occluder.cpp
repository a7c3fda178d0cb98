// Scripted walking occluders (see occluder.h).
#include "trackbed/sim/occluder.h"

#include <cmath>

#include "trackbed/common/option_error.h"

namespace trackbed::sim {

void OccluderSpec::Validate() const {
  if (waypoints.empty()) throw OptionError("waypoints", "needs at least one point");
  for (const Eigen::Vector2d& p : waypoints) {
    if (!p.allFinite()) throw OptionError("waypoints", "must be finite");
  }
  option_check::Positive("speed_mps", speed_mps);
  option_check::NonNegative("start_s", start_s);
  option_check::InRange("height_m", height_m, 0.2, 3.0);
  option_check::InRange("radius_m", radius_m, 0.05, 1.0);
}

OccluderPose OccluderPoseAt(const OccluderSpec& spec, double t_s) {
  const std::vector<Eigen::Vector2d>& w = spec.waypoints;
  OccluderPose pose;
  pose.position_m = w.front();
  double length = 0.0;
  for (std::size_t k = 1; k < w.size(); ++k) length += (w[k] - w[k - 1]).norm();
  if (w.size() < 2 || length <= 0.0) return pose;
  if (w.size() >= 2) {
    const Eigen::Vector2d d = w[1] - w[0];
    pose.yaw_rad = std::atan2(d.y(), d.x());
  }
  double s = std::max(0.0, t_s - spec.start_s) * spec.speed_mps;
  bool backwards = false;
  if (spec.back_and_forth) {
    s = std::fmod(s, 2.0 * length);
    if (s > length) {
      s = 2.0 * length - s;
      backwards = true;
    }
  } else {
    s = std::min(s, length);
  }
  for (std::size_t k = 1; k < w.size(); ++k) {
    const double seg = (w[k] - w[k - 1]).norm();
    if (s <= seg || k + 1 == w.size()) {
      const double a = seg > 0 ? std::min(s / seg, 1.0) : 0.0;
      pose.position_m = w[k - 1] + a * (w[k] - w[k - 1]);
      const Eigen::Vector2d d =
          backwards ? Eigen::Vector2d(w[k - 1] - w[k]) : Eigen::Vector2d(w[k] - w[k - 1]);
      pose.yaw_rad = std::atan2(d.y(), d.x());
      return pose;
    }
    s -= seg;
  }
  return pose;
}

}  // namespace trackbed::sim
