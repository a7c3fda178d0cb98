// What large meshes cost to draw in chunks with far versions (docs/rendering.md, "mesh
// objects"), along a scenario's route: the left camera's poses of a run of the scenario
// (recorded, untimed), then for each far-version bound (`--error-px`, 0 the full
// detail): the renderer's set-up and first frame (chunks split, far versions made,
// buffer objects filled) and the views along the route, each one's mesh triangles
// submitted (Renderer::mesh_triangles_submitted) and the CPU time of the process for
// all of them (llvmpipe's threads included: on a loaded machine steadier than the
// wall clock). Also the world's set-up (the mesh files read, Bullet's hierarchy).
//
//   mesh_chunks_cost [--views N] [--error-px E ...] [--set KEY=VALUE ...] SCENARIO.yaml ...
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <exception>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "bench_args.h"
#include "trackbed/assets/scene_meshes.h"
#include "trackbed/common/split_mix.h"
#include "trackbed/render/renderer.h"
#include "trackbed/robot/stereo_rig.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace {

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  using namespace trackbed;
  CLI::App app{"Mesh objects drawn in chunks with far versions along a scenario's route"};
  int views = 100;
  std::vector<double> errors_px = {0.0, 0.5};
  std::vector<std::string> sets, files;
  app.add_option("--views", views, "Views of the left camera, spread along the route")
      ->capture_default_str();
  app.add_option("--error-px", errors_px, "Far-version bounds (object_far_error_px), 0: full")
      ->capture_default_str();
  bench::AddSetOption(app, &sets);
  app.add_option("scenarios", files, "Scenario files")->required();
  if (const std::optional<int> status = bench::Parse(app, argc, argv)) return *status;
  try {
    std::vector<scenario::Override> overrides{{"robot.stereo.enabled", "true"}};
    for (const std::string& set : sets) overrides.push_back(scenario::ParseOverride(set));
    for (const std::string& f : files) {
      const scenario::Scenario s = scenario::LoadScenario(f, overrides);
      std::vector<Eigen::Isometry3d> left;
      std::vector<Eigen::Vector2d> centers;
      runner::RunObservers record;
      record.on_stereo = [&](const runner::StereoFrame& frame) {
        left.push_back(frame.T_world_left);
        centers.push_back(
            0.5 * (frame.T_world_left.translation() + frame.T_world_right.translation()).head<2>());
      };
      runner::RunClosedLoop(s, record);
      const double world_start = CpuSeconds();
      // Mesh obstacles on the scenario's terrain (ground meshes, elevation models and
      // heightmaps are not read here).
      assets::SceneMeshes meshes = assets::LoadSceneMeshes(scenario::SceneObjects(s));
      const sim::World world(s.scene.world,
                             sim::Terrain(s.scene.terrain, split_mix::Stream(s.seed, 0)),
                             std::move(meshes.primitives), std::move(meshes.obstacles));
      std::printf("%s: world set-up %.3f s CPU (mesh files read, Bullet's hierarchies)\n",
                  f.c_str(), CpuSeconds() - world_start);
      const robot::StereoRig rig(s.robot.stereo);
      const int n = std::min<int>(views, static_cast<int>(left.size()));
      for (const double error_px : errors_px) {
        render::SceneAppearance a = s.scene.appearance;
        a.object_far_error_px = error_px;
        const double setup_start = CpuSeconds();
        render::Renderer renderer(world, a, s.scene.occluders, split_mix::Stream(s.seed, 2),
                                  s.robot.stereo.width_px, s.robot.stereo.height_px,
                                  s.robot.stereo.near_m, s.robot.stereo.far_m);
        GrayImage gray;
        renderer.Render(rig.intrinsics(), left[0], 0.0, &gray, nullptr, &centers[0]);
        const double setup = CpuSeconds() - setup_start;
        std::vector<std::size_t> triangles;
        const double start = CpuSeconds();
        for (int i = 0; i < n; ++i) {
          const std::size_t k = static_cast<std::size_t>(i) * left.size() / n;
          renderer.Render(rig.intrinsics(), left[k], 0.1 * k, &gray, nullptr, &centers[k]);
          triangles.push_back(renderer.mesh_triangles_submitted());
        }
        const double per_view = (CpuSeconds() - start) / n;
        std::vector<std::size_t> sorted = triangles;
        std::sort(sorted.begin(), sorted.end());
        const double mean =
            std::accumulate(sorted.begin(), sorted.end(), 0.0) / static_cast<double>(n);
        std::printf(
            "object_far_error_px %.2f: renderer set-up and first frame %.3f s CPU; %d views: "
            "%.1f ms CPU each; mesh triangles submitted per view: min %zu, median %zu, mean "
            "%.0f, max %zu\n",
            error_px, setup, n, 1e3 * per_view, sorted.front(), sorted[sorted.size() / 2], mean,
            sorted.back());
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mesh_chunks_cost: %s\n", e.what());
    return 1;
  }
  return 0;
}
