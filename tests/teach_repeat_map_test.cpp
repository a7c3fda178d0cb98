// The teach map's on-disk format: an exact, byte-identical round trip, and clear errors
// (naming the file and what is wrong) for missing, corrupt, truncated, inconsistent and
// wrong-version maps, and for unknown keys and wrong types in map.json (by dotted path).
#include "trackbed/teach_repeat/teach_map.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "teach_repeat_test_scene.h"
#include "trackbed/teach_repeat/milestone_builder.h"

namespace trackbed::teach_repeat {
namespace {

namespace fs = std::filesystem;

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

void Replace(const fs::path& path, const std::string& from, const std::string& to) {
  std::string text = ReadBytes(path);
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  WriteBytes(path, text);
}

/// A fresh directory under the test temp dir.
fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("trackbed_teach_map_" + name);
  fs::remove_all(dir);
  return dir;
}

/// A map with awkward numbers (no short decimal form), both odometry cases, two milestones.
TeachMap RandomMap(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  cv::RNG pixels(seed);
  TeachMap map;
  map.mode = TeachMode::k3d;
  map.camera = testing::TestCamera();
  map.camera.fx = 381.40000000000003;
  map.patch_size_px = 11;
  for (int i = 0; i < 12; ++i) {
    TeachImageRecord r;
    r.t_s = 0.1 * i + 1e-13 * u(rng);
    if (i % 3 != 0) r.odometry = geometry::Pose2{u(rng) * 3.0, u(rng) / 3.0, u(rng) * M_PI};
    map.images.push_back(r);
  }
  for (int k = 0; k < 2; ++k) {
    Milestone m;
    m.first_image = 5 * k;
    m.last_image = 5 * k + 5;
    m.first_t_s = map.images[static_cast<std::size_t>(m.first_image)].t_s;
    m.last_t_s = map.images[static_cast<std::size_t>(m.last_image)].t_s;
    m.cut = k == 0 ? MilestoneCut::kReprojectionError : MilestoneCut::kEndOfTeach;
    m.reconstructed = k == 0;
    m.T_first_last.linear() =
        Eigen::AngleAxisd(u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized())
            .toRotationMatrix();
    m.T_first_last.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng)) / 7.0;
    m.reprojection_error_px = 0.1 * std::abs(u(rng));
    m.baseline_m = std::abs(u(rng)) / 3.0;
    m.key_image.create(480, 640, CV_8UC1);
    pixels.fill(m.key_image, cv::RNG::UNIFORM, 0, 256);
    for (int i = 0; i < 20 + 7 * k; ++i) {
      MilestoneFeature f;
      f.first_px = {static_cast<float>(320 + 300 * u(rng)), static_cast<float>(240 + 200 * u(rng))};
      f.last_px = {static_cast<float>(320 + 300 * u(rng)), static_cast<float>(240 + 200 * u(rng))};
      f.p_first = Eigen::Vector3d(u(rng), u(rng), 3.0 + u(rng)) / 3.0;
      f.patch.create(11, 11, CV_8UC1);
      pixels.fill(f.patch, cv::RNG::UNIFORM, 0, 256);
      m.features.push_back(f);
    }
    map.milestones.push_back(m);
  }
  return map;
}

void ExpectEqual(const TeachMap& a, const TeachMap& b) {
  EXPECT_EQ(a.mode, b.mode);
  EXPECT_EQ(a.camera.fx, b.camera.fx);
  EXPECT_EQ(a.camera.fy, b.camera.fy);
  EXPECT_EQ(a.camera.cx, b.camera.cx);
  EXPECT_EQ(a.camera.cy, b.camera.cy);
  EXPECT_EQ(a.camera.width_px, b.camera.width_px);
  EXPECT_EQ(a.camera.height_px, b.camera.height_px);
  EXPECT_EQ(a.patch_size_px, b.patch_size_px);
  ASSERT_EQ(a.images.size(), b.images.size());
  for (std::size_t i = 0; i < a.images.size(); ++i) {
    EXPECT_EQ(a.images[i].t_s, b.images[i].t_s);
    ASSERT_EQ(a.images[i].odometry.has_value(), b.images[i].odometry.has_value());
    if (a.images[i].odometry) {
      EXPECT_EQ(a.images[i].odometry->x, b.images[i].odometry->x);
      EXPECT_EQ(a.images[i].odometry->y, b.images[i].odometry->y);
      EXPECT_EQ(a.images[i].odometry->yaw, b.images[i].odometry->yaw);
    }
  }
  ASSERT_EQ(a.milestones.size(), b.milestones.size());
  for (std::size_t k = 0; k < a.milestones.size(); ++k) {
    const Milestone& x = a.milestones[k];
    const Milestone& y = b.milestones[k];
    EXPECT_EQ(x.first_image, y.first_image);
    EXPECT_EQ(x.last_image, y.last_image);
    EXPECT_EQ(x.first_t_s, y.first_t_s);
    EXPECT_EQ(x.last_t_s, y.last_t_s);
    EXPECT_EQ(x.cut, y.cut);
    EXPECT_EQ(x.reconstructed, y.reconstructed);
    EXPECT_TRUE(x.T_first_last.matrix() == y.T_first_last.matrix());
    EXPECT_EQ(x.reprojection_error_px, y.reprojection_error_px);
    EXPECT_EQ(x.baseline_m, y.baseline_m);
    EXPECT_EQ(cv::norm(x.key_image, y.key_image, cv::NORM_INF), 0.0);
    ASSERT_EQ(x.features.size(), y.features.size());
    for (std::size_t i = 0; i < x.features.size(); ++i) {
      EXPECT_EQ(x.features[i].first_px, y.features[i].first_px);
      EXPECT_EQ(x.features[i].last_px, y.features[i].last_px);
      EXPECT_TRUE(x.features[i].p_first == y.features[i].p_first);
      EXPECT_EQ(cv::norm(x.features[i].patch, y.features[i].patch, cv::NORM_INF), 0.0);
    }
  }
}

void ExpectSameFiles(const fs::path& a, const fs::path& b) {
  std::size_t files = 0;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(a)) {
    if (!e.is_regular_file()) continue;
    const fs::path relative = fs::relative(e.path(), a);
    ASSERT_TRUE(fs::exists(b / relative)) << relative;
    EXPECT_TRUE(ReadBytes(e.path()) == ReadBytes(b / relative)) << relative << " differs";
    ++files;
  }
  std::size_t other = 0;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(b))
    other += e.is_regular_file();
  EXPECT_EQ(files, other);
}

/// Load must throw a runtime_error whose message contains every one of `parts`.
void ExpectLoadError(const fs::path& dir, const std::vector<std::string>& parts) {
  try {
    LoadTeachMap(dir.string());
    ADD_FAILURE() << "loading " << dir << " succeeded";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "\"" << part << "\" not in: " << message;
    }
  }
}

TEST(TeachMapTest, RoundTripIsExactAndSavingAgainGivesTheSameBytes) {
  const TeachMap map = RandomMap(1);
  const fs::path first = Scratch("round_trip_a"), second = Scratch("round_trip_b");
  SaveTeachMap(map, first.string());
  EXPECT_TRUE(fs::exists(first / "map.json"));
  EXPECT_TRUE(fs::exists(first / "patches.bin"));
  EXPECT_TRUE(fs::exists(first / "key_images" / "000001.png"));
  EXPECT_EQ(fs::file_size(first / "patches.bin"), 24u + 47u * 121u);
  EXPECT_EQ(fs::file_size(first / "features.bin"), 24u + 47u * 40u);
  const TeachMap loaded = LoadTeachMap(first.string());
  ExpectEqual(map, loaded);
  SaveTeachMap(loaded, second.string());
  ExpectSameFiles(first, second);
  fs::remove_all(first);
  fs::remove_all(second);
}

// Version 1 listed every feature in map.json, with no features.bin: such a map still
// loads, and saving it writes version 2's files, the same as saving the map itself.
TEST(TeachMapTest, AVersion1MapLoadsAndSavesAsVersion2) {
  const TeachMap map = RandomMap(9);
  const fs::path v2 = Scratch("v2"), v1 = Scratch("v1"), again = Scratch("v1_saved");
  SaveTeachMap(map, v2.string());
  fs::copy(v2, v1, fs::copy_options::recursive);
  fs::remove(v1 / "features.bin");
  Replace(v1 / "map.json", "\"version\": 2", "\"version\": 1");
  Replace(v1 / "map.json", " \"features_file\": \"features.bin\",\n", "");
  for (const Milestone& m : map.milestones) {
    std::string rows;
    for (const MilestoneFeature& f : m.features) {
      char row[256];
      std::snprintf(row, sizeof row, "%s[%.9g, %.9g, %.9g, %.9g, %.17g, %.17g, %.17g]",
                    rows.empty() ? "" : ", ", f.first_px.x, f.first_px.y, f.last_px.x, f.last_px.y,
                    f.p_first.x(), f.p_first.y(), f.p_first.z());
      rows += row;
    }
    const std::string count = "\"feature_count\": " + std::to_string(m.features.size());
    Replace(v1 / "map.json", count + "\n", count + ",\n   \"features\": [" + rows + "]\n");
  }
  const TeachMap loaded = LoadTeachMap(v1.string());
  ExpectEqual(map, loaded);
  SaveTeachMap(loaded, again.string());
  ExpectSameFiles(v2, again);
  // Version 1's own checks: counts against the listed features, numbers a float holds.
  const std::string json = ReadBytes(v1 / "map.json");
  Replace(v1 / "map.json", "\"feature_count\": 20", "\"feature_count\": 21");
  Replace(v1 / "map.json", "\"patch_count\": 47", "\"patch_count\": 48");
  ExpectLoadError(v1, {"map.json", "milestones[0]", "inconsistent counts", "feature_count is 21"});
  WriteBytes(v1 / "map.json", json);
  char first[32];
  std::snprintf(first, sizeof first, "%.9g,", map.milestones[0].features[0].first_px.x);
  Replace(v1 / "map.json", std::string("\"features\": [[") + first, "\"features\": [[1e300,");
  ExpectLoadError(v1, {"map.json", "milestones[0].features[0]", "beyond a float's range"});
  for (const fs::path& dir : {v1, v2, again}) fs::remove_all(dir);
}

TEST(TeachMapTest, ATaughtMapRoundTrips) {
  const testing::CorridorScene scene;
  MilestoneBuilderOptions options;
  options.mode = TeachMode::k3d;
  MilestoneBuilder builder(testing::TestCamera(), options);
  for (int k = 0; k < 30; ++k) {
    const geometry::Pose2 pose{0.02 * k, 0.0, 0.0};
    builder.AddImage(scene.Render(testing::CameraPose(pose)), 0.1 * k, pose);
  }
  const TeachMap map = builder.Finish();
  ASSERT_GE(map.milestones.size(), 1u);
  const fs::path a = Scratch("taught_a"), b = Scratch("taught_b");
  SaveTeachMap(map, a.string());
  ExpectEqual(map, LoadTeachMap(a.string()));
  SaveTeachMap(LoadTeachMap(a.string()), b.string());
  ExpectSameFiles(a, b);
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(TeachMapTest, SavingOverALongerMapLeavesNoStaleKeyImages) {
  TeachMap map = RandomMap(2);
  const fs::path dir = Scratch("overwrite");
  SaveTeachMap(map, dir.string());
  map.milestones.pop_back();
  SaveTeachMap(map, dir.string());
  EXPECT_FALSE(fs::exists(dir / "key_images" / "000001.png"));
  ExpectEqual(map, LoadTeachMap(dir.string()));
  fs::remove_all(dir);
}

TEST(TeachMapTest, MissingMapsAreClearErrors) {
  const fs::path dir = Scratch("missing");
  ExpectLoadError(dir, {dir.string(), "no such directory"});
  fs::create_directories(dir);
  ExpectLoadError(dir, {"map.json", "missing"});
  SaveTeachMap(RandomMap(3), dir.string());
  fs::remove(dir / "patches.bin");
  ExpectLoadError(dir, {"patches.bin", "missing"});
  SaveTeachMap(RandomMap(3), dir.string());
  fs::remove(dir / "features.bin");
  ExpectLoadError(dir, {"features.bin", "missing"});
  SaveTeachMap(RandomMap(3), dir.string());
  fs::remove(dir / "key_images" / "000001.png");
  ExpectLoadError(dir, {"000001.png", "milestones[1]", "missing"});
  fs::remove_all(dir);
}

TEST(TeachMapTest, WrongVersionOrFormatIsNamed) {
  const fs::path dir = Scratch("version");
  SaveTeachMap(RandomMap(4), dir.string());
  Replace(dir / "map.json", "\"version\": 2", "\"version\": 3");
  ExpectLoadError(dir, {"map.json", "version", "unsupported version 3", "reads versions 1 to 2"});
  SaveTeachMap(RandomMap(4), dir.string());
  Replace(dir / "map.json", "trackbed.teach_map", "something.else");
  ExpectLoadError(dir, {"map.json", "format", "something.else"});
  fs::remove_all(dir);
}

TEST(TeachMapTest, TruncatedFilesAreClearErrors) {
  const fs::path dir = Scratch("truncated");
  SaveTeachMap(RandomMap(5), dir.string());
  std::string json = ReadBytes(dir / "map.json");
  WriteBytes(dir / "map.json", json.substr(0, json.size() / 2));
  ExpectLoadError(dir, {"map.json", "not valid JSON"});

  SaveTeachMap(RandomMap(5), dir.string());
  std::string patches = ReadBytes(dir / "patches.bin");
  WriteBytes(dir / "patches.bin", patches.substr(0, patches.size() - 50));
  ExpectLoadError(dir, {"patches.bin", "truncated", std::to_string(patches.size())});
  WriteBytes(dir / "patches.bin", patches + "x");
  ExpectLoadError(dir, {"patches.bin", "trailing bytes"});
  WriteBytes(dir / "patches.bin", "TBPATC");
  ExpectLoadError(dir, {"patches.bin", "bad magic or truncated header"});

  SaveTeachMap(RandomMap(5), dir.string());
  const std::string features = ReadBytes(dir / "features.bin");
  WriteBytes(dir / "features.bin", features.substr(0, features.size() - 1));
  ExpectLoadError(dir, {"features.bin", "truncated", std::to_string(features.size())});
  WriteBytes(dir / "features.bin", features + "x");
  ExpectLoadError(dir, {"features.bin", "trailing bytes"});
  WriteBytes(dir / "features.bin", ReadBytes(dir / "patches.bin"));
  ExpectLoadError(dir, {"features.bin", "not a trackbed feature file"});

  SaveTeachMap(RandomMap(5), dir.string());
  const std::string png = ReadBytes(dir / "key_images" / "000000.png");
  WriteBytes(dir / "key_images" / "000000.png", png.substr(0, 40));
  ExpectLoadError(dir, {"000000.png", "not a decodable image"});
  fs::remove_all(dir);
}

TEST(TeachMapTest, InconsistentCountsAndBadValuesAreNamed) {
  const fs::path dir = Scratch("inconsistent");
  SaveTeachMap(RandomMap(6), dir.string());
  Replace(dir / "map.json", "\"feature_count\": 20", "\"feature_count\": 21");
  Replace(dir / "map.json", "\"patch_count\": 47", "\"patch_count\": 48");
  ExpectLoadError(
      dir, {"features.bin", "inconsistent counts", "holds 47 features", "map.json counts 48"});

  SaveTeachMap(RandomMap(6), dir.string());
  Replace(dir / "map.json", "\"feature_count\": 20", "\"feature_count\": -1");
  ExpectLoadError(dir, {"map.json", "milestones[0].feature_count", "must be in [0, ", "got -1"});

  // Records of another size.
  SaveTeachMap(RandomMap(6), dir.string());
  std::string features = ReadBytes(dir / "features.bin");
  features[8] = 56;
  WriteBytes(dir / "features.bin", features);
  ExpectLoadError(dir, {"features.bin", "records of 56 bytes"});

  SaveTeachMap(RandomMap(6), dir.string());
  Replace(dir / "map.json", "\"patch_count\": 47", "\"patch_count\": 46");
  ExpectLoadError(dir, {"map.json", "patch_count", "inconsistent counts"});

  SaveTeachMap(RandomMap(6), dir.string());
  Replace(dir / "map.json", "\"last_image\": 5", "\"last_image\": 50");
  ExpectLoadError(dir, {"map.json", "milestones[0]", "last_image"});

  SaveTeachMap(RandomMap(6), dir.string());
  Replace(dir / "map.json", "\"mode\": \"3d\"", "\"mode\": \"4d\"");
  ExpectLoadError(dir, {"map.json", "mode", "4d"});

  SaveTeachMap(RandomMap(6), dir.string());
  Replace(dir / "map.json", "\"baseline_m\"", "\"baseline\"");
  ExpectLoadError(dir, {"map.json", "milestones[0].baseline_m", "missing"});

  // A patch file from a map with other patch sizes.
  SaveTeachMap(RandomMap(6), dir.string());
  std::string patches = ReadBytes(dir / "patches.bin");
  patches[8] = 9;
  WriteBytes(dir / "patches.bin", patches);
  ExpectLoadError(dir, {"patches.bin", "patch side 9"});

  // A key image of the wrong size.
  SaveTeachMap(RandomMap(6), dir.string());
  std::vector<unsigned char> small;
  cv::imencode(".png", cv::Mat(10, 10, CV_8UC1, cv::Scalar(3)), small);
  WriteBytes(dir / "key_images" / "000000.png", std::string(small.begin(), small.end()));
  ExpectLoadError(dir, {"000000.png", "640x480"});
  fs::remove_all(dir);
}

// map.json names its files relative to its folder: a map read from elsewhere reads no
// file outside it.
TEST(TeachMapTest, FilesOutsideTheMapsFolderAreRefused) {
  const fs::path dir = Scratch("outside");
  const std::vector<std::pair<std::string, std::string>> edits = {
      {"\"key_images/000000.png\"", "\"../000000.png\""},
      {"\"key_images/000000.png\"", "\"/etc/hostname\""},
      {"\"key_images/000000.png\"", "\"key_images/../../x.png\""},
      {"\"patches.bin\"", "\"../patches.bin\""},
      {"\"patches.bin\"", "\"\""},
      {"\"features.bin\"", "\"../features.bin\""}};
  for (const auto& [from, to] : edits) {
    SCOPED_TRACE(to);
    SaveTeachMap(RandomMap(6), dir.string());
    Replace(dir / "map.json", from, to);
    const std::string key = from == "\"patches.bin\""    ? "patches_file"
                            : from == "\"features.bin\"" ? "features_file"
                                                         : "milestones[0].key_image";
    ExpectLoadError(dir, {"map.json", key, "not a file inside the map's folder"});
  }
  fs::remove_all(dir);
}

/// An edit of a saved map.json and what loading it must say.
struct JsonEdit {
  std::string from, to;
  std::vector<std::string> message_parts;
};

TEST(TeachMapTest, UnknownKeysAndWrongTypesNameTheirPath) {
  const fs::path dir = Scratch("strict");
  const std::vector<JsonEdit> edits = {
      {"\"patch_size_px\": 11",
       "\"patch_size_px\": 11, \"colour\": 1",
       {"map.json: colour: unknown key (allowed: format, version, mode, camera,"}},
      {"\"cut\": \"end_of_teach\"",
       "\"cut\": \"end_of_teach\", \"note\": 1",
       {"map.json: milestones[1].note: unknown key (allowed: first_image,"}},
      {"\"width\": 640",
       "\"width\": \"640\"",
       {"map.json: camera.width: expected an integer, got the quoted string \"640\""}},
      {"\"height\": 480", "\"height\": 0", {"map.json: camera.height: must be > 0 (got 0)"}},
      {"\"reconstructed\": true",
       "\"reconstructed\": 1",
       {"map.json: milestones[0].reconstructed: expected true or false, got '1'"}},
      {"\"cut\": \"end_of_teach\"",
       "\"cut\": \"sideways\"",
       {"map.json: milestones[1].cut: must be one of interval,", "(got 'sideways')"}},
      {"\"T_first_last\": [",
       "\"T_first_last\": [0, ",
       {"map.json: milestones[0].T_first_last: expected a list of 12 numbers, got a list of 13"}},
      {"\"odometry\": [\n   null",
       "\"odometry\": [\n   [1, 2, \"x\"]",
       {"map.json: images.odometry[0][2]: expected a number, got the quoted string \"x\""}},
      {"\"feature_count\": 20",
       "\"feature_count\": 20, \"features\": []",
       {"map.json: milestones[0].features: unknown key (allowed: first_image,"}},
      {"\"images\": {", "\"images\": {\"count\": 1, ", {"map.json: images.count: duplicate key"}},
  };
  for (const JsonEdit& edit : edits) {
    SaveTeachMap(RandomMap(8), dir.string());
    Replace(dir / "map.json", edit.from, edit.to);
    ExpectLoadError(dir, edit.message_parts);
  }
  fs::remove_all(dir);
}

TEST(TeachMapTest, SavingAnInvalidMapThrows) {
  TeachMap map = RandomMap(7);
  map.milestones[1].features[3].patch = cv::Mat(5, 5, CV_8UC1);
  EXPECT_THROW(SaveTeachMap(map, Scratch("invalid").string()), std::invalid_argument);
  map = RandomMap(7);
  map.milestones[1].first_image = 2;  // before the previous milestone's end
  EXPECT_THROW(SaveTeachMap(map, Scratch("invalid").string()), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::teach_repeat
