// Key images and features held on disk (teach_map.h): a map taught with its key images
// spilled as it goes is the same map, byte for byte on disk; a map loaded on demand
// checks its key images and feature files without reading them whole, reads the same
// pixels and features later and saves to the same bytes; both repeaters driven from such
// a map give the same commands as from the map in memory while holding at most two
// milestones' key images and features.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "teach_repeat_test_scene.h"
#include "trackbed/navigation/diff_drive.h"
#include "trackbed/teach_repeat/milestone_builder.h"
#include "trackbed/teach_repeat/repeater_factory.h"
#include "trackbed/teach_repeat/teach_map.h"

namespace trackbed::teach_repeat {
namespace {

namespace fs = std::filesystem;
using geometry::Pose2;
using testing::CameraPose;
using testing::CorridorScene;
using testing::TestCamera;

fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("trackbed_teach_map_on_disk_" + name);
  fs::remove_all(dir);
  return dir;
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Every file under `a` is in `b` with the same bytes, and `b` has no other file.
void ExpectSameFiles(const fs::path& a, const fs::path& b) {
  std::size_t files = 0, other = 0;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(a)) {
    if (!e.is_regular_file()) continue;
    const fs::path relative = fs::relative(e.path(), a);
    EXPECT_TRUE(ReadBytes(e.path()) == ReadBytes(b / relative)) << relative << " differs";
    ++files;
  }
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(b)) {
    other += e.is_regular_file();
  }
  EXPECT_EQ(files, other);
}

/// A straight teach down the corridor, 2 cm per image, milestones every 10 images; with
/// `spill_dir` the key images are spilled there as each milestone closes.
TeachMap TeachStraight(TeachMode mode, int images, const std::string& spill_dir = "") {
  const CorridorScene scene;
  MilestoneBuilderOptions options;
  options.mode = mode;
  options.interval_images = 10;
  MilestoneBuilder builder(TestCamera(), options);
  for (int k = 0; k < images; ++k) {
    const Pose2 pose{0.02 * k, 0.0, 0.0};
    const TeachStep step = builder.AddImage(scene.Render(CameraPose(pose)), 0.1 * k, pose);
    if (!spill_dir.empty() && step.milestone_closed) builder.SpillMilestones(spill_dir);
  }
  return builder.Finish();
}

int KeyImagesHeld(const TeachMap& map) {
  int held = 0;
  for (const Milestone& m : map.milestones) held += m.key_image.empty() ? 0 : 1;
  return held;
}

int FeaturesHeld(const TeachMap& map) {
  int held = 0;
  for (const Milestone& m : map.milestones) held += m.features.empty() ? 0 : 1;
  return held;
}

/// The same positions, points and patches, bit for bit.
void ExpectSameFeatures(const Milestone& a, const Milestone& b) {
  ASSERT_EQ(a.features.size(), b.features.size());
  for (std::size_t i = 0; i < a.features.size(); ++i) {
    const MilestoneFeature &f = a.features[i], &g = b.features[i];
    EXPECT_TRUE(f.first_px == g.first_px && f.last_px == g.last_px && f.p_first == g.p_first)
        << "feature " << i;
    EXPECT_EQ(cv::norm(f.patch, g.patch, cv::NORM_INF), 0.0) << "feature " << i;
  }
}

TEST(TeachMapOnDiskTest, SpillingWhileTeachingSavesTheSameMap) {
  const fs::path held = Scratch("held"), spilled = Scratch("spilled");
  const TeachMap in_memory = TeachStraight(TeachMode::k2d, 65);
  const TeachMap on_disk = TeachStraight(TeachMode::k2d, 65, spilled.string());
  ASSERT_EQ(in_memory.milestones.size(), 7u);
  // Only the milestone still open at the end of the teach holds its key image and
  // features.
  EXPECT_EQ(KeyImagesHeld(on_disk), 1);
  EXPECT_EQ(FeaturesHeld(on_disk), 1);
  EXPECT_FALSE(on_disk.milestones.front().key_image_file.empty());
  EXPECT_TRUE(on_disk.milestones.front().features_file.has_value());
  EXPECT_EQ(on_disk.feature_count(), in_memory.feature_count());
  SaveTeachMap(in_memory, held.string());
  SaveTeachMap(on_disk, spilled.string());  // where its key images lie
  ExpectSameFiles(held, spilled);
  EXPECT_FALSE(fs::exists(spilled / "key_images.new"));
  fs::remove_all(held);
  fs::remove_all(spilled);
}

TEST(TeachMapOnDiskTest, OnDemandLoadingReadsTheSamePixelsAndSavesTheSameBytes) {
  const fs::path a = Scratch("a"), b = Scratch("b");
  SaveTeachMap(TeachStraight(TeachMode::k3d, 41), a.string());
  const TeachMap all = LoadTeachMap(a.string());
  TeachMap lazy = LoadTeachMap(a.string(), MapLoading::kOnDemand);
  EXPECT_EQ(KeyImagesHeld(lazy), 0);
  EXPECT_EQ(FeaturesHeld(lazy), 0);
  EXPECT_EQ(lazy.feature_count(), all.feature_count());
  EXPECT_GT(all.feature_count(), 200u);
  SaveTeachMap(lazy, b.string());  // linked or copied, never decoded
  ExpectSameFiles(a, b);
  SaveTeachMap(lazy, a.string());  // in place: the files it names survive
  ExpectSameFiles(b, a);
  // Without its first milestone, the others' features would move within the files they
  // are read from: refused in place, nothing written; saved elsewhere.
  TeachMap shorter = lazy;
  shorter.milestones.erase(shorter.milestones.begin());
  EXPECT_THROW(SaveTeachMap(shorter, a.string()), std::invalid_argument);
  ExpectSameFiles(b, a);
  const fs::path c = Scratch("c");
  SaveTeachMap(shorter, c.string());
  EXPECT_EQ(LoadTeachMap(c.string()).feature_count(),
            all.feature_count() - all.milestones[0].features.size());
  fs::remove_all(c);
  ASSERT_EQ(lazy.milestones.size(), all.milestones.size());
  for (std::size_t k = 0; k < all.milestones.size(); ++k) {
    Milestone& m = lazy.milestones[k];
    LoadKeyImage(lazy.camera, &m);
    EXPECT_EQ(cv::norm(m.key_image, all.milestones[k].key_image, cv::NORM_INF), 0.0);
    ReleaseKeyImage(&m);
    EXPECT_TRUE(m.key_image.empty());
    LoadFeatures(&m);
    ExpectSameFeatures(m, all.milestones[k]);
    ReleaseFeatures(&m);
    EXPECT_TRUE(m.features.empty());
    EXPECT_EQ(m.feature_count(), all.milestones[k].features.size());
  }
  // A key image and features held in memory only are never released.
  Milestone only_in_memory = all.milestones[0];
  ReleaseKeyImage(&only_in_memory);
  ReleaseFeatures(&only_in_memory);
  EXPECT_FALSE(only_in_memory.key_image.empty());
  EXPECT_FALSE(only_in_memory.features.empty());
  fs::remove_all(a);
  fs::remove_all(b);
}

/// LoadTeachMap(kOnDemand) must throw a runtime_error whose message holds every part.
void ExpectOnDemandError(const fs::path& dir, const std::vector<std::string>& parts) {
  try {
    LoadTeachMap(dir.string(), MapLoading::kOnDemand);
    ADD_FAILURE() << "loading " << dir << " succeeded";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "\"" << part << "\" not in: " << message;
    }
  }
}

TEST(TeachMapOnDiskTest, OnDemandLoadingChecksEveryKeyImageFileUpFront) {
  const fs::path dir = Scratch("bad");
  const fs::path key = dir / "key_images" / "000001.png";
  const auto write = [&key](const std::string& bytes) {
    std::ofstream(key, std::ios::binary | std::ios::trunc) << bytes;
  };
  SaveTeachMap(TeachStraight(TeachMode::k2d, 31), dir.string());
  const std::string png = ReadBytes(key);
  write(png.substr(0, png.size() - 1));
  ExpectOnDemandError(dir, {"000001.png", "not a complete PNG file"});
  std::vector<unsigned char> small, colour;
  cv::imencode(".png", cv::Mat(10, 10, CV_8UC1, cv::Scalar(3)), small);
  write(std::string(small.begin(), small.end()));
  ExpectOnDemandError(dir, {"000001.png", "8-bit grey image of 640x480"});
  cv::imencode(".png", cv::Mat(480, 640, CV_8UC3, cv::Scalar(3, 4, 5)), colour);
  write(std::string(colour.begin(), colour.end()));
  ExpectOnDemandError(dir, {"000001.png", "8-bit grey image of 640x480"});
  fs::remove(key);
  ExpectOnDemandError(dir, {"000001.png", "milestones[1]", "missing"});

  // A file that goes bad after the load is named when the repeat reads it.
  write(png);
  TeachMap lazy = LoadTeachMap(dir.string(), MapLoading::kOnDemand);
  write(png.substr(0, 40));
  try {
    LoadKeyImage(lazy.camera, &lazy.milestones[1]);
    ADD_FAILURE() << "a truncated key image was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("000001.png"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

/// LoadFeatures(m) must throw a runtime_error whose message holds every part.
void ExpectFeatureError(Milestone* m, const std::vector<std::string>& parts) {
  try {
    LoadFeatures(m);
    ADD_FAILURE() << "the features were read";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "\"" << part << "\" not in: " << message;
    }
  }
  EXPECT_TRUE(m->features.empty());
}

TEST(TeachMapOnDiskTest, OnDemandLoadingChecksTheFeatureFilesUpFrontAndWhenRead) {
  const fs::path dir = Scratch("bad_features");
  SaveTeachMap(TeachStraight(TeachMode::k3d, 31), dir.string());
  const fs::path features = dir / "features.bin", patches = dir / "patches.bin";
  const std::string feature_bytes = ReadBytes(features), patch_bytes = ReadBytes(patches);
  const auto write = [](const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  };
  write(features, feature_bytes.substr(0, feature_bytes.size() - 1));
  ExpectOnDemandError(dir, {"features.bin", "truncated"});
  write(features, feature_bytes + "x");
  ExpectOnDemandError(dir, {"features.bin", "trailing bytes"});
  write(features, feature_bytes);
  write(patches, patch_bytes.substr(0, 20));
  ExpectOnDemandError(dir, {"patches.bin", "bad magic or truncated header"});
  fs::remove(patches);
  ExpectOnDemandError(dir, {"patches.bin", "missing"});
  write(patches, patch_bytes);

  // Files that go bad after the load are named when a milestone's features are read.
  TeachMap lazy = LoadTeachMap(dir.string(), MapLoading::kOnDemand);
  Milestone& last = lazy.milestones.back();
  ASSERT_GT(last.feature_count(), 0u);
  std::string nan = feature_bytes;
  const double quiet_nan = std::nan("");
  nan.replace(nan.size() - 8, 8, reinterpret_cast<const char*>(&quiet_nan), 8);
  write(features, nan);
  ExpectFeatureError(&last, {"LoadFeatures: ", "features.bin", "non-finite"});
  write(patches, patch_bytes.substr(0, patch_bytes.size() - 5));
  write(features, feature_bytes);
  ExpectFeatureError(&last, {"LoadFeatures: ", "patches.bin", "truncated"});
  fs::remove_all(dir);
}

TEST(TeachMapOnDiskTest, ASpillThatCannotWriteSaysSoAndKeepsTheImageAndFeatures) {
  const fs::path dir = Scratch("spill_blocked");
  // Where the key image would go, a folder: the file cannot be opened for writing.
  fs::create_directories(dir / "key_images" / "000000.png");
  Milestone m;
  m.key_image = cv::Mat(480, 640, CV_8UC1, cv::Scalar(7));
  try {
    SpillKeyImage(dir.string(), 0, &m);
    ADD_FAILURE() << "spilling into a folder succeeded";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("SpillKeyImage: ", 0), 0u) << message;
    EXPECT_NE(message.find("000000.png"), std::string::npos) << message;
  }
  EXPECT_FALSE(m.key_image.empty());  // still held: nothing was lost
  EXPECT_TRUE(m.key_image_file.empty());

  // Where the features would go, a folder: the same.
  fs::create_directories(dir / "features.bin");
  m.features.resize(3);
  for (MilestoneFeature& f : m.features) f.patch = cv::Mat(11, 11, CV_8UC1, cv::Scalar(9));
  try {
    SpillFeatures(dir.string(), 0, 11, &m);
    ADD_FAILURE() << "spilling features into a folder succeeded";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("SpillFeatures: ", 0), 0u) << message;
    EXPECT_NE(message.find("features.bin"), std::string::npos) << message;
  }
  EXPECT_EQ(m.features.size(), 3u);
  EXPECT_FALSE(m.features_file.has_value());
  // ... and a spill after features the file does not hold.
  fs::remove_all(dir / "features.bin");
  try {
    SpillFeatures(dir.string(), 5, 11, &m);
    ADD_FAILURE() << "spilling after missing features succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("fewer than 5 records"), std::string::npos) << e.what();
  }
  EXPECT_EQ(m.features.size(), 3u);
  fs::remove_all(dir);
}

TEST(TeachMapOnDiskTest, RepeatersDriveTheSameFromAMapOnDiskHoldingTwoKeyImages) {
  const CorridorScene scene;
  for (const TeachMode mode : {TeachMode::k2d, TeachMode::k3d}) {
    SCOPED_TRACE(ToString(mode));
    const fs::path dir = Scratch(std::string("repeat_") + ToString(mode));
    SaveTeachMap(TeachStraight(mode, 81), dir.string());
    FunnelLaneOptions o2;
    o2.forward_speed_mps = 0.2;
    Localizer3dOptions o3;
    o3.forward_speed_mps = 0.2;
    const auto all = MakeRepeater(ToString(mode), LoadTeachMap(dir.string()), o2, o3);
    const auto lazy =
        MakeRepeater(ToString(mode), LoadTeachMap(dir.string(), MapLoading::kOnDemand), o2, o3);
    Pose2 pose{0.0, 0.05, 0.02};
    int frames = 0, most_held = 0, most_features_held = 0;
    for (; frames < 150; ++frames) {
      const cv::Mat image = scene.Render(CameraPose(pose));
      const RepeatCommand a = all->Update(image, 0.1 * frames);
      const RepeatCommand b = lazy->Update(image, 0.1 * frames);
      ASSERT_EQ(a.milestone, b.milestone) << "frame " << frames;
      ASSERT_EQ(a.twist.v_mps, b.twist.v_mps) << "frame " << frames;
      ASSERT_EQ(a.twist.yaw_rate_radps, b.twist.yaw_rate_radps) << "frame " << frames;
      ASSERT_EQ(a.status, b.status);
      most_held = std::max(most_held, KeyImagesHeld(lazy->map()));
      most_features_held = std::max(most_features_held, FeaturesHeld(lazy->map()));
      if (a.status != RepeatStatus::kDriving) break;
      pose = navigation::IntegrateTwist(pose, a.twist, 0.1);
    }
    std::printf(
        "%s: %d frames, %zu milestones, at most %d key images and %d milestones' "
        "features held\n",
        ToString(mode), frames, all->map().milestones.size(), most_held, most_features_held);
    EXPECT_EQ(KeyImagesHeld(all->map()), static_cast<int>(all->map().milestones.size()));
    EXPECT_GE(lazy->map().milestones.size(), 5u);
    EXPECT_LE(most_held, 2);
    EXPECT_LE(most_features_held, 2);
    EXPECT_GE(most_features_held, 1);
    fs::remove_all(dir);
  }
}

}  // namespace
}  // namespace trackbed::teach_repeat
