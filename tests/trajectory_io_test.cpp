// Trajectory files: TUM / KITTI / EuRoC readers and writers (round trips), format
// detection, nanosecond times, errors that name file and line, and association.
#include "trackbed/estimation/trajectory_io.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "real_data.h"

namespace trackbed::estimation {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

fs::path TempDir() {
  const fs::path d = fs::temp_directory_path() / "trackbed_trajectory_io_test";
  fs::create_directories(d);
  return d;
}

fs::path WriteText(const std::string& name, const std::string& text) {
  const fs::path p = TempDir() / name;
  std::ofstream(p) << text;
  return p;
}

fs::path RealTrajectories() { return trackbed::testing_data::RealData("trajectories"); }

Trajectory RandomTrajectory(std::mt19937& rng, int n) {
  std::normal_distribution<double> g(0.0, 1.0);
  Trajectory out;
  double t = 1311868164.25;
  for (int k = 0; k < n; ++k) {
    StampedPose p;
    t += 0.03 + 0.01 * std::abs(g(rng));
    p.t_s = std::round(t * 1e6) / 1e6;  // TUM keeps microseconds
    p.T_world_body.linear() =
        Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    p.T_world_body.translation() = 30.0 * Eigen::Vector3d(g(rng), g(rng), g(rng));
    out.push_back(p);
  }
  return out;
}

// Message of the std::runtime_error that f throws (empty if none).
template <typename F>
std::string ErrorOf(F&& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(TrajectoryIoTest, TumRoundTrip) {
  std::mt19937 rng(1);
  const Trajectory original = RandomTrajectory(rng, 50);
  const fs::path p = TempDir() / "round_trip.tum";
  WriteTum(p, original);
  EXPECT_EQ(DetectFormat(p), TrajectoryFormat::kTum);
  const LoadedTrajectory read = ReadTrajectory(p);
  EXPECT_EQ(read.format, TrajectoryFormat::kTum);
  EXPECT_FALSE(read.indexed);
  EXPECT_FALSE(read.converted_from_ns);
  ASSERT_EQ(read.poses.size(), original.size());
  for (std::size_t k = 0; k < original.size(); ++k) {
    EXPECT_NEAR(read.poses[k].t_s, original[k].t_s, 1e-6);
    EXPECT_LT(
        (read.poses[k].T_world_body.translation() - original[k].T_world_body.translation()).norm(),
        1e-6);
    EXPECT_LT((read.poses[k].T_world_body.linear() - original[k].T_world_body.linear()).norm(),
              1e-7);
  }
}

TEST(TrajectoryIoTest, KittiRoundTripIsExactWithAndWithoutTimes) {
  std::mt19937 rng(2);
  const Trajectory original = RandomTrajectory(rng, 30);
  const fs::path poses = TempDir() / "round_trip_kitti.txt";
  const fs::path times = TempDir() / "round_trip_times.txt";
  WriteKitti(poses, original, times);
  EXPECT_EQ(DetectFormat(poses), TrajectoryFormat::kKitti);

  const LoadedTrajectory timed = ReadTrajectory(poses, std::nullopt, times);
  EXPECT_FALSE(timed.indexed);
  ASSERT_EQ(timed.poses.size(), original.size());
  for (std::size_t k = 0; k < original.size(); ++k) {
    EXPECT_EQ(timed.poses[k].T_world_body.matrix(), original[k].T_world_body.matrix());
    EXPECT_NEAR(timed.poses[k].t_s, original[k].t_s, 1e-9 * original[k].t_s);
  }

  const LoadedTrajectory indexed = ReadTrajectory(poses);
  EXPECT_TRUE(indexed.indexed);
  ASSERT_EQ(indexed.poses.size(), original.size());
  for (std::size_t k = 0; k < original.size(); ++k) {
    EXPECT_EQ(indexed.poses[k].t_s, static_cast<double>(k));
    EXPECT_EQ(indexed.poses[k].T_world_body.matrix(), original[k].T_world_body.matrix());
  }
}

TEST(TrajectoryIoTest, DetectsFormatsFromContent) {
  EXPECT_EQ(DetectFormat(WriteText("d1.txt", "# comment\n\n1.0 0 0 0 0 0 0 1\n")),
            TrajectoryFormat::kTum);
  EXPECT_EQ(DetectFormat(WriteText("d2.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n")),
            TrajectoryFormat::kKitti);
  EXPECT_EQ(DetectFormat(WriteText("d3.csv",
                                   "#timestamp [ns],x,y,z,qw,qx,qy,qz\n"
                                   "1403715524907143168,1,2,3,1,0,0,0,0,0,0\n")),
            TrajectoryFormat::kEuroc);
  const std::string err = ErrorOf([] { DetectFormat(WriteText("d4.txt", "# c\n1 2 3 4 5\n")); });
  EXPECT_NE(err.find("d4.txt:2: cannot detect the format: 5 fields"), std::string::npos) << err;
  EXPECT_NE(
      ErrorOf([] { DetectFormat(WriteText("d5.txt", "# only comments\n")); }).find("no poses"),
      std::string::npos);
  EXPECT_NE(ErrorOf([] { DetectFormat(TempDir() / "missing.txt"); }).find("cannot open"),
            std::string::npos);
}

TEST(TrajectoryIoRealDataTest, DetectsTheBenchmarkFiles) {
  TRACKBED_NEEDS_REAL_DATA(RealTrajectories());
  const fs::path d = RealTrajectories();
  EXPECT_EQ(DetectFormat(d / "KITTI_00_gt.txt"), TrajectoryFormat::kKitti);
  EXPECT_EQ(DetectFormat(d / "KITTI_00_SPTAM.txt"), TrajectoryFormat::kKitti);
  EXPECT_EQ(DetectFormat(d / "fr2_desk_groundtruth.txt"), TrajectoryFormat::kTum);
  EXPECT_EQ(DetectFormat(d / "V102.txt"), TrajectoryFormat::kTum);
  EXPECT_EQ(DetectFormat(d / "V102_groundtruth.csv"), TrajectoryFormat::kEuroc);
  const LoadedTrajectory kitti =
      ReadTrajectory(d / "KITTI_00_gt.txt", std::nullopt, d / "KITTI_00_gt_times.txt");
  EXPECT_EQ(kitti.poses.size(), 4541u);
  EXPECT_FALSE(kitti.indexed);
  EXPECT_NEAR(kitti.poses[1].t_s, 0.1037359, 1e-9);
  const LoadedTrajectory euroc = ReadTrajectory(d / "V102_groundtruth.csv");
  ASSERT_EQ(euroc.poses.size(), 16702u);
  // First row: 1403715524907143168 ns, p = (0.515356, 1.996773, 0.971104),
  // q (w first) = (0.161996, 0.789985, -0.205376, 0.554528).
  EXPECT_NEAR(euroc.poses[0].t_s, 1403715524.907143168, 1e-6);
  EXPECT_TRUE(euroc.poses[0].T_world_body.translation().isApprox(
      Eigen::Vector3d(0.515356, 1.996773, 0.971104)));
  const Eigen::Quaterniond q(euroc.poses[0].T_world_body.linear());
  EXPECT_NEAR(std::abs(q.w()), 0.161996, 1e-5);
  EXPECT_NEAR(std::abs(q.x()), 0.789985, 1e-5);
}

TEST(TrajectoryIoTest, EurocQuaternionIsWFirst) {
  // A 90° yaw: (w, x, y, z) = (cos 45°, 0, 0, sin 45°).
  const double c = std::sqrt(0.5);
  const fs::path p =
      WriteText("yaw.csv",
                "#timestamp [ns], p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], "
                "q_RS_y [], q_RS_z []\n2000000000,1,2,3," +
                    std::to_string(c) + ",0,0," + std::to_string(c) + "\n");
  const LoadedTrajectory t = ReadTrajectory(p);
  EXPECT_EQ(t.format, TrajectoryFormat::kEuroc);
  ASSERT_EQ(t.poses.size(), 1u);
  EXPECT_EQ(t.poses[0].t_s, 2.0);
  EXPECT_LT((t.poses[0].T_world_body.linear() -
             Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitZ()).toRotationMatrix())
                .norm(),
            1e-6);
}

TEST(TrajectoryIoTest, NanosecondTumTimesAreConvertedToSeconds) {
  const fs::path p = WriteText("ns.tum",
                               "1403715524907143168 0 0 0 0 0 0 1\n"
                               "1403715525007143000 1 0 0 0 0 0 1\n");
  const LoadedTrajectory t = ReadTrajectory(p);
  EXPECT_TRUE(t.converted_from_ns);
  ASSERT_EQ(t.poses.size(), 2u);
  EXPECT_NEAR(t.poses[0].t_s, 1403715524.907143168, 1e-6);
  EXPECT_NEAR(t.poses[1].t_s - t.poses[0].t_s, 0.099999832, 1e-6);
  // Seconds stay seconds.
  EXPECT_FALSE(
      ReadTrajectory(WriteText("s.tum", "1403715524.9 0 0 0 0 0 0 1\n")).converted_from_ns);
  const std::string err = ErrorOf([] {
    ReadTrajectory(WriteText("mixed.tum",
                             "1403715524907143168 0 0 0 0 0 0 1\n"
                             "1403715525.0 0 0 0 0 0 0 1\n"));
  });
  EXPECT_NE(err.find("mixed.tum:2: time 1403715525.0 mixes nanosecond and second"),
            std::string::npos)
      << err;
}

TEST(TrajectoryIoTest, MalformedLinesAreNamedWithFileAndLine) {
  struct Case {
    const char* name;
    std::string text;
    std::optional<TrajectoryFormat> format;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"few.tum", "# header\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n", std::nullopt,
       "few.tum:3: expected 8 fields `t x y z qx qy qz qw` (TUM), got 7"},
      {"nan.tum", "1 0 0 0 0 0 0 1\n2 0 abc 0 0 0 0 1\n", std::nullopt,
       "nan.tum:2: bad y 'abc' (not a finite number)"},
      {"inf.tum", "1 0 0 inf 0 0 0 1\n", std::nullopt, "inf.tum:1: bad z 'inf'"},
      {"quat.tum", "1 0 0 0 0 0 0 0.5\n", std::nullopt, "quat.tum:1: quaternion norm 0.5 is not 1"},
      {"kitti.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1\n", TrajectoryFormat::kKitti,
       "kitti.txt:2: 11 numbers, expected 12"},
      {"kitti_rot.txt", "2 0 0 0 0 1 0 0 0 0 1 0\n", std::nullopt,
       "kitti_rot.txt:1: the 3x3 block is not a rotation"},
      {"euroc.csv", "#t,x,y,z,qw,qx,qy,qz\n1,2,3,4,1,0,0,0\n5,6,7\n", TrajectoryFormat::kEuroc,
       "euroc.csv:3: expected at least 8 comma-separated fields"},
      {"as_tum.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n", TrajectoryFormat::kTum,
       "as_tum.txt:1: expected 8 fields"},
      {"empty.tum", "# nothing\n", TrajectoryFormat::kTum, "empty.tum: no poses"},
  };
  for (const Case& c : cases) {
    const fs::path p = WriteText(c.name, c.text);
    const std::string err = ErrorOf([&] { ReadTrajectory(p, c.format); });
    EXPECT_NE(err.find(c.expected), std::string::npos) << c.name << ": got '" << err << "'";
    EXPECT_NE(err.find(p.string()), std::string::npos) << c.name << ": " << err;
  }
}

TEST(TrajectoryIoTest, KittiTimesMustMatchThePoses) {
  const fs::path poses = WriteText("k2.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 1 0 1 0 0 0 0 1 0\n");
  const fs::path times = WriteText("k2_times.txt", "0.0\n0.1\n0.2\n");
  const std::string err = ErrorOf([&] { ReadTrajectory(poses, std::nullopt, times); });
  EXPECT_NE(err.find("k2_times.txt:3: has 3 times for 2 poses in"), std::string::npos) << err;
  const fs::path bad = WriteText("k2_bad_times.txt", "0.0\nx\n");
  EXPECT_NE(ErrorOf([&] {
              ReadTrajectory(poses, std::nullopt, bad);
            }).find("k2_bad_times.txt:2: bad time 'x'"),
            std::string::npos);
  // A times file only makes sense for KITTI.
  const fs::path tum = WriteText("t.tum", "1 0 0 0 0 0 0 1\n");
  EXPECT_THROW(ReadTrajectory(tum, std::nullopt, times), std::invalid_argument);
}

TEST(TrajectoryIoTest, FormatNames) {
  EXPECT_EQ(ParseFormatName("tum"), TrajectoryFormat::kTum);
  EXPECT_EQ(ParseFormatName("KITTI"), TrajectoryFormat::kKitti);
  EXPECT_EQ(ParseFormatName("euroc"), TrajectoryFormat::kEuroc);
  EXPECT_STREQ(FormatName(TrajectoryFormat::kEuroc), "euroc");
  EXPECT_THROW(ParseFormatName("bag"), std::invalid_argument);
}

Trajectory AtTimes(const std::vector<double>& times) {
  Trajectory t;
  for (double s : times) {
    StampedPose p;
    p.t_s = s;
    p.T_world_body.translation().x() = s;
    t.push_back(p);
  }
  return t;
}

TEST(AssociateTest, NearestTimestampsEachPoseUsedOnce) {
  const Trajectory a = AtTimes({0.00, 0.10, 0.20, 0.30, 0.40});
  // 0.105 is nearer to 0.10 than 0.094, so 0.094 stays unmatched; 0.33 is beyond max_dt.
  const Trajectory b = AtTimes({0.005, 0.094, 0.105, 0.21, 0.33, 0.401});
  const Association m = Associate(a, b, 0.02);
  ASSERT_EQ(m.indices.size(), 4u);
  EXPECT_FALSE(m.by_index);
  const std::vector<std::pair<std::size_t, std::size_t>> expected = {
      {0, 0}, {1, 2}, {2, 3}, {4, 5}};
  EXPECT_EQ(m.indices, expected);
  ASSERT_EQ(m.gt.size(), 4u);
  EXPECT_EQ(m.gt[1].t_s, 0.10);
  EXPECT_EQ(m.est[1].t_s, 0.105);  // estimates keep their own times
}

TEST(AssociateTest, OffsetShiftsTheSecondTrajectory) {
  const Trajectory a = AtTimes({10.0, 10.1, 10.2});
  const Trajectory b = AtTimes({0.0, 0.1, 0.2});
  EXPECT_TRUE(Associate(a, b).indices.empty());
  const Association m = Associate(a, b, 0.02, 10.0);
  EXPECT_EQ(m.indices.size(), 3u);
  EXPECT_THROW(Associate(a, b, -1.0), std::invalid_argument);
}

TEST(AssociateTest, UnsortedInputStillAssociates) {
  const Trajectory a = AtTimes({0.3, 0.1, 0.2});
  const Trajectory b = AtTimes({0.201, 0.301, 0.101});
  const Association m = Associate(a, b);
  ASSERT_EQ(m.indices.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(m.gt[k].t_s, m.est[k].t_s, 0.002);
  EXPECT_LT(m.gt[0].t_s, m.gt[1].t_s);  // sorted by the first trajectory's time
}

TEST(AssociateTest, IndexedTrajectoriesAreAssociatedByIndex) {
  LoadedTrajectory a, b;
  a.poses = AtTimes({0, 1, 2, 3});
  b.poses = AtTimes({0, 1, 2});
  a.indexed = true;
  const Association m = Associate(a, b);
  EXPECT_TRUE(m.by_index);
  EXPECT_EQ(m.indices.size(), 3u);
  EXPECT_EQ(m.indices.back(), std::make_pair(std::size_t{2}, std::size_t{2}));
}

}  // namespace
}  // namespace trackbed::estimation
