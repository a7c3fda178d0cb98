// KITTI-layout sequences: the real kitti06 frames, writer→reader round trips, pose-line
// round trips, and the errors malformed folders must raise (with the file named).
#include "trackbed/perception/kitti_sequence.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "real_data.h"

namespace trackbed::perception {
namespace {

namespace fs = std::filesystem;

fs::path RealKittiDir() { return trackbed::testing_data::RealData("kitti06"); }

/// A rectified pair with these intrinsics [px] and baseline [m] (no image size).
geometry::StereoCamera Camera(double fx, double fy, double cx, double cy, double baseline_m) {
  geometry::StereoCamera c;
  c.left.fx = fx;
  c.left.fy = fy;
  c.left.cx = cx;
  c.left.cy = cy;
  c.baseline_m = baseline_m;
  return c;
}

Eigen::Isometry3d RandomPose(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = 50.0 * Eigen::Vector3d(n(rng), n(rng), n(rng));
  return T;
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::trunc);
  out << text;
}

/// Replaces line `line_no` (1-based) of a text file.
void ReplaceLine(const fs::path& path, int line_no, const std::string& replacement) {
  std::istringstream in(ReadText(path));
  std::string line, out;
  for (int k = 1; std::getline(in, line); ++k) out += (k == line_no ? replacement : line) + "\n";
  WriteText(path, out);
}

/// Expects `f` to throw E with a message containing every one of `parts`.
template <typename E>
void ExpectThrowWith(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch (const E& e) {
    const std::string what = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(what.find(part), std::string::npos) << "'" << part << "' not in: " << what;
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "unexpected exception type: " << e.what();
  }
}

class KittiSequenceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("trackbed_kitti_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// A small synthetic sequence in dir_/seq; returns its folder.
  fs::path WriteSynthetic(int frames) {
    const fs::path seq = dir_ / "seq";
    std::mt19937 rng(5);
    KittiWriter writer(seq, calibration_);
    cv::RNG image_rng(11);
    for (int k = 0; k < frames; ++k) {
      cv::Mat left(24, 32, CV_8UC1), right(24, 32, CV_8UC1);
      image_rng.fill(left, cv::RNG::UNIFORM, 0, 256);
      image_rng.fill(right, cv::RNG::UNIFORM, 0, 256);
      writer.Add(0.1 * k, left, right, RandomPose(rng));
    }
    writer.Close();
    return seq;
  }

  fs::path dir_;
  geometry::StereoCamera calibration_ = Camera(400.125, 401.5, 319.75, 239.25, 0.12);
};

// The same, on the real KITTI 06 excerpt (tests/real_data.h).
class KittiSequenceRealDataTest : public KittiSequenceTest {};

TEST_F(KittiSequenceRealDataTest, Kitti06Reads) {
  TRACKBED_NEEDS_REAL_DATA(RealKittiDir());
  const KittiSequence sequence(RealKittiDir());
  ASSERT_EQ(sequence.size(), 51u);
  EXPECT_EQ(sequence.image_size(), cv::Size(1226, 370));
  const geometry::StereoCamera& c = sequence.calibration();
  EXPECT_NEAR(c.left.fx, 707.0912, 1e-9);
  EXPECT_NEAR(c.left.fy, 707.0912, 1e-9);
  EXPECT_NEAR(c.left.cx, 601.8873, 1e-9);
  EXPECT_NEAR(c.left.cy, 183.1104, 1e-9);
  EXPECT_EQ(c.left.width_px, 1226);
  EXPECT_EQ(c.left.height_px, 370);
  EXPECT_NEAR(c.baseline_m, 0.537, 1e-3);
  EXPECT_NEAR(c.baseline_m, 379.8145 / 707.0912, 1e-12);

  ASSERT_EQ(sequence.times_s().size(), 51u);
  EXPECT_EQ(sequence.times_s().front(), 0.0);
  EXPECT_NEAR(sequence.times_s()[1], 0.1044989, 1e-12);
  for (std::size_t k = 1; k < sequence.size(); ++k) {
    EXPECT_GT(sequence.times_s()[k], sequence.times_s()[k - 1]);
  }

  ASSERT_TRUE(sequence.has_poses());
  ASSERT_EQ(sequence.poses().size(), 51u);
  EXPECT_TRUE(sequence.poses().front().matrix().isApprox(Eigen::Matrix4d::Identity(), 1e-9));
  const Eigen::Vector3d p_last = sequence.poses().back().translation();
  EXPECT_NEAR(p_last.z(), 59.83857, 1e-9);  // camera z forward: the car drives ahead
  double path_m = 0.0;
  for (std::size_t k = 1; k < sequence.size(); ++k) {
    path_m += (sequence.poses()[k].translation() - sequence.poses()[k - 1].translation()).norm();
  }
  EXPECT_NEAR(path_m, 59.9, 0.2);

  for (std::size_t k : {std::size_t{0}, std::size_t{50}}) {
    const cv::Mat left = sequence.LoadLeft(k), right = sequence.LoadRight(k);
    EXPECT_EQ(left.type(), CV_8UC1);
    EXPECT_EQ(right.type(), CV_8UC1);
    EXPECT_EQ(left.size(), cv::Size(1226, 370));
    EXPECT_EQ(right.size(), cv::Size(1226, 370));
    EXPECT_GT(cv::norm(left, right, cv::NORM_L1), 0.0);  // two different cameras
  }
  EXPECT_THROW(sequence.LoadLeft(51), std::out_of_range);
}

TEST_F(KittiSequenceRealDataTest, PosesInASeparateFileAsKittiKeepsThem) {
  TRACKBED_NEEDS_REAL_DATA(RealKittiDir());
  const fs::path poses_file = dir_ / "poses" / "06.txt";
  fs::create_directories(poses_file.parent_path());
  fs::copy_file(RealKittiDir() / "poses.txt", poses_file);
  const KittiSequence in_folder(RealKittiDir());
  const KittiSequence separate(RealKittiDir(), poses_file);
  ASSERT_EQ(separate.poses().size(), 51u);
  for (std::size_t k = 0; k < 51; ++k) {
    EXPECT_TRUE(separate.poses()[k].matrix() == in_folder.poses()[k].matrix());
  }
  ExpectThrowWith<std::runtime_error>([&] { KittiSequence(RealKittiDir(), dir_ / "nope.txt"); },
                                      {"nope.txt", "not found"});
}

TEST_F(KittiSequenceTest, WriterReaderRoundTrip) {
  const fs::path seq = dir_ / "out";
  std::mt19937 rng(42);
  cv::RNG image_rng(7);
  std::vector<cv::Mat> lefts, rights;
  std::vector<Eigen::Isometry3d> poses;
  std::vector<double> times;
  {
    KittiWriter writer(seq, calibration_);
    for (int k = 0; k < 6; ++k) {
      cv::Mat left(48, 64, CV_8UC1), right(48, 64, CV_8UC1);
      image_rng.fill(left, cv::RNG::UNIFORM, 0, 256);
      image_rng.fill(right, cv::RNG::UNIFORM, 0, 256);
      const Eigen::Isometry3d T = k == 0 ? Eigen::Isometry3d::Identity() : RandomPose(rng);
      const double t = 1000.000123 + 0.1 * k + 1e-6 * k * k;
      writer.Add(t, left, right, T);
      lefts.push_back(left);
      rights.push_back(right);
      poses.push_back(T);
      times.push_back(t);
    }
    EXPECT_EQ(writer.size(), 6u);
  }  // the destructor closes

  const KittiSequence sequence(seq);
  ASSERT_EQ(sequence.size(), 6u);
  EXPECT_EQ(sequence.image_size(), cv::Size(64, 48));
  const geometry::StereoCamera& read = sequence.calibration();
  EXPECT_LE((read.LeftProjection() - calibration_.LeftProjection()).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE((read.RightProjection() - calibration_.RightProjection()).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(read.baseline_m, 0.12, 1e-9);
  ASSERT_TRUE(sequence.has_poses());
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(cv::norm(sequence.LoadLeft(k), lefts[k], cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(sequence.LoadRight(k), rights[k], cv::NORM_INF), 0.0);
    EXPECT_LE((sequence.poses()[k].matrix() - poses[k].matrix()).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_NEAR(sequence.times_s()[k], times[k], 1e-6);
  }

  // KITTI's own number style, as KITTI's calib.txt files have it.
  const std::string calib = ReadText(seq / "calib.txt");
  EXPECT_EQ(calib.rfind("P0: 4.001250000000e+02 0.000000000000e+00 3.197500000000e+02 ", 0), 0u)
      << calib;
}

TEST_F(KittiSequenceTest, WriterReplacesAnExistingSequence) {
  WriteSynthetic(5);
  const fs::path seq = WriteSynthetic(3);
  EXPECT_EQ(KittiSequence(seq).size(), 3u);
}

TEST_F(KittiSequenceTest, WithoutPosesFileThereIsNoGroundTruth) {
  const fs::path seq = WriteSynthetic(3);
  fs::remove(seq / "poses.txt");
  const KittiSequence sequence(seq);
  EXPECT_EQ(sequence.size(), 3u);
  EXPECT_FALSE(sequence.has_poses());
  EXPECT_TRUE(sequence.poses().empty());
}

TEST_F(KittiSequenceTest, AcceptsRealKittiCalibAndTimesStyle) {
  const fs::path seq = WriteSynthetic(3);
  // Real KITTI calib.txt (sequence 00): P2, P3 and Tr lines are ignored.
  WriteText(seq / "calib.txt",
            "P0: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 0.000000000000e+00 "
            "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 "
            "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 0.000000000000e+00\n"
            "P1: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 -3.861448000000e+02 "
            "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 "
            "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 0.000000000000e+00\n"
            "P2: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 4.538225000000e+01 "
            "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 -1.130887000000e-01 "
            "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 3.779761000000e-03\n"
            "P3: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 -3.372877000000e+02 "
            "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 2.369057000000e+00 "
            "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 4.915215000000e-03\n"
            "Tr: 4.276802385584e-04 -9.999672484946e-01 -8.084491683471e-03 -1.198459927713e-02 "
            "-7.210626507497e-03 8.081198471645e-03 -9.999413164504e-01 -5.403984729748e-02 "
            "9.999738645903e-01 4.859485810390e-04 -7.206933692422e-03 -2.921968648686e-01\r\n");
  WriteText(seq / "times.txt", "0.000000e+00\n1.036224e-01\r\n2.072416e-01\n\n");
  const KittiSequence sequence(seq);
  EXPECT_NEAR(sequence.calibration().left.fx, 718.856, 1e-9);
  EXPECT_NEAR(sequence.calibration().baseline_m, 386.1448 / 718.856, 1e-12);
  EXPECT_NEAR(sequence.times_s()[2], 0.2072416, 1e-12);
}

TEST_F(KittiSequenceTest, MissingOrMalformedFilesThrowNamingTheFile) {
  const fs::path seq = WriteSynthetic(4);
  const auto open = [&] { KittiSequence s(seq); };
  const std::string calib = ReadText(seq / "calib.txt");
  const std::string times = ReadText(seq / "times.txt");
  const std::string poses = ReadText(seq / "poses.txt");
  const auto restore = [&] {
    WriteText(seq / "calib.txt", calib);
    WriteText(seq / "times.txt", times);
    WriteText(seq / "poses.txt", poses);
  };
  ASSERT_NO_THROW(open());

  ExpectThrowWith<std::runtime_error>([&] { KittiSequence s(dir_ / "absent"); },
                                      {"absent", "not a directory"});

  fs::remove(seq / "calib.txt");
  ExpectThrowWith<std::runtime_error>(open, {"calib.txt", "not found"});
  restore();

  // A P1 line with 11 numbers.
  ReplaceLine(seq / "calib.txt", 2, "P1: 4.0e+02 0 3.2e+02 -4.8e+01 0 4.0e+02 2.4e+02 0 0 0 1");
  ExpectThrowWith<std::runtime_error>(open, {"calib.txt:2", "P1 has 11 numbers"});
  restore();

  ReplaceLine(seq / "calib.txt", 1, "P0: 4.0e+02 0 3.2e+02 0 0 4.0e+02 2.4e+02 0 0 0 one 0");
  ExpectThrowWith<std::runtime_error>(open, {"calib.txt:1", "'one'"});
  restore();

  ReplaceLine(seq / "calib.txt", 2, "P2: 1 2 3");
  ExpectThrowWith<std::runtime_error>(open, {"calib.txt", "no P1"});
  restore();

  ReplaceLine(seq / "calib.txt", 2, "P1: 400.125 0 319.75 48 0 401.5 239.25 0 0 0 1 0");
  ExpectThrowWith<std::runtime_error>(open, {"calib.txt", "baseline"});
  restore();

  WriteText(seq / "times.txt", "0.0\n0.1\n0.2\n");
  ExpectThrowWith<std::runtime_error>(open, {"times.txt", "3 times for 4 images"});
  restore();

  ReplaceLine(seq / "times.txt", 2, "0.1s");
  ExpectThrowWith<std::runtime_error>(open, {"times.txt:2", "'0.1s'"});
  restore();

  ReplaceLine(seq / "times.txt", 3, "0.05");
  ExpectThrowWith<std::runtime_error>(open, {"times.txt:3", "decreases"});
  restore();

  WriteText(seq / "poses.txt", poses + FormatKittiPoseLine(Eigen::Isometry3d::Identity()) + "\n");
  ExpectThrowWith<std::runtime_error>(open, {"poses.txt", "5 poses for 4 images"});
  restore();

  ReplaceLine(seq / "poses.txt", 3, "1 0 0 0 0 1 0 0 0 0 1");
  ExpectThrowWith<std::runtime_error>(open, {"poses.txt:3", "11 numbers"});
  restore();

  fs::remove(seq / "image_1" / "000002.png");
  ExpectThrowWith<std::runtime_error>(open, {"image_1", "000002.png"});
  fs::copy_file(seq / "image_0" / "000002.png", seq / "image_1" / "000002.png");
  ASSERT_NO_THROW(open());

  // A corrupt image is found when it is loaded.
  WriteText(seq / "image_0" / "000003.png", "not a png");
  const KittiSequence sequence(seq);
  ExpectThrowWith<std::runtime_error>([&] { sequence.LoadLeft(3); }, {"image_0", "000003.png"});
  EXPECT_NO_THROW(sequence.LoadRight(3));
}

TEST_F(KittiSequenceTest, WriterRejectsBadInput) {
  geometry::StereoCamera bad = calibration_;
  bad.baseline_m = -0.1;
  EXPECT_THROW(KittiWriter(dir_ / "bad", bad), std::invalid_argument);
  bad = calibration_;
  bad.left.fy = 0.0;
  EXPECT_THROW(KittiWriter(dir_ / "bad", bad), std::invalid_argument);

  KittiWriter writer(dir_ / "w", calibration_);
  const cv::Mat gray(24, 32, CV_8UC1, cv::Scalar(9));
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  EXPECT_THROW(writer.Add(0.0, cv::Mat(24, 32, CV_8UC3, cv::Scalar::all(0)), gray, I),
               std::invalid_argument);
  EXPECT_THROW(writer.Add(0.0, gray, cv::Mat(20, 32, CV_8UC1, cv::Scalar(0)), I),
               std::invalid_argument);
  writer.Add(1.0, gray, gray, I);
  EXPECT_THROW(writer.Add(2.0, cv::Mat(20, 30, CV_8UC1, cv::Scalar(0)),
                          cv::Mat(20, 30, CV_8UC1, cv::Scalar(0)), I),
               std::invalid_argument);
  EXPECT_THROW(writer.Add(0.5, gray, gray, I), std::invalid_argument);  // time goes back
  writer.Close();
  writer.Close();  // idempotent
  EXPECT_THROW(writer.Add(3.0, gray, gray, I), std::logic_error);
  EXPECT_EQ(KittiSequence(dir_ / "w").size(), 1u);
}

TEST(KittiPoseLineTest, FormatParseRoundTripsExactly) {
  std::mt19937 rng(3);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Isometry3d T = RandomPose(rng);
    const Eigen::Isometry3d back = ParseKittiPoseLine(FormatKittiPoseLine(T));
    EXPECT_TRUE(back.matrix() == T.matrix()) << FormatKittiPoseLine(T);
  }
  EXPECT_EQ(FormatKittiPoseLine(Eigen::Isometry3d::Identity()), "1 0 0 0 0 1 0 0 0 0 1 0");
}

TEST(KittiPoseLineTest, ParsesRealKittiLines) {
  const Eigen::Isometry3d T = ParseKittiPoseLine(
      "0.9997987 0.01105266 -0.01674529 -0.981436 -0.01089512 0.9998958 0.009469924 "
      "-1.190278 0.01684822 -0.009285574 0.9998149 59.83857\r");
  EXPECT_EQ(T.translation(), Eigen::Vector3d(-0.981436, -1.190278, 59.83857));
  EXPECT_EQ(T.linear()(2, 1), -0.009285574);
  EXPECT_EQ(T.matrix().row(3), Eigen::RowVector4d(0, 0, 0, 1));
}

TEST(KittiPoseLineTest, RejectsMalformedLines) {
  ExpectThrowWith<std::invalid_argument>([] { ParseKittiPoseLine("1 0 0 0 0 1 0 0 0 0 1"); },
                                         {"ParseKittiPoseLine", "11 numbers"});
  ExpectThrowWith<std::invalid_argument>([] { ParseKittiPoseLine("1 0 0 0 0 1 0 0 0 0 1 0 5"); },
                                         {"13 numbers"});
  ExpectThrowWith<std::invalid_argument>([] { ParseKittiPoseLine("1 0 0 x 0 1 0 0 0 0 1 0"); },
                                         {"'x'"});
  ExpectThrowWith<std::invalid_argument>([] { ParseKittiPoseLine("1 0 0 nan 0 1 0 0 0 0 1 0"); },
                                         {"'nan'"});
  ExpectThrowWith<std::invalid_argument>([] { ParseKittiPoseLine("2 0 0 0 0 1 0 0 0 0 1 0"); },
                                         {"not a rotation"});
  ExpectThrowWith<std::invalid_argument>([] { ParseKittiPoseLine("-1 0 0 0 0 1 0 0 0 0 1 0"); },
                                         {"not a rotation"});
}

}  // namespace
}  // namespace trackbed::perception
