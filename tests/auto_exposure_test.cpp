// Auto-exposure (robot/auto_exposure.h): after a brightness step the image's mean grey
// level returns to its target with the configured time constant, exposure time before
// gain; and the motion blur follows the exposure time it chose.
#include "trackbed/robot/auto_exposure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/common/option_error.h"
#include "trackbed/common/units.h"
#include "trackbed/render/camera_exposure.h"
#include "trackbed/render/renderer.h"

namespace trackbed::robot {
namespace {

// A camera whose mean grey level is `light` · 64 at 1 ms and gain 1, linear in the
// exposure and the gain, clipped at 255.
double MeanGrey(double light, const AutoExposure& ae) {
  return std::min(255.0, light * 64.0 * ae.exposure_time_s() / 1e-3 * ae.gain());
}

// The time after t0 at which |log(mean / target)| has fallen to 1/e of its value at t0.
TEST(AutoExposureTest, AfterABrightnessStepTheMeanReturnsWithTheTimeConstant) {
  AutoExposureOptions o;
  o.enabled = true;
  o.target_grey = 128.0;
  o.time_constant_s = 0.5;
  const double dt = 1.0 / 30.0;  // 30 frames a second: steps much shorter than τ
  // The light drops to a quarter, or rises by 80 % (not beyond 255: clipped, the mean
  // would understate the light and the return take longer).
  for (const double step : {0.25, 1.8}) {
    AutoExposure ae(o, 2e-3);  // 2 ms at light 1 is on target
    double t = 0.0, light = 1.0, t_e = -1.0, initial = 0.0;
    for (int k = 0; k < 300; ++k, t += dt) {
      if (k == 30) light = step;
      const double mean = MeanGrey(light, ae);
      const double error = std::abs(std::log(mean / o.target_grey));
      if (k == 30) initial = error;
      if (k > 30 && t_e < 0 && error <= initial / std::exp(1.0)) t_e = t - 30 * dt;
      ae.Update(mean, dt);
    }
    std::printf(
        "light x%.2f: 1/e of the error after %.3f s (time constant %.3f s); "
        "then %.2f ms, gain %.2f, mean %.1f\n",
        step, t_e, o.time_constant_s, 1e3 * ae.exposure_time_s(), ae.gain(), MeanGrey(light, ae));
    EXPECT_NEAR(t_e, o.time_constant_s, 0.2 * o.time_constant_s);
    EXPECT_NEAR(MeanGrey(light, ae), o.target_grey, 1.0);
    EXPECT_EQ(ae.gain(), 1.0);  // exposure time alone suffices within its limits
  }
}

// When the light falls below what the longest exposure makes up for, the gain rises to
// its limit; when it rises, the shortest exposure bounds it.
TEST(AutoExposureTest, ExposureTimeFirstThenGainWithinTheirLimits) {
  AutoExposureOptions o;
  o.enabled = true;
  o.max_exposure_s = 15.3e-3;
  o.max_gain = 4.0;
  AutoExposure ae(o, 2e-3);
  for (int k = 0; k < 200; ++k) ae.Update(MeanGrey(1.0 / 16.0, ae), 0.1);
  EXPECT_EQ(ae.exposure_time_s(), 15.3e-3);
  EXPECT_NEAR(ae.gain(), 128.0 / (64.0 / 16.0 * 15.3), 1e-3);  // 2.09
  for (int k = 0; k < 200; ++k) ae.Update(MeanGrey(1.0 / 64.0, ae), 0.1);
  EXPECT_EQ(ae.gain(), 4.0);
  for (int k = 0; k < 200; ++k) ae.Update(MeanGrey(1e4, ae), 0.1);
  EXPECT_EQ(ae.exposure_time_s(), o.min_exposure_s);
  EXPECT_EQ(ae.gain(), 1.0);
  AutoExposureOptions bad = o;
  bad.max_exposure_s = 1e-6;
  try {
    AutoExposure(bad, 1e-3);
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "auto_exposure.max_exposure_s");
  }
}

// The length of the linear ramp a plate's vertical edge smears into along one row:
// over a ramp L pixels long, the sum of f (1 − f) of the pixels' fractions f of full
// brightness is L / 6 (a sharp edge adds at most a quarter from its one mixed pixel);
// the paint's own shading adds a little on the plate, which the still image's sum
// removes.
double RampLength(const GrayImage& image, int row, double bright) {
  double sum = 0.0;
  for (int u = 200; u < 320; ++u) {
    const double f = std::min(1.0, image.at(u, row) / bright);
    sum += f * (1.0 - f);
  }
  return 6.0 * sum;
}

// Darkened, the controller lengthens the exposure; yawing at 1 rad/s, the edge of a
// plate smears over ω · exposure · f pixels at each exposure it chose.
TEST(AutoExposureTest, TheBlurFollowsTheExposureTimeItChose) {
  // A 1 m plate 4 m ahead, 100 m above the floor (out of view), against a black sky.
  const sim::World world =
      render::test::FlatWorld({render::test::Plate({4.0, 0.0, 100.0}, 1.0, 1.0, "plain_paint")});
  const render::SceneAppearance flat = render::test::AmbientOnly();
  const geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(640, 480, units::Radians(80.0));
  const geometry::PinholeCamera render_camera = render::RenderCameraFor(K, 8);
  render::Renderer renderer(world, flat, {}, 3, render_camera.width_px, render_camera.height_px,
                            0.05, 120.0);
  render::CameraExposure camera(K, render_camera, 32, 0.0);
  render::BodyMotion motion;
  motion.T_world_body.translation() = Eigen::Vector3d(0, 0, 100.0);
  motion.omega_world = {0.0, 0.0, 1.0};
  Eigen::Isometry3d T_body_camera = Eigen::Isometry3d::Identity();
  T_body_camera.linear().col(0) = -Eigen::Vector3d::UnitY();
  T_body_camera.linear().col(1) = -Eigen::Vector3d::UnitZ();
  T_body_camera.linear().col(2) = Eigen::Vector3d::UnitX();

  AutoExposureOptions o;
  o.enabled = true;
  o.max_exposure_s = 0.05;
  AutoExposure ae(o, 2e-3);
  std::vector<double> chosen;
  for (const double light : {1.0, 0.25, 0.1}) {
    for (int k = 0; k < 100; ++k) ae.Update(MeanGrey(light, ae), 0.1);
    chosen.push_back(ae.exposure_time_s());
  }
  GrayImage still;
  camera.Render(renderer, motion, T_body_camera, 0.0, 0.0, &still);
  const double bright = still.at(320, 240);
  ASSERT_GT(bright, 100.0);
  for (const double exposure : chosen) {
    GrayImage image;
    camera.Render(renderer, motion, T_body_camera, 0.0, exposure, &image);
    const double expected = 1.0 * exposure * K.fx;
    const double length = RampLength(image, 240, bright) - RampLength(still, 240, bright);
    std::printf("exposure %.2f ms: edge ramp %.2f px (omega T f = %.2f px)\n", 1e3 * exposure,
                length, expected);
    EXPECT_NEAR(length, expected, 0.15 * expected + 0.5);
  }
}

// The metering window: the mean over the window's pixels only (a bright sky above, dark
// ground below), and a window that is not one is refused.
TEST(AutoExposureTest, TheMeteringWindowMetersItsPixelsOnly) {
  GrayImage image;
  image.width = 40;
  image.height = 30;
  image.pixels.assign(40 * 30, 50);
  std::fill(image.pixels.begin(), image.pixels.begin() + 40 * 10, 250);  // top third
  AutoExposureOptions o;
  EXPECT_NEAR(AutoExposure(o, 1e-3).Meter(image), (250.0 + 2 * 50.0) / 3.0, 1e-9);
  o.metering_window = {0.0, 0.5, 1.0, 1.0};  // the lower half
  EXPECT_DOUBLE_EQ(AutoExposure(o, 1e-3).Meter(image), 50.0);
  o.metering_window = {0.25, 0.0, 0.75, 0.5};  // rows 0-14: 10 at 250, 5 at 50
  EXPECT_NEAR(AutoExposure(o, 1e-3).Meter(image), (10 * 250.0 + 5 * 50.0) / 15.0, 1e-9);
  o.metering_window = {0.5, 0.0, 0.5, 1.0};
  EXPECT_THROW(o.Validate(), OptionError);
  o.metering_window = {0.0, 0.0, 1.0, 1.5};
  EXPECT_THROW(o.Validate(), OptionError);
}

}  // namespace
}  // namespace trackbed::robot
