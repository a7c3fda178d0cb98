// A gyro's rotation over an interval cut between samples (see gyro_rotation.h).
#include "trackbed/estimation/gyro_rotation.h"

#include <algorithm>

#include "trackbed/common/se3.h"

namespace trackbed::estimation {

Eigen::Matrix3d IntegrateGyro(const std::deque<GyroInterval>& intervals, double t0_s, double t1_s) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  if (intervals.empty() || !(t1_s > t0_s)) return R;
  const auto add = [&](const Eigen::Vector3d& rate, double a, double b) {
    const double from = std::max(a, t0_s), to = std::min(b, t1_s);
    if (to > from) R = R * geometry::ExpSO3(rate * (to - from));
  };
  add(intervals.front().rate_radps, t0_s, intervals.front().t0_s);  // before the first
  for (const GyroInterval& g : intervals) add(g.rate_radps, g.t0_s, g.t1_s);
  add(intervals.back().rate_radps, intervals.back().t1_s, t1_s);  // after the last
  return R;
}

void DropGyroBefore(double t_s, std::deque<GyroInterval>* intervals) {
  while (!intervals->empty() && intervals->front().t1_s <= t_s) intervals->pop_front();
}

}  // namespace trackbed::estimation
