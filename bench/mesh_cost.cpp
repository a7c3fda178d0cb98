// What a large mesh costs: a binary PLY of a rippled sheet with --quads × --quads
// quads (two triangles each; 708 gives a million) is written, then timed (the
// process's CPU time, best of --repeats): assimp reading it (assets::ReadMesh), the plan grid
// (sim::PlacedMesh), Bullet's bounding volume hierarchy (a World with the sheet as an
// obstacle, less one without), 360 range-sensor rays cast at it, the footprint
// clearance against it, and sampling it as ground onto a terrain of 0.1 m cells over
// it (assets::SampleMeshGround); then the renderer: its set-up with the sheet (placing
// its vertices, normals, buffer objects filled at the first frame) less without it, and
// a 640 × 480 view (90° across, from 0.8 m over the sheet's centre, looking along +x
// over half of it) with and without the sheet. The sheet is one material: one drawable
// of every triangle, submitted whole whenever any of it is in view.
//
//   mesh_cost [--quads N] [--size-m S] [--repeats R] [--file OUT.ply]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "bench_args.h"
#include "trackbed/assets/scene_meshes.h"
#include "trackbed/render/renderer.h"
#include "trackbed/runner/footprint_clearance.h"
#include "trackbed/sim/world.h"

namespace {

using namespace trackbed;

// A sheet of `quads`² quads over `size_m`² m, centred on the origin, rippled 0.3 m.
void WritePly(const std::string& file, int quads, double size_m) {
  const int n = quads + 1;
  std::ofstream out(file, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << n * n
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face "
      << 2 * quads * quads << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const float x = static_cast<float>(size_m * i / quads - size_m / 2);
      const float y = static_cast<float>(size_m * j / quads - size_m / 2);
      const float v[3] = {x, y, static_cast<float>(0.3 * std::sin(0.7 * x) * std::cos(0.5 * y))};
      out.write(reinterpret_cast<const char*>(v), sizeof v);
    }
  }
  for (int j = 0; j < quads; ++j) {
    for (int i = 0; i < quads; ++i) {
      const std::int32_t a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
      const std::array<std::array<std::int32_t, 3>, 2> triangles = {{{a, b, c}, {a, c, d}}};
      for (const std::array<std::int32_t, 3>& t : triangles) {
        const std::uint8_t three = 3;
        out.write(reinterpret_cast<const char*>(&three), 1);
        out.write(reinterpret_cast<const char*>(t.data()), 3 * sizeof(std::int32_t));
      }
    }
  }
}

// Fewest CPU seconds of the process in `repeats` calls (all single-threaded: on a
// shared machine a steadier figure than the wall clock's).
double Best(int repeats, const std::function<void()>& f) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const std::clock_t t0 = std::clock();
    f();
    best = std::min(best, static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC);
  }
  return best;
}

// The renderer's set-up and a view's CPU time with the sheet in `with` and without it.
void RenderCost(const sim::World& with, const sim::World& without, std::size_t triangles,
                int repeats) {
  const geometry::PinholeCamera K = geometry::PinholeCamera::FromFieldOfView(640, 480, M_PI / 2);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();  // OpenCV axes: z along +x
  T.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  T.translation() = Eigen::Vector3d(0.0, 0.0, 0.8);
  GrayImage gray;
  const auto setup = [&](const sim::World& w) {
    return Best(repeats, [&] {
      render::Renderer r(w, render::SceneAppearance{}, {}, 1, 640, 480, 0.05, 120.0);
      r.Render(K, T, 0.0, &gray, nullptr);  // fills the buffer objects
    });
  };
  const double setup_with = setup(with), setup_without = setup(without);
  std::printf("renderer set-up + first frame: %8.3f s more with it (%.3f s, without %.3f s)\n",
              setup_with - setup_without, setup_with, setup_without);
  for (const sim::World* w : {&with, &without}) {
    render::Renderer r(*w, render::SceneAppearance{}, {}, 1, 640, 480, 0.05, 120.0);
    r.Render(K, T, 0.0, &gray, nullptr);
    const double frame = Best(repeats, [&] {
      for (int k = 0; k < 10; ++k) r.Render(K, T, 0.0, &gray, nullptr);
    });
    std::printf("a 640 x 480 view:        %8.3f ms (%s; %zu triangles of it submitted)\n",
                1e3 * frame / 10, w == &with ? "with the sheet" : "without",
                w == &with ? triangles : std::size_t{0});
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("The cost of a large mesh: reading, indexing, collision, sampling");
  int quads = 708, repeats = 3;
  double size_m = 100.0;
  std::string file = (std::filesystem::temp_directory_path() / "mesh_cost.ply").string();
  app.add_option("--quads", quads, "Quads along each side (two triangles each)");
  app.add_option("--size-m", size_m, "Side of the sheet [m]");
  app.add_option("--repeats", repeats, "Timings per figure (the best is printed)");
  app.add_option("--file", file, "Where the PLY file is written");
  if (const auto status = bench::Parse(app, argc, argv)) return *status;
  WritePly(file, quads, size_m);
  std::printf("%s: %d triangles, %.1f MB\n", file.c_str(), 2 * quads * quads,
              std::filesystem::file_size(file) / 1e6);
  assets::MeshRead read;
  std::printf("read (assimp):           %8.3f s\n",
              Best(repeats, [&] { read = assets::ReadMesh(file); }));
  const auto mesh = std::make_shared<const sim::TriangleMesh>(read.mesh);
  std::printf("%zu vertices after joining exact repeats\n", mesh->vertices.size());
  std::printf("plan grid:               %8.3f s\n", Best(repeats, [&] {
                sim::PlacedMesh p(*mesh, Eigen::Vector3d::Ones(), Eigen::Isometry3d::Identity());
              }));
  sim::TerrainOptions terrain;
  const double half = size_m / 2 - 1.0;
  terrain.extent_m = Eigen::Vector4d(-half, -half, half, half);
  terrain.cell_size_m = 0.1;
  sim::MeshObject object;
  object.entry.shape = sim::StaticObject::Shape::kMesh;
  object.entry.kind = "mesh";
  object.entry.mesh.file = file;
  object.entry.base_z_m = 0.0;
  object.visual = mesh;
  const double without = Best(repeats, [&] { sim::World w({}, sim::Terrain(terrain, 1), {}); });
  const double with =
      Best(repeats, [&] { sim::World w({}, sim::Terrain(terrain, 1), {}, {object}); });
  std::printf("Bullet's hierarchy:      %8.3f s (a world with it %.3f s, without %.3f s)\n",
              with - without, with, without);
  const sim::World world({}, sim::Terrain(terrain, 1), {}, {object});
  int hits = 0;
  const double rays = Best(repeats, [&] {
    hits = 0;
    for (int k = 0; k < 360; ++k) {
      const double a = k * M_PI / 180.0;
      const Eigen::Vector3d from(0.0, 0.0, 0.35);
      hits += world
                  .CastRay(from, from + 8.0 * Eigen::Vector3d(std::cos(a), std::sin(a), -0.05),
                           sim::kGroupObstacle)
                  .has_value();
    }
  });
  std::printf("360 rays (one scan):     %8.3f ms (%d hit it)\n", 1e3 * rays, hits);
  Eigen::Isometry3d body = Eigen::Isometry3d::Identity();
  body.translation() = Eigen::Vector3d(0.0, 0.0, 0.5);
  // The chassis's heights as the closed loop takes them (runner/closed_loop_navigation.cpp):
  // on the sheet, many triangles within them; 5 m above it, none.
  for (const double z : {0.2, 5.0}) {
    body.translation().z() = z;
    double d = 0.0;
    const double clearance = Best(repeats, [&] {
      d = runner::ChassisClearance(body, {0.7, 0.42}, {}, world.mesh_solids(), {-0.2, 0.08});
    });
    std::printf("footprint clearance:     %8.3f ms (body at z %.1f m: %.3f m)\n", 1e3 * clearance,
                z, d);
  }
  RenderCost(world, sim::World({}, sim::Terrain(terrain, 1), {}), mesh->triangles.size(), repeats);
  object.entry.mesh.ground = true;
  std::shared_ptr<const sim::ElevationGrid> grid;
  const double sampling =
      Best(repeats, [&] { grid = assets::SampleMeshGround({object}, terrain); });
  std::printf("ground sampling:         %8.3f s (%d × %d grid points)\n", sampling, grid->cols(),
              grid->rows());
  return 0;
}
