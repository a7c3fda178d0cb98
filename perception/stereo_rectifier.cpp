// Stereo rectification (see stereo_rectifier.h).
#include "trackbed/perception/stereo_rectifier.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "trackbed/perception/lens_undistorter.h"
#include "trackbed/perception/opencv_views.h"

namespace trackbed::perception {
namespace {

cv::Matx33d ToCv(const Eigen::Matrix3d& m) {
  cv::Matx33d out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out(r, c) = m(r, c);
  }
  return out;
}

}  // namespace

StereoRectifier::StereoRectifier(const calibration::StereoCalibration& given) {
  given.Validate();
  if (given.IsRectified()) {
    camera_ = given.RectifiedPair();
    T_body_left_ = given.T_body_left;
    return;
  }
  identity_ = false;
  // OpenCV's R, T map left-camera coordinates into the right camera's frame.
  const Eigen::Isometry3d T_right_left = given.T_left_right().inverse();
  const cv::Matx33d R = ToCv(T_right_left.linear());
  const cv::Vec3d T(T_right_left.translation().x(), T_right_left.translation().y(),
                    T_right_left.translation().z());
  const cv::Size size(given.width_px, given.height_px);
  cv::Mat R1, R2, P1, P2, Q;
  const geometry::PinholeCamera left = given.LeftCamera(), right = given.RightCamera();
  const auto fisheye = [](const geometry::PinholeCamera& c) {
    return c.distortion.model == geometry::LensModel::kEquidistant;
  };
  if (fisheye(left) || fisheye(right)) {
    // The fisheye module's rectification (balance 0: no invalid pixels in view).
    cv::fisheye::stereoRectify(CvCameraMatrix(left), CvLensCoefficients(left.distortion),
                               CvCameraMatrix(right), CvLensCoefficients(right.distortion), size, R,
                               T, R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, size,
                               /*balance=*/0.0);
  } else {
    cv::stereoRectify(CvCameraMatrix(left), CvLensCoefficients(left.distortion),
                      CvCameraMatrix(right), CvLensCoefficients(right.distortion), size, R, T, R1,
                      R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, /*alpha=*/0.0, size);
  }
  UndistortRectifyMap(left, R1, P1, &map_left_x_, &map_left_y_);
  UndistortRectifyMap(right, R2, P2, &map_right_x_, &map_right_y_);
  interpolation_ = RemapInterpolation(!left.distortion.is_zero() || !right.distortion.is_zero());
  if (interpolation_ == cv::INTER_CUBIC) {
    // Maps decoded once: cv::remap's bytes at about a quarter of its cost (bicubic_remap.h).
    remaps_.emplace_back(map_left_x_, map_left_y_, size);
    remaps_.emplace_back(map_right_x_, map_right_y_, size);
  }
  camera_.left.width_px = given.width_px;
  camera_.left.height_px = given.height_px;
  camera_.left.fx = P1.at<double>(0, 0);
  camera_.left.fy = P1.at<double>(1, 1);
  camera_.left.cx = P1.at<double>(0, 2);
  camera_.left.cy = P1.at<double>(1, 2);
  camera_.baseline_m = -P2.at<double>(0, 3) / P2.at<double>(0, 0);
  // R1 rotates the left camera's coordinates into the rectified left camera's.
  Eigen::Matrix3d R_rect_left;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R_rect_left(r, c) = R1.at<double>(r, c);
  }
  T_body_left_ = given.T_body_left;
  T_body_left_.linear() = given.T_body_left.linear() * R_rect_left.transpose();
}

void StereoRectifier::Rectify(const cv::Mat& left, const cv::Mat& right, cv::Mat* left_out,
                              cv::Mat* right_out) const {
  if (identity_) {
    *left_out = left;
    *right_out = right;
    return;
  }
  if (!remaps_.empty()) {
    remaps_[0].Apply(left, left_out);
    remaps_[1].Apply(right, right_out);
    return;
  }
  // RemapInterpolation (lens_undistorter.h says why).
  cv::remap(left, *left_out, map_left_x_, map_left_y_, interpolation_, cv::BORDER_CONSTANT, 0);
  cv::remap(right, *right_out, map_right_x_, map_right_y_, interpolation_, cv::BORDER_CONSTANT, 0);
}

}  // namespace trackbed::perception
