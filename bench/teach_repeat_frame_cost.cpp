// Whether a repeat's cost per frame grows with the route: a straight route down a long
// synthetic corridor (the teach & repeat tests' scene, without the simulator) is taught,
// its map saved and loaded with the key images on disk, and repeated; the repeater's
// CPU time per frame (its thread's clock, so that other processes on the machine do
// not count) is printed by tenth of the route, with the most key images held at once.
//
//   teach_repeat_frame_cost [--length-m 60] [--method 2d|3d]
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "teach_repeat_test_scene.h"
#include "trackbed/common/median.h"
#include "trackbed/navigation/diff_drive.h"
#include "trackbed/teach_repeat/milestone_builder.h"
#include "trackbed/teach_repeat/repeater_factory.h"
#include "trackbed/teach_repeat/teach_map.h"

namespace {

using namespace trackbed;
using teach_repeat::testing::CameraPose;

double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Teaches `length_m` of corridor at 2 cm per image into `dir` (key images spilled as
// milestones close), and returns the number of milestones.
std::size_t Teach(const teach_repeat::testing::CorridorScene& scene, double length_m,
                  teach_repeat::TeachMode mode, const std::string& dir) {
  teach_repeat::MilestoneBuilderOptions options;
  options.mode = mode;
  options.interval_images = 10;
  teach_repeat::MilestoneBuilder builder(teach_repeat::testing::TestCamera(), options);
  const int images = static_cast<int>(length_m / 0.02) + 1;
  for (int k = 0; k < images; ++k) {
    const geometry::Pose2 pose{0.02 * k, 0.0, 0.0};
    if (builder.AddImage(scene.Render(CameraPose(pose)), 0.1 * k, pose).milestone_closed) {
      builder.SpillMilestones(dir);
    }
  }
  const teach_repeat::TeachMap map = builder.Finish();
  teach_repeat::SaveTeachMap(map, dir);
  return map.milestones.size();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Teach & repeat: the repeater's CPU time per frame along a long route"};
  double length_m = 60.0;
  std::string method = "2d";
  app.add_option("--length-m", length_m, "Route length [m]")->capture_default_str();
  app.add_option("--method", method, "2d or 3d")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    teach_repeat::testing::CorridorOptions corridor;
    corridor.far_wall_x_m = length_m + 3.0;
    const teach_repeat::testing::CorridorScene scene(corridor);
    const std::string dir =
        (std::filesystem::temp_directory_path() / ("trackbed_frame_cost_" + method)).string();
    std::filesystem::remove_all(dir);
    const std::size_t milestones =
        Teach(scene, length_m, teach_repeat::ParseTeachMode(method), dir);
    teach_repeat::FunnelLaneOptions o2;
    o2.forward_speed_mps = 0.2;  // 2 cm per frame at 10 Hz
    teach_repeat::Localizer3dOptions o3;
    o3.forward_speed_mps = 0.2;
    const auto repeater = teach_repeat::MakeRepeater(
        method, teach_repeat::LoadTeachMap(dir, teach_repeat::MapLoading::kOnDemand), o2, o3);
    std::vector<double> ms, x;
    int most_held = 0;
    geometry::Pose2 pose;
    for (int k = 0; k < static_cast<int>(1.5 * length_m / 0.02); ++k) {
      const cv::Mat image = scene.Render(CameraPose(pose));
      const double start = ThreadCpuSeconds();
      const teach_repeat::RepeatCommand c = repeater->Update(image, 0.1 * k);
      ms.push_back(1e3 * (ThreadCpuSeconds() - start));
      x.push_back(pose.x);
      int held = 0;
      for (const teach_repeat::Milestone& m : repeater->map().milestones) {
        held += m.key_image.empty() ? 0 : 1;
      }
      most_held = std::max(most_held, held);
      if (c.status != teach_repeat::RepeatStatus::kDriving) break;
      pose = navigation::IntegrateTwist(pose, c.twist, 0.1);
    }
    std::printf(
        "%s, %.0f m, %zu milestones, %zu frames, at most %d key images held, ended at "
        "x = %.2f m\nrepeater CPU time per frame, median by tenth of the route [ms]:",
        method.c_str(), length_m, milestones, ms.size(), most_held, pose.x);
    std::vector<double> tenths;
    for (int t = 0; t < 10; ++t) {
      std::vector<double> part;
      for (std::size_t k = 0; k < ms.size(); ++k) {
        if (x[k] >= 0.1 * t * length_m && x[k] < 0.1 * (t + 1) * length_m) part.push_back(ms[k]);
      }
      tenths.push_back(part.empty() ? 0.0 : Median(part));
      std::printf(" %.2f", tenths.back());
    }
    std::printf("\nlast tenth / first tenth: %.2f\n", tenths.back() / tenths.front());
    std::filesystem::remove_all(dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "teach_repeat_frame_cost: %s\n", e.what());
    return 2;
  }
  return 0;
}
