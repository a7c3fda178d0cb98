// Calibration files (see robot_calibration.h).
#include "trackbed/common/robot_calibration.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "trackbed/common/option_error.h"

namespace trackbed::calibration {
namespace {

constexpr char kConvention[] =
    "OpenCV camera axes (x right, y down, z forward); pixel (0,0) is the centre of the top-left "
    "pixel; T_body_cam maps camera coordinates to body coordinates";

void CheckRotation(const char* field, const Eigen::Matrix3d& R) {
  const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!R.allFinite() || !(off <= 1e-6) || !(R.determinant() > 0)) {
    throw OptionError(field, "must be a rotation (orthonormal to 1e-6, determinant +1)");
  }
}

void CheckIntrinsics(const std::string& prefix, const CameraIntrinsics& k) {
  option_check::Positive((prefix + "fx").c_str(), k.fx);
  option_check::Positive((prefix + "fy").c_str(), k.fy);
  option_check::Finite((prefix + "cx").c_str(), k.cx);
  option_check::Finite((prefix + "cy").c_str(), k.cy);
  if (!k.distortion) return;
  try {
    k.distortion->Validate();
  } catch (const OptionError& e) {
    throw OptionError(prefix + "distortion." + e.field(), e.reason());
  }
}

// A calibration file's form: its struct's keys, plus `source` (and for the stereo file
// `convention`), which reading accepts and writing adds.
template <class Calibration>
struct FileForm {
  Calibration* calibration;
  std::string source;
  std::string convention;
  bool stereo = false;

  template <class Archive>
  void Serialize(Archive* a) {
    calibration->Serialize(a);
    if (stereo) a->Visit("convention", &convention);
    a->Visit("source", &source);
  }
};

template <class Calibration>
std::string FileJson(const Calibration& c, const std::string& source, bool stereo) {
  Calibration copy = c;
  FileForm<Calibration> form{&copy, source, kConvention, stereo};
  return archive::ToJson(archive::Write(form)) + "\n";
}

std::string ReadText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw archive::Error(file.string(), "cannot be read (missing?)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Reads and validates one file; errors name the file and the key.
template <class Calibration>
Calibration ReadFile(const std::filesystem::path& file, bool stereo) {
  Calibration c;
  FileForm<Calibration> form{&c, "", "", stereo};
  const std::string name = file.string();
  try {
    archive::Read(archive::ParseJson(ReadText(file)), "", archive::Wording::kDetailed, &form);
    archive::ValidateAt(c, "");
  } catch (const archive::Error& e) {
    if (e.path() == name) throw;
    throw archive::Error(name + (e.path().empty() ? "" : ": " + e.path()), e.reason());
  }
  return c;
}

}  // namespace

geometry::PinholeCamera StereoCalibration::Camera(const CameraIntrinsics& k) const {
  geometry::PinholeCamera c;
  c.width_px = width_px;
  c.height_px = height_px;
  c.fx = k.fx;
  c.fy = k.fy;
  c.cx = k.cx;
  c.cy = k.cy;
  c.distortion = k.Lens();
  return c;
}

bool StereoCalibration::IsRectified() const {
  if (!(left == right) || T_body_left.linear() != T_body_right.linear()) return false;
  if (!left.Lens().is_zero()) return false;
  const Eigen::Vector3d t = T_left_right().translation();
  return std::abs(t.x() - baseline_m) <= 1e-9 && std::abs(t.y()) <= 1e-9 && std::abs(t.z()) <= 1e-9;
}

void StereoCalibration::Validate() const {
  if (width_px < 16 || width_px > 8192) throw OptionError("width_px", "must be in [16, 8192]");
  if (height_px < 16 || height_px > 8192) throw OptionError("height_px", "must be in [16, 8192]");
  CheckIntrinsics("", left);
  CheckIntrinsics("right.", right);
  option_check::Positive("baseline_m", baseline_m);
  const double t = T_left_right().translation().norm();
  if (std::abs(t - baseline_m) > 1e-3 * baseline_m) {
    throw OptionError("baseline_m",
                      "must be the distance between T_body_left's and "
                      "T_body_right's origins (" +
                          option_check::Describe(t) + " m) to 0.1 %");
  }
}

bool ImuCalibration::IsIdentity() const {
  return gyro_axes == Eigen::Matrix3d::Identity() && gyro_g_sensitivity.isZero(0.0) &&
         R_body_imu == Eigen::Matrix3d::Identity();
}

void ImuCalibration::Validate() const {
  const auto check_axes = [](const char* field, const Eigen::Matrix3d& A) {
    if (!A.allFinite() || !(std::abs(A.determinant()) > 1e-6)) {
      throw OptionError(field, "must be finite and invertible");
    }
  };
  check_axes("gyro_axes", gyro_axes);
  check_axes("accel_axes", accel_axes);
  if (!gyro_g_sensitivity.allFinite()) throw OptionError("gyro_g_sensitivity", "must be finite");
  CheckRotation("R_body_imu", R_body_imu);
  option_check::InRange("camera_time_offset_s", camera_time_offset_s, -1.0, 1.0);
}

void VehicleCalibration::Validate() const {
  option_check::Positive("sprocket_radius_left_m", sprocket_radius_left_m);
  option_check::Positive("sprocket_radius_right_m", sprocket_radius_right_m);
  option_check::Positive("track_gauge_m", track_gauge_m);
  if (icr_expansion) option_check::InRange("icr_expansion", *icr_expansion, 0.5, 5.0);
}

std::string StereoCalibrationJson(const StereoCalibration& c, const std::string& source) {
  // The keys a rectified pair's file had first, `convention` after the poses, then the
  // right camera and the source.
  StereoCalibration copy = c;
  FileForm<StereoCalibration> form{&copy, source, kConvention, true};
  archive::Node node = archive::Write(form);
  std::vector<archive::Node::Entry>& e = node.entries();
  const auto right =
      std::find_if(e.begin(), e.end(), [](const auto& x) { return x.first == "right"; });
  const auto convention =
      std::find_if(e.begin(), e.end(), [](const auto& x) { return x.first == "convention"; });
  std::rotate(right, convention, convention + 1);
  return archive::ToJson(node) + "\n";
}

std::string ImuCalibrationJson(const ImuCalibration& c, const std::string& source) {
  return FileJson(c, source, false);
}

std::string VehicleCalibrationJson(const VehicleCalibration& c, const std::string& source) {
  return FileJson(c, source, false);
}

std::string GroundTruthCalibrationJson(const RobotCalibration& truth) {
  archive::Node node = archive::Node::Map();
  if (truth.stereo) {
    StereoCalibration stereo = *truth.stereo;
    node.Set("stereo", archive::Write(stereo));
  }
  ImuCalibration imu = truth.imu;
  node.Set("imu", archive::Write(imu));
  VehicleCalibration vehicle = truth.vehicle;
  node.Set("vehicle", archive::Write(vehicle));
  node.Set("source", archive::Node::Scalar("the robot as built (the simulated plant)",
                                           archive::Node::Tag::kString));
  return archive::ToJson(node) + "\n";
}

RobotCalibration ReadCalibrationFolder(const std::filesystem::path& dir, bool with_stereo) {
  RobotCalibration c;
  if (with_stereo) {
    c.stereo = ReadFile<StereoCalibration>(dir / kStereoFile, true);
    c.stereo_source = "calibration folder " + (dir / kStereoFile).string();
  }
  c.imu = ReadFile<ImuCalibration>(dir / kImuFile, false);
  c.imu_source = "calibration folder " + (dir / kImuFile).string();
  c.vehicle = ReadFile<VehicleCalibration>(dir / kVehicleFile, false);
  c.vehicle_source = "calibration folder " + (dir / kVehicleFile).string();
  return c;
}

}  // namespace trackbed::calibration
