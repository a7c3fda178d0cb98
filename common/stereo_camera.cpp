// Rectified stereo pair and its KITTI form (see stereo_camera.h).
#include "trackbed/common/stereo_camera.h"

#include <cmath>

#include "trackbed/common/option_error.h"

namespace trackbed::geometry {

Eigen::Vector3d StereoCamera::Triangulate(double u, double v, double disparity_px) const {
  const double Z = left.fx * baseline_m / disparity_px;
  return {(u - left.cx) * Z / left.fx, (v - left.cy) * Z / left.fy, Z};
}

Eigen::Vector3d StereoCamera::Project(const Eigen::Vector3d& p) const {
  const PinholeCamera& c = left;
  const double inv_z = 1.0 / p.z();
  return {c.fx * p.x() * inv_z + c.cx, c.fy * p.y() * inv_z + c.cy,
          c.fx * (p.x() - baseline_m) * inv_z + c.cx};
}

Eigen::Matrix<double, 3, 4> StereoCamera::LeftProjection() const {
  Eigen::Matrix<double, 3, 4> P;
  P.leftCols<3>() = left.K();
  P.col(3).setZero();
  return P;
}

Eigen::Matrix<double, 3, 4> StereoCamera::RightProjection() const {
  Eigen::Matrix<double, 3, 4> P;
  P.leftCols<3>() = left.K();
  P.col(3) << -left.fx * baseline_m, 0.0, 0.0;
  return P;
}

void StereoCamera::Validate() const {
  option_check::Nested("left", left);
  option_check::Positive("baseline_m", baseline_m);
}

StereoCamera StereoCamera::FromProjections(const Eigen::Matrix<double, 3, 4>& P0,
                                           const Eigen::Matrix<double, 3, 4>& P1) {
  StereoCamera c;
  c.left.fx = P0(0, 0);
  c.left.fy = P0(1, 1);
  c.left.cx = P0(0, 2);
  c.left.cy = P0(1, 2);
  c.baseline_m = -P1(0, 3) / P1(0, 0);
  return c;
}

}  // namespace trackbed::geometry
