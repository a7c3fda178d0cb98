// The robot's own track marks: a bounded record, written by the vehicle where it sinks
// and not where it does not, without changing the physics; drawn only inside the
// projected rut (none outside), darker there on average, the same bytes on a rerender,
// and nothing drawn without a record. Bad keys name the file, the key and the reason.
#include "trackbed/sim/track_marks.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "scenario_error_of.h"
#include "trackbed/render/renderer.h"
#include "trackbed/robot/tracked_vehicle.h"

namespace trackbed {
namespace {

TEST(TrackMarksTest, TheRecordStaysWithinItsCapacityOnALongDrive) {
  sim::TrackMarkOptions o;
  o.capacity = 1000;
  sim::TrackMarks marks(o);
  // 10 km on a circle of 50 m radius at 1 mm a step, both tracks.
  const double step_m = 0.001, radius = 50.0;
  const int steps = 10000000;
  for (int k = 0; k < steps; ++k) {
    const double a = k * step_m / radius;
    for (int side = 0; side < 2; ++side) {
      const double r = radius + (side == 0 ? 0.25 : -0.25);
      marks.Update(side, {r * std::cos(a), r * std::sin(a), 0.0}, a + M_PI / 2, 0.01, 0.1,
                   k * step_m);
    }
  }
  for (int side = 0; side < 2; ++side) {
    EXPECT_EQ(marks.size(side), 1000u);
    // One point per 2 cm of the track's own path, rounded up to a whole number of steps.
    const double per_step_m = step_m * (radius + (side == 0 ? 0.25 : -0.25)) / radius;
    const double expected = steps / std::ceil(o.spacing_m / per_step_m);
    EXPECT_NEAR(static_cast<double>(marks.recorded(side)), expected, 0.001 * expected);
    // The points held are the newest, oldest first, 2 cm apart.
    const sim::TrackMarkPoint& last = marks.point(side, 999);
    const double a_end = (steps - 1) * step_m / radius;
    EXPECT_LT(
        std::abs(std::atan2(last.p_world.y(), last.p_world.x()) - std::remainder(a_end, 2 * M_PI)),
        0.03 / radius);
    for (std::size_t i = 1; i < 1000; ++i) {
      const double gap = (marks.point(side, i).p_world - marks.point(side, i - 1).p_world).norm();
      EXPECT_NEAR(gap, o.spacing_m, 0.0011) << i;
      EXPECT_LT(marks.point(side, i - 1).travel_m, marks.point(side, i).travel_m);
    }
  }
  EXPECT_EQ(marks.capacity_bytes(), 2u * 1000u * sizeof(sim::TrackMarkPoint));
}

TEST(TrackMarksTest, RigidGroundEndsARut) {
  sim::TrackMarks marks(sim::TrackMarkOptions{});
  marks.Update(0, {0, 0, 0}, 0, 0.01, 0.1, 0);
  marks.Update(0, {0.05, 0, 0}, 0, 0.01, 0.1, 0.05);
  marks.Update(0, {0.10, 0, 0}, 0, 0.0, 0.1, 0.10);  // rigid: nothing, the rut ends
  marks.Update(0, {0.15, 0, 0}, 0, 0.01, 0.1, 0.15);
  ASSERT_EQ(marks.size(0), 3u);
  EXPECT_TRUE(marks.point(0, 0).starts_rut);
  EXPECT_FALSE(marks.point(0, 1).starts_rut);
  EXPECT_TRUE(marks.point(0, 2).starts_rut);
  EXPECT_EQ(marks.size(1), 0u);
}

// The vehicle driving 4 s at 0.4 m/s on `material`; its marks when `record`.
struct Drive {
  Eigen::Isometry3d T_world_body;
  sim::TrackMarks marks{sim::TrackMarkOptions{}};
  std::size_t points[2] = {0, 0};
  double max_depth_m = 0.0;
};
Drive DriveOn(const std::string& material, bool record) {
  sim::TerrainOptions t;
  t.extent_m = {-2, -3, 6, 3};
  t.cell_size_m = 0.1;
  t.default_material = material;
  sim::World world(sim::WorldOptions{}, sim::Terrain(t, 1), {});
  robot::TrackedVehicle vehicle(robot::TrackedVehicleOptions{}, &world, 0.0, 0.0, 0.0);
  sim::TrackMarks marks(sim::TrackMarkOptions{});
  if (record) vehicle.SetTrackMarks(&marks);
  for (int k = 0; k < 4000; ++k) {
    vehicle.CommandTrackSpeeds(0.4, 0.4);
    vehicle.ApplyForces(world.options().physics_step_s);
    world.Step();
  }
  Drive d;
  d.T_world_body = vehicle.chassis().T_world_body;
  d.marks = marks;
  for (int side = 0; side < 2; ++side) {
    d.points[side] = marks.size(side);
    for (std::size_t i = 0; i < marks.size(side); ++i) {
      d.max_depth_m = std::max(d.max_depth_m, double{marks.point(side, i).depth_m});
    }
  }
  return d;
}

TEST(TrackMarksTest, TheVehicleLeavesRutsOnSandNoneOnTheFloorAndDrivesTheSame) {
  const Drive sand = DriveOn("dry_sand", true);
  const Drive floor = DriveOn("hard_floor", true);
  std::printf("dry sand: %zu and %zu points, deepest rut %.4f m\n", sand.points[0], sand.points[1],
              sand.max_depth_m);
  EXPECT_GT(sand.points[0], 50u);
  EXPECT_GT(sand.points[1], 50u);
  EXPECT_GT(sand.max_depth_m, 0.003);  // Bekker's sinkage of this robot on dry sand: ~9 mm
  EXPECT_LT(sand.max_depth_m, 0.05);
  EXPECT_EQ(floor.points[0] + floor.points[1], 0u);
  // Drawn only: the physics the same to the bit.
  const Drive unrecorded = DriveOn("dry_sand", false);
  EXPECT_TRUE(sand.T_world_body.matrix() == unrecorded.T_world_body.matrix());
}

// A straight rut along x from 0 to 2 m at y = 0, 1 cm deep, 0.1 m wide.
sim::TrackMarks StraightRut() {
  sim::TrackMarks marks(sim::TrackMarkOptions{});
  for (int k = 0; k <= 200; ++k) marks.Update(0, {0.01 * k, 0.0, 0.0}, 0.0, 0.01, 0.1, 0.01 * k);
  return marks;
}

render::SceneAppearance Sunlit() {
  render::SceneAppearance a;
  a.sky_gray = 0.0;
  a.tree_crowns = false;
  return a;
}

TEST(TrackMarksTest, MarksAreDrawnInsideTheProjectedRutOnlyAndDarkenIt) {
  const sim::World world = render::test::FlatWorld({}, {-4, -4, 6, 4});
  const geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(640, 480, 60.0 * M_PI / 180.0);
  const Eigen::Vector3d eye(1.0, -1.2, 1.2), target(1.0, 0.0, 0.0);
  const Eigen::Isometry3d T_wc = render::test::Looking(eye, target - eye);
  const sim::TrackMarks marks = StraightRut();
  render::Renderer marked(world, Sunlit(), {}, 5, 640, 480, 0.05, 60.0);
  render::Renderer plain(world, Sunlit(), {}, 5, 640, 480, 0.05, 60.0);
  marked.SetTrackMarks(&marks);
  GrayImage on, off, again;
  marked.Render(K, T_wc, 0.0, &on, nullptr);
  plain.Render(K, T_wc, 0.0, &off, nullptr);
  // The strip: the rut 0.1 m wide and its walls at the angle of repose (1 cm / tan 34°),
  // plus the 1 cm margin; a pixel's footprint here is under 4 mm.
  const double reach = 0.05 + 0.01 / std::tan(34.0 * M_PI / 180.0) + 0.01;
  const double pixel_m = 0.004;
  int outside_changed = 0, inside = 0;
  double floor_on = 0.0, floor_off = 0.0;
  int floor_pixels = 0;
  for (int v = 0; v < K.height_px; ++v) {
    for (int u = 0; u < K.width_px; ++u) {
      const Eigen::Vector3d ray =
          T_wc.linear() * Eigen::Vector3d((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
      if (ray.z() >= -1e-9) continue;
      const Eigen::Vector3d p = T_wc.translation() - ray * (T_wc.translation().z() / ray.z());
      const bool in_strip =
          p.x() > -pixel_m && p.x() < 2.0 + pixel_m && std::abs(p.y()) < reach + pixel_m;
      const bool changed = on.at(u, v) != off.at(u, v);
      if (!in_strip && changed) ++outside_changed;
      inside += in_strip && changed;
      if (p.x() > 0.1 && p.x() < 1.9 && std::abs(p.y()) < 0.05 - pixel_m) {
        floor_on += on.at(u, v);
        floor_off += off.at(u, v);
        ++floor_pixels;
      }
    }
  }
  std::printf("changed inside the strip %d, outside %d; the floor's mean %.2f against %.2f\n",
              inside, outside_changed, floor_on / floor_pixels, floor_off / floor_pixels);
  EXPECT_EQ(outside_changed, 0);
  EXPECT_GT(inside, 5000);
  EXPECT_GT(floor_pixels, 5000);
  EXPECT_LT(floor_on / floor_pixels, floor_off / floor_pixels - 1.0);
  // A rerender gives the same bytes; without a record the image is the plain one.
  marked.Render(K, T_wc, 0.0, &again, nullptr);
  EXPECT_EQ(again.pixels, on.pixels);
  marked.SetTrackMarks(nullptr);
  marked.Render(K, T_wc, 0.0, &again, nullptr);
  EXPECT_EQ(again.pixels, off.pixels);
  const sim::TrackMarks empty(sim::TrackMarkOptions{});
  marked.SetTrackMarks(&empty);
  marked.Render(K, T_wc, 0.0, &again, nullptr);
  EXPECT_EQ(again.pixels, off.pixels);
}

TEST(TrackMarksTest, TheCameraSeesTheVehiclesRutsOnSandBehindIt) {
  const Drive sand = DriveOn("dry_sand", true);
  sim::TerrainOptions t;
  t.extent_m = {-2, -3, 6, 3};
  t.cell_size_m = 0.1;
  t.default_material = "dry_sand";
  const sim::World world(sim::WorldOptions{}, sim::Terrain(t, 1), {});
  const geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(640, 480, 80.0 * M_PI / 180.0);
  // The robot's camera's height, 0.8 m behind where the vehicle started, looking along
  // its ruts.
  const Eigen::Vector3d eye(-0.8, 0.0, 0.5), target(1.5, 0.0, 0.0);
  const Eigen::Isometry3d T_wc = render::test::Looking(eye, target - eye);
  render::SceneAppearance a = Sunlit();
  a.ground_look = render::GroundLook::kDetailed;
  render::Renderer r(world, a, {}, 5, 640, 480, 0.05, 60.0);
  GrayImage on, off;
  r.Render(K, T_wc, 0.0, &off, nullptr);
  r.SetTrackMarks(&sand.marks);
  r.Render(K, T_wc, 0.0, &on, nullptr);
  // Every changed pixel sees the ground within the ruts' strips (|y| about the tracks'
  // centrelines at ±0.25 m, within half the width, the walls and the margin).
  int changed = 0, outside = 0;
  double darkening = 0.0;
  for (int v = 0; v < K.height_px; ++v) {
    for (int u = 0; u < K.width_px; ++u) {
      if (on.at(u, v) == off.at(u, v)) continue;
      ++changed;
      darkening += off.at(u, v) - on.at(u, v);
      const Eigen::Vector3d ray =
          T_wc.linear() * Eigen::Vector3d((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
      const Eigen::Vector3d p = T_wc.translation() - ray * (T_wc.translation().z() / ray.z());
      outside +=
          std::abs(std::abs(p.y()) - 0.25) > 0.05 + 0.03 / std::tan(34.0 * M_PI / 180.0) + 0.02;
    }
  }
  std::printf("changed %d pixels (%d outside the strips), darker by %.2f grey on average\n",
              changed, outside, darkening / std::max(changed, 1));
  EXPECT_GT(changed, 5000);
  EXPECT_EQ(outside, 0);
  EXPECT_GT(darkening / changed, 1.0);
}

using scenario::test::ErrorOf;

TEST(TrackMarksTest, BadKeysNameTheFileTheKeyAndTheReason) {
  const std::string drive = "drive:\n  waypoints: [[0, 0], [5, 0]]\n";
  EXPECT_EQ(ErrorOf(drive + "scene:\n  appearance: {track_marks: {}}\n"), "");
  EXPECT_EQ(ErrorOf(drive + "scene:\n  appearance: {track_marks: {capacity: 1}}\n"),
            "test.yaml: scene.appearance.track_marks.capacity: must be in [2, 10000000] points "
            "(got 1)");
  EXPECT_EQ(ErrorOf(drive + "scene:\n  appearance: {track_marks: {grouser_pitch_m: 0}}\n"),
            "test.yaml: scene.appearance.track_marks.grouser_pitch_m: must be > 0 (got 0)");
  EXPECT_EQ(ErrorOf(drive + "scene:\n  appearance: {track_marks: {spacing_m: 2}}\n"),
            "test.yaml: scene.appearance.track_marks.spacing_m: must be in [0.005, 1] (got 2)");
  EXPECT_EQ(ErrorOf(drive + "scene:\n  appearance: {track_marks: {grouser: 1}}\n")
                .rfind("test.yaml: scene.appearance.track_marks.grouser: ", 0),
            0u);
}

}  // namespace
}  // namespace trackbed
