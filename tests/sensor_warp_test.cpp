// What the sensor records of a render (render/sensor_warp.h, render/camera_exposure.h): a
// marker through a lens lands where the lens model puts it, a rolling shutter shears a
// vertical edge by line delay × rows × ω × f, the warp in time matches renders of each
// band of rows at its own pose, and an exposure smears an edge by the motion during it.
#include "trackbed/render/sensor_warp.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/common/units.h"
#include "trackbed/render/camera_exposure.h"
#include "trackbed/render/renderer.h"
#include "trackbed/robot/stereo_rig.h"

namespace trackbed::render {
namespace {

// A floor 80 m across, the scene's plates (render_test_scene.h).
sim::World MakeWorld(std::vector<sim::StaticObject> objects) {
  return test::FlatWorld(std::move(objects), {-2, -40, 40, 40});
}

SceneAppearance Flat() { return test::AmbientOnly(); }
using test::Plate;

// A level camera looking along +x (OpenCV axes), on a body whose origin is the
// camera's centre.
Eigen::Isometry3d T_body_camera() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = -Eigen::Vector3d::UnitY();
  T.linear().col(1) = -Eigen::Vector3d::UnitZ();
  T.linear().col(2) = Eigen::Vector3d::UnitX();
  return T;
}

// At rest `height_m` above the floor (at 100 m the floor, 40 m long, is out of view).
BodyMotion AtRest(double height_m = 1.0) {
  BodyMotion m;
  m.T_world_body.translation() = Eigen::Vector3d(0, 0, height_m);
  return m;
}

geometry::PinholeCamera Camera() {
  return geometry::PinholeCamera::FromFieldOfView(640, 480, units::Radians(80.0));
}

// The grey-level centroid of a window of `image` around (u, v) (a marker of uniform
// paint against a black sky: a thresholded mask would round it to half pixels).
Eigen::Vector2d Centroid(const GrayImage& image, double u, double v, int half) {
  double sum = 0, su = 0, sv = 0;
  for (int y = static_cast<int>(v) - half; y <= static_cast<int>(v) + half; ++y) {
    for (int x = static_cast<int>(u) - half; x <= static_cast<int>(u) + half; ++x) {
      const double g = image.at(x, y);
      sum += g, su += g * x, sv += g * y;
    }
  }
  return {su / sum, sv / sum};
}

// Where a square plate's image centroid falls through the camera: the mean of its
// projected points weighted by the image area each covers.
Eigen::Vector2d ProjectedCentroid(const geometry::PinholeCamera& K, const Eigen::Vector3d& c_cam,
                                  double side) {
  constexpr int kN = 60;
  std::vector<Eigen::Vector2d> p((kN + 1) * (kN + 1));
  for (int i = 0; i <= kN; ++i) {
    for (int j = 0; j <= kN; ++j) {
      const Eigen::Vector3d q =
          c_cam + side * Eigen::Vector3d(i / double(kN) - 0.5, j / double(kN) - 0.5, 0.0);
      p[i * (kN + 1) + j] = K.Project(q);
    }
  }
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double area = 0;
  for (int i = 0; i < kN; ++i) {
    for (int j = 0; j < kN; ++j) {
      const Eigen::Vector2d a = p[i * (kN + 1) + j], b = p[(i + 1) * (kN + 1) + j],
                            c = p[i * (kN + 1) + j + 1], d = p[(i + 1) * (kN + 1) + j + 1];
      const double cell = 0.5 * std::abs((d - a).x() * (c - b).y() - (d - a).y() * (c - b).x());
      sum += cell * 0.25 * (a + b + c + d);
      area += cell;
    }
  }
  return sum / area;
}

// Through EuRoC's left lens (k1 = −0.283), markers from the centre to near the corners
// land where the lens model puts them, to 0.3 px.
TEST(SensorWarpTest, AMarkerThroughTheLensLandsWhereTheModelPredicts) {
  geometry::PinholeCamera K = Camera();
  K.distortion = geometry::LensDistortion::RadialTangential(-0.28340811, 0.07395907, 0.00019359,
                                                            1.76187114e-05);
  const double side = 0.2, depth = 3.0;
  // Marker centres in the camera frame (x right, y down), out to 40 px from a corner.
  const std::vector<Eigen::Vector2d> xy = {{0.0, 0.0},  {1.2, 0.0},   {-2.4, 0.9},
                                           {2.6, -1.5}, {-2.8, -2.0}, {3.0, 2.1}};
  std::vector<sim::StaticObject> plates;
  for (const Eigen::Vector2d& p : xy) {
    // Camera (x, y, z) is world (z, −x, 100 − y).
    plates.push_back(Plate({depth, -p.x(), 100.0 - p.y()}, side, side, "plain_paint"));
  }
  const sim::World world = MakeWorld(plates);
  const geometry::PinholeCamera render = RenderCameraFor(K, 0);
  ASSERT_GT(render.width_px, 640);
  Renderer renderer(world, Flat(), {}, 3, render.width_px, render.height_px, 0.05, 120.0);
  CameraExposure camera(K, render, 1, 0.0);
  GrayImage image;
  camera.Render(renderer, AtRest(100.0), T_body_camera(), 0.0, 0.0, &image);
  ASSERT_EQ(image.width, 640);
  double worst = 0.0;
  for (const Eigen::Vector2d& p : xy) {
    const Eigen::Vector2d predicted = ProjectedCentroid(K, {p.x(), p.y(), depth}, side);
    ASSERT_TRUE(predicted.x() > 20 && predicted.x() < 619 && predicted.y() > 20 &&
                predicted.y() < 459)
        << predicted.transpose();
    const Eigen::Vector2d found = Centroid(image, predicted.x(), predicted.y(), 20);
    const double error = (found - predicted).norm();
    worst = std::max(worst, error);
    // Without the lens, the marker would be far from there.
    const Eigen::Vector2d pinhole = Camera().Project({p.x(), p.y(), depth});
    std::printf("marker at (%6.1f, %6.1f) px: found %.3f px off (pinhole: %.1f px off)\n",
                predicted.x(), predicted.y(), error, (pinhole - predicted).norm());
  }
  EXPECT_LE(worst, 0.3);
}

// The column where row `v` crosses half of `bright`, left to right, interpolated.
double EdgeColumn(const GrayImage& image, int v, double bright) {
  for (int u = 1; u < image.width; ++u) {
    const double a = image.at(u - 1, v), b = image.at(u, v);
    if (a < 0.5 * bright && b >= 0.5 * bright) return u - 1 + (0.5 * bright - a) / (b - a);
  }
  return std::nan("");
}

// A distant plate's vertical left edge, seen while the camera yaws: a rolling shutter
// shifts the edge between the first and the last row by line delay × (H − 1) × ω × f.
TEST(SensorWarpTest, ARollingShutterShearsAVerticalEdgeByTheYawDuringReadout) {
  // A plate 30 m ahead, 40 m wide and tall, its left edge straight ahead.
  const sim::World world = MakeWorld({Plate({30.0, -20.0, 100.0}, 40.0, 40.0, "ceiling")});
  const geometry::PinholeCamera K = Camera();
  const geometry::PinholeCamera render = RenderCameraFor(K, 4);
  Renderer renderer(world, Flat(), {}, 3, render.width_px, render.height_px, 0.05, 120.0);
  const double line_delay = 60e-6, omega = 1.0;
  CameraExposure global(K, render, 1, 0.0), rolling(K, render, 1, line_delay);
  BodyMotion motion = AtRest(100.0);
  motion.omega_world = {0.0, 0.0, omega};  // turning left
  GrayImage still, sheared;
  global.Render(renderer, motion, T_body_camera(), 0.0, 0.0, &still);
  rolling.Render(renderer, motion, T_body_camera(), 0.0, 0.0, &sheared);
  const double bright = still.at(500, 240);
  ASSERT_GT(bright, 100.0);
  const double top = EdgeColumn(sheared, 0, bright), bottom = EdgeColumn(sheared, 479, bright);
  const double expected = line_delay * 479 * omega * K.fx;
  std::printf("edge at %.2f px (row 0), %.2f px (row 479): shift %.2f px, expected %.2f px\n", top,
              bottom, top - bottom, expected);
  // The global shutter's edge is straight; the middle row keeps its place.
  EXPECT_NEAR(EdgeColumn(still, 0, bright), EdgeColumn(still, 479, bright), 0.05);
  EXPECT_NEAR(EdgeColumn(sheared, 240, bright), EdgeColumn(still, 240, bright), 0.2);
  // Turning left, later rows see the scene further right.
  EXPECT_NEAR(bottom - top, expected, 0.1 * expected);
}

// Mean absolute difference [grey levels] of two images, and the share of pixels that
// differ by more than 32.
std::pair<double, double> Difference(const GrayImage& a, const GrayImage& b) {
  double sum = 0;
  int large = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const int d = std::abs(int(a.pixels[i]) - int(b.pixels[i]));
    sum += d;
    large += d > 32;
  }
  const double n = static_cast<double>(a.pixels.size());
  return {sum / n, large / n};
}

// A textured scene with depth edges near and far, the camera driving and turning: the
// warp in time against renders of each 4-row band at its own pose, and against the
// global-shutter image (what ignoring the rolling shutter would give).
TEST(SensorWarpTest, TheWarpInTimeMatchesRendersOfEachBandAtItsPose) {
  const sim::World world = MakeWorld({Plate({2.5, 0.6, 1.0}, 0.5, 1.2, "brick"),
                                      Plate({4.0, -0.5, 0.8}, 0.8, 0.8, "wood"),
                                      Plate({12.0, 1.5, 2.0}, 3.0, 4.0, "bark")});
  const geometry::PinholeCamera K = Camera();
  const geometry::PinholeCamera render = RenderCameraFor(K, 4);
  SceneAppearance lit = Flat();
  lit.sky_gray = 0.6;
  Renderer renderer(world, lit, {}, 3, render.width_px, render.height_px, 0.05, 120.0);
  Renderer band_renderer(world, lit, {}, 3, 640, 480, 0.05, 120.0);
  BodyMotion motion = AtRest();
  motion.v_world = {0.8, 0.1, 0.0};
  motion.omega_world = {0.0, 0.1, 0.8};
  const double line_delay = 68.75e-6;  // 33 ms for 480 rows
  CameraExposure rolling(K, render, 1, line_delay);
  GrayImage warped, band, reference, global;
  rolling.Render(renderer, motion, T_body_camera(), 0.0, 0.0, &warped);
  band_renderer.Render(K, motion.T_world_body * T_body_camera(), 0.0, &global, nullptr);
  // The reference: each 4-row band rendered at its middle's time.
  reference = warped;
  constexpr int kBand = 4;
  for (int v0 = 0; v0 < 480; v0 += kBand) {
    const double dt = (v0 + 0.5 * (kBand - 1) - 239.5) * line_delay;
    band_renderer.Render(K, motion.PoseAfter(dt) * T_body_camera(), 0.0, &band, nullptr);
    for (int v = v0; v < v0 + kBand; ++v) {
      for (int u = 0; u < 640; ++u) reference.pixels[v * 640 + u] = band.at(u, v);
    }
  }
  const auto [mean, share] = Difference(warped, reference);
  const auto [global_mean, global_share] = Difference(global, reference);
  std::printf(
      "against per-band renders: the warp %.2f grey levels mean, %.3f %% of pixels off by "
      "more than 32; the global shutter %.2f, %.3f %%\n",
      mean, 100 * share, global_mean, 100 * global_share);
  // (The warp resamples the render, the bands do not: part of its difference is that.)
  EXPECT_LT(mean, 0.5 * global_mean);
  EXPECT_LT(share, 0.25 * global_share);
}

// An exposure of T seconds while the camera yaws at ω smears a vertical edge into a
// ramp ω·T·fx wide and leaves its mean position; an instant is the render itself.
TEST(SensorWarpTest, AnExposureSmearsAnEdgeByTheCameraMotionDuringIt) {
  const sim::World world = MakeWorld({Plate({4.0, 0.0, 1.3}, 1.0, 1.0, "ceiling")});
  const geometry::PinholeCamera K = Camera();
  Renderer plain_renderer(world, Flat(), {}, 3, 640, 480, 0.05, 120.0);
  BodyMotion motion = AtRest();
  motion.omega_world = {0.0, 0.0, 1.0};
  GrayImage instant, plain, blurred;
  CameraExposure exact(K, K, 16, 0.0);
  exact.Render(plain_renderer, motion, T_body_camera(), 0.0, 0.0, &instant);
  plain_renderer.Render(K, motion.T_world_body * T_body_camera(), 0.0, &plain, nullptr);
  EXPECT_EQ(instant.pixels, plain.pixels);
  const geometry::PinholeCamera render = RenderCameraFor(K, 4);
  Renderer renderer(world, Flat(), {}, 3, render.width_px, render.height_px, 0.05, 120.0);
  CameraExposure open(K, render, 16, 0.0);
  EXPECT_EQ(open.samples(0.01), 16);
  open.Render(renderer, motion, T_body_camera(), 0.0, 0.01, &blurred);
  // Along row 200 (through the plate), the left edge near u = cx − fx · 0.5 / 4.
  const int row = 200;
  const double bright = plain.at(320, row);
  ASSERT_GT(bright, 100.0);
  const auto ramp = [&](const GrayImage& img, double* mass) {
    int width = 0;
    *mass = 0.0;
    for (int u = 240; u < 300; ++u) {
      const double f = img.at(u, row) / bright;
      width += f > 0.05 && f < 0.95;
      *mass += f;
    }
    return width;
  };
  double mass_plain, mass_blurred;
  const int width_plain = ramp(plain, &mass_plain);
  const int width_blurred = ramp(blurred, &mass_blurred);
  const double expected = 1.0 * 0.01 * K.fx;  // 3.8 px
  std::printf("edge ramp: %d px instant, %d px over 10 ms at 1 rad/s (omega T fx = %.1f px)\n",
              width_plain, width_blurred, expected);
  EXPECT_LE(width_plain, 1);
  EXPECT_GE(width_blurred, 3);
  EXPECT_LE(width_blurred, 5);
  EXPECT_NEAR(mass_blurred, mass_plain, 0.3);
}

// Supersampled twice, each pixel is the mean of the 2 × 2 render pixels it covers
// (to rounding): what a pixel integrating over its area records.
TEST(SensorWarpTest, ASupersampledPixelIsTheMeanOfTheRenderPixelsItCovers) {
  const sim::World world = MakeWorld({Plate({3.0, 0.4, 1.2}, 0.7, 0.5, "brick")});
  const geometry::PinholeCamera K = Camera();
  const geometry::PinholeCamera fine = Supersampled(K, 2);
  ASSERT_EQ(fine.width_px, 1280);
  Renderer renderer(world, Flat(), {}, 3, fine.width_px, fine.height_px, 0.05, 120.0);
  CameraExposure camera(K, fine, 1, 0.0);
  GrayImage image, render;
  camera.Render(renderer, AtRest(), T_body_camera(), 0.0, 0.0, &image);
  renderer.Render(fine, AtRest().T_world_body * T_body_camera(), 0.0, &render, nullptr);
  int worst = 0;
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 640; ++u) {
      const int sum = render.at(2 * u, 2 * v) + render.at(2 * u + 1, 2 * v) +
                      render.at(2 * u, 2 * v + 1) + render.at(2 * u + 1, 2 * v + 1);
      worst = std::max(worst, std::abs(4 * image.at(u, v) - sum));
    }
  }
  EXPECT_LE(worst, 2);  // 4 × (mean rounded) differs from the sum by at most 2
}

}  // namespace
}  // namespace trackbed::render
