// Mesh objects: files of each format written here and read through assimp
// (assets/mesh_reader.h), the triangles placed in the world (sim/triangle_mesh.h),
// ground meshes sampled onto the terrain's grid, and the scenario's keys and errors.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "mesh_files.h"
#include "trackbed/assets/mesh_reader.h"
#include "trackbed/assets/scene_meshes.h"
#include "trackbed/runner/footprint_clearance.h"
#include "trackbed/runner/input_files.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "trackbed/sim/world.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;
using test_mesh::TempPath;
using test_mesh::Write;

void ExpectBounds(const sim::TriangleMesh& m, const Eigen::Vector3d& lo,
                  const Eigen::Vector3d& hi) {
  const Eigen::AlignedBox3d b = m.Bounds();
  EXPECT_TRUE(b.min().isApprox(lo, 1e-6) || (b.min() - lo).norm() < 1e-6) << b.min().transpose();
  EXPECT_LT((b.max() - hi).norm(), 1e-6) << b.max().transpose();
}

// The message of the AssetError `read` throws.
template <class F>
std::string AssetErrorOf(F&& read) {
  try {
    read();
  } catch (const assets::AssetError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(MeshReaderTest, AnObjBoxWithItsMaterialAndTexture) {
  // A 3 × 2 image: its texels decoded, red, green and blue as written, rows top first.
  cv::Mat paint(2, 3, CV_8UC3, cv::Scalar(30, 20, 10));  // OpenCV's order: blue, green, red
  paint.at<cv::Vec3b>(1, 2) = cv::Vec3b(3, 2, 1);
  ASSERT_TRUE(cv::imwrite(TempPath("paint.png"), paint));
  const std::string file = test_mesh::ObjBox("box.obj", -1, -0.5, 0, 1, 0.5, 2, "paint.png");
  const assets::MeshRead r = assets::ReadMesh(file);
  EXPECT_EQ(r.mesh.triangles.size(), 12u);
  EXPECT_EQ(r.mesh.vertices.size(), r.mesh.uvs.size());
  ExpectBounds(r.mesh, {-1, -0.5, 0}, {1, 0.5, 2});
  ASSERT_EQ(r.mesh.parts.size(), 1u);
  EXPECT_EQ(r.mesh.parts[0].triangles, 12u);
  EXPECT_EQ(r.mesh.parts[0].base_color_texture, TempPath("paint.png"));
  EXPECT_NEAR(r.mesh.parts[0].base_color.x(), 0.8, 1e-6);
  ASSERT_NE(r.mesh.parts[0].base_color_image, nullptr);
  const sim::MeshImage& image = *r.mesh.parts[0].base_color_image;
  EXPECT_EQ(image.width, 3);
  EXPECT_EQ(image.height, 2);
  EXPECT_EQ(image.rgb, (std::vector<std::uint8_t>{10, 20, 30, 10, 20, 30, 10, 20, 30,  //
                                                  10, 20, 30, 10, 20, 30, 1, 2, 3}));
  ASSERT_EQ(r.textures.size(), 1u);
  // assimp opened the OBJ and its material library.
  EXPECT_NE(std::find(r.files.begin(), r.files.end(), TempPath("box.mtl")), r.files.end());
  EXPECT_NE(std::find(r.files.begin(), r.files.end(), TempPath("box.obj")), r.files.end());
  // Every texture coordinate is one the file gave.
  for (const Eigen::Vector2f& uv : r.mesh.uvs) {
    EXPECT_TRUE((uv.array() == 0.0f || uv.array() == 1.0f).all()) << uv.transpose();
  }
}

TEST(MeshReaderTest, AnAsciiPlyAndAnAsciiStl) {
  const assets::MeshRead ply = assets::ReadMesh(test_mesh::PlySquare("square.ply"));
  EXPECT_EQ(ply.mesh.triangles.size(), 3u);
  ExpectBounds(ply.mesh, {0, 0, 0}, {6, 5, 3});
  const assets::MeshRead stl = assets::ReadMesh(test_mesh::StlRoof("roof.stl"));
  EXPECT_EQ(stl.mesh.triangles.size(), 4u);
  ExpectBounds(stl.mesh, {0, 0, 0}, {4, 2, 1});
}

TEST(MeshReaderTest, GltfNodeTransformsAppliedAndYUpTurnedToZUp) {
  const assets::MeshRead r = assets::ReadMesh(test_mesh::GltfTriangle("tri.gltf"));
  // The mesh twice: under the translated, scaled node and under the plain one.
  ASSERT_EQ(r.mesh.triangles.size(), 2u);
  // glTF's (x, y, z) with y up is (x, −z, y) here. The plain node's triangle spans
  // x 0..1, z 0..1 at y 0; the other's x 10..12, y −30, z 20..22.
  ExpectBounds(r.mesh, {0, -30, 0}, {12, 0, 22});
  bool found = false;
  for (const Eigen::Vector3f& v : r.mesh.vertices) {
    found = found || (v - Eigen::Vector3f(12, -30, 20)).norm() < 1e-5;
  }
  EXPECT_TRUE(found) << "the transformed node's (1, 0, 0) at (12, −30, 20)";
  EXPECT_NE(std::find(r.files.begin(), r.files.end(), TempPath("tri.bin")), r.files.end());
}

TEST(MeshReaderTest, ColladaInCentimetresWithZUp) {
  const assets::MeshRead r = assets::ReadMesh(test_mesh::DaeTriangle("tri.dae"));
  ASSERT_EQ(r.mesh.triangles.size(), 1u);
  // 100 cm along x and y, z up as written.
  ExpectBounds(r.mesh, {0, 0, 0}, {1, 1, 0});
}

TEST(MeshReaderTest, ErrorsNameTheFileAndWhatIsWrong) {
  const std::string fbx = Write("model.fbx", "x");
  EXPECT_NE(AssetErrorOf([&] { assets::ReadMesh(fbx); }).find(fbx + ": not a mesh file"),
            std::string::npos);
  const std::string missing = TempPath("missing.obj");
  EXPECT_EQ(AssetErrorOf([&] { assets::ReadMesh(missing); }), missing + ": no such file");
  const std::string empty = Write("points.obj", "v 0 0 0\nv 1 0 0\n");
  EXPECT_EQ(AssetErrorOf([&] { assets::ReadMesh(empty); }), empty + ": holds no triangle");
  const std::string broken = Write("broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  EXPECT_EQ(AssetErrorOf([&] { assets::ReadMesh(broken); }).rfind(broken + ": ", 0), 0u);
  // assimp 5.2.5 loops forever on a PLY header that does not end: refused before.
  const std::string cut = Write("cut.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  EXPECT_EQ(AssetErrorOf([&] { assets::ReadMesh(cut); }),
            cut + ": its PLY header does not end (no end_header line in its first 64 KiB)");
  const std::string no_texture = test_mesh::ObjBox("lost.obj", 0, 0, 0, 1, 1, 1, "gone.png");
  EXPECT_NE(AssetErrorOf([&] {
              assets::ReadMesh(no_texture);
            }).find(no_texture + ": a material's image is not a file: " + TempPath("gone.png")),
            std::string::npos);
  Write("junk.png", "not an image");
  const std::string junk = test_mesh::ObjBox("junk.obj", 0, 0, 0, 1, 1, 1, "junk.png");
  EXPECT_EQ(
      AssetErrorOf([&] { assets::ReadMesh(junk); }),
      junk + ": its material's image " + TempPath("junk.png") + " cannot be decoded as an image");
}

TEST(MeshReaderTest, AKeptReadIsTheFilesAsLongAsItIsUnchanged) {
  const std::string file = test_mesh::ObjBox("kept.obj", 0, 0, 0, 1, 1, 1);
  const auto first = assets::ReadMeshKept(file);
  EXPECT_EQ(assets::ReadMeshKept(file), first);        // the same read
  test_mesh::ObjBox("kept.obj", 0, 0, 0, 10, 10, 10);  // another size
  const auto second = assets::ReadMeshKept(file);
  EXPECT_NE(second, first);
  ExpectBounds(second->mesh, {0, 0, 0}, {10, 10, 10});
}

TEST(PlacedMeshTest, HeightsAndPlanDistancesOfPlacedTriangles) {
  const assets::MeshRead r = assets::ReadMesh(test_mesh::StlRoof("roof2.stl"));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(10, 0, 1);
  const sim::PlacedMesh roof(r.mesh, Eigen::Vector3d(1, 1, 2), pose);
  // The ridge at y = 1 is 2 m high after the scale, 1 m up.
  EXPECT_NEAR(*roof.HighestAt(12, 1), 3.0, 1e-12);
  EXPECT_NEAR(*roof.HighestAt(12, 0.5), 2.0, 1e-12);
  EXPECT_FALSE(roof.HighestAt(9.9, 1).has_value());
  // A unit square 2 m west of the roof's western end, within and above its heights.
  const std::vector<Eigen::Vector2d> square = {{7, 0.5}, {8, 0.5}, {8, 1.5}, {7, 1.5}};
  EXPECT_NEAR(roof.PlanDistance(square, 0, 5), 2.0, 1e-12);
  EXPECT_TRUE(std::isinf(roof.PlanDistance(square, 3.5, 5)));
  // Overlapping the roof's end by 0.5 m: a triangle's corner may be pushed out by less.
  const std::vector<Eigen::Vector2d> over = {{9.5, 0.5}, {10.5, 0.5}, {10.5, 1.5}, {9.5, 1.5}};
  EXPECT_LT(roof.PlanDistance(over, 0, 5), 0.0);
  EXPECT_GE(roof.PlanDistance(over, 0, 5), -0.5 - 1e-12);
}

TEST(PlacedMeshTest, ChassisClearanceCountsAMeshWallsTriangles) {
  const assets::MeshRead r = assets::ReadMesh(test_mesh::ObjBox("wall.obj", 0, -2, 0, 0.2, 2, 1));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(3, 0, 0);
  const auto wall = std::make_shared<const sim::PlacedMesh>(r.mesh, Eigen::Vector3d::Ones(), pose);
  Eigen::Isometry3d body = Eigen::Isometry3d::Identity();
  body.translation() = Eigen::Vector3d(1, 0, 0.2);
  // The hull 0.7 m long: its front at 1.35 m, the wall's face at 3 m.
  EXPECT_NEAR(runner::ChassisClearance(body, {0.7, 0.42}, {}, {wall}, {-0.2, 0.1}), 1.65, 1e-12);
  // Turned 90°: the hull's side, 0.21 m from its centre, faces the wall.
  body.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NEAR(runner::ChassisClearance(body, {0.7, 0.42}, {}, {wall}, {-0.2, 0.1}), 1.79, 1e-9);
  // A wall high above the hull is no obstacle to it.
  pose.translation().z() = 2.0;
  const auto high = std::make_shared<const sim::PlacedMesh>(r.mesh, Eigen::Vector3d::Ones(), pose);
  EXPECT_TRUE(std::isinf(runner::ChassisClearance(body, {0.7, 0.42}, {}, {high}, {-0.2, 0.1})));
}

// A ground mesh: a 1 m-high ridge of two facets, scaled to cover the terrain.
sim::TerrainOptions SmallTerrain() {
  sim::TerrainOptions t;
  t.extent_m = Eigen::Vector4d(0.5, 0.1, 3.5, 1.9);
  t.cell_size_m = 0.1;
  return t;
}

TEST(MeshGroundTest, TheTerrainsGridPointsTakeTheMeshsHeights) {
  sim::StaticObject o;
  o.shape = sim::StaticObject::Shape::kMesh;
  o.kind = "mesh";
  o.mesh.file = test_mesh::StlRoof("ground.stl");
  o.mesh.ground = true;
  o.mesh.scale = Eigen::Vector3d(1, 1, 0.5);
  const assets::SceneMeshes m = assets::LoadSceneMeshes({o});
  ASSERT_EQ(m.grounds.size(), 1u);
  EXPECT_TRUE(m.obstacles.empty());
  const sim::TerrainOptions t = SmallTerrain();
  const auto grid = assets::SampleMeshGround(m.grounds, t);
  const sim::Terrain terrain(t, 1, grid);
  // The roof rises 0.5 m from y = 0 to the ridge at y = 1 (half the file's 1 m).
  for (int i = 0; i < terrain.cols(); ++i) {
    for (int j = 0; j < terrain.rows(); ++j) {
      const double y = terrain.y_min() + j * terrain.cell_size_m();
      const double mesh = 0.5 * (y <= 1.0 ? y : 2.0 - y);
      ASSERT_NEAR(terrain.GridHeight(i, j), mesh, 1e-9) << i << ", " << j;
    }
  }
  // Off the grid points the terrain's triangles, here on the ridge's planes.
  EXPECT_NEAR(terrain.Height(1.234, 0.456), 0.5 * 0.456, 1e-9);
  // A terrain wider than the mesh: the first grid point without a triangle is named.
  sim::TerrainOptions wide = t;
  wide.extent_m[2] = 4.5;
  try {
    assets::SampleMeshGround(m.grounds, wide);
    ADD_FAILURE() << "no error";
  } catch (const assets::AssetError& e) {
    EXPECT_NE(std::string(e.what()).find(o.mesh.file + ": the ground mesh leaves the terrain's "
                                                       "grid point (4.1, 0.1)"),
              std::string::npos)
        << e.what();
  }
}

TEST(MeshScenarioTest, KeysReadWrittenAndCheckedWithTheirNames) {
  test_mesh::ObjBox("scene_box.obj", -0.5, -0.5, 0, 0.5, 0.5, 1);
  const std::string yaml = Write("mesh_scene.yaml",
                                 "drive: {waypoints: [[0, 0], [1, 0]]}\n"
                                 "scene:\n  objects:\n"
                                 "    - {type: mesh, file: scene_box.obj, center: [3, 1], "
                                 "roll_deg: 10, pitch_deg: -5, yaw_deg: 90, scale: [1, 2, 0.5], "
                                 "collision: box}\n");
  const scenario::Scenario s = scenario::LoadScenario(yaml);
  const sim::StaticObject& o = s.scene.objects.at(0);
  EXPECT_EQ(o.shape, sim::StaticObject::Shape::kMesh);
  EXPECT_EQ(o.mesh.file, TempPath("scene_box.obj"));
  EXPECT_EQ(o.mesh.scale, Eigen::Vector3d(1, 2, 0.5));
  EXPECT_EQ(o.mesh.collision, sim::MeshSource::Collision::kBox);
  EXPECT_NEAR(o.roll_rad, 10 * M_PI / 180, 1e-15);
  // Written and read again: the same text.
  const std::string text = scenario::ScenarioToYaml(s);
  EXPECT_EQ(scenario::ScenarioToYaml(scenario::ParseScenario(text, "again.yaml")), text);
  EXPECT_NE(text.find("type: mesh"), std::string::npos) << text;
  // inputs.json lists the mesh file.
  const std::vector<runner::InputFile> inputs = runner::InputFiles(s);
  ASSERT_FALSE(inputs.empty());
  EXPECT_EQ(inputs[0].key, "scene.objects[0].file");
  EXPECT_EQ(inputs[0].path, TempPath("scene_box.obj"));
  EXPECT_EQ(inputs[0].sha256.size(), 64u);

  const auto error_of = [&](const std::string& object) {
    try {
      scenario::LoadScenario(Write("bad.yaml",
                                   "drive: {waypoints: [[0, 0], [1, 0]]}\n"
                                   "scene:\n  objects:\n    - " +
                                       object + "\n"));
    } catch (const scenario::ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::string bad = TempPath("bad.yaml");
  EXPECT_EQ(error_of("{type: mesh, file: scene_box.obj, scale: 0}"),
            bad + ": scene.objects[0].scale[0]: must be > 0 (got 0)");
  EXPECT_EQ(error_of("{type: mesh, file: scene_box.obj, scale: [1, .nan, 1]}"),
            bad + ": scene.objects[0].scale[1]: must be > 0 (got nan)");
  EXPECT_EQ(error_of("{type: mesh, file: nowhere.obj}"),
            bad + ": scene.objects[0].file: no such file: " + TempPath("nowhere.obj"));
  Write("model.fbx", "x");
  EXPECT_NE(error_of("{type: mesh, file: model.fbx}")
                .find(bad + ": scene.objects[0].file: " + TempPath("model.fbx") +
                      ": not a mesh file of a known kind"),
            std::string::npos);
  EXPECT_EQ(error_of("{type: mesh, file: scene_box.obj, collision: file}"),
            bad +
                ": scene.objects[0].collision_file: names the collision mesh exactly when "
                "collision is 'file'");
  Write("empty.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\n");
  EXPECT_EQ(
      error_of("{type: mesh, file: scene_box.obj, collision: file, collision_file: "
               "empty.obj}"),
      bad + ": scene.objects[0].collision_file: " + TempPath("empty.obj") + ": holds no triangle");
  EXPECT_EQ(error_of("{type: mesh}"),
            bad + ": scene.objects[0].file: missing: a mesh names its file");
  // A ground mesh short of the terrain (the default extent, ±5 m).
  EXPECT_NE(error_of("{type: mesh, file: scene_box.obj, ground: true}")
                .find(bad + ": scene.objects[0].file: the ground meshes span x -0.5 to 0.5 m"),
            std::string::npos);
}

}  // namespace
}  // namespace trackbed
