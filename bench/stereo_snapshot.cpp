// Writes the stereo pair a scenario's cameras see at a given time, side by
// side (left | right), as a PNG — the pictures in the README come from this.
//
//   stereo_snapshot SCENARIO.yaml TIME_S OUT.png
#include <cstdio>
#include <exception>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "trackbed/perception/opencv_views.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"

int main(int argc, char** argv) {
  using namespace trackbed;
  if (argc != 4) {
    std::fprintf(stderr, "usage: stereo_snapshot SCENARIO.yaml TIME_S OUT.png\n");
    return 2;
  }
  try {
    const scenario::Scenario s = scenario::LoadScenario(
        argv[1], {{"duration_s", argv[2]}, {"robot.stereo.enabled", "true"}});
    cv::Mat pair;
    runner::RunObservers obs;
    obs.on_stereo = [&](const runner::StereoFrame& f) {
      cv::hconcat(perception::AsCvMat(*f.left), perception::AsCvMat(*f.right), pair);
    };
    runner::RunClosedLoop(s, obs);
    if (pair.empty() || !cv::imwrite(argv[3], pair)) {
      std::fprintf(stderr, "stereo_snapshot: could not write %s\n", argv[3]);
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stereo_snapshot: %s\n", e.what());
    return 1;
  }
  return 0;
}
