// Undistortion of one camera's images, as a real pipeline does before a method that
// assumes a pinhole (teach & repeat's milestones): OpenCV's initUndistortRectifyMap
// (its fisheye module's for an equidistant lens) with the camera's own intrinsics
// kept, and one remap per image. The software knows the lens only as calibrated.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "trackbed/common/pinhole_camera.h"

namespace trackbed::perception {

/// How rectification and undistortion resample (cv::remap). An interpolator low-passes
/// a pixel by an amount that depends on where it falls between the source's pixels, so
/// a corner's sharpness changes from frame to frame as it moves across the image and
/// Lucas–Kanade tracking inherits the change as motion; bilinear's response varies most
/// with the sub-pixel phase, bicubic's less, Lanczos's (8 × 8 taps) least. Through a
/// lens, whose map stretches and squeezes the image, Lanczos: VO's median ATE through
/// EuRoC's lens went from 1.56× the pinhole camera's (bicubic) to 1.01×. Without one (a
/// calibration error's small rotation and shift), bicubic: there Lanczos left VO where
/// it was (outdoor `typical`, mean ATE 0.363 against 0.361 m) at 0.63 instead of 0.82 of
/// `ideal`'s real-time factor (docs/results/2026-12-05-lanczos-remap.md). Bilinear
/// before bicubic: `typical`'s outdoor VO 1.18 m against 0.363 m.
inline int RemapInterpolation(bool through_lens) {
  return through_lens ? cv::INTER_LANCZOS4 : cv::INTER_CUBIC;
}

/// OpenCV's coefficient vector for `lens`: (k1, k2, p1, p2, k3) for calib3d's
/// radial–tangential model, (k1, k2, k3, k4) for its fisheye module.
cv::Mat CvLensCoefficients(const geometry::LensDistortion& lens);

/// The map from the pixels of a rectified camera (projection P, rotated by R from
/// `camera`'s frame) to `camera`'s pixels through its lens, as
/// initUndistortRectifyMap makes it (the fisheye module's for an equidistant lens), in
/// the fixed-point form cv::remap works in (CV_16SC2 and CV_16UC1, 1/32 px, cv::convertMaps):
/// the same images as float maps give, without their conversion on every remap.
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
  /// Undistorts an 8-bit grey image of the camera's size into *out (Lanczos,
  /// RemapInterpolation; outside the source: black). With identity(), *out shares the
  /// input's pixels.
  void Undistort(const cv::Mat& image, cv::Mat* out) const;

 private:
  bool identity_ = true;
  geometry::PinholeCamera camera_;
  cv::Mat map_x_, map_y_;
};

}  // namespace trackbed::perception
