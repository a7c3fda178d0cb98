// Undistortion of one camera's images, as a real pipeline does before a method that
// assumes a pinhole (teach & repeat's milestones): OpenCV's initUndistortRectifyMap
// (its fisheye module's for an equidistant lens) with the camera's own intrinsics
// kept, and one remap per image. The software knows the lens only as calibrated.
#pragma once

#include <opencv2/core.hpp>

#include "trackbed/common/pinhole_camera.h"

namespace trackbed::perception {

/// OpenCV's coefficient vector for `lens`: (k1, k2, p1, p2, k3) for calib3d's
/// radial–tangential model, (k1, k2, k3, k4) for its fisheye module.
cv::Mat CvLensCoefficients(const geometry::LensDistortion& lens);

/// The map from the pixels of a rectified camera (projection P, rotated by R from
/// `camera`'s frame) to `camera`'s pixels through its lens, as
/// initUndistortRectifyMap makes it (the fisheye module's for an equidistant lens).
void UndistortRectifyMap(const geometry::PinholeCamera& camera, const cv::Mat& R, const cv::Mat& P,
                         cv::Mat* map_x, cv::Mat* map_y);

class LensUndistorter {
 public:
  /// Throws OptionError for an invalid camera or lens.
  explicit LensUndistorter(const geometry::PinholeCamera& camera);

  /// Whether the lens is an ideal pinhole already: then images pass through untouched.
  bool identity() const { return identity_; }
  /// The camera of the undistorted images: the given intrinsics, no lens.
  const geometry::PinholeCamera& camera() const { return camera_; }
  /// Undistorts an 8-bit grey image of the camera's size into *out (bilinear; outside
  /// the source: black). With identity(), *out shares the input's pixels.
  void Undistort(const cv::Mat& image, cv::Mat* out) const;

 private:
  bool identity_ = true;
  geometry::PinholeCamera camera_;
  cv::Mat map_x_, map_y_;
};

}  // namespace trackbed::perception
