// A stereo pair seen through a lens (EuRoC's, k1 = −0.283) and rectified from its
// calibration with the lens (perception/stereo_rectifier.h): markers from the centre to
// the corners come out on the same row in both images at the disparity of their depth.
// Rectified as if the lens were a pinhole (undistortion skipped), they do not.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/common/units.h"
#include "trackbed/perception/lens_undistorter.h"
#include "trackbed/perception/opencv_views.h"
#include "trackbed/perception/stereo_rectifier.h"
#include "trackbed/render/camera_exposure.h"
#include "trackbed/render/renderer.h"
#include "trackbed/robot/as_built.h"
#include "trackbed/robot/stereo_rig.h"

namespace trackbed {
namespace {

// A square plate of uniform paint facing the cameras, its front face centred at `c`.
sim::StaticObject Plate(const Eigen::Vector3d& c, double side) {
  return render::test::Plate(c, side, side, "plain_paint");
}

// Grey-level centroid of a window of `image` around (u, v).
Eigen::Vector2d Centroid(const cv::Mat& image, double u, double v, int half) {
  double sum = 0, su = 0, sv = 0;
  for (int y = std::max(0, static_cast<int>(v) - half);
       y <= std::min(image.rows - 1, static_cast<int>(v) + half); ++y) {
    for (int x = std::max(0, static_cast<int>(u) - half);
         x <= std::min(image.cols - 1, static_cast<int>(u) + half); ++x) {
      const double g = image.at<std::uint8_t>(y, x);
      sum += g, su += g * x, sv += g * y;
    }
  }
  return {su / sum, sv / sum};
}

struct PairError {
  double worst_row_px = 0.0;     // |v_left − v_right|
  double worst_depth_rel = 0.0;  // |f b / d − Z| / Z
};

// Renders the pair through the lens and rectifies it with `given`; measures each marker.
PairError Measure(const calibration::StereoCalibration& as_built,
                  const calibration::StereoCalibration& given,
                  const robot::StereoRigOptions& options) {
  const render::BodyMotion body = [] {
    render::BodyMotion m;  // 100 m up: the floor is out of view
    m.T_world_body.translation() = Eigen::Vector3d(0, 0, 100.0);
    return m;
  }();
  const robot::StereoRig rig(options, as_built);
  // Markers 2 m ahead of the left camera (23 px of disparity: the renderer's edges,
  // antialiased, place a marker to about 0.3 px), from the centre out to the corners.
  const double depth = 2.0, side = 0.125;
  const std::vector<Eigen::Vector2d> xy = {{0.0, 0.0},    {1.0, 0.1},   {-1.3, 0.6},
                                           {1.25, -0.95}, {-1.5, -0.9}, {1.6, 1.05}};
  const Eigen::Isometry3d T_world_left = body.T_world_body * rig.T_body_left();
  std::vector<sim::StaticObject> plates;
  for (const Eigen::Vector2d& p : xy) {
    plates.push_back(Plate(T_world_left * Eigen::Vector3d(p.x(), p.y(), depth), side));
  }
  const sim::World world = render::test::FlatWorld(plates);
  const render::SceneAppearance flat = render::test::AmbientOnly();
  const geometry::PinholeCamera left_render = render::RenderCameraFor(rig.intrinsics(), 0);
  const geometry::PinholeCamera right_render = render::RenderCameraFor(rig.right_intrinsics(), 0);
  const int w = std::max(left_render.width_px, right_render.width_px);
  const int h = std::max(left_render.height_px, right_render.height_px);
  render::Renderer renderer(world, flat, {}, 3, w, h, 0.05, 120.0);
  render::CameraExposure left_camera(rig.intrinsics(), render::GrownTo(left_render, w, h), 1, 0.0);
  render::CameraExposure right_camera(rig.right_intrinsics(), render::GrownTo(right_render, w, h),
                                      1, 0.0);
  GrayImage left, right;
  left_camera.Render(renderer, body, rig.T_body_left(), 0.0, 0.0, &left);
  right_camera.Render(renderer, body, rig.T_body_right(), 0.0, 0.0, &right);

  const perception::StereoRectifier rectifier(given);
  cv::Mat rect_left, rect_right;
  rectifier.Rectify(perception::AsCvMat(left), perception::AsCvMat(right), &rect_left, &rect_right);
  // Where each marker is in the rectified pair, from the truth.
  const geometry::StereoCamera& pair = rectifier.camera();
  const Eigen::Isometry3d T_rect_left = rectifier.T_body_left().inverse() * rig.T_body_left();
  PairError e;
  for (const Eigen::Vector2d& p : xy) {
    const Eigen::Vector3d in_rect = T_rect_left * Eigen::Vector3d(p.x(), p.y(), depth);
    // Where to look: the rectified pair's projection, or (images left as they are) the
    // lens's.
    const Eigen::Vector3d p_left(p.x(), p.y(), depth);
    const Eigen::Vector3d p_right = rig.T_body_right().inverse() * rig.T_body_left() * p_left;
    const Eigen::Vector3d rectified = pair.Project(in_rect);  // (u_left, v, u_right)
    const Eigen::Vector2d at_l =
        rectifier.identity() ? rig.intrinsics().Project(p_left) : rectified.head<2>();
    const Eigen::Vector2d at_r = rectifier.identity()
                                     ? rig.right_intrinsics().Project(p_right)
                                     : Eigen::Vector2d(rectified.z(), rectified.y());
    const Eigen::Vector2d l = Centroid(rect_left, at_l.x(), at_l.y(), 24);
    const Eigen::Vector2d r = Centroid(rect_right, at_r.x(), at_r.y(), 24);
    const double z = pair.left.fx * pair.baseline_m / (l.x() - r.x());
    e.worst_row_px = std::max(e.worst_row_px, std::abs(l.y() - r.y()));
    e.worst_depth_rel = std::max(e.worst_depth_rel, std::abs(z - in_rect.z()) / in_rect.z());
  }
  return e;
}

TEST(LensRectificationTest, ThePairRectifiedThroughItsLensHasRowsAndDepthsRight) {
  robot::StereoRigOptions options;
  options.enabled = true;
  options.pitch_down_deg = 0.0;
  options.distortion = geometry::LensDistortion::RadialTangential(-0.28340811, 0.07395907,
                                                                  0.00019359, 1.76187114e-05);
  const calibration::StereoCalibration as_built =
      *robot::DesignCalibration(robot::TrackedVehicleOptions{}, options).stereo;
  ASSERT_TRUE(as_built.left.distortion.has_value());
  const PairError with_lens = Measure(as_built, as_built, options);
  calibration::StereoCalibration skipped = as_built;
  skipped.left.distortion.reset();
  skipped.right.distortion.reset();
  const PairError without = Measure(as_built, skipped, options);
  std::printf("undistorted with the lens: rows %.3f px apart, depth off %.2f %% (worst marker)\n",
              with_lens.worst_row_px, 100 * with_lens.worst_depth_rel);
  std::printf("undistortion skipped:      rows %.3f px apart, depth off %.2f %%\n",
              without.worst_row_px, 100 * without.worst_depth_rel);
  EXPECT_LT(with_lens.worst_row_px, 0.3);
  // Measured 0.7 % (0.14 px of 20 px of disparity); the renderer places an edge to half
  // a pixel.
  EXPECT_LT(with_lens.worst_depth_rel, 0.02);
  EXPECT_GT(without.worst_depth_rel, 0.3);
  EXPECT_GT(without.worst_row_px, 1.0);
}

// Teach & repeat's undistortion (perception/lens_undistorter.h): through EuRoC's lens
// and undistorted with it, markers land where the pinhole camera puts them.
TEST(LensRectificationTest, OneCameraUndistortedLandsMarkersWhereThePinholeDoes) {
  geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(640, 480, units::Radians(80.0));
  K.distortion = geometry::LensDistortion::RadialTangential(-0.28340811, 0.07395907, 0.00019359,
                                                            1.76187114e-05);
  const double depth = 2.0, side = 0.125;
  const std::vector<Eigen::Vector2d> xy = {{0.0, 0.0}, {1.0, 0.1}, {-1.3, 0.6}, {1.25, -0.95}};
  std::vector<sim::StaticObject> plates;
  for (const Eigen::Vector2d& p : xy) plates.push_back(Plate({depth, -p.x(), 100.0 - p.y()}, side));
  const sim::World world = render::test::FlatWorld(plates);
  const geometry::PinholeCamera render_camera = render::RenderCameraFor(K, 0);
  render::Renderer renderer(world, render::test::AmbientOnly(), {}, 3, render_camera.width_px,
                            render_camera.height_px, 0.05, 120.0);
  render::CameraExposure camera(K, render_camera, 1, 0.0);
  render::BodyMotion body;
  body.T_world_body.translation() = Eigen::Vector3d(0, 0, 100.0);
  Eigen::Isometry3d T_body_camera = Eigen::Isometry3d::Identity();
  T_body_camera.linear().col(0) = -Eigen::Vector3d::UnitY();
  T_body_camera.linear().col(1) = -Eigen::Vector3d::UnitZ();
  T_body_camera.linear().col(2) = Eigen::Vector3d::UnitX();
  GrayImage image;
  camera.Render(renderer, body, T_body_camera, 0.0, 0.0, &image);
  const perception::LensUndistorter undistorter(K);
  ASSERT_FALSE(undistorter.identity());
  EXPECT_TRUE(undistorter.camera().distortion.is_zero());
  cv::Mat undistorted;
  undistorter.Undistort(perception::AsCvMat(image), &undistorted);
  double worst = 0.0;
  for (const Eigen::Vector2d& p : xy) {
    const Eigen::Vector2d at = undistorter.camera().Project({p.x(), p.y(), depth});
    worst = std::max(worst, (Centroid(undistorted, at.x(), at.y(), 24) - at).norm());
  }
  std::printf("undistorted markers within %.3f px of the pinhole's projection\n", worst);
  // The renderer places an edge to half a pixel (no antialiasing); skipping the
  // undistortion would leave these markers 34 to 44 px away.
  EXPECT_LT(worst, 0.5);
}

}  // namespace
}  // namespace trackbed
