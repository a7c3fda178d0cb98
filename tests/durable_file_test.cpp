// Durable files: written whole through a temporary file, synced, errors naming the file.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/common/durable_file.h"
#include "trackbed/runner/run_folder.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("trackbed_durable_file_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string Read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(DurableFileTest, ReplacesTheFileWholeAndLeavesNoTemporary) {
  const fs::path dir = FreshDir("replace");
  WriteFileAtomically(dir / "a.json", "old\n");
  WriteFileAtomically(dir / "a.json", std::string(1 << 20, 'x'));  // more than one write
  EXPECT_EQ(Read(dir / "a.json"), std::string(1 << 20, 'x'));
  EXPECT_FALSE(fs::exists(dir / "a.json.tmp"));
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
}

TEST(DurableFileTest, AFileThatCannotBeWrittenIsNamed) {
  const fs::path dir = FreshDir("missing");
  try {
    WriteFileAtomically(dir / "no_such_folder" / "metrics.json", "{}\n");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_folder/metrics.json.tmp: cannot create"),
              std::string::npos)
        << e.what();
  }
}

TEST(DurableFileTest, SyncsAFolderTreeAndNamesAMissingOne) {
  const fs::path dir = FreshDir("tree");
  fs::create_directories(dir / "teach" / "images");
  std::ofstream(dir / "teach" / "images" / "000000.png") << "png";
  std::ofstream(dir / "ground_truth.tum") << "0 0 0 0 0 0 0 1\n";
  EXPECT_NO_THROW(SyncFolder(dir));
  EXPECT_EQ(Read(dir / "ground_truth.tum"), "0 0 0 0 0 0 0 1\n");
  EXPECT_THROW(SyncFolder(dir / "gone"), std::runtime_error);
}

// The durable steps taken while the hook is set.
std::vector<std::pair<std::string, fs::path>> steps;

void Record(const char* step, const fs::path& path) { steps.emplace_back(step, path); }

class DurableStepsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    steps.clear();
    SetDurableStepHookForTesting(&Record);
  }
  void TearDown() override { SetDurableStepHookForTesting(nullptr); }
};

TEST_F(DurableStepsTest, TheTemporaryIsOnDiskBeforeTheRenameAndTheFolderAfter) {
  const fs::path dir = FreshDir("order");
  WriteFileAtomically(dir / "cell.json", "{}\n");
  const std::vector<std::pair<std::string, fs::path>> expected = {
      {"sync", dir / "cell.json.tmp"}, {"rename", dir / "cell.json"}, {"sync", dir}};
  EXPECT_EQ(steps, expected);
}

TEST_F(DurableStepsTest, ARunsFilesAreOnDiskBeforeItsMetricsSayItFinished) {
  const fs::path dir = FreshDir("run");
  fs::create_directories(dir / "teach");
  std::ofstream(dir / "ground_truth.tum") << "0 0 0 0 0 0 0 1\n";
  std::ofstream(dir / "teach" / "encoders.csv") << "t,left_ticks,right_ticks\n";
  runner::RunMetrics m;
  m.stop_reason = "duration reached";
  runner::WriteMetricsJson(m, dir);
  std::size_t rename = steps.size();
  for (std::size_t k = 0; k < steps.size(); ++k) {
    if (steps[k].first == "rename") rename = k;
  }
  ASSERT_LT(rename, steps.size());
  EXPECT_EQ(steps[rename].second, dir / "metrics.json");
  const auto synced_before = [&](const fs::path& p) {
    for (std::size_t k = 0; k < rename; ++k) {
      if (steps[k] == std::make_pair(std::string("sync"), p)) return true;
    }
    return false;
  };
  EXPECT_TRUE(synced_before(dir / "ground_truth.tum"));
  EXPECT_TRUE(synced_before(dir / "teach" / "encoders.csv"));
  EXPECT_TRUE(synced_before(dir / "teach"));
  EXPECT_TRUE(synced_before(dir / "metrics.json.tmp"));
}

}  // namespace
}  // namespace trackbed
