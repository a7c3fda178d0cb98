// An SDF visual's PBR <albedo_map> drawn as a pattern on a box and on a cylinder, laid
// as Gazebo lays it (gz-common's MeshManager::CreateBox and CreateCylinder;
// description/textured_unit_shapes.h): a white block on a black map lands where the
// pinhole projection of its texture coordinates on the true shape puts it (≤ 0.5 px).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "render_test_scene.h"
#include "trackbed/assets/scene_meshes.h"
#include "trackbed/description/sdf_world.h"
#include "trackbed/render/renderer.h"
#include "trackbed/sim/world.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

geometry::PinholeCamera Camera() { return render::test::Pinhole(400, 300, 320.0, 199.5, 149.5); }

// A black map of n × n texels with a white 4 × 4 block whose centre is at
// (u, v) = (46/64, 14/64), v down the image (OGRE's convention, as Gazebo reads it).
void WriteBlockMap(const fs::path& file, int n) {
  cv::Mat image(n, n, CV_8UC3, cv::Scalar(0, 0, 0));
  const int c = n * 46 / 64 - 2, r = n * 14 / 64 - 2;
  image(cv::Rect(c, r, 4, 4)).setTo(cv::Scalar(255, 255, 255));
  cv::imwrite(file.string(), image);
}

// The brightness centroid in a window of ±half px about `at`, and its peak.
Vec2 Centroid(const GrayImage& g, const Vec2& at, int half, double* peak) {
  double sum = 0, su = 0, sv = 0;
  *peak = 0;
  for (int r = static_cast<int>(at.y()) - half; r <= static_cast<int>(at.y()) + half; ++r) {
    for (int c = static_cast<int>(at.x()) - half; c <= static_cast<int>(at.x()) + half; ++c) {
      const double v = g.pixels[static_cast<std::size_t>(r) * g.width + c];
      sum += v;
      su += v * c;
      sv += v * r;
      *peak = std::max(*peak, v);
    }
  }
  return {su / sum, sv / sum};
}

TEST(SdfAlbedoMapTest, ATexelOfTheMapLandsWhereGazebosTextureCoordinatesPutIt) {
  if (!description::CanReadDescriptions()) GTEST_SKIP() << "built without sdformat";
  const fs::path dir =
      fs::temp_directory_path() / ("sdf_albedo_map_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  WriteBlockMap(dir / "box_map.png", 64);
  WriteBlockMap(dir / "drum_map.png", 256);
  // An upright box (1 m cube centred at (3, −0.8, 0.5)) and an upright cylinder (radius
  // 0.5, length 1, at (3, 0.8, 0.5)), each with a black and white albedo map.
  const std::string world = R"(<?xml version='1.0'?>
<sdf version='1.9'><world name='w'>
  <model name='crate'><static>true</static><pose>3 -0.8 0.5 0 0 0</pose><link name='l'>
    <visual name='v'><geometry><box><size>1 1 1</size></box></geometry>
      <material><pbr><metal><albedo_map>box_map.png</albedo_map></metal></pbr></material>
    </visual></link></model>
  <model name='drum'><static>true</static><pose>3 0.8 0.5 0 0 0</pose><link name='l'>
    <visual name='v'><geometry><cylinder><radius>0.5</radius><length>1</length></cylinder>
      </geometry><material><diffuse>1 1 1 1</diffuse><pbr><metal><albedo_map>drum_map.png</albedo_map>
      </metal></pbr></material></visual></link></model>
</world></sdf>
)";
  std::ofstream(dir / "world.sdf") << world;
  description::SdfWorldOptions options;
  options.file = (dir / "world.sdf").string();
  const description::SdfScene scene = description::ReadSdfWorld(options, (dir / "shapes").string());
  ASSERT_EQ(scene.objects.size(), 2u);
  for (const sim::StaticObject& o : scene.objects) {
    EXPECT_EQ(o.shape, sim::StaticObject::Shape::kMesh);
    EXPECT_FALSE(o.albedo);  // the map's own pattern, not a plain grey
    EXPECT_EQ(fs::path(o.mesh.file).extension(), ".obj");
  }
  for (const std::string& u : scene.unmapped)
    EXPECT_EQ(u.find("albedo_map"), std::string::npos) << u;

  const assets::SceneMeshes meshes = assets::LoadSceneMeshes(scene.objects);
  sim::TerrainOptions t;
  t.extent_m = {-2, -6, 12, 6};
  t.cell_size_m = 0.5;
  const sim::World w(sim::WorldOptions{}, sim::Terrain(t, 1), meshes.primitives, meshes.obstacles);
  const geometry::PinholeCamera K = Camera();
  const Eigen::Isometry3d T = render::test::Looking({0, 0, 1.0}, {1, 0, 0});
  render::Renderer renderer(w, render::test::AmbientOnly(), {}, 7, K.width_px, K.height_px, 0.1,
                            60.0);
  GrayImage gray;
  render::DepthImage depth;
  renderer.Render(K, T, 0.0, &gray, &depth);

  const double u = 46.0 / 64, v = 14.0 / 64;
  // The box's face towards −x (CreateBox's fourth face): u = 1 at its −y edge, 0 at its
  // +y edge; v = 0 at its top.
  const Vec3 on_box(2.5, -0.8 + 0.5 - u, 1.0 - v);
  // The cylinder's side: the angle 2πu from +y towards +x, v = 0 at its foot.
  const double a = 2 * kPi * u;
  const Vec3 on_drum(3 + 0.5 * std::sin(a), 0.8 + 0.5 * std::cos(a), v);
  for (const Vec3& p : {on_box, on_drum}) {
    const Vec2 predicted = K.Project(T.inverse() * p);
    double peak = 0;
    const Vec2 centroid = Centroid(gray, predicted, 8, &peak);
    EXPECT_GT(peak, 100.0) << p.transpose();
    std::printf("block at (%.4f, %.4f, %.4f): centroid %.3f px from the prediction, peak %.0f\n",
                p.x(), p.y(), p.z(), (centroid - predicted).norm(), peak);
    EXPECT_LT((centroid - predicted).norm(), 0.5)
        << "at " << p.transpose() << ": centroid " << centroid.transpose() << ", predicted "
        << predicted.transpose();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace trackbed
