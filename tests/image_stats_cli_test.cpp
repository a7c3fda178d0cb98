// `trackbed image-stats` on constructed folders: the three layouts it reads, the table,
// the JSON and CSV it writes with their known figures, the selection flags, and its
// errors (apps/image_stats_command.h; docs/image_statistics.md).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using trackbed::testing_cli::RunTrackbed;

fs::path TestDir(const std::string& what) {
  return trackbed::testing_cli::FreshTempDir(
      "trackbed_image_stats_cli_",
      std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" + what);
}

std::string Quoted(const fs::path& p) { return "'" + p.string() + "'"; }

// `frames` images 000000.png … in `dir`: 12 × 12 squares (grey 200 on 40, blurred σ = 1
// px) in the top band only, two of them, moving 1 px right per frame.
void WriteSquares(const fs::path& dir, int frames) {
  fs::create_directories(dir);
  for (int k = 0; k < frames; ++k) {
    cv::Mat image(160, 300, CV_8UC1, cv::Scalar(40));
    image(cv::Rect(20 + k, 10, 12, 12)).setTo(200);
    image(cv::Rect(80 + k, 14, 12, 12)).setTo(200);
    cv::GaussianBlur(image, image, cv::Size(0, 0), 1.0);
    char name[16];
    std::snprintf(name, sizeof(name), "%06d.png", k);
    ASSERT_TRUE(cv::imwrite((dir / name).string(), image));
  }
}

TEST(ImageStatsCliTest, ReadsTheThreeLayoutsAndWritesTheFigures) {
  const fs::path d = TestDir("layouts");
  WriteSquares(d / "run" / "images" / "image_0", 11);  // a run folder
  WriteSquares(d / "kitti" / "image_0", 11);           // a KITTI sequence
  WriteSquares(d / "pngs", 11);                        // PNG images
  const auto r = RunTrackbed("image-stats " + Quoted(d / "run") + " " + Quoted(d / "kitti") + " " +
                                 Quoted(d / "pngs") + " --json " + Quoted(d / "s.json") +
                                 " --csv " + Quoted(d / "s.csv"),
                             d / "io");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stdout_text.find("FAST corners"), std::string::npos) << r.stdout_text;
  EXPECT_NE(r.stdout_text.find("000000.png .. 000010.png"), std::string::npos) << r.stdout_text;
  std::ifstream in(d / "s.json");
  const json j = json::parse(in);
  EXPECT_EQ(j["options"]["bands"], 4);
  EXPECT_EQ(j["selection"]["every"], 5);
  ASSERT_EQ(j["folders"].size(), 3u);
  for (const json& folder : j["folders"]) {
    EXPECT_EQ(folder["images"], json({"000000.png", "000005.png", "000010.png"}));
    EXPECT_EQ(folder["image_size"], json({300, 160}));
    const json& top = folder["bands"][0];
    EXPECT_EQ(top["rows"], json({0, 40}));
    EXPECT_EQ(top["fast_corners"], 8.0);  // two squares' 4 corners
    EXPECT_EQ(top["shi_tomasi_corners"], 8.0);
    EXPECT_GE(top["track_share"].get<double>(), 0.99);  // into the next frame, 1 px on
    // The last image (000010.png) has no next one: its mean is over the other two.
    const json& flat = folder["bands"][2];
    EXPECT_EQ(flat["mean_gradient"], 0.0);
    EXPECT_EQ(flat["grey_mean"], 40.0);
    EXPECT_TRUE(flat["spectrum_slope"].is_null());
    EXPECT_TRUE(flat["track_share"].is_null());
  }
  const std::string csv = trackbed::testing_cli::Slurp(d / "s.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "folder,band,row_begin,row_end,images,fast_corners,shi_tomasi_corners,"
            "mean_gradient,spectrum_slope,grey_mean,grey_std,track_share");
  // Band 3 of each folder: flat, its slope and track share undefined (empty).
  EXPECT_NE(csv.find(",3,80,120,3,0,0,0,,40,0,\n"), std::string::npos) << csv;
}

TEST(ImageStatsCliTest, SelectionAndBandsFollowTheFlags) {
  const fs::path d = TestDir("flags");
  WriteSquares(d / "pngs", 8);
  const auto r =
      RunTrackbed("image-stats " + Quoted(d / "pngs") +
                      " --every 2 --first 1 --count 3 --bands 2 --json " + Quoted(d / "s.json"),
                  d / "io");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  std::ifstream in(d / "s.json");
  const json j = json::parse(in);
  EXPECT_EQ(j["folders"][0]["images"], json({"000001.png", "000003.png", "000005.png"}));
  ASSERT_EQ(j["folders"][0]["bands"].size(), 2u);
  EXPECT_EQ(j["folders"][0]["bands"][1]["rows"], json({80, 160}));
  EXPECT_EQ(j["folders"][0]["bands"][0]["fast_corners"], 8.0);
}

TEST(ImageStatsCliTest, ErrorsNameTheFolderOrTheFlag) {
  const fs::path d = TestDir("errors");
  fs::create_directories(d / "empty");
  auto r = RunTrackbed("image-stats " + Quoted(d / "empty"), d / "io1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(
      r.stderr_text.find("trackbed image-stats: " + (d / "empty").string() + ": no PNG image"),
      std::string::npos)
      << r.stderr_text;
  WriteSquares(d / "pngs", 3);
  r = RunTrackbed("image-stats " + Quoted(d / "pngs") + " --every 0", d / "io2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("trackbed image-stats: --every: must be >= 1 (got 0)"),
            std::string::npos)
      << r.stderr_text;
  r = RunTrackbed("image-stats " + Quoted(d / "pngs") + " --bands 30", d / "io3");
  EXPECT_EQ(r.exit_code, 2);  // 160 rows cannot hold 30 bands of 8 rows
  EXPECT_NE(r.stderr_text.find("30 bands"), std::string::npos) << r.stderr_text;
  r = RunTrackbed("image-stats " + Quoted(d / "pngs") + " --evrey 2", d / "io4");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.stderr_text.find("unknown option '--evrey'; did you mean '--every'?"),
            std::string::npos)
      << r.stderr_text;
}

}  // namespace
