// What one stereo frame costs in the stages after rendering, in CPU time of one thread
// (one OpenCV thread): the image sensor on both images (robot::ImageSensor::Apply), the
// rectification of the pair (perception::StereoRectifier) and visual odometry on the
// rectified pair (tracking, matching, new features: estimation::StereoVisualOdometry
// through the localization stack, without its IMU), on the frames of the scenario's
// first seconds with its given calibration. Prints milliseconds per frame, the best of
// --repeats passes; never fails on them (docs/results/2026-12-07-cheaper-closed-loop.md).
//
//   localization_frame_cost [--frames 100] [--repeats 3] [--set KEY=VALUE ...] [SCENARIO.yaml]
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bench_args.h"
#include "trackbed/estimation/localization.h"
#include "trackbed/perception/opencv_views.h"
#include "trackbed/perception/stereo_rectifier.h"
#include "trackbed/robot/image_sensor.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/runner/localization_options.h"
#include "trackbed/runner/robot_build.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace {

double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The least CPU time of `repeats` calls of `pass` [s].
template <class Pass>
double Best(int repeats, const Pass& pass) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const double start = ThreadCpuSeconds();
    pass();
    best = std::min(best, ThreadCpuSeconds() - start);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace trackbed;
  CLI::App app{"CPU milliseconds per stereo frame: image sensor, rectification, visual odometry"};
  int frames = 100, repeats = 3;
  std::vector<std::string> sets;
  std::string file = TRACKBED_SOURCE_DIR "/scenes/outdoor.yaml";
  app.add_option("--frames", frames, "Stereo frames from the run's start")
      ->check(CLI::Range(2, 100000));
  app.add_option("--repeats", repeats, "Passes over the frames; the best counts")
      ->check(CLI::Range(1, 1000));
  bench::AddSetOption(app, &sets);
  app.add_option("scenario", file, "Scenario file (default: scenes/outdoor.yaml)");
  if (const std::optional<int> status = bench::Parse(app, argc, argv)) return *status;
  try {
    std::vector<scenario::Override> overrides{{"robot.stereo.enabled", "true"}};
    for (const std::string& set : sets) overrides.push_back(scenario::ParseOverride(set));
    scenario::Scenario s = scenario::LoadScenario(file, overrides);
    const double rate = s.robot.stereo.rate_hz;
    s.duration_s = (frames + 0.5) / rate;
    std::vector<double> times;
    std::vector<cv::Mat> lefts, rights;
    runner::RunObservers record;
    record.on_stereo = [&](const runner::StereoFrame& f) {
      times.push_back(f.t_s);
      lefts.push_back(perception::AsCvMat(*f.left).clone());
      rights.push_back(perception::AsCvMat(*f.right).clone());
    };
    runner::RunClosedLoop(s, record);
    const runner::RobotBuild robot = runner::BuildRunRobot(s);
    const std::size_t n = lefts.size();
    cv::setNumThreads(1);

    // The image sensor, on copies of the developed images (its cost does not depend on
    // what the pixels hold).
    const scenario::Scenario resolved = scenario::WithRealismResolved(s);
    const robot::StereoRigOptions& stereo = resolved.robot.stereo;
    double sensor_ms = 0.0;
    if (*stereo.photometric.enabled) {
      const robot::ImageSensor sensor(stereo.photometric, stereo.width_px, stereo.height_px, 1, 0);
      std::vector<GrayImage> images;
      for (std::size_t i = 0; i < 2 * n; ++i) {
        const cv::Mat& m = i % 2 == 0 ? lefts[i / 2] : rights[i / 2];
        GrayImage& g = images.emplace_back();
        g.width = m.cols;
        g.height = m.rows;
        g.pixels.assign(m.datastart, m.dataend);
      }
      sensor_ms = 1e3 *
                  Best(repeats,
                       [&] {
                         for (std::size_t i = 0; i < images.size(); ++i) {
                           sensor.Apply(1.0, 7, i, &images[i]);
                         }
                       }) /
                  static_cast<double>(n);
    }
    // Rectification alone, then the stack (rectification and visual odometry).
    const perception::StereoRectifier rectifier(*robot.given.stereo);
    cv::Mat l, r;
    const double rectify_ms = 1e3 *
                              Best(repeats,
                                   [&] {
                                     for (std::size_t i = 0; i < n; ++i) {
                                       rectifier.Rectify(lefts[i], rights[i], &l, &r);
                                     }
                                   }) /
                              static_cast<double>(n);
    const double stack_ms = 1e3 *
                            Best(repeats,
                                 [&] {
                                   estimation::LocalizationStack stack(
                                       runner::LocalizationOptionsOf(s, robot.given),
                                       &*robot.given.stereo, Eigen::Isometry3d::Identity());
                                   for (std::size_t i = 0; i < n; ++i)
                                     stack.AddStereoFrame(times[i], lefts[i], rights[i]);
                                 }) /
                            static_cast<double>(n);
    std::printf(
        "%s, %zu frames of %dx%d, CPU ms per frame (one thread, best of %d): image sensor "
        "%.2f (both images), rectification %.2f, visual odometry %.2f, stack %.2f\n",
        s.scene.name.c_str(), n, stereo.width_px, stereo.height_px, repeats, sensor_ms, rectify_ms,
        stack_ms - rectify_ms, stack_ms);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "localization_frame_cost: %s\n", e.what());
    return 1;
  }
  return 0;
}
