// Rendering and vision speed: stereo pairs per second at the scenes' camera
// size along their routes (rendering alone), visual odometry frames per second
// on those pairs (one thread), and the closed loop's real-time factor with the
// camera rendering at its rate and the whole localization stack running.
//
//   render_benchmark [--pairs N] [--set KEY=VALUE ...] [SCENARIO.yaml ...]
#include <chrono>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bench_args.h"
#include "trackbed/common/split_mix.h"
#include "trackbed/estimation/stereo_visual_odometry.h"
#include "trackbed/perception/opencv_views.h"
#include "trackbed/render/renderer.h"
#include "trackbed/robot/stereo_rig.h"
#include "trackbed/robot/tracked_vehicle.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"

int main(int argc, char** argv) {
  using namespace trackbed;
  CLI::App app{
      "Rendering and vision speed: stereo pairs per second rendering alone, visual "
      "odometry frames per second, and the closed loop's real-time factor with rendering "
      "and the localization stack"};
  int pairs = 200;
  std::vector<std::string> sets, files;
  app.add_option("--pairs", pairs, "Stereo pairs to render and to run visual odometry on")
      ->capture_default_str()
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  bench::AddSetOption(app, &sets);
  bench::AddScenarioFiles(app, &files);
  if (const std::optional<int> status = bench::Parse(app, argc, argv)) return *status;
  files = bench::ScenarioFilesOrDefault(files);
  try {
    std::vector<scenario::Override> overrides{{"robot.stereo.enabled", "true"}};
    for (const std::string& set : sets) overrides.push_back(scenario::ParseOverride(set));
    for (const std::string& f : files) {
      scenario::Scenario s = scenario::LoadScenario(f, overrides);
      // The closed loop as `trackbed run` runs it: nothing on the main thread looks at
      // the images, so the sensor model runs on the localization thread.
      const runner::RunMetrics loop = runner::RunClosedLoop(s);
      // Rendering alone: the poses of the same run's cameras, recorded in a second,
      // untimed run (identical: the same scenario and seed), replayed.
      std::vector<Eigen::Isometry3d> left, right;
      std::vector<Eigen::Vector2d> centers;
      runner::RunObservers record;
      record.on_stereo = [&](const runner::StereoFrame& frame) {
        left.push_back(frame.T_world_left);
        right.push_back(frame.T_world_right);
        // The terrain's detail centre, as the closed loop passes it.
        centers.push_back(
            0.5 * (frame.T_world_left.translation() + frame.T_world_right.translation()).head<2>());
      };
      runner::RunClosedLoop(s, record);
      // The run's terrain and textures: the streams of its seed the closed loop uses.
      const sim::World world(s.scene.world,
                             sim::Terrain(s.scene.terrain, split_mix::Stream(s.seed, 0)),
                             scenario::SceneObjects(s));
      const robot::StereoRig rig(s.robot.stereo);
      render::Renderer renderer(world, s.scene.appearance, s.scene.occluders,
                                split_mix::Stream(s.seed, 2), s.robot.stereo.width_px,
                                s.robot.stereo.height_px, s.robot.stereo.near_m,
                                s.robot.stereo.far_m);
      // The robot's shadow (when the appearance asks for it) at the design rig's body pose.
      renderer.SetRobotShape(robot::ShadowBoxes(s.robot.vehicle));
      const auto place_robot = [&](std::size_t k) {
        renderer.SetRobotPose(left[k] * rig.T_body_left().inverse());
      };
      GrayImage l, r;
      const int n = std::min<int>(pairs, static_cast<int>(left.size()));
      // Rendering speed on n pairs spread along the whole route.
      const auto start = std::chrono::steady_clock::now();
      for (int i = 0; i < n; ++i) {
        const std::size_t k = static_cast<std::size_t>(i) * left.size() / n;
        place_robot(k);
        renderer.Render(rig.intrinsics(), left[k], 0.1 * k, &l, nullptr, &centers[k]);
        renderer.Render(rig.intrinsics(), right[k], 0.1 * k, &r, nullptr, &centers[k]);
      }
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      // The first n consecutive pairs (untimed), for visual odometry.
      std::vector<cv::Mat> lefts, rights;
      for (int i = 0; i < n; ++i) {
        const std::size_t k = static_cast<std::size_t>(i);
        place_robot(k);
        renderer.Render(rig.intrinsics(), left[k], 0.1 * i, &l, nullptr, &centers[k]);
        renderer.Render(rig.intrinsics(), right[k], 0.1 * i, &r, nullptr, &centers[k]);
        lefts.push_back(perception::AsCvMat(l).clone());
        rights.push_back(perception::AsCvMat(r).clone());
      }
      // Visual odometry on the first n consecutive pairs, one OpenCV thread.
      const int threads = cv::getNumThreads();
      cv::setNumThreads(1);
      estimation::StereoVisualOdometry vo(rig.stereo_camera());
      const auto vo_start = std::chrono::steady_clock::now();
      for (int i = 0; i < n; ++i) vo.Process(lefts[i], rights[i], 0.1 * i);
      const double vo_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - vo_start).count();
      cv::setNumThreads(threads);
      // The sensor model (exposure and noise) on the left images, as the closed loop applies it.
      const auto sensor_start = std::chrono::steady_clock::now();
      for (int i = 0; i < n; ++i) {
        GrayImage img;
        img.width = lefts[i].cols;
        img.height = lefts[i].rows;
        img.pixels.assign(lefts[i].data, lefts[i].data + lefts[i].total());
        robot::ApplySensorModel(s.robot.stereo.exposure, s.robot.stereo.noise_std, s.seed,
                                static_cast<std::uint64_t>(i), 0, &img);
      }
      const double sensor_ms =
          1e3 *
          std::chrono::duration<double>(std::chrono::steady_clock::now() - sensor_start).count() /
          n;
      std::printf(
          "%-9s %dx%d: %6.1f stereo pairs/s rendering alone (%d pairs); visual odometry "
          "%6.1f frames/s (one thread); sensor model %.2f ms per image (copy included); closed "
          "loop with rendering at %.0f Hz and the "
          "localization stack: %.1f s simulated in %.2f s, real-time factor %.1fx (rendering "
          "busy %.0f %% of it on the main thread, estimation %.0f %% on the second); %s\n",
          s.scene.name.c_str(), s.robot.stereo.width_px, s.robot.stereo.height_px, n / seconds, n,
          n / vo_seconds, sensor_ms, s.robot.stereo.rate_hz, loop.sim_time_s, loop.wall_time_s,
          loop.real_time_factor(), 100.0 * loop.render_wall_s / loop.wall_time_s,
          100.0 * loop.estimation_wall_s / loop.wall_time_s, renderer.gl_description().c_str());
      if (s.robot.stereo.exposure_time_s > 0.0) {
        std::printf(
            "%-9s rendering alone draws instants; the closed loop renders %d per image "
            "(robot.stereo.exposure_time_s = %g s)\n",
            s.scene.name.c_str(), s.robot.stereo.exposure_samples, s.robot.stereo.exposure_time_s);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_benchmark: %s\n", e.what());
    return 1;
  }
  return 0;
}
