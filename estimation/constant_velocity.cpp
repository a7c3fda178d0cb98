// The constant-velocity motion model (see constant_velocity.h).
#include "trackbed/estimation/constant_velocity.h"

namespace trackbed::estimation {

Eigen::Isometry3d ContinuedMotion(const Eigen::Isometry3d& T, double dt_from, double dt_to) {
  const double s = dt_from > 0.0 ? dt_to / dt_from : 1.0;
  const Eigen::AngleAxisd r(T.linear());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::AngleAxisd(s * r.angle(), r.axis()).toRotationMatrix();
  out.translation() = s * T.translation();
  return out;
}

}  // namespace trackbed::estimation
