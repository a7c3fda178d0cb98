// The OSMesa renderer: geometry agrees with the pinhole model to sub-pixel,
// depth is metric, stereo disparity is f·b/Z, images are reproducible.
#include "trackbed/render/renderer.h"
#include "trackbed/render/camera_exposure.h"
#include "trackbed/render/object_detail.h"
#include "trackbed/render/scene_lighting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "render_test_scene.h"
#include "trackbed/robot/stereo_rig.h"

namespace trackbed::render {
namespace {

sim::World MakeWorld(std::vector<sim::StaticObject> objects) {
  return test::FlatWorld(std::move(objects));
}

SceneAppearance Flat() { return test::AmbientOnly(); }

// A square plate of side `side` facing the cameras, its front face centred at `c`.
sim::StaticObject Marker(const Eigen::Vector3d& c, double side, const std::string& appearance) {
  return test::Plate(c, side, side, appearance);
}

// The rig on a body at (0, 0, 0.7) looking along +x, level.
robot::StereoRig LevelRig() {
  robot::StereoRigOptions o;
  o.pitch_down_deg = 0.0;
  o.mount_m = {0.0, 0.0, 0.3};
  return robot::StereoRig(o);
}

Eigen::Isometry3d Body() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0, 0, 0.7);
  return T;
}

TEST(RendererTest, MarkerAppearsWherePinholeModelPredictsInBothCameras) {
  const Eigen::Vector3d marker(5.0, 0.4, 1.35);
  sim::World world = MakeWorld({Marker(marker, 0.2, "ceiling")});
  const robot::StereoRig rig = LevelRig();
  Renderer renderer(world, Flat(), {}, 3, 640, 480, 0.05, 120.0);
  for (const Eigen::Isometry3d& T_body_cam : {rig.T_body_left(), rig.T_body_right()}) {
    const Eigen::Isometry3d T_world_cam = Body() * T_body_cam;
    GrayImage img;
    renderer.Render(rig.intrinsics(), T_world_cam, 0.0, &img, nullptr);
    const Eigen::Vector2d predicted = rig.intrinsics().Project(T_world_cam.inverse() * marker);
    double su = 0, sv = 0, n = 0;
    for (int v = 0; v < 236; ++v) {  // above the horizon: the floor is below it
      for (int u = 0; u < img.width; ++u) {
        if (img.at(u, v) > 100) {
          su += u;
          sv += v;
          n += 1;
        }
      }
    }
    ASSERT_GT(n, 100);  // the 0.2 m square is about 15 px across at 5 m
    std::printf("marker centroid - pinhole prediction: (%+.3f, %+.3f) px\n", su / n - predicted.x(),
                sv / n - predicted.y());
    EXPECT_NEAR(su / n, predicted.x(), 0.5);
    EXPECT_NEAR(sv / n, predicted.y(), 0.5);
  }
}

TEST(RendererTest, DepthImageIsMetricDepthAlongTheOpticalAxis) {
  // A large wall whose front face is 5 m ahead of the left camera.
  const robot::StereoRig rig = LevelRig();
  const Eigen::Isometry3d T_world_cam = Body() * rig.T_body_left();
  const double wall_x = T_world_cam.translation().x() + 5.0;
  sim::StaticObject wall = Marker({wall_x, 0.0, 1.5}, 4.0, "brick");
  sim::World world = MakeWorld({wall});
  Renderer renderer(world, Flat(), {}, 3, 640, 480, 0.05, 120.0);
  DepthImage depth;
  renderer.Render(rig.intrinsics(), T_world_cam, 0.0, nullptr, &depth);
  int checked = 0;
  double worst = 0.0;
  for (int v = 150; v < 310; ++v) {  // rows whose rays meet the wall, not the floor
    for (int u = 200; u < 440; ++u) {
      worst = std::max(worst, std::abs(depth.at(u, v) - 5.0));
      ++checked;
    }
  }
  EXPECT_EQ(checked, 160 * 240);
  std::printf("depth of a plane 5 m ahead: worst error %.5f m over %d px\n", worst, checked);
  EXPECT_LT(worst, 0.01);
  EXPECT_TRUE(std::isinf(depth.at(320, 5)) || depth.at(320, 5) > 5.0);  // sky or far
}

TEST(RendererTest, StereoDisparityOfATexturedPlaneIsFocalTimesBaselineOverDepth) {
  const robot::StereoRig rig = LevelRig();
  const Eigen::Isometry3d T_world_left = Body() * rig.T_body_left();
  const double z = 4.0;
  sim::World world =
      MakeWorld({Marker({T_world_left.translation().x() + z, 0.0, 1.0}, 4.0, "brick")});
  SceneAppearance lit;
  lit.sky_gray = 0.0;
  Renderer renderer(world, lit, {}, 3, 640, 480, 0.05, 120.0);
  GrayImage left, right;
  renderer.Render(rig.intrinsics(), T_world_left, 0.0, &left, nullptr);
  renderer.Render(rig.intrinsics(), Body() * rig.T_body_right(), 0.0, &right, nullptr);
  const cv::Rect roi(224, 176, 128, 128);
  cv::Mat l, r;
  cv::Mat(480, 640, CV_8UC1, left.pixels.data())(roi).convertTo(l, CV_64F);
  cv::Mat(480, 640, CV_8UC1, right.pixels.data())(roi).convertTo(r, CV_64F);
  const cv::Point2d shift = cv::phaseCorrelate(r, l);  // left = right shifted by +d
  const double expected = rig.intrinsics().fx * rig.options().baseline_m / z;
  std::printf("disparity at 4 m: measured %.3f px, f b / Z = %.3f px\n", shift.x, expected);
  EXPECT_NEAR(shift.x, expected, 0.5) << "expected disparity " << expected;
  EXPECT_NEAR(shift.y, 0.0, 0.5);
}

TEST(RendererTest, SameSceneAndSeedGiveIdenticalBytesWithoutADisplay) {
  unsetenv("DISPLAY");
  sim::World world = MakeWorld({Marker({5.0, 0.0, 1.0}, 1.0, "brick")});
  const robot::StereoRig rig = LevelRig();
  GrayImage a, b, c;
  {
    Renderer r1(world, SceneAppearance{}, {}, 11, 640, 480, 0.05, 120.0);
    r1.Render(rig.intrinsics(), Body() * rig.T_body_left(), 0.0, &a, nullptr);
    r1.Render(rig.intrinsics(), Body() * rig.T_body_left(), 0.0, &c, nullptr);
  }
  Renderer r2(world, SceneAppearance{}, {}, 11, 640, 480, 0.05, 120.0);
  r2.Render(rig.intrinsics(), Body() * rig.T_body_left(), 0.0, &b, nullptr);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_EQ(a.pixels, c.pixels);
  EXPECT_NE(r2.gl_description().find("llvmpipe"), std::string::npos) << r2.gl_description();
}

// Rough grass, as outdoors: the far terrain at lower detail leaves the near
// ground's pixels as they are, changes far ones, and gives both cameras of a
// pair the same ground.
TEST(RendererTest, FarTerrainDetailLeavesTheNearGroundUnchanged) {
  sim::TerrainOptions t;
  t.extent_m = {-2, -8, 16, 8};
  t.cell_size_m = 0.1;
  t.roughness.undulation_amplitude_m = 0.25;
  t.roughness.undulation_wavelength_m = 7.0;
  t.roughness.bump_amplitude_m = 0.03;
  t.roughness.bump_wavelength_m = 0.7;
  t.default_material = "grass";
  const sim::World world(sim::WorldOptions{}, sim::Terrain(t, 2), {});
  robot::StereoRigOptions o;
  o.mount_m = {0.0, 0.0, 0.5};
  const robot::StereoRig rig(o);
  Eigen::Isometry3d body = Eigen::Isometry3d::Identity();
  body.translation() = Eigen::Vector3d(0, 0, world.terrain().Height(0, 0));
  const Eigen::Isometry3d left = body * rig.T_body_left(), right = body * rig.T_body_right();
  const Eigen::Vector2d center = 0.5 * (left.translation() + right.translation()).head<2>();
  SceneAppearance full, lod;
  lod.terrain_full_detail_m = 2.0;
  Renderer r_full(world, full, {}, 3, 640, 480, 0.05, 120.0);
  Renderer r_lod(world, lod, {}, 3, 640, 480, 0.05, 120.0);
  GrayImage a, b;
  DepthImage depth;
  r_full.Render(rig.intrinsics(), left, 0.0, &a, &depth, &center);
  r_lod.Render(rig.intrinsics(), left, 0.0, &b, nullptr, &center);
  int near = 0, near_same = 0, far = 0, far_changed = 0;
  for (int v = 0; v < a.height; ++v) {
    for (int u = 0; u < a.width; ++u) {
      const float z = depth.at(u, v);
      const bool same = a.at(u, v) == b.at(u, v);
      if (z < 1.0f) {  // well inside 2 m of the rig, at any angle in the view
        ++near;
        near_same += same;
      } else if (z > 6.0f && z < 100.0f) {
        ++far;
        far_changed += !same;
      }
    }
  }
  EXPECT_GT(near, 20000);
  EXPECT_EQ(near_same, near);
  EXPECT_GT(far, 5000);
  EXPECT_GT(far_changed, far / 20);
  std::printf("near ground: %d of %d pixels identical; far: %d of %d changed\n", near_same, near,
              far_changed, far);
  // The right camera with the same centre draws the same meshes as the left
  // one did: rendering it after the left or on its own gives the same bytes.
  GrayImage r1, r2;
  r_lod.Render(rig.intrinsics(), right, 0.0, &r1, nullptr, &center);
  Renderer r_alone(world, lod, {}, 3, 640, 480, 0.05, 120.0);
  r_alone.Render(rig.intrinsics(), right, 0.0, &r2, nullptr, &center);
  EXPECT_EQ(r1.pixels, r2.pixels);
}

// Trees with far versions (object_far_error_px): those near the detail centre keep
// every byte; farther ones are drawn with fewer facets, which move no pixel's depth:
// their departure (under half a pixel) falls in the band the outline pass draws from
// the true shape (the bound itself is checked on the outlines' geometry in
// object_detail_test).
TEST(RendererTest, FarTreesMoveTheirSilhouettesOnlyAtTheirEdges) {
  struct Placed {
    double x, y, height;
  };
  const Placed placed[] = {{14, -3, 6}, {60, 4, 3}, {95, -6, 5}, {112, 8, 3}};
  std::vector<sim::StaticObject> trees;
  for (const Placed& p : placed) {
    sim::StaticObject tree;
    tree.shape = sim::StaticObject::Shape::kCylinder;
    tree.kind = "tree";
    tree.appearance = "bark";
    tree.center_m = {p.x, p.y};
    tree.radius_m = 0.3;
    tree.height_m = p.height;
    trees.push_back(tree);
  }
  const sim::World world = test::FlatWorld(trees, {-2, -20, 130, 20});
  const robot::StereoRig rig = LevelRig();
  const geometry::PinholeCamera K = rig.intrinsics();
  SceneAppearance full = Flat(), far = Flat();
  full.tree_crowns = far.tree_crowns = true;
  far.object_far_error_px = 0.5;
  // The level each tree is drawn at, by the rule the renderer applies.
  std::vector<int> levels;
  for (const sim::StaticObject& o : world.objects()) {
    const double crown = TreeCrownRadius(o), reach = std::max(crown, o.radius_m);
    int level = 0;
    for (std::size_t l = 1; l < kTreeLevels.size(); ++l) {
      const double departure = TreeLevelDeparture(crown, o.radius_m, kTreeLevels[l]);
      if (o.center_m.norm() - reach >= FarVersionDistance(departure, K.fx, 0.5)) level = l;
    }
    levels.push_back(level);
  }
  EXPECT_EQ(levels, (std::vector<int>{0, 1, 1, 2}));
  const Eigen::Vector2d center = Body().translation().head<2>();
  Renderer r_full(world, full, {}, 3, 640, 480, 0.05, 120.0);
  Renderer r_far(world, far, {}, 3, 640, 480, 0.05, 120.0);
  GrayImage a, b;
  DepthImage za, zb;
  r_full.Render(K, Body() * rig.T_body_left(), 0.0, &a, &za, &center);
  r_far.Render(K, Body() * rig.T_body_left(), 0.0, &b, &zb, &center);
  const auto covered_differently = [](float z1, float z2) { return std::abs(z1 - z2) > 0.5f; };
  int near = 0, near_same = 0, moved = 0, moved_inside = 0;
  for (int v = 1; v + 1 < a.height; ++v) {
    for (int u = 1; u + 1 < a.width; ++u) {
      if (za.at(u, v) < 20.0f) {  // the near tree and the ground before it
        ++near;
        near_same += a.at(u, v) == b.at(u, v) && za.at(u, v) == zb.at(u, v);
      }
      if (!covered_differently(za.at(u, v), zb.at(u, v))) continue;
      ++moved;
      bool at_edge = false;  // the full version's silhouette passes beside it
      for (int dv = -1; dv <= 1; ++dv) {
        for (int du = -1; du <= 1; ++du) {
          at_edge = at_edge || covered_differently(za.at(u, v), za.at(u + du, v + dv));
        }
      }
      moved_inside += !at_edge;
    }
  }
  std::printf("near: %d of %d pixels identical; %d pixels covered differently, %d off an edge\n",
              near_same, near, moved, moved_inside);
  EXPECT_GT(near, 20000);
  EXPECT_EQ(near_same, near);
  // The far versions depart from the full ones by under half a pixel, the band whose
  // pixels a curved object's core leaves to the outline pass, which draws the true
  // shape's outline (docs/rendering.md): no pixel's depth moves.
  EXPECT_EQ(moved, 0);
  EXPECT_EQ(moved_inside, 0);
}

// A texture first used by an object is made before the object's display list is
// compiled: made while compiling, its upload went into the list of the first tree, and
// every crown drawn before that tree first came into view had no texture.
TEST(RendererTest, ATreeLooksTheSameWhetherOrNotTheFirstTreeWasSeenBefore) {
  std::vector<sim::StaticObject> trees;
  for (const Eigen::Vector2d& at : {Eigen::Vector2d(-8, 0), Eigen::Vector2d(8, 0)}) {
    sim::StaticObject tree;
    tree.shape = sim::StaticObject::Shape::kCylinder;
    tree.kind = "tree";
    tree.appearance = "bark";
    tree.center_m = at;
    tree.radius_m = 0.3;
    tree.height_m = 3.0;
    trees.push_back(tree);
  }
  const sim::World world = test::FlatWorld(trees, {-12, -6, 12, 6});
  SceneAppearance a;
  a.tree_crowns = true;
  const robot::StereoRig rig = LevelRig();
  Eigen::Isometry3d towards_first = Body(), towards_second = Body();  // looking along -x, +x
  towards_first.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  GrayImage alone, after_first, first;
  Renderer r1(world, a, {}, 3, 640, 480, 0.05, 120.0);
  r1.Render(rig.intrinsics(), towards_second * rig.T_body_left(), 0.0, &alone, nullptr);
  Renderer r2(world, a, {}, 3, 640, 480, 0.05, 120.0);
  r2.Render(rig.intrinsics(), towards_first * rig.T_body_left(), 0.0, &first, nullptr);
  r2.Render(rig.intrinsics(), towards_second * rig.T_body_left(), 0.0, &after_first, nullptr);
  EXPECT_EQ(alone.pixels, after_first.pixels);
  EXPECT_NE(alone.pixels, first.pixels);  // the views differ
}

// The body's pose over an exposure (BodyMotion::PoseAfter, which the camera's warps in
// time use).
TEST(RendererTest, BodyMotionTurnsAboutTheWorldFramesAngularVelocity) {
  // The body's pose over the exposure: turned by ω·dt about ω's axis in the world
  // frame (Bullet's angular velocity is the world frame's), moved by v·dt. A pitched
  // and rolled body and an ω off its axes tell a world-frame rotation from a
  // body-frame one: here they differ by about 3e-3 rad.
  BodyMotion tilted;
  tilted.T_world_body = Body();
  tilted.T_world_body.linear() = (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()) *
                                  Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitY()))
                                     .toRotationMatrix();
  tilted.omega_world = {0.3, -0.5, 0.8};
  tilted.v_world = {0.4, 0.1, 0.0};
  const double dt = 0.005;
  const Eigen::Isometry3d later = tilted.PoseAfter(dt);
  const Eigen::AngleAxisd turn(tilted.omega_world.norm() * dt, tilted.omega_world.normalized());
  const Eigen::Matrix3d in_world = turn * tilted.T_world_body.linear();
  const Eigen::Matrix3d in_body = tilted.T_world_body.linear() * turn;
  ASSERT_GT((in_world - in_body).norm(), 1e-3);
  EXPECT_LT((later.linear() - in_world).norm(), 1e-12);
  EXPECT_TRUE(later.translation().isApprox(Body().translation() + dt * tilted.v_world, 1e-12));
}

// A level camera at `eye` looking horizontally towards `target` (OpenCV axes).
Eigen::Isometry3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  return test::Looking(eye, target - eye);
}

// Back faces are culled, so a surface wound the wrong way would vanish and
// show what is behind it: every shape must be seen, from every side, at the
// distance of its near surface.
TEST(RendererTest, EveryShapeIsSeenFromEverySideWithBackFacesCulled) {
  sim::StaticObject box;
  box.center_m = {0, 0};
  box.base_z_m = 0;
  box.size_m = {1.2, 0.6, 1.0};
  box.yaw_rad = 0.5;
  sim::StaticObject post;
  post.shape = sim::StaticObject::Shape::kCylinder;
  post.kind = "post";
  post.center_m = {6, 0};
  post.base_z_m = 0;
  post.radius_m = 0.3;
  post.height_m = 2.0;
  sim::StaticObject tree = post;
  tree.kind = "tree";
  tree.center_m = {0, 8};
  tree.height_m = 1.2;  // crown of radius 0.6 centred on the trunk's top
  sim::OccluderSpec person;
  person.waypoints = {{6, 8}};
  sim::TerrainOptions t;
  t.extent_m = {-8, -8, 14, 16};
  t.cell_size_m = 0.5;
  const sim::World world(sim::WorldOptions{}, sim::Terrain(t, 1), {box, post, tree});
  SceneAppearance a = Flat();
  a.tree_crowns = true;
  Renderer renderer(world, a, {person}, 3, 640, 480, 0.05, 120.0);
  const robot::StereoRig rig = LevelRig();
  const double far_away = 4.0;
  // The distance from `eye` to the box along the ray to `c` (slabs in the box frame).
  const auto box_distance = [&](const Eigen::Vector3d& eye, const Eigen::Vector3d& c) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(box.yaw_rad, Eigen::Vector3d::UnitZ()).matrix();
    const Eigen::Vector3d o = R.transpose() * (eye - c);
    const Eigen::Vector3d d = R.transpose() * (c - eye).normalized();
    double enter = 0.0;
    for (int i = 0; i < 3; ++i) {
      if (std::abs(d[i]) < 1e-12) continue;
      const double t0 = (-box.size_m[i] / 2 - o[i]) / d[i], t1 = (box.size_m[i] / 2 - o[i]) / d[i];
      enter = std::max(enter, std::min(t0, t1));
    }
    return enter;
  };
  struct Case {
    std::string what;
    Eigen::Vector3d centre;
    std::function<double(const Eigen::Vector3d&)> near_surface;  // distance from an eye
    double tolerance_m;  // the polygons' inset from the true shape, and some
  };
  const std::vector<Case> cases = {
      {"box",
       {0, 0, 0.5},
       [&](const Eigen::Vector3d& e) {
         return box_distance(e, {0, 0, 0.5});
       },
       0.002},
      {"post", {6, 0, 1.0}, [&](const Eigen::Vector3d&) { return far_away - 0.3; }, 0.005},
      {"crown", {0, 8, 1.2}, [&](const Eigen::Vector3d&) { return far_away - 0.6; }, 0.02},
      {"person", {6, 8, 0.8}, [&](const Eigen::Vector3d&) { return far_away - 0.25; }, 0.005},
  };
  for (const Case& c : cases) {
    for (int k = 0; k < 8; ++k) {
      const double az = k * M_PI / 4 + 0.1;
      const Eigen::Vector3d eye =
          c.centre + far_away * Eigen::Vector3d(std::cos(az), std::sin(az), 0);
      DepthImage depth;
      renderer.Render(rig.intrinsics(), LookAt(eye, c.centre), 0.0, nullptr, &depth);
      // The ray through the principal point, (319.5, 239.5): the mean of the four pixels about it.
      const double seen = 0.25 * (depth.at(319, 239) + depth.at(320, 239) + depth.at(319, 240) +
                                  depth.at(320, 240));
      EXPECT_NEAR(seen, c.near_surface(eye), c.tolerance_m) << c.what << " from azimuth " << az;
    }
  }
  // The ceiling, from below: 30 degrees up, 1.8 m under it.
  SceneAppearance indoor = a;
  indoor.ceiling_height_m = 2.5;
  Renderer under(world, indoor, {}, 3, 640, 480, 0.05, 120.0);
  Eigen::Isometry3d up = LookAt({-4, -6, 0.7}, {-3, -6, 0.7});
  up.linear() = up.linear() * Eigen::AngleAxisd(30 * M_PI / 180, Eigen::Vector3d::UnitX()).matrix();
  DepthImage depth;
  under.Render(rig.intrinsics(), up, 0.0, nullptr, &depth);
  // Depth along the optical axis of the ray that meets the ceiling 1.8 / sin 30° = 3.6 m away.
  EXPECT_NEAR(depth.at(319, 239), 3.6, 0.05);
}

// Per-vertex lighting uses the outward normals: a post lit from the camera's
// left is brighter on its left half (a surface wound the wrong way would be lit
// from inside, as the posts and trunks were before back faces were culled).
TEST(RendererTest, APostIsBrighterOnItsSunlitSide) {
  sim::StaticObject post;
  post.shape = sim::StaticObject::Shape::kCylinder;
  post.kind = "post";
  post.appearance = "plain_test";  // no texture of that name: plain grey
  post.center_m = {4, 0};
  post.base_z_m = 0;
  post.radius_m = 0.3;
  post.height_m = 3.0;
  SceneAppearance a;
  a.ambient = 0.2;
  a.diffuse = 0.7;
  a.sun_azimuth_deg = 90;  // from +y: the left of a camera looking along +x
  a.sun_elevation_deg = 10;
  a.sky_gray = 0.0;
  const sim::World world = MakeWorld({post});
  Renderer renderer(world, a, {}, 3, 640, 480, 0.05, 120.0);
  const robot::StereoRig rig = LevelRig();
  GrayImage img;
  renderer.Render(rig.intrinsics(), LookAt({0, 0, 1.5}, {4, 0, 1.5}), 0.0, &img, nullptr);
  // The post spans fx * 0.3 / 3.7 = 31 px either side of the centre column.
  double left = 0, right = 0;
  for (int v = 100; v < 140; ++v) {
    for (int du = 10; du < 25; ++du) {
      left += img.at(319 - du, v);
      right += img.at(320 + du, v);
    }
  }
  left /= 40 * 15;
  right /= 40 * 15;
  std::printf("post lit from the left: left half %.1f, right half %.1f grey levels\n", left, right);
  EXPECT_GT(left, right + 20);
}

TEST(RendererTest, WalkingOccluderMovesThroughTheView) {
  sim::World world = MakeWorld({});
  sim::OccluderSpec person;
  person.waypoints = {{4.0, -3.0}, {4.0, 3.0}};
  person.speed_mps = 1.0;
  const robot::StereoRig rig = LevelRig();
  Renderer renderer(world, Flat(), {person}, 5, 640, 480, 0.05, 120.0);
  // Where is the person in the image at t = 0 (off to the right), 3 s (centre), 6 s (left)?
  std::vector<double> columns;
  for (double t : {1.0, 3.0, 5.0}) {
    GrayImage img;
    renderer.Render(rig.intrinsics(), Body() * rig.T_body_left(), t, &img, nullptr);
    double su = 0, n = 0;
    for (int v = 0; v < 200; ++v) {  // above the horizon: only the person is lit there
      for (int u = 0; u < img.width; ++u) {
        if (img.at(u, v) > 20) {
          su += u;
          n += 1;
        }
      }
    }
    ASSERT_GT(n, 50) << "t = " << t;
    columns.push_back(su / n);
  }
  EXPECT_GT(columns[0], columns[1] + 50);  // walking from the right (−y) to the left (+y)
  EXPECT_GT(columns[1], columns[2] + 50);
  EXPECT_NEAR(columns[1], 319.5, 20);
}

}  // namespace
}  // namespace trackbed::render
