// The shipped scenes look as Ham et al.'s experiment needs: the corridor has
// few trackable corners, the outdoor park many — counted with one Harris
// detector setting (absolute threshold) on views along each scene's route.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "trackbed/perception/harris_corners.h"
#include "trackbed/render/renderer.h"
#include "trackbed/render/sensor_warp.h"
#include "trackbed/robot/stereo_rig.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed {
namespace {

// Each f x f block of `im` averaged into one pixel, rounded.
GrayImage BlockMeans(const GrayImage& im, int f) {
  if (f == 1) return im;
  GrayImage out;
  out.width = im.width / f;
  out.height = im.height / f;
  out.pixels.resize(static_cast<std::size_t>(out.width) * out.height);
  for (int v = 0; v < out.height; ++v) {
    for (int u = 0; u < out.width; ++u) {
      int sum = 0;
      for (int j = 0; j < f; ++j) {
        for (int i = 0; i < f; ++i)
          sum += im.pixels[static_cast<std::size_t>(f * v + j) * im.width + f * u + i];
      }
      out.pixels[static_cast<std::size_t>(v) * out.width + u] =
          static_cast<std::uint8_t>((sum + f * f / 2) / (f * f));
    }
  }
  return out;
}

// Mean Harris corners per left image over `views` poses spread along the scene's route,
// its edges drawn at `edge_samples` a pixel, `supersampling` x `supersampling` render
// pixels averaged into each image pixel.
double MeanCornersAlongRoute(const std::string& file, int views, double min_response,
                             int edge_samples = 1, int supersampling = 1) {
  const scenario::Scenario s =
      scenario::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/" + file);
  const sim::World world(s.scene.world, sim::Terrain(s.scene.terrain, s.seed),
                         scenario::SceneObjects(s));
  const robot::StereoRig rig(s.robot.stereo);
  const geometry::PinholeCamera K = render::Supersampled(rig.intrinsics(), supersampling);
  render::Renderer renderer(world, s.scene.appearance, s.scene.occluders, s.seed, K.width_px,
                            K.height_px, s.robot.stereo.near_m, s.robot.stereo.far_m, edge_samples);
  const std::vector<Eigen::Vector2d>& w = s.drive.waypoints;
  std::vector<double> cumulative{0.0};
  for (std::size_t k = 1; k < w.size(); ++k) {
    cumulative.push_back(cumulative.back() + (w[k] - w[k - 1]).norm());
  }
  perception::HarrisOptions harris;  // one setting for every scene
  harris.min_response = min_response;
  double total = 0.0;
  for (int i = 0; i < views; ++i) {
    const double along = (i + 0.5) / views * cumulative.back();
    std::size_t k = 1;
    while (k + 1 < w.size() && cumulative[k] < along) ++k;
    const Eigen::Vector2d dir = (w[k] - w[k - 1]).normalized();
    const Eigen::Vector2d p = w[k - 1] + (along - cumulative[k - 1]) * dir;
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    T_world_body.linear() =
        Eigen::AngleAxisd(std::atan2(dir.y(), dir.x()), Eigen::Vector3d::UnitZ())
            .toRotationMatrix();
    T_world_body.translation() =
        Eigen::Vector3d(p.x(), p.y(), world.terrain().Height(p.x(), p.y()) + 0.2);
    GrayImage drawn, image;
    renderer.Render(K, T_world_body * rig.T_body_left(), 0.0, &drawn, nullptr);
    image = BlockMeans(drawn, supersampling);
    robot::ApplySensorModel(s.robot.stereo.exposure, s.robot.stereo.noise_std, s.seed,
                            static_cast<std::uint64_t>(i), 0, &image);
    const cv::Mat mat(image.height, image.width, CV_8UC1, image.pixels.data());
    total += static_cast<double>(perception::DetectHarrisCorners(mat, harris).size());
  }
  return total / views;
}

TEST(SceneAppearanceTest, OutdoorViewsHaveAtLeastFiveTimesTheCornersOfCorridorViews) {
  // One absolute threshold for both scenes: R > 1e-6 keeps sharp corners of
  // contrast above about 0.11 (see harris_corners.h for the scale of R).
  const double min_response = 1e-6;
  const double corridor = MeanCornersAlongRoute("corridor.yaml", 12, min_response);
  const double outdoor = MeanCornersAlongRoute("outdoor.yaml", 12, min_response);
  std::printf(
      "Harris corners per 640x480 left image (min_response %g): corridor %.1f, "
      "outdoor %.1f, ratio %.1f\n",
      min_response, corridor, outdoor, outdoor / std::max(corridor, 1e-9));
  RecordProperty("corridor_corners", std::to_string(corridor));
  RecordProperty("outdoor_corners", std::to_string(outdoor));
  EXPECT_GT(corridor, 1.0);  // not blank: doors and posters give a few
  EXPECT_GE(outdoor, 5.0 * corridor);
}

TEST(SceneAppearanceTest, FittedCorridorHasMoreCornersAndStaysALowFeatureScene) {
  // The corridor with its fittings (scene.fittings): skirting, door frames, switches,
  // ceiling lights, radiators, notice boards and extinguishers add corners; plain walls
  // still dominate, so the park keeps at least five times as many.
  const double min_response = 1e-6;
  const double corridor = MeanCornersAlongRoute("corridor.yaml", 12, min_response);
  const double fitted = MeanCornersAlongRoute("corridor_fitted.yaml", 12, min_response);
  const double outdoor = MeanCornersAlongRoute("outdoor.yaml", 12, min_response);
  std::printf(
      "Harris corners per 640x480 left image (min_response %g): corridor %.1f, "
      "fitted corridor %.1f, outdoor %.1f\n",
      min_response, corridor, fitted, outdoor);
  RecordProperty("fitted_corridor_corners", std::to_string(fitted));
  EXPECT_GT(fitted, corridor);
  EXPECT_GE(outdoor, 5.0 * fitted);
}

TEST(SceneAppearanceTest, AntialiasedEdgesBringTheFittedCorridorsCornersToTheAreaMeans) {
  // The fittings' edges at one sample a pixel are staircases whose steps are corners;
  // a camera pixel integrates over its area. With four samples a pixel at the edges the
  // count is nearer that of the 2 x 2 supersampled views (each pixel the mean of four
  // render pixels) than the one-sample count is.
  const double min_response = 1e-6;
  const double one = MeanCornersAlongRoute("corridor_fitted.yaml", 12, min_response, 1, 1);
  const double four = MeanCornersAlongRoute("corridor_fitted.yaml", 12, min_response, 4, 1);
  const double area = MeanCornersAlongRoute("corridor_fitted.yaml", 12, min_response, 1, 2);
  std::printf(
      "Harris corners per 640x480 left image of the fitted corridor (min_response %g): "
      "one sample a pixel %.1f, four at edges %.1f, 2 x 2 supersampled %.1f\n",
      min_response, one, four, area);
  RecordProperty("fitted_corridor_corners_edge_antialiased", std::to_string(four));
  EXPECT_LT(std::abs(four - area), std::abs(one - area));
}

}  // namespace
}  // namespace trackbed
