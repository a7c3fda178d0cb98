// What rectifying one image costs with each interpolation cv::remap offers, on the maps
// the stack builds for a 640 × 480, 80° camera through EuRoC's lens (the `harsh` lens;
// under `typical` the maps are a small rotation, the cost per pixel the same). One
// OpenCV thread; then the stack's own bicubic remap (perception/bicubic_remap.h,
// cv::remap's bytes) on the same maps. Prints milliseconds per image; never fails on
// them.
//
//   build/bench/remap_benchmark [--repeats 300]
#include <chrono>
#include <cmath>
#include <cstdio>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "bench_args.h"
#include "trackbed/common/units.h"
#include "trackbed/perception/bicubic_remap.h"
#include "trackbed/perception/lens_undistorter.h"
#include "trackbed/perception/opencv_views.h"

int main(int argc, char** argv) {
  using namespace trackbed;
  CLI::App app{"Milliseconds per rectified 640 x 480 image, per cv::remap interpolation"};
  int repeats = 300;
  app.add_option("--repeats", repeats, "Images per interpolation")->check(CLI::Range(1, 100000));
  if (const auto status = bench::Parse(app, argc, argv)) return *status;
  cv::setNumThreads(1);
  geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(640, 480, units::Radians(80.0));
  K.distortion = geometry::LensDistortion::RadialTangential(-0.28340811, 0.07395907, 0.00019359,
                                                            1.76187114e-05);
  const cv::Mat D = perception::CvLensCoefficients(K.distortion);
  const cv::Mat camera(perception::CvCameraMatrix(K));
  const cv::Mat T = (cv::Mat_<double>(3, 1) << -0.12, 0.0, 0.0);
  cv::Mat R1, R2, P1, P2, Q, map_x, map_y;
  cv::stereoRectify(camera, D, camera, D, perception::CvImageSize(K), cv::Mat::eye(3, 3, CV_64F), T,
                    R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, 0.0);
  perception::UndistortRectifyMap(K, R1, P1, &map_x, &map_y);
  cv::Mat image(perception::CvImageSize(K), CV_8U), out;
  cv::randu(image, 0, 256);
  const struct {
    const char* name;
    int flag;
  } kinds[] = {{"bilinear", cv::INTER_LINEAR},
               {"bicubic", cv::INTER_CUBIC},
               {"lanczos4", cv::INTER_LANCZOS4}};
  // Milliseconds per call of `remap`, after ten calls to warm up.
  const auto time = [&](const auto& remap) {
    for (int i = 0; i < 10; ++i) remap();
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < repeats; ++i) remap();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
               .count() /
           repeats;
  };
  for (const auto& kind : kinds) {
    const double ms = time([&] { cv::remap(image, out, map_x, map_y, kind.flag); });
    const char* role =
        kind.flag == perception::RemapInterpolation(true)    ? "  (the stack's, through a lens)"
        : kind.flag == perception::RemapInterpolation(false) ? "  (the stack's, without a lens)"
                                                             : "";
    std::printf("%-9s %6.2f ms per image%s\n", kind.name, ms, role);
  }
  const perception::BicubicRemap bicubic(map_x, map_y, image.size());
  std::printf("bicubic   %6.2f ms per image  (perception::BicubicRemap, the same bytes)\n",
              time([&] { bicubic.Apply(image, &out); }));
  return 0;
}
