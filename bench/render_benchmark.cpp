// Rendering speed: stereo pairs per second at the scenes' camera size along
// their routes (rendering alone), and the closed loop's real-time factor with
// the stereo camera rendering at its rate (no vision yet).
//
//   render_benchmark [--pairs N] [SCENARIO.yaml ...]
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "trackbed/robot/stereo_rig.h"
#include "trackbed/scenes/closed_loop_runner.h"
#include "trackbed/scenes/scenario_yaml.h"
#include "trackbed/sim/renderer.h"

int main(int argc, char** argv) {
  using namespace trackbed;
  std::vector<std::string> files;
  int pairs = 200;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--pairs") == 0 && i + 1 < argc) {
      pairs = std::stoi(argv[++i]);
    } else {
      files.emplace_back(argv[i]);
    }
  }
  if (files.empty()) {
    files = {TRACKBED_SOURCE_DIR "/scenes/corridor.yaml",
             TRACKBED_SOURCE_DIR "/scenes/outdoor.yaml"};
  }
  try {
    for (const std::string& f : files) {
      scenes::Scenario s = scenes::LoadScenario(f, {{"robot.stereo.enabled", "true"}});
      // Rendering alone: the poses of one closed-loop run's cameras, replayed.
      std::vector<Eigen::Isometry3d> left, right;
      scenes::RunObservers record;
      record.on_stereo = [&](const scenes::StereoFrame& frame) {
        left.push_back(frame.T_world_left);
        right.push_back(frame.T_world_right);
      };
      const scenes::RunMetrics loop = scenes::RunClosedLoop(s, record);
      const sim::World world(s.scene.world, sim::Terrain(s.scene.terrain, s.seed), s.scene.objects);
      const robot::StereoRig rig(s.robot.stereo);
      sim::Renderer renderer(world, s.scene.appearance, s.scene.occluders, s.seed,
                             s.robot.stereo.width_px, s.robot.stereo.height_px,
                             s.robot.stereo.near_m, s.robot.stereo.far_m);
      sim::GrayImage l, r;
      const int n = std::min<int>(pairs, static_cast<int>(left.size()));
      const auto start = std::chrono::steady_clock::now();
      for (int i = 0; i < n; ++i) {
        const std::size_t k = static_cast<std::size_t>(i) * left.size() / n;
        renderer.Render(rig.intrinsics(), left[k], 0.1 * k, &l, nullptr);
        renderer.Render(rig.intrinsics(), right[k], 0.1 * k, &r, nullptr);
      }
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf(
          "%-9s %dx%d: %6.1f stereo pairs/s rendering alone (%d pairs); closed loop with "
          "rendering at %.0f Hz: %.1f s simulated in %.2f s, real-time factor %.1fx "
          "(rendering %.0f %% of it); %s\n",
          s.scene.name.c_str(), s.robot.stereo.width_px, s.robot.stereo.height_px, n / seconds, n,
          s.robot.stereo.rate_hz, loop.sim_time_s, loop.wall_time_s, loop.real_time_factor(),
          100.0 * loop.render_wall_s / loop.wall_time_s, renderer.gl_description().c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_benchmark: %s\n", e.what());
    return 1;
  }
  return 0;
}
