// One camera's undistortion (see lens_undistorter.h).
#include "trackbed/perception/lens_undistorter.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "trackbed/common/option_error.h"

namespace trackbed::perception {

LensUndistorter::LensUndistorter(const geometry::PinholeCamera& camera) : camera_(camera) {
  camera_.Validate();
  const geometry::LensDistortion lens = camera.distortion;
  lens.Validate();
  camera_.distortion = geometry::LensDistortion{};
  if (lens.is_zero()) return;
  identity_ = false;
  const cv::Matx33d K(camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0);
  const cv::Size size(camera.width_px, camera.height_px);
  const cv::Mat R = cv::Mat::eye(3, 3, CV_64F);
  if (lens.model == geometry::LensModel::kEquidistant) {
    const cv::Mat D = (cv::Mat_<double>(1, 4) << lens.k1, lens.k2, lens.k3, lens.k4);
    cv::fisheye::initUndistortRectifyMap(K, D, R, K, size, CV_32FC1, map_x_, map_y_);
  } else {
    const cv::Mat D = (cv::Mat_<double>(1, 5) << lens.k1, lens.k2, lens.p1, lens.p2, lens.k3);
    cv::initUndistortRectifyMap(K, D, R, K, size, CV_32FC1, map_x_, map_y_);
  }
}

void LensUndistorter::Undistort(const cv::Mat& image, cv::Mat* out) const {
  if (identity_) {
    *out = image;
    return;
  }
  cv::remap(image, *out, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
}

}  // namespace trackbed::perception
