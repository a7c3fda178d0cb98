// Trajectories and their TUM form (see trajectory.h).
#include "trackbed/estimation/trajectory.h"

#include <cstdio>

namespace trackbed::estimation {

std::string FormatTumLine(const StampedPose& pose) {
  const Eigen::Vector3d p = pose.T_world_body.translation();
  Eigen::Quaterniond q(pose.T_world_body.linear());
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;  // one sign convention: qw >= 0
  char buf[256];
  std::snprintf(buf, sizeof(buf), "%.6f %.9g %.9g %.9g %.9g %.9g %.9g %.9g", pose.t_s, p.x(), p.y(),
                p.z(), q.x(), q.y(), q.z(), q.w());
  return buf;
}

double PathLength(const Trajectory& trajectory) {
  double length = 0.0;
  for (std::size_t k = 1; k < trajectory.size(); ++k) {
    length +=
        (trajectory[k].T_world_body.translation() - trajectory[k - 1].T_world_body.translation())
            .norm();
  }
  return length;
}

}  // namespace trackbed::estimation
