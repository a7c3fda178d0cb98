// The renderer's paged terrain: a window of the grid in detail around the robot
// (TerrainWindow) and coarse rings beyond (FarTerrain). The window moves in steps and
// stays far enough that the ground beyond it is already at the coarsest level; the
// first ring is that level exactly; a paged world's near ground is drawn as a small
// world's, bit for bit; and the rings leave no more cracks than the full grid.
#include "trackbed/render/far_terrain.h"
#include "trackbed/render/terrain_window.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "trackbed/render/renderer.h"
#include "trackbed/robot/stereo_rig.h"

namespace trackbed::render {
namespace {

sim::TerrainOptions Hills(double half_side_m, double cell_m) {
  sim::TerrainOptions t;
  t.extent_m = {-half_side_m, -half_side_m, half_side_m, half_side_m};
  t.cell_size_m = cell_m;
  t.roughness.undulation_amplitude_m = 1.0;
  t.roughness.undulation_wavelength_m = 20.0;
  t.roughness.bump_amplitude_m = 0.03;
  t.roughness.bump_wavelength_m = 0.7;
  t.default_material = "grass";
  sim::MaterialRegion sand;
  sand.material = "dry_sand";
  sand.min_m = {-30, -3};
  sand.max_m = {40, 2};
  t.regions = {sand};
  return t;
}

TEST(TerrainWindowTest, ASmallWorldOrFullDetailIsNotPaged) {
  const sim::Terrain park(Hills(13, 0.1), 1), big(Hills(100, 0.1), 1);
  EXPECT_FALSE(TerrainWindow(park, 2.0).paged());
  EXPECT_FALSE(TerrainWindow(big, 0.0).paged());  // the full grid everywhere, as asked
  const auto whole = TerrainWindow(park, 2.0).Follow({50, 50}, std::nullopt);
  ASSERT_TRUE(whole.has_value());
  EXPECT_TRUE(whole->window == GridWindow::Whole(park));
  EXPECT_FALSE(TerrainWindow(park, 2.0).Follow({3, 3}, whole).has_value());
}

TEST(TerrainWindowTest, TheWindowMovesInStepsAndKeepsTheCoarsestLevelBeyondIt) {
  const sim::Terrain t(Hills(100, 0.1), 1);
  const TerrainWindow w(t, 2.0);
  ASSERT_TRUE(w.paged());
  // TerrainDetail reaches its coarsest level 12 m out with 2 m of full detail.
  const double coarsest_m = 12.0;
  auto p = w.Follow({0.13, -0.4}, std::nullopt);
  ASSERT_TRUE(p.has_value());
  for (double x = 0.13; x < 60.0; x += 0.37) {
    const Eigen::Vector2d c(x, -0.4 + 0.3 * x);
    if (auto next = w.Follow(c, p)) p = next;
    const GridWindow& g = p->window;
    for (int v : {g.i0, g.j0, g.i1, g.j1}) EXPECT_EQ(v % TerrainWindow::kSnapCells, 0) << v;
    // From the centre to every edge of the window: at least the coarsest level's distance.
    const double ci = (c.x() - t.x_min()) / 0.1, cj = (c.y() - t.y_min()) / 0.1;
    EXPECT_GE(std::min({ci - g.i0, g.i1 - ci, cj - g.j0, g.j1 - cj}) * 0.1, coarsest_m) << x;
  }
}

TEST(FarTerrainTest, TheFirstRingIsTheNearWindowsCoarsestLevel) {
  const sim::Terrain t(Hills(100, 0.1), 3);
  const TerrainWindow w(t, 2.0);
  const GridWindow near = w.Follow({5, 5}, std::nullopt)->window;
  const TerrainDetail detail(t, 2.0, 16, near);
  const FarTerrain far(t, near, 120.0, std::vector<double>(t.materials().size(), 1.0));
  EXPECT_GT(far.pieces().size(), 20u);
  // A vertex of the first ring on the window's edge has the near level's height and
  // normal there (as floats, to the bit).
  int checked = 0;
  const double c = t.cell_size_m();
  for (const FarTerrain::Piece& piece : far.pieces()) {
    for (const TerrainVertex& v : piece.vertices) {
      const int i = static_cast<int>(std::lround((v.x - t.x_min()) / c));
      const int j = static_cast<int>(std::lround((v.y - t.y_min()) / c));
      const bool on_edge = (i == near.i0 || i == near.i1) && j >= near.j0 && j <= near.j1;
      if (!on_edge || v.s != static_cast<float>(v.x / 1.0)) continue;  // not a skirt's bottom
      EXPECT_EQ(v.z, static_cast<float>(detail.Height(i, j, TerrainDetail::kMaxLevel))) << i;
      ++checked;
    }
  }
  EXPECT_GT(checked, 50);
}

// A camera `height_m` above the ground at (x, y), pitched `pitch_deg` down, turned
// to `yaw_deg`.
Eigen::Isometry3d Camera(const sim::Terrain& t, double x, double y, double yaw_deg,
                         double height_m = 1.0, double pitch_deg = 5.0) {
  const Eigen::Matrix3d level =
      (Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(pitch_deg * M_PI / 180, Eigen::Vector3d::UnitY()))
          .toRotationMatrix();
  Eigen::Matrix3d body_to_cam;  // OpenCV camera axes: x right, y down, z forward
  body_to_cam << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = level * body_to_cam;
  T.translation() = Eigen::Vector3d(x, y, t.Height(x, y) + height_m);
  return T;
}

TEST(TerrainPagingTest, APagedWorldsNearGroundIsASmallWorldsAndPagingOpensNoCracks) {
  // 160 m x 160 m of hills at 0.2 m: the full grid is 640 000 vertices.
  const sim::World big(sim::WorldOptions{}, sim::Terrain(Hills(80, 0.2), 5), {});
  // The small world fits the window; its grid is the big one's shifted by a multiple
  // of every level's lattice and of the chunks (256 cells).
  sim::TerrainOptions small_options = Hills(80, 0.2);
  small_options.extent_m = {-28.8, -28.8, 22.4, 22.4};
  const sim::World small(sim::WorldOptions{}, sim::Terrain(small_options, 5), {});
  SceneAppearance lod, full;
  lod.terrain_full_detail_m = 2.0;
  ASSERT_TRUE(TerrainWindow(big.terrain(), 2.0).paged());
  ASSERT_FALSE(TerrainWindow(small.terrain(), 2.0).paged());
  Renderer paged(big, lod, {}, 3, 320, 240, 0.05, 120.0);
  Renderer whole(big, full, {}, 3, 320, 240, 0.05, 120.0);
  Renderer smaller(small, lod, {}, 3, 320, 240, 0.05, 120.0);
  geometry::PinholeCamera K;
  K.width_px = 320;
  K.height_px = 240;
  K.fx = K.fy = 200;
  K.cx = 159.5;
  K.cy = 119.5;
  // Cracks: pixels at the far plane with ground on both sides of them, across or up
  // and down (a silhouette against the sky has sky on one side). Paging must add none
  // where the small world has ground; beyond it (the window's edge and the rings) and
  // within it (the near levels' seams) the paged world must have no more than the full
  // grid.
  const auto crack = [](const DepthImage& d, int u, int v) {
    const auto ground = [&](int a, int b) { return d.at(a, b) < 119.0f; };
    return !ground(u, v) &&
           ((ground(u - 1, v) && ground(u + 1, v)) || (ground(u, v - 1) && ground(u, v + 1)));
  };
  const auto inside_small = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector4d& e = small_options.extent_m;
    return p.x() > e[0] && p.x() < e[2] && p.y() > e[1] && p.y() < e[3];
  };
  int added = 0, near_cracks = 0, near_whole = 0, beyond = 0, beyond_paged = 0, beyond_whole = 0;
  int near = 0, near_same = 0;
  // 40 views from the robot's height, then 10 from 20 m up onto the window's edge and
  // the rings.
  for (int view = 0; view < 50; ++view) {
    const double a = view * 2 * M_PI / 40;
    const double x = 3 * std::cos(a), y = 3 * std::sin(a), yaw = view * 37.0;
    const Eigen::Isometry3d T =
        view < 40 ? Camera(big.terrain(), x, y, yaw) : Camera(big.terrain(), x, y, yaw, 20, 25);
    GrayImage g_paged, g_small;
    DepthImage d_paged, d_whole, d_small;
    paged.Render(K, T, 0.0, &g_paged, &d_paged);
    whole.Render(K, T, 0.0, nullptr, &d_whole);
    smaller.Render(K, T, 0.0, &g_small, &d_small);
    for (int v = 1; v + 1 < K.height_px; ++v) {
      for (int u = 1; u + 1 < K.width_px; ++u) {
        const bool c_paged = crack(d_paged, u, v), c_whole = crack(d_whole, u, v);
        added += c_paged && !crack(d_small, u, v) && d_small.at(u, v) < 119.0f;
        if (d_small.at(u, v) < 119.0f || d_whole.at(u, v) < 119.0f) {
          const Eigen::Vector3d ray =
              T.linear() * Eigen::Vector3d((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1);
          const float depth = c_whole ? d_paged.at(u, v) : d_whole.at(u, v);
          if (inside_small(T.translation() + ray * depth)) {
            near_cracks += c_paged;
            near_whole += c_whole;
          } else {
            ++beyond;
            beyond_paged += c_paged;
            beyond_whole += c_whole;
          }
        }
        if (d_small.at(u, v) < 8.0f) {
          ++near;
          near_same += g_paged.at(u, v) == g_small.at(u, v);
        }
      }
    }
  }
  std::printf(
      "cracks in 50 views: added by paging %d; beyond the small world (%d ground pixels) "
      "paged %d, full grid %d; within it (the near levels' seams) paged %d, full grid %d; "
      "near pixels %d of %d identical to the small world's\n",
      added, beyond, beyond_paged, beyond_whole, near_cracks, near_whole, near_same, near);
  EXPECT_EQ(near_same, near);
  EXPECT_GT(near, 40 * 5000);
  EXPECT_EQ(added, 0);
  EXPECT_GT(beyond, 10 * 20000);  // the window's edge and the rings are in view
  EXPECT_LE(beyond_paged, beyond_whole);
  EXPECT_LE(near_cracks, near_whole);  // the levels' seams open no holes
}

}  // namespace
}  // namespace trackbed::render
