// One camera's undistortion (see lens_undistorter.h).
#include "trackbed/perception/lens_undistorter.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "trackbed/perception/opencv_views.h"

namespace trackbed::perception {

cv::Mat CvLensCoefficients(const geometry::LensDistortion& lens) {
  if (lens.model == geometry::LensModel::kEquidistant) {
    return (cv::Mat_<double>(1, 4) << lens.k1, lens.k2, lens.k3, lens.k4);
  }
  return (cv::Mat_<double>(1, 5) << lens.k1, lens.k2, lens.p1, lens.p2, lens.k3);
}

void UndistortRectifyMap(const geometry::PinholeCamera& camera, const cv::Mat& R, const cv::Mat& P,
                         cv::Mat* map_x, cv::Mat* map_y) {
  const cv::Mat D = CvLensCoefficients(camera.distortion);
  cv::Mat x, y;
  if (camera.distortion.model == geometry::LensModel::kEquidistant) {
    cv::fisheye::initUndistortRectifyMap(CvCameraMatrix(camera), D, R, P, CvImageSize(camera),
                                         CV_32FC1, x, y);
  } else {
    cv::initUndistortRectifyMap(CvCameraMatrix(camera), D, R, P, CvImageSize(camera), CV_32FC1, x,
                                y);
  }
  cv::convertMaps(x, y, *map_x, *map_y, CV_16SC2);
}

LensUndistorter::LensUndistorter(const geometry::PinholeCamera& camera) : camera_(camera) {
  camera_.Validate();
  camera.distortion.Validate();
  camera_.distortion = geometry::LensDistortion{};
  if (camera.distortion.is_zero()) return;
  identity_ = false;
  // The undistorted camera keeps the intrinsics: no rotation, P = K.
  UndistortRectifyMap(camera, cv::Mat::eye(3, 3, CV_64F), cv::Mat(CvCameraMatrix(camera_)), &map_x_,
                      &map_y_);
}

void LensUndistorter::Undistort(const cv::Mat& image, cv::Mat* out) const {
  if (identity_) {
    *out = image;
    return;
  }
  cv::remap(image, *out, map_x_, map_y_, RemapInterpolation(/*through_lens=*/true),
            cv::BORDER_CONSTANT, 0);
}

}  // namespace trackbed::perception
