// KITTI-layout sequence reader and writer (see kitti_sequence.h).
#include "trackbed/perception/kitti_sequence.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <system_error>

#include <opencv2/imgcodecs.hpp>

namespace trackbed::perception {
namespace {

namespace fs = std::filesystem;

constexpr const char* kWhitespace = " \t\r\n\v\f";

/// Splits `text` on whitespace and parses every token as a finite double (C locale,
/// fixed or scientific). Returns false with a reason in `error` on a bad token.
bool ParseNumbers(const std::string& text, std::vector<double>* values, std::string* error) {
  values->clear();
  std::size_t pos = text.find_first_not_of(kWhitespace);
  while (pos != std::string::npos) {
    std::size_t end = text.find_first_of(kWhitespace, pos);
    if (end == std::string::npos) end = text.size();
    const char* first = text.data() + pos;
    const char* last = text.data() + end;
    // from_chars does not take a leading '+', which printf-style writers may emit.
    if (last - first > 1 && *first == '+') ++first;
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || ptr != last || !std::isfinite(value)) {
      *error = "'" + text.substr(pos, end - pos) + "' is not a finite number";
      return false;
    }
    values->push_back(value);
    pos = text.find_first_not_of(kWhitespace, end);
  }
  return true;
}

bool IsBlank(const std::string& line) {
  return line.find_first_not_of(kWhitespace) == std::string::npos;
}

std::string Trim(const std::string& text) {
  const std::size_t begin = text.find_first_not_of(kWhitespace);
  if (begin == std::string::npos) return {};
  return text.substr(begin, text.find_last_not_of(kWhitespace) - begin + 1);
}

std::string Where(const fs::path& file, int line) {
  return file.string() + ":" + std::to_string(line) + ": ";
}

std::string FrameName(std::size_t i) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%06zu.png", i);
  return buf;
}

/// True for KITTI frame names: six digits and ".png". Sets *index.
bool IsFrameName(const std::string& name, std::size_t* index) {
  if (name.size() != 10 || name.compare(6, 4, ".png") != 0) return false;
  std::size_t value = 0;
  for (int k = 0; k < 6; ++k) {
    const char c = name[static_cast<std::size_t>(k)];
    if (c < '0' || c > '9') return false;
    value = value * 10 + static_cast<std::size_t>(c - '0');
  }
  *index = value;
  return true;
}

/// Number of frames in `folder`: its NNNNNN.png files, which must run 000000…N-1.
std::size_t CountFrames(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    throw std::runtime_error("KittiSequence: " + folder.string() + " is not a directory");
  }
  std::vector<std::size_t> indices;
  for (const auto& entry : fs::directory_iterator(folder)) {
    std::size_t index = 0;
    if (IsFrameName(entry.path().filename().string(), &index)) indices.push_back(index);
  }
  std::sort(indices.begin(), indices.end());
  for (std::size_t k = 0; k < indices.size(); ++k) {
    if (indices[k] != k) {
      throw std::runtime_error("KittiSequence: " + (folder / FrameName(k)).string() +
                               " is missing (frames must be numbered consecutively from 0)");
    }
  }
  return indices.size();
}

/// The calibration as calib.txt holds it: KITTI's P0 (left) and P1 (right).
struct KittiProjections {
  Eigen::Matrix<double, 3, 4> P0 = Eigen::Matrix<double, 3, 4>::Zero();
  Eigen::Matrix<double, 3, 4> P1 = Eigen::Matrix<double, 3, 4>::Zero();
};

/// Empty if `c` is a rectified KITTI stereo pair P0 = K [I|0], P1 = K [I|t] with
/// t = (-fx b, 0, 0) and b > 0; otherwise the reason.
std::string CalibrationProblem(const KittiProjections& c) {
  if (!c.P0.allFinite() || !c.P1.allFinite()) return "P0/P1 must be finite";
  if (!(c.P0(0, 0) > 0.0) || !(c.P0(1, 1) > 0.0)) return "P0 must have fx > 0 and fy > 0";
  const double tol = 1e-9 * std::max(1.0, std::abs(c.P0(0, 0)));
  Eigen::Matrix<double, 1, 4> last_row;
  last_row << 0.0, 0.0, 1.0, 0.0;
  if ((c.P0.row(2) - last_row).cwiseAbs().maxCoeff() > tol || std::abs(c.P0(1, 0)) > tol) {
    return "P0 must be K [I | 0] with K upper triangular and K(2,2) = 1";
  }
  if (c.P0.col(3).cwiseAbs().maxCoeff() > tol) {
    return "P0 must be K [I | 0] (its last column must be zero)";
  }
  if ((c.P1.leftCols<3>() - c.P0.leftCols<3>()).cwiseAbs().maxCoeff() > tol) {
    return "P1 must share P0's K (rectified stereo)";
  }
  if (std::abs(c.P1(1, 3)) > tol || std::abs(c.P1(2, 3)) > tol) {
    return "P1's last column must be (-fx*baseline, 0, 0)";
  }
  if (!(-c.P1(0, 3) / c.P1(0, 0) > 0.0)) {
    return "P1 must have a positive baseline (P1(0,3) < 0)";
  }
  return {};
}

geometry::StereoCamera ReadCalibration(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw std::runtime_error("KittiSequence: " + path.string() + " not found");
  }
  std::ifstream in(path);
  if (!in) throw std::runtime_error("KittiSequence: cannot open " + path.string());
  KittiProjections calibration;
  bool have_p0 = false, have_p1 = false;
  std::string line;
  std::vector<double> values;
  std::string error;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (IsBlank(line)) continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) {
      throw std::runtime_error("KittiSequence: " + Where(path, line_no) +
                               "expected 'KEY: numbers'");
    }
    const std::string key = Trim(line.substr(0, colon));
    if (key != "P0" && key != "P1") continue;  // P2, P3, Tr, ...: not ours
    bool& have = key == "P0" ? have_p0 : have_p1;
    if (have) {
      throw std::runtime_error("KittiSequence: " + Where(path, line_no) + "duplicate " + key);
    }
    if (!ParseNumbers(line.substr(colon + 1), &values, &error)) {
      throw std::runtime_error("KittiSequence: " + Where(path, line_no) + key + ": " + error);
    }
    if (values.size() != 12) {
      throw std::runtime_error("KittiSequence: " + Where(path, line_no) + key + " has " +
                               std::to_string(values.size()) + " numbers, expected 12");
    }
    Eigen::Matrix<double, 3, 4>& P = key == "P0" ? calibration.P0 : calibration.P1;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) P(r, c) = values[static_cast<std::size_t>(4 * r + c)];
    }
    have = true;
  }
  if (!have_p0 || !have_p1) {
    throw std::runtime_error("KittiSequence: " + path.string() + ": no " + (have_p0 ? "P1" : "P0") +
                             " line");
  }
  const std::string problem = CalibrationProblem(calibration);
  if (!problem.empty()) {
    throw std::runtime_error("KittiSequence: " + path.string() + ": " + problem);
  }
  return geometry::StereoCamera::FromProjections(calibration.P0, calibration.P1);
}

std::vector<double> ReadTimes(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw std::runtime_error("KittiSequence: " + path.string() + " not found");
  }
  std::ifstream in(path);
  if (!in) throw std::runtime_error("KittiSequence: cannot open " + path.string());
  std::vector<double> times;
  std::string line;
  std::vector<double> values;
  std::string error;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (IsBlank(line)) continue;
    if (!ParseNumbers(line, &values, &error)) {
      throw std::runtime_error("KittiSequence: " + Where(path, line_no) + error);
    }
    if (values.size() != 1) {
      throw std::runtime_error("KittiSequence: " + Where(path, line_no) +
                               "expected one time [s], got " + std::to_string(values.size()) +
                               " numbers");
    }
    if (!times.empty() && values[0] < times.back()) {
      throw std::runtime_error("KittiSequence: " + Where(path, line_no) +
                               "time decreases from the previous line");
    }
    times.push_back(values[0]);
  }
  return times;
}

std::vector<Eigen::Isometry3d> ReadPoses(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("KittiSequence: cannot open " + path.string());
  std::vector<Eigen::Isometry3d> poses;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (IsBlank(line)) continue;
    try {
      poses.push_back(ParseKittiPoseLine(line));
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error("KittiSequence: " + Where(path, line_no) + e.what());
    }
  }
  return poses;
}

}  // namespace

// ---------------------------------------------------------------------------
// KittiSequence

KittiSequence::KittiSequence(const std::filesystem::path& dir,
                             const std::filesystem::path& poses_file)
    : dir_(dir) {
  std::error_code ec;
  if (!fs::is_directory(dir_, ec)) {
    throw std::runtime_error("KittiSequence: " + dir_.string() + " is not a directory");
  }
  calibration_ = ReadCalibration(dir_ / "calib.txt");

  const std::size_t left_count = CountFrames(dir_ / "image_0");
  const std::size_t right_count = CountFrames(dir_ / "image_1");
  if (left_count == 0) {
    throw std::runtime_error("KittiSequence: " + (dir_ / "image_0").string() +
                             " holds no NNNNNN.png images");
  }
  if (right_count != left_count) {
    throw std::runtime_error("KittiSequence: " + (dir_ / "image_1").string() + " holds " +
                             std::to_string(right_count) + " images but image_0 holds " +
                             std::to_string(left_count));
  }

  const fs::path times_path = dir_ / "times.txt";
  times_s_ = ReadTimes(times_path);
  if (times_s_.size() != left_count) {
    throw std::runtime_error("KittiSequence: " + times_path.string() + ": " +
                             std::to_string(times_s_.size()) + " times for " +
                             std::to_string(left_count) + " images");
  }

  fs::path poses_path = poses_file;
  if (!poses_path.empty()) {
    if (!fs::is_regular_file(poses_path, ec)) {
      throw std::runtime_error("KittiSequence: poses file " + poses_path.string() + " not found");
    }
  } else if (fs::is_regular_file(dir_ / "poses.txt", ec)) {
    poses_path = dir_ / "poses.txt";
  }
  if (!poses_path.empty()) {
    poses_ = ReadPoses(poses_path);
    if (poses_.size() != left_count) {
      throw std::runtime_error("KittiSequence: " + poses_path.string() + ": " +
                               std::to_string(poses_.size()) + " poses for " +
                               std::to_string(left_count) + " images");
    }
  }

  // The image size comes from frame 0; every later load is checked against it.
  const fs::path first = dir_ / "image_0" / FrameName(0);
  const cv::Mat image = cv::imread(first.string(), cv::IMREAD_GRAYSCALE);
  if (image.empty()) {
    throw std::runtime_error("KittiSequence: cannot read image " + first.string());
  }
  image_size_ = image.size();
  calibration_.left.width_px = image_size_.width;
  calibration_.left.height_px = image_size_.height;
}

cv::Mat KittiSequence::LoadLeft(std::size_t i) const { return Load("image_0", i); }

cv::Mat KittiSequence::LoadRight(std::size_t i) const { return Load("image_1", i); }

cv::Mat KittiSequence::Load(const char* folder, std::size_t i) const {
  if (i >= size()) {
    throw std::out_of_range("KittiSequence: frame " + std::to_string(i) + " out of range (" +
                            std::to_string(size()) + " frames)");
  }
  const fs::path path = dir_ / folder / FrameName(i);
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
  if (image.empty()) {
    throw std::runtime_error("KittiSequence: cannot read image " + path.string());
  }
  if (image.size() != image_size_) {
    throw std::runtime_error("KittiSequence: " + path.string() + " is " +
                             std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                             ", frame 0 is " + std::to_string(image_size_.width) + "x" +
                             std::to_string(image_size_.height));
  }
  return image;
}

// ---------------------------------------------------------------------------
// KittiWriter

KittiWriter::KittiWriter(const std::filesystem::path& dir, const geometry::StereoCamera& camera)
    : dir_(dir) {
  const KittiProjections calibration{camera.LeftProjection(), camera.RightProjection()};
  const std::string problem = CalibrationProblem(calibration);
  if (!problem.empty()) throw std::invalid_argument("KittiWriter: " + problem);

  for (const char* folder : {"image_0", "image_1"}) {
    const fs::path sub = dir_ / folder;
    std::error_code ec;
    fs::create_directories(sub, ec);
    if (ec || !fs::is_directory(sub)) {
      throw std::runtime_error("KittiWriter: cannot create " + sub.string() + ": " + ec.message());
    }
    // Replace an earlier sequence: stale frames beyond the new end would otherwise
    // make the folder inconsistent with times.txt.
    std::vector<fs::path> stale;
    for (const auto& entry : fs::directory_iterator(sub)) {
      std::size_t index = 0;
      if (entry.is_regular_file() && IsFrameName(entry.path().filename().string(), &index)) {
        stale.push_back(entry.path());
      }
    }
    for (const fs::path& p : stale) {
      if (!fs::remove(p, ec) || ec) {
        throw std::runtime_error("KittiWriter: cannot remove old frame " + p.string());
      }
    }
  }

  const fs::path calib_path = dir_ / "calib.txt";
  std::ofstream calib(calib_path, std::ios::trunc);
  for (const auto& [name, P] : {std::pair{"P0", &calibration.P0}, {"P1", &calibration.P1}}) {
    calib << name << ':';
    char buf[32];
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        std::snprintf(buf, sizeof(buf), " %.12e", (*P)(r, c));
        calib << buf;
      }
    }
    calib << '\n';
  }
  calib.close();
  if (calib.fail()) throw std::runtime_error("KittiWriter: cannot write " + calib_path.string());

  times_.open(dir_ / "times.txt", std::ios::trunc);
  if (!times_) {
    throw std::runtime_error("KittiWriter: cannot write " + (dir_ / "times.txt").string());
  }
  poses_.open(dir_ / "poses.txt", std::ios::trunc);
  if (!poses_) {
    throw std::runtime_error("KittiWriter: cannot write " + (dir_ / "poses.txt").string());
  }
}

KittiWriter::~KittiWriter() {
  try {
    Close();
  } catch (...) {
    // A destructor must not throw; callers who care call Close() themselves.
  }
}

void KittiWriter::Add(double t_s, const cv::Mat& left, const cv::Mat& right,
                      const Eigen::Isometry3d& T_cam0_cam) {
  if (closed_) throw std::logic_error("KittiWriter::Add: the writer is closed");
  if (left.empty() || right.empty() || left.type() != CV_8UC1 || right.type() != CV_8UC1) {
    throw std::invalid_argument("KittiWriter::Add: images must be non-empty CV_8UC1");
  }
  if (left.size() != right.size() || (frames_ > 0 && left.size() != image_size_)) {
    throw std::invalid_argument("KittiWriter::Add: all images must have one size");
  }
  if (!std::isfinite(t_s) || (frames_ > 0 && t_s < last_t_s_)) {
    throw std::invalid_argument("KittiWriter::Add: time must be finite and non-decreasing");
  }
  if (!T_cam0_cam.matrix().allFinite()) {
    throw std::invalid_argument("KittiWriter::Add: pose must be finite");
  }
  const std::vector<int> png = {cv::IMWRITE_PNG_COMPRESSION, 1};
  for (const auto& [folder, image] : {std::pair{"image_0", &left}, {"image_1", &right}}) {
    const fs::path path = dir_ / folder / FrameName(frames_);
    bool ok = false;
    try {
      ok = cv::imwrite(path.string(), *image, png);
    } catch (const cv::Exception&) {
      ok = false;
    }
    if (!ok) throw std::runtime_error("KittiWriter: cannot write " + path.string());
  }
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.6f\n", t_s);
  times_ << buf;
  poses_ << FormatKittiPoseLine(T_cam0_cam) << '\n';
  if (!times_ || !poses_) {
    throw std::runtime_error("KittiWriter: cannot write times.txt/poses.txt in " + dir_.string());
  }
  image_size_ = left.size();
  last_t_s_ = t_s;
  ++frames_;
}

void KittiWriter::Close() {
  if (closed_) return;
  closed_ = true;
  times_.close();
  poses_.close();
  if (times_.fail() || poses_.fail()) {
    throw std::runtime_error("KittiWriter: cannot flush times.txt/poses.txt in " + dir_.string());
  }
}

// ---------------------------------------------------------------------------
// Pose lines

Eigen::Isometry3d ParseKittiPoseLine(const std::string& line) {
  std::vector<double> values;
  std::string error;
  if (!ParseNumbers(line, &values, &error)) {
    throw std::invalid_argument("ParseKittiPoseLine: " + error);
  }
  if (values.size() != 12) {
    throw std::invalid_argument("ParseKittiPoseLine: " + std::to_string(values.size()) +
                                " numbers, expected 12");
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) T.matrix()(r, c) = values[static_cast<std::size_t>(4 * r + c)];
  }
  const Eigen::Matrix3d R = T.linear();
  // KITTI ground truth is printed with ~7 significant digits: |RᵀR − I| ~ 1e-7.
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-3 ||
      !(R.determinant() > 0.0)) {
    throw std::invalid_argument("ParseKittiPoseLine: the 3x3 block is not a rotation");
  }
  return T;
}

std::string FormatKittiPoseLine(const Eigen::Isometry3d& T) {
  std::string out;
  char buf[32];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      // Shortest representation that parses back to the same double.
      const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), T.matrix()(r, c));
      if (ec != std::errc()) throw std::logic_error("FormatKittiPoseLine: to_chars failed");
      if (!out.empty()) out += ' ';
      out.append(buf, ptr);
    }
  }
  return out;
}

}  // namespace trackbed::perception
