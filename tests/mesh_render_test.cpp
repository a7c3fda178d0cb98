// Mesh objects as the renderer draws them: a texel of the file's image where the
// pinhole projection puts its texture coordinates, the outline where the projected
// vertices put it (glTF node transforms included), a ground mesh as the terrain it
// became, mesh shadows as a box's, and the same bytes on a second renderer.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "mesh_files.h"
#include "render_test_scene.h"
#include "trackbed/assets/mesh_reader.h"
#include "trackbed/assets/scene_meshes.h"
#include "trackbed/render/renderer.h"
#include "trackbed/render/scene_lighting.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "trackbed/sim/world.h"

namespace trackbed {
namespace {

using render::test::Looking;

using Vec2 = Eigen::Vector2d;

// A camera of 320 × 240 px, f = 300 px, looking along +y_dir from `eye` (level).
geometry::PinholeCamera Camera() { return render::test::Pinhole(320, 240, 300.0, 159.5, 119.5); }

// A mesh object read from `file`, its origin at (x, y, z).
sim::MeshObject MeshAt(const std::string& file, double x, double y, double z, double roll = 0,
                       double pitch = 0, double yaw = 0) {
  sim::MeshObject m;
  m.entry.shape = sim::StaticObject::Shape::kMesh;
  m.entry.kind = "mesh";
  m.entry.mesh.file = file;
  m.entry.center_m = Vec2(x, y);
  m.entry.base_z_m = z;
  m.entry.roll_rad = roll;
  m.entry.pitch_rad = pitch;
  m.entry.yaw_rad = yaw;
  m.visual = std::make_shared<const sim::TriangleMesh>(assets::ReadMesh(file).mesh);
  return m;
}

sim::World FlatWorldWith(std::vector<sim::MeshObject> meshes) {
  sim::TerrainOptions t;
  t.extent_m = {-6, -6, 12, 6};
  t.cell_size_m = 0.5;
  return sim::World(sim::WorldOptions{}, sim::Terrain(t, 1), {}, std::move(meshes));
}

struct Frame {
  GrayImage gray;
  render::DepthImage depth;
};

Frame RenderOnce(const sim::World& world, const Eigen::Isometry3d& T,
                 const render::SceneAppearance& a = render::test::AmbientOnly()) {
  const geometry::PinholeCamera K = Camera();
  render::Renderer r(world, a, {}, 7, K.width_px, K.height_px, 0.1, 60.0);
  Frame f;
  r.Render(K, T, 0.0, &f.gray, &f.depth);
  return f;
}

// A quad facing −x at x = 0, y from 0.5 (texture u = 0) to −0.5 (u = 1), z from 0 (v = 0)
// to 1 (v = 1), its material a 64 × 64 black image with a white 4 × 4 block at columns
// 44–47 and rows 12–15 (top first): the block's centre at u = 46/64, v = 1 − 14/64.
std::string TexturedQuad() {
  cv::Mat image(64, 64, CV_8UC3, cv::Scalar(0, 0, 0));
  image(cv::Rect(44, 12, 4, 4)).setTo(cv::Scalar(255, 255, 255));
  cv::imwrite(test_mesh::TempPath("block.png"), image);
  test_mesh::Write("quad.mtl", "newmtl m\nKd 1 1 1\nmap_Kd block.png\n");
  return test_mesh::Write("quad.obj",
                          "mtllib quad.mtl\nusemtl m\n"
                          "v 0 0.5 0\nv 0 -0.5 0\nv 0 -0.5 1\nv 0 0.5 1\n"
                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n");
}

TEST(MeshRenderTest, ATexelLandsWhereTheProjectionPutsItsTextureCoordinates) {
  const sim::World world = FlatWorldWith({MeshAt(TexturedQuad(), 3, 0, 0.5)});
  const Eigen::Isometry3d T = Looking({0, 0, 1}, {1, 0, 0});
  const Frame f = RenderOnce(world, T);
  const double u = 46.0 / 64, v = 1.0 - 14.0 / 64;
  const Eigen::Vector3d texel_world(3, 0.5 - u, 0.5 + v);
  const Vec2 predicted = Camera().Project(T.inverse() * texel_world);
  // The block's centroid in a window about the prediction (the quad is black about it).
  double sum = 0, su = 0, sv = 0, peak = 0;
  for (int r = static_cast<int>(predicted.y()) - 10; r <= static_cast<int>(predicted.y()) + 10;
       ++r) {
    for (int c = static_cast<int>(predicted.x()) - 10; c <= static_cast<int>(predicted.x()) + 10;
         ++c) {
      const double g = f.gray.pixels[static_cast<std::size_t>(r) * 320 + c];
      sum += g;
      su += g * c;
      sv += g * r;
      peak = std::max(peak, g);
    }
  }
  ASSERT_GT(peak, 200.0);  // white, ambient light 1
  const Vec2 centroid(su / sum, sv / sum);
  EXPECT_LT((centroid - predicted).norm(), 0.5)
      << "centroid " << centroid.transpose() << ", predicted " << predicted.transpose();
  // A second renderer draws the same bytes.
  const Frame again = RenderOnce(world, T);
  EXPECT_EQ(again.gray.pixels, f.gray.pixels);
  EXPECT_EQ(again.depth.depth_m, f.depth.depth_m);
}

// The convex hull of points, counter-clockwise (Andrew's monotone chain).
std::vector<Vec2> Hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

// Signed distance of `q` from a convex counter-clockwise polygon's outline [px]:
// negative inside.
double SignedDistance(const std::vector<Vec2>& hull, const Vec2& q) {
  double inside = -1e9, nearest = 1e9;
  bool in = true;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2 a = hull[i], b = hull[(i + 1) % hull.size()];
    const Vec2 e = b - a;
    const double side = (e.x() * (q - a).y() - e.y() * (q - a).x()) / e.norm();  // > 0 left
    if (side < 0) in = false;
    inside = std::max(inside, -side);
    const double t = std::clamp((q - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    nearest = std::min(nearest, (a + t * e - q).norm());
  }
  return in ? inside : nearest;
}

// The pixels the mesh covers (its depth in front of the scene without it) against the
// convex outline of `vertices` projected: every pixel whose centre lies more than
// `tolerance_px` inside is covered, every one more than that outside is not.
void ExpectOutline(const sim::World& with, const sim::World& without, const Eigen::Isometry3d& T,
                   const std::vector<Eigen::Vector3d>& vertices, double tolerance_px) {
  const Frame a = RenderOnce(with, T), b = RenderOnce(without, T);
  std::vector<Vec2> projected;
  for (const Eigen::Vector3d& p : vertices) projected.push_back(Camera().Project(T.inverse() * p));
  const std::vector<Vec2> hull = Hull(projected);
  int covered = 0, wrong = 0;
  double worst = 0.0;
  for (int r = 0; r < 240; ++r) {
    for (int c = 0; c < 320; ++c) {
      const std::size_t k = static_cast<std::size_t>(r) * 320 + c;
      const bool drawn = a.depth.depth_m[k] < b.depth.depth_m[k] - 1e-3;
      const double d = SignedDistance(hull, Vec2(c, r));
      covered += drawn;
      if (drawn != (d < 0)) {
        ++wrong;
        worst = std::max(worst, std::abs(d));
      }
    }
  }
  EXPECT_GT(covered, 500);
  EXPECT_LE(worst, tolerance_px) << wrong << " pixels on the wrong side";
}

TEST(MeshRenderTest, ATurnedBoxsOutlineIsWhereItsVerticesProject) {
  const std::string file = test_mesh::ObjBox("turned.obj", -0.5, -0.5, 0, 0.5, 0.5, 1);
  const sim::MeshObject box = MeshAt(file, 4, 0.3, 0.6, 0.3, 0.2, 0.5);
  std::vector<Eigen::Vector3d> corners;
  for (const Eigen::Vector3f& v : box.visual->vertices)
    corners.push_back(box.Pose() * v.cast<double>());
  ExpectOutline(FlatWorldWith({box}), FlatWorldWith({}), Looking({0, 0, 1}, {1, 0, 0}), corners,
                0.5);
}

TEST(MeshRenderTest, AGltfNodesTransformIsDrawnWhereItPutsTheMesh) {
  // The triangle under the node translated by (10, 20, 30) and scaled by 2, y up: in the
  // object's frame (10, −30, 20), (12, −30, 20), (10, −30, 22); the object placed so
  // that it stands 4 m ahead of the camera, the second (untransformed) copy underground.
  const sim::MeshObject m = MeshAt(test_mesh::GltfTriangle("nodes.gltf"), -10, 34, -19);
  const std::vector<Eigen::Vector3d> drawn = {{0, 4, 1}, {2, 4, 1}, {0, 4, 3}};
  ExpectOutline(FlatWorldWith({m}), FlatWorldWith({}), Looking({1, 0, 1.5}, {0, 1, 0}), drawn, 0.5);
}

TEST(MeshRenderTest, AGroundMeshIsDrawnAsTheTerrainItBecame) {
  // A ramp: flat for x < 2, rising 10 % beyond; as ground, it is the terrain's heights.
  sim::StaticObject o;
  o.shape = sim::StaticObject::Shape::kMesh;
  o.kind = "mesh";
  o.mesh.file = test_mesh::Write("ground_ramp.obj",
                                 "v -6 -6 0\nv 2 -6 0\nv 2 6 0\nv -6 6 0\nv 14 -6 1.2\nv 14 6 1.2\n"
                                 "f 1 2 3 4\nf 2 5 6 3\n");
  o.mesh.ground = true;
  const assets::SceneMeshes meshes = assets::LoadSceneMeshes({o});
  sim::TerrainOptions t;
  t.extent_m = {-5, -5, 13, 5};
  t.cell_size_m = 0.25;
  const sim::World world(sim::WorldOptions{},
                         sim::Terrain(t, 1, assets::SampleMeshGround(meshes.grounds, t)), {});
  EXPECT_TRUE(world.meshes().empty());  // not an obstacle: drawn as the terrain
  const Eigen::Isometry3d T = Looking({-1, 0, 1.5}, {1, 0, 0});
  const Frame f = RenderOnce(world, T);
  const auto ramp = [](double x) { return x < 2.0 ? 0.0 : 0.1 * (x - 2.0); };
  const geometry::PinholeCamera K = Camera();
  int checked = 0;
  double worst = 0.0;
  for (int r = 130; r < 240; r += 4) {
    for (int c = 0; c < 320; c += 8) {
      // The ray's depth where it meets the ramp, by bisection on its height above it.
      const Eigen::Vector3d ray =
          T.linear() * Eigen::Vector3d((c - K.cx) / K.fx, (r - K.cy) / K.fy, 1);
      double lo = 0.1, hi = 60.0;
      for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        const Eigen::Vector3d p = T.translation() + mid * ray;
        (p.z() > ramp(p.x()) ? lo : hi) = mid;
      }
      const Eigen::Vector3d p = T.translation() + lo * ray;
      if (std::abs(p.x() - 2.0) < 0.3 || p.x() > 12.5 || std::abs(p.y()) > 4.5) continue;
      const double depth = f.depth.depth_m[static_cast<std::size_t>(r) * 320 + c];
      worst = std::max(worst, std::abs(depth - lo) / lo);
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
  EXPECT_LT(worst, 2e-3);  // relative: the depth buffer's 24 bits at up to 14 m
}

TEST(MeshRenderTest, AMeshBoxCastsTheShadowOfTheBoxItIs) {
  const std::string file = test_mesh::ObjBox("shadow_box.obj", -0.5, -0.4, 0, 0.5, 0.4, 1.2);
  sim::StaticObject box;
  box.center_m = Vec2(2, 1);
  box.base_z_m = 0;
  box.size_m = {1.0, 0.8, 1.2};
  render::SceneLighting lighting;
  lighting.texel_m = 0.05;
  const Eigen::Vector3d sun =
      render::SunDirection(130.0, 40.0);  // no edge on the texels' diagonals
  sim::TerrainOptions t;
  t.extent_m = {-2, -2, 6, 4};
  const sim::World with_box(sim::WorldOptions{}, sim::Terrain(t, 1), {box});
  const sim::World with_mesh(sim::WorldOptions{}, sim::Terrain(t, 1), {}, {MeshAt(file, 2, 1, 0)});
  const render::LightMap a = render::BakeLightMap(with_box, lighting, sun, false);
  const render::LightMap b = render::BakeLightMap(with_mesh, lighting, sun, false);
  ASSERT_EQ(a.sunlit.size(), b.sunlit.size());
  // The same texels shadowed, but for single sample points on the shadow's edge (the
  // mesh's corners rounded to floats, its triangles' edges counted as covering).
  int shadowed = 0, different = 0;
  float largest = 0.0f;
  for (std::size_t k = 0; k < a.sunlit.size(); ++k) {
    shadowed += a.sunlit[k] < 1.0f;
    different += a.sunlit[k] != b.sunlit[k];
    largest = std::max(largest, std::abs(a.sunlit[k] - b.sunlit[k]));
  }
  EXPECT_GT(shadowed, 500);
  EXPECT_LE(largest, 0.25f);
  EXPECT_LE(different, shadowed / 50) << shadowed << " texels shadowed";
}

// scenes/mesh_props.yaml on the models Debian's assimp-testmodels ships
// (scripts/setup.sh installs them): an OBJ with five JPEG images, a glTF with a PNG
// beside it and a .glb with it embedded are read, decoded and drawn.
TEST(MeshRenderTest, TheExampleSceneDrawsAssimpsTestModels) {
  const std::string dir = "/usr/local/share/trackbed/assimp-testmodels";
  if (!std::filesystem::exists(dir + "/OBJ/spider.obj")) {
    GTEST_SKIP() << dir << " absent (scripts/setup.sh installs it)";
  }
  const scenario::Scenario s =
      scenario::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/mesh_props.yaml");
  assets::SceneMeshes meshes = assets::LoadSceneMeshes(scenario::SceneObjects(s));
  ASSERT_EQ(meshes.obstacles.size(), 3u);
  int images = 0;
  for (const sim::MeshPart& p : meshes.obstacles[0].visual->parts)
    images += p.base_color_image != nullptr;
  EXPECT_EQ(images, static_cast<int>(meshes.obstacles[0].visual->parts.size()));
  const sim::MeshPart& embedded = meshes.obstacles[2].visual->parts.at(0);
  EXPECT_TRUE(embedded.base_color_texture.empty());
  ASSERT_NE(embedded.base_color_image, nullptr);
  const sim::MeshImage& gltf_image = *meshes.obstacles[1].visual->parts.at(0).base_color_image;
  EXPECT_EQ(embedded.base_color_image->rgb, gltf_image.rgb);  // the same PNG
  // Seen from the start, the models cover pixels the scene without them shows as grass
  // and sky; the boxes' logo is dark and light.
  sim::TerrainOptions t;
  t.extent_m = {-5, -6, 16, 6};
  const Eigen::Isometry3d T = Looking({0, 0, 0.5}, {1, 0, 0});
  const sim::World with(sim::WorldOptions{}, sim::Terrain(t, 1), {}, meshes.obstacles);
  const Frame a = RenderOnce(with, T), b = RenderOnce(FlatWorldWith({}), T);
  int covered = 0, dark = 0, light = 0;
  for (std::size_t k = 0; k < a.depth.depth_m.size(); ++k) {
    if (!(a.depth.depth_m[k] < b.depth.depth_m[k] - 1e-3)) continue;
    ++covered;
    dark += a.gray.pixels[k] < 40;
    light += a.gray.pixels[k] > 150;
  }
  EXPECT_GT(covered, 2000);
  EXPECT_GT(dark, 100);
  EXPECT_GT(light, 100);
}

}  // namespace
}  // namespace trackbed
