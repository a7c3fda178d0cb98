// Rectification of a stereo pair from its calibration, as a real stereo pipeline
// does before matching: OpenCV's stereoRectify (Bouguet's method: both image planes
// rotated half way to a common orientation, rows aligned) and one remap per image.
// A lens (radial–tangential or equidistant) is undistorted by the same remap, as
// initUndistortRectifyMap does (the fisheye module's for an equidistant lens).
// The software knows the pair only through its given calibration, so a calibration
// error leaves rows misaligned and disparities biased: the error a real robot's VO
// lives with (docs/calibration.md).
#pragma once

#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "trackbed/common/robot_calibration.h"
#include "trackbed/common/stereo_camera.h"
#include "trackbed/perception/bicubic_remap.h"

namespace trackbed::perception {

class StereoRectifier {
 public:
  /// Throws OptionError for an invalid calibration.
  explicit StereoRectifier(const calibration::StereoCalibration& given);

  /// Whether the given pair is rectified already: then images pass through untouched.
  bool identity() const { return identity_; }
  /// The rectified pair (one pinhole camera and the baseline).
  const geometry::StereoCamera& camera() const { return camera_; }
  /// The rectified left camera in the body frame.
  const Eigen::Isometry3d& T_body_left() const { return T_body_left_; }
  /// Rectifies a pair of 8-bit grey images of the calibration's size into *left_out
  /// and *right_out (RemapInterpolation: Lanczos when either camera has a lens, else
  /// bicubic; outside the source image: black, which alpha = 0 keeps out of the
  /// rectified view). With identity(), the outputs share the inputs' pixels.
  void Rectify(const cv::Mat& left, const cv::Mat& right, cv::Mat* left_out,
               cv::Mat* right_out) const;

 private:
  bool identity_ = true;
  geometry::StereoCamera camera_;
  Eigen::Isometry3d T_body_left_ = Eigen::Isometry3d::Identity();
  cv::Mat map_left_x_, map_left_y_, map_right_x_, map_right_y_;
  int interpolation_ = 0;             // cv::InterpolationFlags
  std::vector<BicubicRemap> remaps_;  // left and right, when bicubic
};

}  // namespace trackbed::perception
