// The localization stack (see localization.h).
#include "trackbed/estimation/localization.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "trackbed/common/option_error.h"
#include "trackbed/common/se3.h"
#include "trackbed/estimation/constant_velocity.h"

namespace trackbed::estimation {
namespace {

WheelOdometryOptions WithSlip(WheelOdometryOptions o, bool estimate) {
  o.estimate_slip = estimate;
  return o;
}

FuzzyFusionWeight MakeFuzzy(const std::string& file) {
  return file.empty() ? FuzzyFusionWeight() : FuzzyFusionWeight::FromFile(file);
}

}  // namespace

void LocalizationOptions::Validate() const {
  option_check::Nested("wheel", wheel);
  option_check::Nested("vo", vo);
  option_check::Nested("ekf", ekf);
  option_check::Nested("imu", imu);
  option_check::Nested("fusion", fusion);
  option_check::Nested("gyro", gyro);
  option_check::Nested("gyro_model", gyro_model);
  option_check::Nested("localization_lost", localization_lost);
  if (min_inliers_for_slip < 0) {
    throw OptionError("min_inliers_for_slip",
                      "must be >= 0 (got " + std::to_string(min_inliers_for_slip) + ")");
  }
  option_check::NonNegative("vo_coast_time_s", vo_coast_time_s);
}

LocalizationStack::LocalizationStack(const LocalizationOptions& options,
                                     const geometry::StereoCamera* camera,
                                     const Eigen::Isometry3d& T_body_left,
                                     const Eigen::Isometry3d& T_world_body0)
    : options_(options),
      T_body_left_(T_body_left),
      z0_(T_world_body0.translation().z()),
      wheel_(WithSlip(options.wheel, true), geometry::PlanarPose(T_world_body0)),
      wheel_noslip_(WithSlip(options.wheel, false), geometry::PlanarPose(T_world_body0)),
      vo_(camera ? std::make_unique<StereoVisualOdometry>(*camera, options.vo) : nullptr),
      fuzzy_(MakeFuzzy(options.fusion.rules_file)),
      fused_(geometry::PlanarPose(T_world_body0)),
      ekf_(options.ekf, geometry::PlanarPose(T_world_body0)),
      weight_(options.fusion.weight_rise_time_s),
      imu_(options.imu),
      T_world_body_vo_(T_world_body0),
      wheel_at_frame_(geometry::PlanarPose(T_world_body0)),
      zupt_(options.gyro_model, options.gyro.standstill_window_s),
      wheel_gyro_at_frame_(geometry::PlanarPose(T_world_body0)) {
  options_.Validate();
  const bool covariance = options_.fusion.method == FusionOptions::Method::kCovariance;
  if (options_.gyro.wheel_rotation || options_.gyro.fusion_rotation || covariance) {
    wheel_gyro_ = std::make_unique<WheelOdometry>(WithSlip(options_.wheel, true),
                                                  geometry::PlanarPose(T_world_body0));
    gate_1dof_ = ChiSquareQuantile(1, options_.fusion.gate_probability);
  }
  if (covariance) {
    covariance_fused_ =
        std::make_unique<CovarianceFusion>(geometry::PlanarPose(T_world_body0),
                                           ChiSquareQuantile(3, options_.fusion.gate_probability));
  }
}

LocalizationStack::LocalizationStack(const LocalizationOptions& options,
                                     const calibration::StereoCalibration* stereo,
                                     const Eigen::Isometry3d& T_world_body0)
    : LocalizationStack(
          options, stereo ? std::make_shared<const perception::StereoRectifier>(*stereo) : nullptr,
          T_world_body0) {}

LocalizationStack::LocalizationStack(const LocalizationOptions& options,
                                     std::shared_ptr<const perception::StereoRectifier> rectifier,
                                     const Eigen::Isometry3d& T_world_body0)
    : LocalizationStack(options, rectifier ? &rectifier->camera() : nullptr,
                        rectifier ? rectifier->T_body_left() : Eigen::Isometry3d::Identity(),
                        T_world_body0) {
  if (rectifier && !rectifier->identity()) rectifier_ = std::move(rectifier);
}

LocalizationStack::~LocalizationStack() = default;

const char* ToString(InputStatus status) {
  switch (status) {
    case InputStatus::kUsed:
      return "used";
    case InputStatus::kTimeNotFinite:
      return "time_not_finite";
    case InputStatus::kTimeNotIncreasing:
      return "time_not_increasing";
    case InputStatus::kValueNotFinite:
      return "value_not_finite";
    case InputStatus::kImageInvalid:
      return "image_invalid";
  }
  return "?";
}

namespace {

// A stamp's status against the stream's last used one (`has_last` false: none yet).
InputStatus StampStatus(double t_s, bool has_last, double last_s) {
  if (!std::isfinite(t_s)) return InputStatus::kTimeNotFinite;
  if (has_last && !(t_s > last_s)) return InputStatus::kTimeNotIncreasing;
  return InputStatus::kUsed;
}

/// The covariance of a VO frame's planar increment (x, y, yaw in the previous pose's
/// heading frame) from the body motion's: the body's motion curr-from-prev is off by
/// the left increment (ρ, φ) in the current body's axes, so T_prev_curr is off by
/// (−R_pc·ρ, −R_pc·φ) in the previous body's, carried into the heading frame (the
/// previous body's world rotation without its yaw). To first order: x, y from the
/// translation, yaw from the rotation's vertical component.
Eigen::Matrix3d PlanarCovariance(const MotionCovarianceMatrix& body_covariance,
                                 const Eigen::Isometry3d& T_world_body_prev, double yaw_prev,
                                 const Eigen::Isometry3d& T_prev_curr) {
  const Eigen::Matrix3d M = Eigen::AngleAxisd(-yaw_prev, Eigen::Vector3d::UnitZ()).matrix() *
                            T_world_body_prev.linear() * T_prev_curr.linear();
  Eigen::Matrix<double, 3, 6> J = Eigen::Matrix<double, 3, 6>::Zero();
  J.block<2, 3>(0, 0) = M.topRows<2>();
  J.block<1, 3>(2, 3) = M.row(2);
  return J * body_covariance * J.transpose();
}

}  // namespace

InputStatus LocalizationStack::AddImuSample(double t_s, const Eigen::Vector3d& gyro_radps,
                                            const Eigen::Vector3d& accel_mps2) {
  if (!gyro_radps.allFinite() || !accel_mps2.allFinite()) {
    ++rejected_.gyro;
    return InputStatus::kValueNotFinite;
  }
  if (wheel_gyro_ && std::isfinite(t_s)) {
    // The vertical in the body's axes: the specific force low-passed (at rest it points up).
    const Eigen::Vector3d force = imu_.BodySpecificForce(accel_mps2);
    if (!has_accel_) {
      up_body_ = force;
    } else if (t_s > t_accel_) {
      const double a = 1.0 - std::exp(-(t_s - t_accel_) / options_.gyro.vertical_filter_time_s);
      up_body_ += a * (force - up_body_);
    }
    has_accel_ = true;
    t_accel_ = t_s;
  }
  return AddGyroSample(t_s, imu_.BodyRate(gyro_radps, accel_mps2));
}

InputStatus LocalizationStack::AddEncoderSample(double t_s, std::int64_t left_ticks,
                                                std::int64_t right_ticks) {
  const InputStatus status = StampStatus(t_s, has_encoder_, t_encoder_);
  if (status != InputStatus::kUsed) {
    ++rejected_.encoder;
    return status;
  }
  has_encoder_ = true;
  t_encoder_ = t_s;
  wheel_.AddEncoderSample(t_s, left_ticks, right_ticks);
  wheel_noslip_.AddEncoderSample(t_s, left_ticks, right_ticks);
  ekf_.AddWheelTwist(t_s, wheel_noslip_.forward_mps(), wheel_noslip_.yaw_rate_radps());
  zupt_.AddEncoderSample(t_s, left_ticks, right_ticks);
  if (options_.ekf.zero_velocity_updates && zupt_.standstill()) ekf_.AddZeroVelocity(t_s);
  if (wheel_gyro_) {
    wheel_gyro_->AddEncoderSample(
        t_s, left_ticks, right_ticks,
        gyro_yaw_pending_ ? std::optional<double>(gyro_yaw_since_encoder_) : std::nullopt);
    gyro_yaw_since_encoder_ = 0.0;
    gyro_yaw_pending_ = false;
  }
  return InputStatus::kUsed;
}

InputStatus LocalizationStack::AddGyroSample(double t_s, const Eigen::Vector3d& rate_radps) {
  InputStatus status = StampStatus(t_s, has_gyro_, t_gyro_);
  if (status == InputStatus::kUsed && !rate_radps.allFinite()) {
    status = InputStatus::kValueNotFinite;
  }
  if (status != InputStatus::kUsed) {
    ++rejected_.gyro;
    return status;
  }
  ekf_.AddGyro(t_s, rate_radps.z());
  zupt_.AddGyroSample(t_s, rate_radps);
  // VO's rotation prior: the rate less the standstills' bias where it is estimated.
  const Eigen::Vector3d rate_for_prior =
      options_.gyro.zero_velocity_bias ? Eigen::Vector3d(rate_radps - zupt_.bias()) : rate_radps;
  if (wheel_gyro_ && has_gyro_) {
    // The heading's change: the bias-corrected rate about the vertical.
    const Eigen::Vector3d bias =
        options_.gyro.zero_velocity_bias ? zupt_.bias() : Eigen::Vector3d::Zero();
    const double up_norm = up_body_.norm();
    const Eigen::Vector3d up = up_norm > 0.0 ? Eigen::Vector3d(up_body_ / up_norm)
                                             : Eigen::Vector3d(Eigen::Vector3d::UnitZ());
    // Standing still (zero-velocity updates on), the robot does not turn.
    const bool still = options_.gyro.zero_velocity_bias && zupt_.standstill();
    if (!still) gyro_yaw_since_encoder_ += up.dot(rate_radps - bias) * (t_s - t_gyro_);
    gyro_yaw_pending_ = true;
  }
  if (options_.apply_camera_time_offset && vo_ && has_gyro_) {
    gyro_intervals_.push_back({t_gyro_, t_s, rate_for_prior});
  }
  if (has_gyro_) {
    // The rate held over the interval since the last sample (body frame: right-multiplied).
    const Eigen::Vector3d phi = rate_for_prior * (t_s - t_gyro_);
    const double angle = phi.norm();
    if (angle > 0.0) {
      R_gyro_since_frame_ = R_gyro_since_frame_ * geometry::ExpSO3(phi);
    }
    gyro_since_frame_ = true;
  }
  has_gyro_ = true;
  t_gyro_ = t_s;
  return InputStatus::kUsed;
}

InputStatus LocalizationStack::CheckStereoFrame(double t_s, const cv::Mat& left,
                                                const cv::Mat& right) const {
  const InputStatus status = StampStatus(t_s, has_frame_, t_frame_);
  if (status != InputStatus::kUsed) return status;
  const cv::Size size =
      rectifier_ ? cv::Size(rectifier_->camera().left.width_px, rectifier_->camera().left.height_px)
                 : cv::Size(vo_->camera().left.width_px, vo_->camera().left.height_px);
  for (const cv::Mat* image : {&left, &right}) {
    if (image->empty() || image->type() != CV_8UC1 || image->size() != size) {
      return InputStatus::kImageInvalid;
    }
  }
  return InputStatus::kUsed;
}

LocalizationFrameReport LocalizationStack::AddStereoFrame(double t_s, const cv::Mat& left,
                                                          const cv::Mat& right) {
  if (!vo_) throw std::logic_error("LocalizationStack: stereo frame without a camera calibration");
  LocalizationFrameReport report;
  report.input = CheckStereoFrame(t_s, left, right);
  if (report.input != InputStatus::kUsed) {
    ++rejected_.stereo;
    report.vo.status = VoStatus::kNotProcessed;
    report.vo.reason = std::string("input set aside: ") + ToString(report.input);
    report.slip = wheel_.slip();
    report.slip_velocity_mps = report.slip.max_abs_mps();
    return report;
  }
  if (rectifier_) {
    rectifier_->Rectify(left, right, &rectified_left_, &rectified_right_);
    return ProcessStereoFrame(t_s, rectified_left_, rectified_right_);
  }
  return ProcessStereoFrame(t_s, left, right);
}

const Eigen::Matrix3d* LocalizationStack::RotationPrior(double t_s, Eigen::Matrix3d* R) {
  const Eigen::Matrix3d& R_bc = T_body_left_.linear();
  if (!options_.apply_camera_time_offset) {
    // The gyro's rotation since the last frame's stamp, in the left camera's frame.
    *R = R_bc.transpose() * R_gyro_since_frame_ * R_bc;
    return gyro_since_frame_ ? R : nullptr;
  }
  const double t_exposure = t_s + options_.imu.camera_time_offset_s;
  const bool has_prior = has_exposure_ && !gyro_intervals_.empty() && t_exposure > t_exposure_;
  if (has_prior) {
    *R = R_bc.transpose() * IntegrateGyro(gyro_intervals_, t_exposure_, t_exposure) * R_bc;
  }
  DropGyroBefore(t_exposure, &gyro_intervals_);
  t_exposure_ = t_exposure;
  has_exposure_ = true;
  return has_prior ? R : nullptr;
}

LocalizationFrameReport LocalizationStack::ProcessStereoFrame(double t_s, const cv::Mat& left,
                                                              const cv::Mat& right) {
  LocalizationFrameReport report;
  Eigen::Matrix3d R_prior;
  report.vo = vo_->Process(left, right, t_s, RotationPrior(t_s, &R_prior));
  R_gyro_since_frame_.setIdentity();
  gyro_since_frame_ = false;
  report.vo_valid = report.vo.status == VoStatus::kOk;
  std::optional<geometry::Pose2> vo_increment;
  std::optional<Eigen::Matrix3d> vo_planar_covariance;
  if (report.vo_valid) {
    // The left camera's motion, expressed as the body's motion.
    const Eigen::Isometry3d T_body_motion =
        T_body_left_ * report.vo.T_prev_curr * T_body_left_.inverse();
    report.vo_body_motion = T_body_motion;
    const geometry::Pose2 planar_before = geometry::PlanarPose(T_world_body_vo_);
    if (report.vo.covariance_valid) {
      report.vo_body_covariance = TransformMotionCovariance(report.vo.covariance, T_body_left_);
      vo_planar_covariance = PlanarCovariance(report.vo_body_covariance, T_world_body_vo_,
                                              planar_before.yaw, T_body_motion);
    }
    T_world_body_vo_ = T_world_body_vo_ * T_body_motion;
    // The planar motion is the change of the 3-D pose's planar projection, not the
    // planar part of the 3-D increment: on tilted ground the body's x axis is not
    // horizontal, and chaining the planar parts of tilted increments over-counts the
    // horizontal distance (by 1 − cos(pitch)) and leaks roll into heading.
    vo_increment = Between(planar_before, geometry::PlanarPose(T_world_body_vo_));
    // VO's pose covariance: the frames' composed; without one, VO cannot say.
    vo_pose_covariance_ = vo_planar_covariance
                              ? ComposeCovariance(planar_before, vo_pose_covariance_, *vo_increment,
                                                  *vo_planar_covariance)
                              : Eigen::Matrix3d::Constant(std::numeric_limits<double>::infinity());
    if (has_frame_ && t_s > t_frame_ && report.vo.inliers >= options_.min_inliers_for_slip) {
      // Slip from the independent (visual) velocity over the frame interval.
      const double dt = t_s - t_frame_;
      wheel_.AddMeasuredVelocity(t_frame_, t_s, vo_increment->x / dt, vo_increment->yaw / dt);
    }
    if (has_frame_ && t_s > t_frame_) {
      const double dt = t_s - t_frame_;
      vo_last_motion_ = T_body_motion;
      vo_last_dt_ = dt;
      t_vo_valid_ = t_s;
      has_vo_motion_ = true;
    }
  } else if (has_vo_motion_ && has_frame_ && t_s > t_frame_ &&
             t_s - t_vo_valid_ <= options_.vo_coast_time_s + 1e-9) {
    // The next valid frame's motion starts at this frame: the gap is this interval's.
    T_world_body_vo_ =
        T_world_body_vo_ * ContinuedMotion(vo_last_motion_, vo_last_dt_, t_s - t_frame_);
    report.vo_coasted = true;
  }
  if (!report.vo_valid && has_frame_) {
    // A frame without a motion: VO alone knows nothing of this interval.
    vo_pose_covariance_.setConstant(std::numeric_limits<double>::infinity());
  }
  // Only a measured motion enters the EKF; after a failed or coasted frame the next
  // motion starts from here.
  ekf_.AddCameraFrame(t_s, vo_increment, report.vo.inliers,
                      vo_planar_covariance ? &*vo_planar_covariance : nullptr);
  report.slip = wheel_led().slip();
  report.slip_velocity_mps = wheel_for_fusion().slip().max_abs_mps();
  report.features = report.vo.inliers;
  if (has_frame_) {
    const geometry::Pose2 wheel_increment = Between(wheel_at_frame_, wheel_for_fusion().pose());
    // A frame without VO counts as w = 1: the weight climbs back toward the wheels.
    report.w_rule =
        report.vo_valid ? fuzzy_.Weight(report.slip_velocity_mps, report.features) : 1.0;
    const double w = weight_.Update(report.w_rule, t_s - t_frame_);
    report.w = report.vo_valid ? w : 1.0;
    fused_.Add(wheel_increment, vo_increment, report.w);
  }
  if (wheel_gyro_) {
    GyroLedFrame(t_s, report, vo_increment, vo_planar_covariance);
    wheel_gyro_at_frame_ = wheel_gyro_->pose();
  }
  wheel_at_frame_ = wheel_for_fusion().pose();
  t_frame_ = t_s;
  has_frame_ = true;
  return report;
}

void LocalizationStack::GyroLedFrame(double t_s, const LocalizationFrameReport& report,
                                     const std::optional<geometry::Pose2>& vo_increment,
                                     const std::optional<Eigen::Matrix3d>& vo_covariance) {
  if (!has_frame_ || !(t_s > t_frame_)) return;
  const double dt = t_s - t_frame_;
  const geometry::Pose2 prediction = Between(wheel_gyro_at_frame_, wheel_gyro_->pose());
  const double var_gyro = options_.gyro_model.RotationVariance(dt, GyroBiasVarianceZ());
  const std::optional<geometry::Pose2> measured =
      vo_increment && vo_covariance ? vo_increment : std::nullopt;
  double yaw = prediction.yaw;
  if (measured) {
    // VO's rotation weighed by its variance against the gyro's over the interval.
    const double var_vo = (*vo_covariance)(2, 2);
    const double nu = geometry::WrapAngle(measured->yaw - prediction.yaw);
    if (nu * nu <= gate_1dof_ * (var_gyro + var_vo)) {
      const double correction = var_gyro / (var_gyro + var_vo) * nu;
      wheel_gyro_->Rotate(correction);
      yaw += correction;
    }
  }
  if (vo_increment && report.vo.inliers >= options_.min_inliers_for_slip) {
    wheel_gyro_->AddMeasuredVelocity(t_frame_, t_s, vo_increment->x / dt, yaw / dt);
  }
  if (covariance_fused_) {
    // The wheels' forward speed is as good as the slip estimate it carries: σ the
    // encoders' own plus the estimate's size.
    const double sf =
        (options_.fusion.wheel_speed_std_mps + wheel_gyro_->slip().max_abs_mps()) * dt;
    const double sl = options_.fusion.wheel_lateral_speed_std_mps * dt;
    const Eigen::Matrix3d Q = Eigen::Vector3d(sf * sf, sl * sl, var_gyro).asDiagonal();
    covariance_fused_->Add(prediction, Q, measured,
                           measured ? *vo_covariance : Eigen::Matrix3d(Eigen::Matrix3d::Zero()));
  }
}

double LocalizationStack::GyroBiasVarianceZ() const {
  if (options_.gyro.zero_velocity_bias) return zupt_.variance().z();
  return options_.gyro_model.turn_on_bias_std * options_.gyro_model.turn_on_bias_std;
}

const WheelOdometry& LocalizationStack::wheel_led() const {
  return options_.gyro.wheel_rotation && wheel_gyro_ ? *wheel_gyro_ : wheel_;
}

const WheelOdometry& LocalizationStack::wheel_for_fusion() const {
  return options_.gyro.fusion_rotation && wheel_gyro_ ? *wheel_gyro_ : wheel_;
}

Eigen::Isometry3d LocalizationStack::wheel_odometry() const {
  return ToIsometry(wheel_led().pose(), z0_);
}

Eigen::Isometry3d LocalizationStack::wheel_odometry_noslip() const {
  return ToIsometry(wheel_noslip_.pose(), z0_);
}

Eigen::Isometry3d LocalizationStack::ekf() const { return ToIsometry(ekf_.pose(), z0_); }

Eigen::Isometry3d LocalizationStack::visual_odometry() const { return T_world_body_vo_; }

Eigen::Isometry3d LocalizationStack::fused() const {
  // The fused pose at the last frame, carried forward by the wheels since.
  if (covariance_fused_) {
    return ToIsometry(
        Compose(covariance_fused_->pose(), Between(wheel_gyro_at_frame_, wheel_gyro_->pose())),
        z0_);
  }
  return ToIsometry(Compose(fused_.pose(), Between(wheel_at_frame_, wheel_for_fusion().pose())),
                    z0_);
}

PoseCovariances LocalizationStack::pose_covariances() const {
  PoseCovariances c;
  if (vo_) c.visual_odometry = vo_pose_covariance_;
  if (covariance_fused_) c.fused = covariance_fused_->covariance();
  c.ekf = ekf_.pose_covariance();
  return c;
}

std::optional<Eigen::Isometry3d> LocalizationStack::fused_ham2012() const {
  if (!covariance_fused_) return std::nullopt;
  return ToIsometry(Compose(fused_.pose(), Between(wheel_at_frame_, wheel_for_fusion().pose())),
                    z0_);
}

}  // namespace trackbed::estimation
