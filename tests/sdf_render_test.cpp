// An SDF world's shapes as the cameras draw them: the silhouettes of a turned box, a
// tilted cylinder and a sphere within half a pixel of the pinhole projection of the
// shapes the world describes (their true surfaces, not the facets), and each visual's
// <diffuse> colour drawn as its grey albedo (docs/gazebo_users.md).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/assets/scene_meshes.h"
#include "trackbed/description/sdf_world.h"
#include "trackbed/render/renderer.h"
#include "trackbed/sim/world.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;
using Vec3 = Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

// Three static models above the camera's horizon (the ground never behind them), each
// with a colour: a box turned 0.5 rad about z, a cylinder rolled 0.6 rad and pitched
// 0.4 rad, a sphere.
const char* kShapes = R"(<?xml version='1.0'?>
<sdf version='1.9'><world name='shapes'>
  <model name='box'><static>true</static><pose>6 -1.3 1.6 0 0 0.5</pose><link name='l'>
    <visual name='v'><geometry><box><size>0.8 0.6 0.5</size></box></geometry>
      <material><diffuse>0.8 0.1 0.1 1</diffuse></material></visual></link></model>
  <model name='log'><static>true</static><pose>6 0 1.9 0.6 0.4 0</pose><link name='l'>
    <visual name='v'><geometry><cylinder><radius>0.25</radius><length>0.9</length></cylinder>
      </geometry><material><diffuse>0.2 0.6 0.3 1</diffuse></material></visual></link></model>
  <model name='ball'><static>true</static><pose>6 1.3 1.75 0 0 0</pose><link name='l'>
    <visual name='v'><geometry><sphere><radius>0.35</radius></sphere></geometry>
      <material><diffuse>0.9 0.9 0.9 1</diffuse></material></visual></link></model>
</world></sdf>
)";

// The three true shapes, for rays through pixel centres.
struct Ray {
  Vec3 o, d;
};

bool HitsBox(const Ray& world_ray, const Vec3& centre, double yaw, const Vec3& size) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
  const Vec3 o = R.transpose() * (world_ray.o - centre), d = R.transpose() * world_ray.d;
  double t0 = 0.0, t1 = 1e9;
  for (int k = 0; k < 3; ++k) {
    const double a = (-0.5 * size[k] - o[k]) / d[k], b = (0.5 * size[k] - o[k]) / d[k];
    t0 = std::max(t0, std::min(a, b));
    t1 = std::min(t1, std::max(a, b));
  }
  return t0 <= t1;
}

bool HitsCylinder(const Ray& world_ray, const Eigen::Isometry3d& pose, double r, double length) {
  const Vec3 o = pose.inverse() * world_ray.o, d = pose.linear().transpose() * world_ray.d;
  const double a = d.x() * d.x() + d.y() * d.y(), b = 2 * (o.x() * d.x() + o.y() * d.y()),
               c = o.x() * o.x() + o.y() * o.y() - r * r;
  const double disc = b * b - 4 * a * c;
  if (disc >= 0 && a > 0) {
    for (double s : {-1.0, 1.0}) {
      const double t = (-b + s * std::sqrt(disc)) / (2 * a);
      if (t > 0 && std::abs(o.z() + t * d.z()) <= 0.5 * length) return true;
    }
  }
  for (double cap : {-0.5 * length, 0.5 * length}) {
    const double t = (cap - o.z()) / d.z();
    const Vec3 p = o + t * d;
    if (t > 0 && p.x() * p.x() + p.y() * p.y() <= r * r) return true;
  }
  return false;
}

bool HitsSphere(const Ray& ray, const Vec3& centre, double r) {
  const Vec3 oc = ray.o - centre;
  const double b = oc.dot(ray.d), c = oc.squaredNorm() - r * r;
  return b * b - ray.d.squaredNorm() * c >= 0 && b < 0;
}

class SdfRenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!description::CanReadDescriptions()) {
      GTEST_SKIP() << "built without sdformat (TRACKBED_WITH_SDF=OFF)";
    }
    shapes_dir_ = fs::temp_directory_path() / ("sdf_render_test_" + std::to_string(::getpid()));
  }
  void TearDown() override { fs::remove_all(shapes_dir_); }
  fs::path shapes_dir_;
};

geometry::PinholeCamera Camera() { return render::test::Pinhole(400, 300, 320.0, 199.5, 149.5); }

// Which shape (0 box, 1 cylinder, 2 sphere) the ray through (u, v) meets; -1: none.
int TrueShapeAt(const geometry::PinholeCamera& K, const Eigen::Isometry3d& T_world_camera, double u,
                double v) {
  const Ray ray{T_world_camera.translation(),
                T_world_camera.linear() * Vec3((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0)};
  Eigen::Isometry3d log = Eigen::Isometry3d::Identity();
  log.linear() = (Eigen::AngleAxisd(0.4, Vec3::UnitY()) * Eigen::AngleAxisd(0.6, Vec3::UnitX()))
                     .toRotationMatrix();
  log.translation() = Vec3(6, 0, 1.9);
  if (HitsBox(ray, {6, -1.3, 1.6}, 0.5, {0.8, 0.6, 0.5})) return 0;
  if (HitsCylinder(ray, log, 0.25, 0.9)) return 1;
  if (HitsSphere(ray, {6, 1.3, 1.75}, 0.35)) return 2;
  return -1;
}

// The distance from (u, v) to the nearest point where the true shapes' coverage
// changes [px], searched in 0.01 px steps along 64 directions up to 3 px.
double DistanceToTrueOutline(const geometry::PinholeCamera& K, const Eigen::Isometry3d& T, int u,
                             int v) {
  const bool inside = TrueShapeAt(K, T, u, v) >= 0;
  for (int step = 1; step <= 300; ++step) {
    const double r = 0.01 * step;
    for (int k = 0; k < 64; ++k) {
      const double a = 2 * kPi * k / 64;
      if ((TrueShapeAt(K, T, u + r * std::cos(a), v + r * std::sin(a)) >= 0) != inside) return r;
    }
  }
  return 3.0;
}

// Whether the same shape covers the points 2 px and 3 px about (u, v) in 16 directions:
// a pixel of the shape's interior, whose grey is its albedo's alone.
bool FarFromTrueOutline(const geometry::PinholeCamera& K, const Eigen::Isometry3d& T, int u, int v,
                        int shape) {
  for (double r : {2.0, 3.0}) {
    for (int k = 0; k < 16; ++k) {
      const double a = 2 * kPi * k / 16;
      if (TrueShapeAt(K, T, u + r * std::cos(a), v + r * std::sin(a)) != shape) return false;
    }
  }
  return true;
}

TEST_F(SdfRenderTest, SilhouettesWithinHalfAPixelOfTheProjectedShapes) {
  const description::SdfScene scene = description::ReadSdfWorldString(
      kShapes, "shapes.sdf", description::SdfWorldOptions{}, shapes_dir_.string());
  ASSERT_EQ(scene.objects.size(), 3u);
  const assets::SceneMeshes meshes = assets::LoadSceneMeshes(scene.objects);
  sim::TerrainOptions t;
  t.extent_m = {-2, -6, 12, 6};
  t.cell_size_m = 0.5;
  const sim::World world(sim::WorldOptions{}, sim::Terrain(t, 1), meshes.primitives,
                         meshes.obstacles);
  const geometry::PinholeCamera K = Camera();
  const Eigen::Isometry3d T = render::test::Looking({0, 0, 1.0}, {1, 0, 0});
  render::Renderer renderer(world, render::test::AmbientOnly(), {}, 7, K.width_px, K.height_px, 0.1,
                            60.0);
  GrayImage gray;
  render::DepthImage depth;
  renderer.Render(K, T, 0.0, &gray, &depth);
  int covered[3] = {0, 0, 0}, wrong = 0;
  double worst = 0.0, grey_sum[3] = {0, 0, 0};
  int grey_n[3] = {0, 0, 0};
  // Rows above the horizon (the camera is level): the ground is never drawn there.
  for (int v = 0; v < static_cast<int>(K.cy) - 1; ++v) {
    for (int u = 0; u < K.width_px; ++u) {
      const bool drawn = depth.at(u, v) < 30.0f;
      const int shape = TrueShapeAt(K, T, u, v);
      if (shape >= 0) ++covered[shape];
      if (drawn != (shape >= 0)) {
        ++wrong;
        worst = std::max(worst, DistanceToTrueOutline(K, T, u, v));
      } else if (shape >= 0 && FarFromTrueOutline(K, T, u, v, shape)) {
        grey_sum[shape] += gray.pixels[static_cast<std::size_t>(v) * K.width_px + u];
        ++grey_n[shape];
      }
    }
  }
  std::printf(
      "pixels covered: box %d, cylinder %d, sphere %d; %d drawn otherwise, the farthest "
      "%.3f px from the true outline\n",
      covered[0], covered[1], covered[2], wrong, worst);
  for (int k = 0; k < 3; ++k) EXPECT_GT(covered[k], 1000) << k;
  EXPECT_LE(worst, 0.5);
  // Each colour as its grey albedo: Rec. 709 luma of the linear diffuse, drawn under
  // ambient light 1 as 255 · albedo (the plain texture's grain is under a grey level),
  // over the pixels 3 px or more inside each shape's outline.
  const double albedo[3] = {0.2126 * 0.8 + 0.7152 * 0.1 + 0.0722 * 0.1,
                            0.2126 * 0.2 + 0.7152 * 0.6 + 0.0722 * 0.3, 0.9};
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(scene.objects[k].albedo);
    EXPECT_NEAR(*scene.objects[k].albedo, albedo[k], 1e-6);
    ASSERT_GT(grey_n[k], 100);
    std::printf("shape %d: mean grey %.2f, 255 x albedo %.2f\n", k, grey_sum[k] / grey_n[k],
                255 * albedo[k]);
    EXPECT_NEAR(grey_sum[k] / grey_n[k], 255 * albedo[k], 2.0) << k;
  }
}

}  // namespace
}  // namespace trackbed
