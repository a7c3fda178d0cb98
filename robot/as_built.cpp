// The robot as built and its given calibration (see as_built.h). The profiles' values
// and their sources are listed in docs/calibration.md; a datasheet's bound (max or ±)
// is read as 3σ in `typical` and as 1σ in `harsh`, a stated 1σ or a calibration's
// printed σ as it is.
#include "trackbed/robot/as_built.h"

#include <cmath>
#include <string>

#include "trackbed/common/option_error.h"
#include "trackbed/common/random.h"
#include "trackbed/common/se3.h"
#include "trackbed/common/units.h"
#include "trackbed/robot/lens_calibration_error.h"

namespace trackbed::robot {
namespace {

Imperfections IdealProfile() {
  Imperfections p;
  p.sprocket_radius_rel_std = p.track_gauge_rel_std = 0.0;
  p.wheel_calibration = WheelCalibration::kTruth;
  p.gyro_scale_std = p.gyro_misalignment_std_deg = p.gyro_g_sensitivity_std_dps_per_g = 0.0;
  p.accel_scale_std = p.accel_misalignment_std_deg = p.imu_mount_std_deg = 0.0;
  p.focal_length_rel_std = p.principal_point_std_px = p.camera_mount_std_deg = 0.0;
  p.stereo_translation_std_mm = p.stereo_rotation_std_mrad = Eigen::Vector3d::Zero();
  p.focal_length_calibration_rel_std = p.principal_point_calibration_std_px = 0.0;
  p.stereo_translation_calibration_std_mm = Eigen::Vector3d::Zero();
  p.stereo_rotation_calibration_std_mrad = Eigen::Vector3d::Zero();
  p.camera_mount_calibration_std_deg = 0.0;
  p.distortion_calibration_std = Eigen::Vector4d::Zero();
  p.distortion_calibration_rms_px = 0.0;
  p.camera_time_offset_s = 0.0;
  return p;
}

// A careful lab build: an ADIS16448-class factory-calibrated IMU, a checkerboard stereo
// calibration as in Bouguet's toolbox examples, camera and IMU on one clock.
Imperfections TypicalProfile() {
  Imperfections p = IdealProfile();
  p.wheel_calibration = WheelCalibration::kStraightRun;
  p.gyro_scale_std = p.accel_scale_std = 0.01 / 3.0;    // ADIS16460 Table 1: ≤ 1 %
  p.gyro_misalignment_std_deg = 0.05 / 3.0;             // ADIS16448: < 0.05° axis to axis
  p.accel_misalignment_std_deg = 0.2 / 3.0;             // ADIS16448 accelerometer: 0.2°
  p.gyro_g_sensitivity_std_dps_per_g = 0.01;            // ADIS16460 Table 1, 1σ
  p.imu_mount_std_deg = 1.0 / 3.0;                      // ADIS16460: ±1° axis to frame
  p.focal_length_calibration_rel_std = 0.653 / 1038.0;  // MATLAB stereo example, 1σ
  p.principal_point_calibration_std_px = 0.3;           // MATLAB 0.26–0.34, Bouguet 0.25–0.27
  p.stereo_translation_calibration_std_mm = Eigen::Vector3d(0.047, 0.038, 0.166);  // Bouguet 5
  p.stereo_rotation_calibration_std_mrad = Eigen::Vector3d(0.90, 1.03, 0.097);     // Bouguet 5
  // Bouguet's first calibration example (640 × 480, 20 views): its kc_error / 3 on its
  // own image (scripts/lens_calibration_rms.py; docs/calibration.md).
  p.distortion_calibration_rms_px = 0.017;
  p.camera_time_offset_s = 0.3e-3;  // RealSense T265, one device clock (Kalibr)
  return p;
}

// A consumer IMU (MPU-6000/9250 class) used as shipped, a hurried stereo calibration,
// a camera not synchronised with the IMU.
Imperfections HarshProfile() {
  Imperfections p = TypicalProfile();
  p.gyro_scale_std = p.accel_scale_std = 0.03;  // MPU-6000 §6.1–6.2: ±3 %
  p.gyro_misalignment_std_deg = p.accel_misalignment_std_deg =
      units::Degrees(std::asin(0.02));          // MPU-6000: cross-axis ±2 %
  p.gyro_g_sensitivity_std_dps_per_g = 0.1;     // MPU-6000 §6.1: 0.1 °/s/g
  p.imu_mount_std_deg = 1.0;                    // ADIS16460: ±1° axis to frame
  p.focal_length_calibration_rel_std = 0.0022;  // 0.22 %
  p.principal_point_calibration_std_px = 1.2;   // ≈1.2 px
  p.stereo_translation_calibration_std_mm = Eigen::Vector3d(0.82, 0.82, 2.89);  // D435i
  p.stereo_rotation_calibration_std_mrad = Eigen::Vector3d(1.26, 1.36, 0.111);  // D435i
  // A Kinect v2 infrared camera's Bouguet calibration (512 × 424, 70° across): its
  // kc_error / 3 on its own image (scripts/lens_calibration_rms.py; docs/calibration.md).
  p.distortion_calibration_rms_px = 0.22;
  p.camera_time_offset_s = -44.3e-3;  // median of seven unsynchronised rigs (Kalibr)
  return p;
}

// Every key of `over` that is set replaces `base`'s.
Imperfections Overlay(const Imperfections& base, const Imperfections& over) {
  archive::Node node = archive::Write(base);
  const archive::Node given = archive::Write(over);
  for (const auto& [key, value] : given.entries()) node.Set(key, value);
  Imperfections out;
  archive::Read(node, "", archive::Wording::kDetailed, &out);
  return out;
}

// Draws in a fixed order: three Gaussians, scaled per axis.
Eigen::Vector3d Gaussian3(random::Generator* g, const Eigen::Vector3d& sigma) {
  const double a = g->Gaussian(), b = g->Gaussian(), c = g->Gaussian();
  return {sigma.x() * a, sigma.y() * b, sigma.z() * c};
}

// Scale factors on the diagonal, cross-axis terms (small angles) off it.
Eigen::Matrix3d DrawAxes(random::Generator* g, double scale_std, double misalignment_std_deg) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d s = Gaussian3(g, Eigen::Vector3d::Constant(scale_std));
  const double m = units::Radians(misalignment_std_deg);
  const Eigen::Vector3d upper = Gaussian3(g, Eigen::Vector3d::Constant(m));
  const Eigen::Vector3d lower = Gaussian3(g, Eigen::Vector3d::Constant(m));
  for (int i = 0; i < 3; ++i) A(i, i) += s[i];
  A(0, 1) = upper[0], A(0, 2) = upper[1], A(1, 2) = upper[2];
  A(1, 0) = lower[0], A(2, 0) = lower[1], A(2, 1) = lower[2];
  return A;
}

// A rotation by a drawn small rotation vector (identity exactly for zero spreads).
Eigen::Matrix3d DrawRotation(random::Generator* g, const Eigen::Vector3d& sigma_rad) {
  const Eigen::Vector3d phi = Gaussian3(g, sigma_rad);
  return phi.isZero(0.0) ? Eigen::Matrix3d::Identity() : geometry::ExpSO3(phi);
}

// One camera's intrinsics perturbed: focal lengths relatively, principal point in px.
void PerturbIntrinsics(random::Generator* g, double focal_rel_std, double pp_std_px,
                       calibration::CameraIntrinsics* k) {
  const Eigen::Vector3d f = Gaussian3(g, Eigen::Vector3d::Constant(focal_rel_std));
  const Eigen::Vector3d c = Gaussian3(g, Eigen::Vector3d::Constant(pp_std_px));
  if (focal_rel_std > 0) k->fx *= 1.0 + f.x(), k->fy *= 1.0 + f.y();
  if (pp_std_px > 0) k->cx += c.x(), k->cy += c.y();
}

// The stereo pair perturbed: intrinsics, the right camera's pose in the left camera's
// frame, and the pair's mounting on the body (about the left camera's axes). Zero
// spreads leave the pair bit for bit as it was.
void PerturbStereo(random::Generator* g, double focal_rel_std, double pp_std_px,
                   const Eigen::Vector3d& translation_std_mm,
                   const Eigen::Vector3d& rotation_std_mrad, double mount_std_deg,
                   calibration::StereoCalibration* s) {
  PerturbIntrinsics(g, focal_rel_std, pp_std_px, &s->left);
  PerturbIntrinsics(g, focal_rel_std, pp_std_px, &s->right);
  const Eigen::Vector3d dt = Gaussian3(g, translation_std_mm * 1e-3);
  const Eigen::Matrix3d dR = DrawRotation(g, rotation_std_mrad * 1e-3);
  const Eigen::Matrix3d mount =
      DrawRotation(g, Eigen::Vector3d::Constant(units::Radians(mount_std_deg)));
  const bool pair_moves = !dt.isZero(0.0) || dR != Eigen::Matrix3d::Identity();
  const bool mount_moves = mount != Eigen::Matrix3d::Identity();
  if (!pair_moves && !mount_moves) return;
  Eigen::Isometry3d T_lr = s->T_left_right();
  T_lr.linear() = dR * T_lr.linear();
  T_lr.translation() += dt;
  Eigen::Isometry3d T_body_left = s->T_body_left;
  T_body_left.linear() = T_body_left.linear() * mount;
  s->T_body_left = T_body_left;
  s->T_body_right = T_body_left * T_lr;
  s->baseline_m = T_lr.translation().norm();
}

// Each camera's lens coefficients perturbed (k1, k2, p1, p2): independently by `sigma`,
// then as a fit over the image to `rms_px` leaves them (lens_calibration_error.h); drawn
// whatever the lens, and an ideal pinhole stays one.
void PerturbLenses(random::Generator* g, const Eigen::Vector4d& sigma, double rms_px,
                   calibration::StereoCalibration* s) {
  for (calibration::CameraIntrinsics* k : {&s->left, &s->right}) {
    const Eigen::Vector3d a = Gaussian3(g, sigma.head<3>());
    const double b = sigma[3] * g->Gaussian();
    const geometry::PinholeCamera camera = s->Camera(*k);
    const Eigen::Vector4d fitted = DrawLensCalibrationError(g, camera, rms_px);
    if (!k->distortion || k->distortion->model == geometry::LensModel::kNone) continue;
    geometry::LensDistortion& d = *k->distortion;
    d.k1 += a.x(), d.k2 += a.y();
    if (d.model == geometry::LensModel::kRadialTangential) d.p1 += a.z(), d.p2 += b;
    d = WithCalibrationError(d, fitted);
  }
}

// The lens of EuRoC's VI-Sensor left camera (MT9V034 behind an S-mount lens of about
// 80° across, as ours), as its published Kalibr calibration gives it.
geometry::LensDistortion EurocCam0Lens() {
  return geometry::LensDistortion::RadialTangential(-0.28340811, 0.07395907, 0.00019359,
                                                    1.76187114e-05);
}

}  // namespace

StereoRigOptions WithCameraEffectsResolved(StereoRigOptions stereo, Realism profile) {
  // `harsh` has EuRoC's lens and a RealSense colour camera's rolling shutter, 33 ms to
  // read 480 rows (VINS-Mono's configuration, from its datasheet); `typical` a global
  // shutter (the IMX174's) and images free of distortion, as a stereo camera that
  // rectifies them itself delivers them (docs/camera_model.md, "Profiles").
  const bool harsh = profile == Realism::kHarsh;
  if (!stereo.distortion) stereo.distortion = harsh ? EurocCam0Lens() : geometry::LensDistortion{};
  if (!stereo.rolling_shutter.line_delay_s) {
    stereo.rolling_shutter.line_delay_s = harsh ? 0.033 / 480.0 : 0.0;
  }
  // The sensor: typical's a Sony IMX174 (EMVA 1288 figures Point Grey published),
  // harsh's a Sony ICX625 (Basler piA2400-17gm's EMVA 1288 datasheet) behind a lens
  // whose corners get half the light (Alexandrov et al. 2016: an Asus Xtion's colour
  // camera); typical's corner 0.71 (a wide-angle lens measured at full aperture).
  PhotometricOptions& p = stereo.photometric;
  if (!p.enabled) p.enabled = profile != Realism::kIdeal;
  if (!p.full_well_e) p.full_well_e = harsh ? 7000.0 : 32691.0;
  if (!p.read_noise_e) p.read_noise_e = harsh ? 13.0 : 6.83;
  if (!p.prnu_std) p.prnu_std = 0.0;
  if (!p.dsnu_std_e) p.dsnu_std_e = 0.0;
  if (!p.adc_bits) p.adc_bits = 12;
  if (!p.vignetting_corner) p.vignetting_corner = harsh ? 0.5 : 0.71;
  if (!p.gain) p.gain = 1.0;
  return stereo;
}

Imperfections Imperfections::Resolve(Realism profile) const {
  switch (profile) {
    case Realism::kIdeal:
      return Overlay(IdealProfile(), *this);
    case Realism::kTypical:
      return Overlay(TypicalProfile(), *this);
    case Realism::kHarsh:
      return Overlay(HarshProfile(), *this);
  }
  return Overlay(TypicalProfile(), *this);
}

void Imperfections::Validate() const {
  const auto spread = [](const char* key, const std::optional<double>& v, double max) {
    if (v) option_check::InRange(key, *v, 0.0, max);
  };
  const auto spread3 = [](const char* key, const std::optional<Eigen::Vector3d>& v, double max) {
    if (!v) return;
    for (int i = 0; i < 3; ++i) {
      option_check::InRange((std::string(key) + "[" + std::to_string(i) + "]").c_str(), (*v)[i],
                            0.0, max);
    }
  };
  spread("sprocket_radius_rel_std", sprocket_radius_rel_std, 0.2);
  spread("track_gauge_rel_std", track_gauge_rel_std, 0.2);
  spread("gyro_scale_std", gyro_scale_std, 0.2);
  spread("gyro_misalignment_std_deg", gyro_misalignment_std_deg, 10.0);
  spread("gyro_g_sensitivity_std_dps_per_g", gyro_g_sensitivity_std_dps_per_g, 10.0);
  spread("accel_scale_std", accel_scale_std, 0.2);
  spread("accel_misalignment_std_deg", accel_misalignment_std_deg, 10.0);
  spread("imu_mount_std_deg", imu_mount_std_deg, 10.0);
  spread("focal_length_rel_std", focal_length_rel_std, 0.2);
  spread("principal_point_std_px", principal_point_std_px, 100.0);
  spread3("stereo_translation_std_mm", stereo_translation_std_mm, 100.0);
  spread3("stereo_rotation_std_mrad", stereo_rotation_std_mrad, 100.0);
  spread("camera_mount_std_deg", camera_mount_std_deg, 10.0);
  spread("distortion_calibration_rms_px", distortion_calibration_rms_px, 10.0);
  spread("focal_length_calibration_rel_std", focal_length_calibration_rel_std, 0.2);
  spread("principal_point_calibration_std_px", principal_point_calibration_std_px, 100.0);
  spread3("stereo_translation_calibration_std_mm", stereo_translation_calibration_std_mm, 100.0);
  spread3("stereo_rotation_calibration_std_mrad", stereo_rotation_calibration_std_mrad, 100.0);
  spread("camera_mount_calibration_std_deg", camera_mount_calibration_std_deg, 10.0);
  if (distortion_calibration_std) {
    for (int i = 0; i < 4; ++i) {
      option_check::InRange(("distortion_calibration_std[" + std::to_string(i) + "]").c_str(),
                            (*distortion_calibration_std)[i], 0.0, 1.0);
    }
  }
  if (camera_time_offset_s) {
    option_check::InRange("camera_time_offset_s", *camera_time_offset_s, -0.5, 0.5);
  }
}

calibration::RobotCalibration DesignCalibration(const TrackedVehicleOptions& vehicle,
                                                const StereoRigOptions& stereo) {
  calibration::RobotCalibration c;
  c.vehicle.sprocket_radius_left_m = c.vehicle.sprocket_radius_right_m = vehicle.sprocket_radius_m;
  c.vehicle.track_gauge_m = vehicle.track_gauge_m;
  if (stereo.enabled) {
    const StereoRig rig(stereo);
    calibration::StereoCalibration s;
    const geometry::PinholeCamera& k = rig.intrinsics();
    s.width_px = k.width_px;
    s.height_px = k.height_px;
    s.left = s.right = {k.fx, k.fy, k.cx, k.cy, std::nullopt};
    if (stereo.distortion && !stereo.distortion->is_zero()) {
      s.left.distortion = s.right.distortion = *stereo.distortion;
    }
    s.baseline_m = stereo.baseline_m;
    s.T_body_left = rig.T_body_left();
    s.T_body_right = rig.T_body_right();
    c.stereo = s;
  }
  return c;
}

calibration::RobotCalibration DrawAsBuilt(const calibration::RobotCalibration& design,
                                          const Imperfections& imperfections, std::uint64_t seed) {
  const Imperfections& p = imperfections;
  random::Generator g(seed);
  calibration::RobotCalibration c = design;
  // The vehicle: each track's radius, the gauge.
  const Eigen::Vector3d v =
      Gaussian3(&g, Eigen::Vector3d(*p.sprocket_radius_rel_std, *p.sprocket_radius_rel_std,
                                    *p.track_gauge_rel_std));
  if (v.x() != 0) c.vehicle.sprocket_radius_left_m *= 1.0 + v.x();
  if (v.y() != 0) c.vehicle.sprocket_radius_right_m *= 1.0 + v.y();
  if (v.z() != 0) c.vehicle.track_gauge_m *= 1.0 + v.z();
  // The IMU.
  c.imu.gyro_axes = DrawAxes(&g, *p.gyro_scale_std, *p.gyro_misalignment_std_deg);
  const double gs = units::Radians(*p.gyro_g_sensitivity_std_dps_per_g) / units::kStandardGravity;
  for (int r = 0; r < 3; ++r) {
    c.imu.gyro_g_sensitivity.row(r) = Gaussian3(&g, Eigen::Vector3d::Constant(gs)).transpose();
  }
  c.imu.accel_axes = DrawAxes(&g, *p.accel_scale_std, *p.accel_misalignment_std_deg);
  c.imu.R_body_imu =
      DrawRotation(&g, Eigen::Vector3d::Constant(units::Radians(*p.imu_mount_std_deg)));
  c.imu.camera_time_offset_s = *p.camera_time_offset_s;
  // The cameras (drawn whether or not the robot has them: the same draws either way).
  calibration::StereoCalibration stereo = design.stereo.value_or(calibration::StereoCalibration{});
  PerturbStereo(&g, *p.focal_length_rel_std, *p.principal_point_std_px,
                *p.stereo_translation_std_mm, *p.stereo_rotation_std_mrad, *p.camera_mount_std_deg,
                &stereo);
  if (c.stereo) c.stereo = stereo;
  return c;
}

calibration::RobotCalibration DrawGivenCalibration(const calibration::RobotCalibration& truth,
                                                   const calibration::RobotCalibration& design,
                                                   const Imperfections& imperfections,
                                                   std::uint64_t seed) {
  const Imperfections& p = imperfections;
  random::Generator g(seed);
  calibration::RobotCalibration c = design;
  c.imu.camera_time_offset_s = truth.imu.camera_time_offset_s;
  calibration::StereoCalibration stereo = truth.stereo.value_or(calibration::StereoCalibration{});
  PerturbStereo(&g, *p.focal_length_calibration_rel_std, *p.principal_point_calibration_std_px,
                *p.stereo_translation_calibration_std_mm, *p.stereo_rotation_calibration_std_mrad,
                *p.camera_mount_calibration_std_deg, &stereo);
  PerturbLenses(&g, *p.distortion_calibration_std, *p.distortion_calibration_rms_px, &stereo);
  if (c.stereo) c.stereo = stereo;
  return c;
}

}  // namespace trackbed::robot

namespace trackbed::archive {

void Codec<robot::WheelCalibration>::Read(const Node& node, const std::string& path,
                                          Wording wording, robot::WheelCalibration* value) {
  std::string name;
  Codec<std::string>::Read(node, path, wording, &name);
  if (name == "truth") {
    *value = robot::WheelCalibration::kTruth;
  } else if (name == "straight_run") {
    *value = robot::WheelCalibration::kStraightRun;
  } else {
    throw Error(path, "expected truth or straight_run, got '" + name + "'");
  }
}

Node Codec<robot::WheelCalibration>::Write(robot::WheelCalibration value) {
  return Node::Scalar(value == robot::WheelCalibration::kTruth ? "truth" : "straight_run",
                      Node::Tag::kString);
}

}  // namespace trackbed::archive
