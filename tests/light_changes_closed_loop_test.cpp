// Light that changes, in the closed loop (scenes/corridor_daylight.yaml): driving into
// the stretch a window lights at 20 times the corridor's level, a fixed exposure
// saturates, and the auto-exposure brings the image back to its target with its
// texture — which it can only do because the render is exposed before it clips.
#include <algorithm>
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {
namespace {

struct Exposure {
  double mean = 0.0;       // mean grey level
  double saturated = 0.0;  // fraction of pixels at 255
  double commonest = 0.0;  // fraction of pixels at the commonest level in [1, 254]
};

Exposure Measure(const GrayImage& image) {
  std::array<std::size_t, 256> histogram{};
  double sum = 0.0;
  for (const std::uint8_t p : image.pixels) ++histogram[p], sum += p;
  const double n = static_cast<double>(image.pixels.size());
  return {sum / n, histogram[255] / n,
          *std::max_element(histogram.begin() + 1, histogram.end() - 1) / n};
}

// The left images of the last second of a run from x = 15 m into the window's stretch
// (full gain from x = 16.75 m; the robot is at about x = 18.6 m by then).
std::vector<Exposure> LastSecond(bool auto_exposure) {
  std::vector<scenario::Override> set = {
      {"duration_s", "9"}, {"robot.start.x_m", "15"}, {"robot.stereo.exposure_time_s", "0.005"}};
  if (auto_exposure) set.push_back({"robot.stereo.auto_exposure.enabled", "true"});
  ClosedLoopOptions options;
  options.step_images = true;
  ClosedLoop loop(scenario::LoadScenario(
                      std::string(TRACKBED_SOURCE_DIR) + "/scenes/corridor_daylight.yaml", set),
                  std::move(options));
  loop.Start();
  std::vector<Exposure> last;
  while (!loop.done()) {
    for (const StereoImages& pair : loop.Step().stereo) {
      if (pair.t_s >= 8.0) last.push_back(Measure(pair.left));
    }
  }
  loop.Finish();
  return last;
}

TEST(LightChangesClosedLoopTest, AutoExposureRecoversTheWindowLitStretchAFixedExposureLoses) {
  double fixed_saturated = 0.0;
  for (const bool auto_exposure : {false, true}) {
    const std::vector<Exposure> last = LastSecond(auto_exposure);
    ASSERT_GE(last.size(), 9u);
    double mean = 0.0, saturated = 0.0, commonest = 0.0;
    for (const Exposure& e : last) {
      mean += e.mean / last.size(), saturated += e.saturated / last.size();
      commonest = std::max(commonest, e.commonest);
    }
    std::printf(
        "%s: mean grey %.1f, %.1f %% of pixels saturated, at most %.1f %% at one level in "
        "[1, 254]\n",
        auto_exposure ? "auto-exposure" : "fixed exposure", mean, 100 * saturated, 100 * commonest);
    if (auto_exposure) {
      // The mean is near the controller's target (128), saturation is less than half
      // the fixed exposure's (the mean metering leaves the brightest floor clipped, as a
      // real camera's does while the far corridor is dark), and the lit stretch keeps
      // its texture: no level between black and white holds more than a quarter of
      // the image, where a render clipped and then scaled would put the stretch, 42 %
      // of the image saturated under the fixed exposure, on one level (plain paint
      // alone puts 10 % on one).
      EXPECT_NEAR(mean, 128.0, 0.15 * 128.0);
      EXPECT_LT(saturated, 0.5 * fixed_saturated);
      EXPECT_LT(commonest, 0.25);
    } else {
      EXPECT_GT(saturated, 0.3);  // most of the lit stretch
      fixed_saturated = saturated;
    }
  }
}

}  // namespace
}  // namespace trackbed::runner
