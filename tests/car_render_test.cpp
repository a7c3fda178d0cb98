// A parked car (objects of type `car`, render/car_model.h) as the renderer draws it:
// its outline and its rims land where the pinhole model puts them, and the same scene
// renders to the same bytes.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/render/car_model.h"
#include "trackbed/render/renderer.h"

namespace trackbed::render {
namespace {

constexpr double kLength = 4.255, kWidth = 1.799, kHeight = 1.452;
constexpr double kCarY = 6.0;  // the car's centre line, along x

sim::StaticObject Car() {
  sim::StaticObject o;
  o.kind = "car";
  o.appearance = "plain_paint";
  o.center_m = {0.0, kCarY};
  o.base_z_m = 0.0;
  o.size_m = {kLength, kWidth, kHeight};
  return o;
}

geometry::PinholeCamera Camera() { return test::Pinhole(640, 480, 500.0, 319.0, 240.0); }

// A level camera at x = 0 looking along +y at the car's right side, at `height` [m]:
// image row cy sees that height.
Eigen::Isometry3d CameraAt(double height) {
  return test::Looking({0.0, 0.0, height}, Eigen::Vector3d::UnitY());
}

GrayImage Draw(double height) {
  const sim::World world = test::FlatWorld({Car()}, {-6, -2, 6, 10});
  Renderer renderer(world, test::AmbientOnly(), {}, 5, 640, 480, 0.05, 100.0);
  GrayImage img;
  renderer.Render(Camera(), CameraAt(height), 0.0, &img, nullptr);
  return img;
}

// The columns [first, last] of the run of pixels in row `v` with grey in [lo, hi] that
// holds column `u`; {-1, -1} when `u` is not in such a run.
std::pair<int, int> RunAround(const GrayImage& img, int v, int u, int lo, int hi) {
  const auto in = [&](int x) { return img.at(x, v) >= lo && img.at(x, v) <= hi; };
  if (!in(u)) return {-1, -1};
  int a = u, b = u;
  while (a > 0 && in(a - 1)) --a;
  while (b + 1 < img.width && in(b + 1)) ++b;
  return {a, b};
}

// A pixel is drawn by its centre, so a run's outer pixel edges lie within half a pixel
// of the outline: first - 0.5 and last + 0.5 within 0.5 px of the prediction.
void ExpectEdges(std::pair<int, int> run, double left, double right, const char* what) {
  std::printf("%s: edges %+.3f / %+.3f px from the pinhole prediction\n", what,
              run.first - 0.5 - left, run.second + 0.5 - right);
  EXPECT_NEAR(run.first - 0.5, left, 0.5) << what;
  EXPECT_NEAR(run.second + 0.5, right, 0.5) << what;
}

TEST(CarRenderTest, OutlineAndRimsLandWherePinholeModelPredicts) {
  const geometry::PinholeCamera K = Camera();
  const std::vector<CarPart> parts = CarParts({kLength, kWidth, kHeight});
  // Through the wheels' centres: the rims (grey 140) between the dark tyres.
  const double wheel_z = 0.5 * kCarWheelDiameterM;
  const GrayImage wheels = Draw(wheel_z);
  const int row = static_cast<int>(K.cy);
  int rims = 0;
  for (const CarPart& p : parts) {
    if (p.appearance != "car_rim" || p.side != -1) continue;  // the side facing the camera
    const double depth = kCarY + p.center.y();                // the rim's outer face
    const double left = K.cx + K.fx * (p.center.x() - p.radius) / depth;
    const double right = K.cx + K.fx * (p.center.x() + p.radius) / depth;
    const auto run =
        RunAround(wheels, row, static_cast<int>(std::lround(0.5 * (left + right))), 120, 160);
    ASSERT_GE(run.first, 0);
    ExpectEdges(run, left, right, "rim");
    ++rims;
  }
  EXPECT_EQ(rims, 2);
  // At 0.27 m, under the plates: the body's ends (paint, grey 200) against the sky.
  const GrayImage body = Draw(0.27);
  const double depth = kCarY - 0.5 * kWidth;
  const double left = K.cx + K.fx * (-0.5 * kLength + 0.02) / depth;
  const double right = K.cx + K.fx * (0.5 * kLength - 0.02) / depth;
  const auto rear = RunAround(body, row, static_cast<int>(std::lround(left)) + 3, 190, 210);
  const auto front = RunAround(body, row, static_cast<int>(std::lround(right)) - 3, 190, 210);
  ASSERT_GE(rear.first, 0);
  ASSERT_GE(front.first, 0);
  ExpectEdges({rear.first, front.second}, left, right, "body");
}

TEST(CarRenderTest, TheSameSceneRendersToTheSameBytes) {
  const GrayImage a = Draw(1.0);
  const GrayImage b = Draw(1.0);
  EXPECT_EQ(a.pixels, b.pixels);
  long painted = 0;
  for (const std::uint8_t g : a.pixels) painted += g > 0;
  EXPECT_GT(painted, 20000);  // the car fills a good part of the view
}

}  // namespace
}  // namespace trackbed::render
