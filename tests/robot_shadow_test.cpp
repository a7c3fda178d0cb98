// The robot's own shadow: the ground is darkened exactly where rays towards the sun
// pass through the robot's boxes at its pose in the frame, nowhere else, by the sun's
// share of the light (checked beyond a pixel of the shadow's outline and outside the
// sun's penumbra, and beyond 3 px of the outline without exception); it moves with the
// robot; reruns give the same bytes.
#include "trackbed/render/robot_shadow.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/render/renderer.h"
#include "trackbed/render/scene_lighting.h"
#include "trackbed/robot/tracked_vehicle.h"

namespace trackbed::render {
namespace {

constexpr double kAmbient = 0.3, kDiffuse = 0.7, kElevationDeg = 20.0;

SceneAppearance SunLit(bool robot_shadow) {
  SceneAppearance a;
  a.ambient = kAmbient;
  a.diffuse = kDiffuse;
  a.sky_gray = 0.0;
  a.tree_crowns = false;
  a.sun_azimuth_deg = 160.0;  // from behind the robot and a little to its left
  a.sun_elevation_deg = kElevationDeg;
  a.robot_shadow = robot_shadow;
  return a;
}

// The body of the default vehicle standing on the floor (z = 0) at (x, y), heading yaw.
Eigen::Isometry3d Body(double x, double y, double yaw_deg) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  T.translation() = Eigen::Vector3d(x, y, robot::TrackedVehicleOptions{}.com_height_m);
  return T;
}

// A camera 4 m from the robot, looking down at it from its right and ahead: its
// pixels are about 1 cm on the ground, wider than the penumbra.
Eigen::Isometry3d Camera() {
  const Eigen::Vector3d eye(1.2, -3.2, 2.6), target(0.8, 0.0, 0.0);
  return test::Looking(eye, target - eye);
}

// Whether the ray from `p` towards `sun` meets an oriented box grown by `grow` on every
// side (the slab method).
bool RayHitsBox(const ShadowBox& b, const Eigen::Isometry3d& T_world_body,
                const Eigen::Vector3d& sun, const Eigen::Vector3d& p, double grow = 0.0) {
  const Eigen::Vector3d q = T_world_body.inverse() * p - b.center_m;
  const Eigen::Vector3d d = T_world_body.linear().transpose() * sun;
  double t0 = 0.0, t1 = 1e9;
  for (int i = 0; i < 3; ++i) {
    const double h = 0.5 * b.size_m[i] + grow;
    if (std::abs(d[i]) < 1e-12) {
      if (std::abs(q[i]) > h) return false;
      continue;
    }
    double a = (-h - q[i]) / d[i], c = (h - q[i]) / d[i];
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a);
    t1 = std::min(t1, c);
  }
  return t0 <= t1;
}

// Whether `p` lies in a box's penumbra: its ray towards the sun meets the box grown by
// the penumbra's half-width but misses it shrunk by as much (the sun's angular radius
// times the distance to the box; √3 of it, the most a box's growth along its three axes
// moves its outline sideways).
bool InPenumbra(const ShadowBox& b, const Eigen::Isometry3d& T_world_body,
                const Eigen::Vector3d& sun, const Eigen::Vector3d& p) {
  const double distance = std::abs((T_world_body * b.center_m - p).dot(sun));
  const double half = std::sqrt(3.0) * (kSunAngularRadiusRad * distance + 1e-4);
  return RayHitsBox(b, T_world_body, sun, p, half) != RayHitsBox(b, T_world_body, sun, p, -half);
}

// Per pixel of the view: 1 where the floor point its centre sees is in the robot's
// shadow, 0 where it is not, -1 where it sees no floor; `penumbra` set where it lies
// in a box's penumbra.
std::vector<int> PredictedShadow(const geometry::PinholeCamera& K, const Eigen::Isometry3d& T_wc,
                                 const std::vector<ShadowBox>& boxes,
                                 const Eigen::Isometry3d& T_world_body,
                                 std::vector<bool>* penumbra) {
  const Eigen::Vector3d sun = SunDirection(SunLit(true).sun_azimuth_deg, kElevationDeg);
  std::vector<int> mask(static_cast<std::size_t>(K.width_px) * K.height_px, -1);
  penumbra->assign(mask.size(), false);
  for (int v = 0; v < K.height_px; ++v) {
    for (int u = 0; u < K.width_px; ++u) {
      const Eigen::Vector3d ray =
          T_wc.linear() * Eigen::Vector3d((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
      if (ray.z() >= -1e-9) continue;
      const Eigen::Vector3d p = T_wc.translation() - ray * (T_wc.translation().z() / ray.z());
      bool shadow = false, soft = false;
      for (const ShadowBox& b : boxes) {
        shadow = shadow || RayHitsBox(b, T_world_body, sun, p);
        soft = soft || InPenumbra(b, T_world_body, sun, p);
      }
      const std::size_t i = static_cast<std::size_t>(v) * K.width_px + u;
      mask[i] = shadow ? 1 : 0;
      (*penumbra)[i] = soft;
    }
  }
  return mask;
}

struct Agreement {
  int shadowed = 0, lit = 0;  // pixels checked, more than `margin` from the outline
  int penumbra = 0;           // pixels more than `margin` from it but in the penumbra
  int shadowed_wrong = 0, lit_wrong = 0;
  double ratio_sum = 0.0;  // shadowed over unshadowed grey, summed over shadowed pixels
};

// The shadowed and unshadowed renders against the prediction, at pixels more than
// `margin` pixels from the predicted outline and, unless `penumbra` is null, outside
// the penumbra.
Agreement Compare(const std::vector<int>& mask, const std::vector<bool>* penumbra,
                  const GrayImage& on, const GrayImage& off, int margin) {
  Agreement a;
  const int W = on.width, H = on.height;
  for (int v = margin; v + margin < H; ++v) {
    for (int u = margin; u + margin < W; ++u) {
      const int m = mask[static_cast<std::size_t>(v) * W + u];
      bool near_outline = m < 0;
      for (int dv = -margin; dv <= margin; ++dv) {
        for (int du = -margin; du <= margin; ++du) {
          near_outline = near_outline || mask[static_cast<std::size_t>(v + dv) * W + u + du] != m;
        }
      }
      if (near_outline) continue;
      if (penumbra && (*penumbra)[static_cast<std::size_t>(v) * W + u]) {
        ++a.penumbra;
        continue;
      }
      const double g_on = on.at(u, v), g_off = off.at(u, v);
      if (m == 1) {
        ++a.shadowed;
        a.ratio_sum += g_on / std::max(g_off, 1.0);
        // The sun's share gone: at most the ambient share of the grey, and a rounding.
        const double expected =
            g_off * kAmbient / (kAmbient + kDiffuse * std::sin(kElevationDeg * M_PI / 180.0));
        if (std::abs(g_on - expected) > 1.5) ++a.shadowed_wrong;
      } else {
        ++a.lit;
        if (g_on != g_off) ++a.lit_wrong;
      }
    }
  }
  return a;
}

TEST(RobotShadowTest, DarkensTheFloorWhereTheHullAndTracksShadowIt) {
  const sim::World world = test::FlatWorld({}, {-6, -6, 8, 6});
  const geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(640, 480, 60.0 * M_PI / 180.0);
  const std::vector<ShadowBox> boxes = robot::ShadowBoxes(robot::TrackedVehicleOptions{});
  Renderer shadowed(world, SunLit(true), {}, 5, 640, 480, 0.05, 60.0);
  Renderer plain(world, SunLit(false), {}, 5, 640, 480, 0.05, 60.0);
  shadowed.SetRobotShape(boxes);
  plain.SetRobotShape(boxes);
  // Two poses: the shadow follows the robot.
  for (const Eigen::Isometry3d& T_body : {Body(0.0, 0.0, 0.0), Body(0.4, 0.3, 25.0)}) {
    shadowed.SetRobotPose(T_body);
    plain.SetRobotPose(T_body);
    GrayImage on, off;
    shadowed.Render(K, Camera(), 0.0, &on, nullptr);
    plain.Render(K, Camera(), 0.0, &off, nullptr);
    std::vector<bool> penumbra;
    const std::vector<int> mask = PredictedShadow(K, Camera(), boxes, T_body, &penumbra);
    const Agreement a = Compare(mask, &penumbra, on, off, 1);
    std::printf(
        "shadowed %d (wrong %d, grey ratio %.3f), lit %d (wrong %d), in the penumbra beyond a "
        "pixel %d\n",
        a.shadowed, a.shadowed_wrong, a.ratio_sum / std::max(a.shadowed, 1), a.lit, a.lit_wrong,
        a.penumbra);
    EXPECT_GT(a.shadowed, 3000);
    EXPECT_GT(a.lit, 100000);
    EXPECT_EQ(a.shadowed_wrong, 0);
    EXPECT_EQ(a.lit_wrong, 0);
    // The penumbra here is at most 3 px wide: beyond 3 px of the outline, all as predicted.
    const Agreement b = Compare(mask, nullptr, on, off, 3);
    std::printf("beyond 3 px: shadowed %d (wrong %d), lit %d (wrong %d)\n", b.shadowed,
                b.shadowed_wrong, b.lit, b.lit_wrong);
    EXPECT_EQ(b.shadowed_wrong, 0);
    EXPECT_EQ(b.lit_wrong, 0);
  }
}

TEST(RobotShadowTest, RerunsGiveTheSameBytes) {
  const sim::World world = test::FlatWorld({}, {-6, -6, 8, 6});
  const geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(320, 240, 60.0 * M_PI / 180.0);
  const std::vector<ShadowBox> boxes = robot::ShadowBoxes(robot::TrackedVehicleOptions{});
  GrayImage first, second, again;
  {
    Renderer r(world, SunLit(true), {}, 5, 320, 240, 0.05, 60.0);
    r.SetRobotShape(boxes);
    r.SetRobotPose(Body(0.1, 0.0, 10.0));
    r.Render(K, Camera(), 0.0, &first, nullptr);
    r.SetRobotPose(Body(0.5, 0.0, 10.0));
    r.Render(K, Camera(), 0.1, &again, nullptr);
    EXPECT_NE(first.pixels, again.pixels);  // the shadow moved
  }
  Renderer r(world, SunLit(true), {}, 5, 320, 240, 0.05, 60.0);
  r.SetRobotShape(boxes);
  r.SetRobotPose(Body(0.1, 0.0, 10.0));
  r.Render(K, Camera(), 0.0, &second, nullptr);
  EXPECT_EQ(first.pixels, second.pixels);
}

TEST(RobotShadowTest, TheCpuShareAgreesWithTheRayAndSoftensOverTheSunsDisc) {
  const std::vector<ShadowBox> boxes = robot::ShadowBoxes(robot::TrackedVehicleOptions{});
  const Eigen::Isometry3d T = Body(0.0, 0.0, 30.0);
  const Eigen::Vector3d sun = SunDirection(200.0, 25.0);
  int agree = 0, total = 0;
  for (double x = -1.0; x <= 2.0; x += 0.037) {
    for (double y = -1.0; y <= 1.0; y += 0.041) {
      const Eigen::Vector3d p(x, y, 0.0);
      bool hit = false;
      for (const ShadowBox& b : boxes) hit = hit || RayHitsBox(b, T, sun, p);
      const double lit = RobotSunlit(boxes, T, sun, p);
      ++total;
      agree += (lit < 0.5) == hit;
    }
  }
  // Points within the penumbra (a few millimetres) may fall either way.
  EXPECT_GE(agree, total - 3);
  // Across the shadow's edge the light rises over about the penumbra's width: the sun's
  // disc at the distance to the box.
  const Eigen::Isometry3d level = Body(0.0, 0.0, 0.0);
  const Eigen::Vector3d behind = SunDirection(180.0, 20.0);
  double edge = 0.0;  // where a line across the shadow's side leaves it
  for (double y = 0.0; y < 1.0; y += 1e-4) {
    if (RobotSunlit(boxes, level, behind, {1.0, y, 0.0}) > 0.5) {
      edge = y;
      break;
    }
  }
  // At x = 1 m only the hull's shadow (the tracks' ends at 0.93 m).
  const double a = RobotSunlit(boxes, level, behind, {1.0, edge - 0.02, 0.0});
  const double b = RobotSunlit(boxes, level, behind, {1.0, edge + 0.02, 0.0});
  EXPECT_NEAR(edge, 0.21, 0.005);  // the hull's side, 0.21 m from the centreline
  EXPECT_EQ(a, 0.0);
  EXPECT_EQ(b, 1.0);
  const double mid = RobotSunlit(boxes, level, behind, {1.0, edge, 0.0});
  EXPECT_GT(mid, 0.3);
  EXPECT_LT(mid, 0.7);
}

}  // namespace
}  // namespace trackbed::render
