// EKF odometry baseline (see ekf_odometry.h).
#include "trackbed/estimation/ekf_odometry.h"

#include <cmath>

#include <Eigen/Cholesky>

#include "trackbed/common/option_error.h"

namespace trackbed::estimation {
namespace {

// State layout.
constexpr int kX = 0, kY = 1, kTheta = 2, kVx = 3, kVy = 4, kOmega = 5, kBias = 6;
constexpr int kCloneX = 7, kCloneY = 8, kCloneTheta = 9;

}  // namespace

void EkfOdometryOptions::Validate() const {
  option_check::Positive("accel_noise", accel_noise);
  option_check::Positive("lateral_accel_noise", lateral_accel_noise);
  option_check::Positive("yaw_accel_noise", yaw_accel_noise);
  option_check::NonNegative("gyro_bias_walk", gyro_bias_walk);
  option_check::Positive("wheel_speed_std", wheel_speed_std);
  option_check::Positive("wheel_lateral_speed_std", wheel_lateral_speed_std);
  option_check::Positive("wheel_yaw_rate_std", wheel_yaw_rate_std);
  option_check::Positive("gyro_std", gyro_std);
  option_check::Positive("vo_speed_std", vo_speed_std);
  option_check::Positive("vo_yaw_rate_std", vo_yaw_rate_std);
  option_check::Positive("vo_reference_inliers", vo_reference_inliers);
  option_check::Positive("zero_velocity_std", zero_velocity_std);
}

EkfOdometry::EkfOdometry(const EkfOdometryOptions& options, const geometry::Pose2& initial_pose)
    : options_(options) {
  options_.Validate();
  x_(kX) = initial_pose.x;
  x_(kY) = initial_pose.y;
  x_(kTheta) = initial_pose.yaw;
  // The start pose is known (every estimator starts at the true initial pose,
  // docs/run_folder.md); velocity, yaw rate and bias are not.
  P_.diagonal().head<7>() << 1e-8, 1e-8, 1e-8, 0.1, 0.1, 0.1, 1e-4;
  ClonePose();
}

void EkfOdometry::ClonePose() {
  x_.segment<3>(kCloneX) = x_.segment<3>(kX);
  // The clone is the pose itself: same variances, fully correlated with it.
  P_.block<3, kN>(kCloneX, 0) = P_.block<3, kN>(kX, 0);
  P_.block<kN, 3>(0, kCloneX) = P_.block<kN, 3>(0, kX);
  P_.block<3, 3>(kCloneX, kCloneX) = P_.block<3, 3>(kX, kX);
}

void EkfOdometry::PredictTo(double t_s) {
  if (!started_) {
    started_ = true;
    t_ = t_s;
    return;
  }
  const double dt = t_s - t_;
  if (dt <= 0.0) return;
  const double th = x_(kTheta), vx = x_(kVx), vy = x_(kVy), w = x_(kOmega);
  const double c = std::cos(th), s = std::sin(th);
  x_(kX) += (vx * c - vy * s) * dt;
  x_(kY) += (vx * s + vy * c) * dt;
  x_(kTheta) += w * dt;
  Mat F = Mat::Identity();
  F(kX, kTheta) = -(vx * s + vy * c) * dt;
  F(kY, kTheta) = (vx * c - vy * s) * dt;
  F(kX, kVx) = c * dt;
  F(kX, kVy) = -s * dt;
  F(kY, kVx) = s * dt;
  F(kY, kVy) = c * dt;
  F(kTheta, kOmega) = dt;
  // P ← F P Fᵀ, where F differs from the identity only in the pose rows.
  const Mat P = P_;
  for (const int r : {kX, kY, kTheta}) P_.row(r) = F.row(r).lazyProduct(P);
  const Mat FP = P_;
  for (const int r : {kX, kY, kTheta}) P_.col(r) = FP.lazyProduct(F.row(r).transpose());
  P_(kVx, kVx) += options_.accel_noise * options_.accel_noise * dt;
  P_(kVy, kVy) += options_.lateral_accel_noise * options_.lateral_accel_noise * dt;
  P_(kOmega, kOmega) += options_.yaw_accel_noise * options_.yaw_accel_noise * dt;
  P_(kBias, kBias) += options_.gyro_bias_walk * options_.gyro_bias_walk * dt;
  t_ = t_s;
}

template <int M>
void EkfOdometry::Update(const Eigen::Matrix<double, M, 1>& innovation,
                         const Eigen::Matrix<double, M, kN>& H,
                         const Eigen::Matrix<double, M, M>& R) {
  // Coefficient-wise products: for a 10-state filter they are several times
  // faster than Eigen's blocked matrix product, which it picks from 20 rows,
  // columns and depth combined.
  const Eigen::Matrix<double, kN, M> PHt = P_.lazyProduct(H.transpose());
  const Eigen::Matrix<double, M, M> S = H.lazyProduct(PHt) + R;
  const Eigen::Matrix<double, kN, M> K = PHt.lazyProduct(S.inverse());
  x_ += K.lazyProduct(innovation);
  // Joseph form keeps P symmetric positive definite.
  const Mat I_KH = Mat::Identity() - K.lazyProduct(H);
  const Mat A = I_KH.lazyProduct(P_);
  const Eigen::Matrix<double, kN, M> KR = K.lazyProduct(R);
  P_ = A.lazyProduct(I_KH.transpose()) + KR.lazyProduct(K.transpose());
}

void EkfOdometry::AddWheelTwist(double t_s, double forward_mps, double yaw_rate_radps) {
  PredictTo(t_s);
  Eigen::Matrix<double, 3, kN> H = Eigen::Matrix<double, 3, kN>::Zero();
  H(0, kVx) = 1.0;
  H(1, kVy) = 1.0;
  H(2, kOmega) = 1.0;
  const Eigen::Vector3d z(forward_mps, 0.0, yaw_rate_radps);
  const Eigen::Vector3d sigma(options_.wheel_speed_std, options_.wheel_lateral_speed_std,
                              options_.wheel_yaw_rate_std);
  const Eigen::Matrix3d R = sigma.cwiseAbs2().asDiagonal();
  Update<3>(z - H * x_, H, R);
}

void EkfOdometry::AddZeroVelocity(double t_s) {
  PredictTo(t_s);
  Eigen::Matrix<double, 3, kN> H = Eigen::Matrix<double, 3, kN>::Zero();
  H(0, kVx) = 1.0;
  H(1, kVy) = 1.0;
  H(2, kOmega) = 1.0;
  const double var = options_.zero_velocity_std * options_.zero_velocity_std;
  const Eigen::Matrix3d R = Eigen::Vector3d::Constant(var).asDiagonal();
  Update<3>(-H * x_, H, R);
}

void EkfOdometry::AddGyro(double t_s, double yaw_rate_radps) {
  PredictTo(t_s);
  Eigen::Matrix<double, 1, kN> H = Eigen::Matrix<double, 1, kN>::Zero();
  H(0, kOmega) = 1.0;
  H(0, kBias) = 1.0;
  Eigen::Matrix<double, 1, 1> z, R;
  z << yaw_rate_radps;
  R << options_.gyro_std * options_.gyro_std;
  Update<1>(z - H * x_, H, R);
}

void EkfOdometry::AddCameraFrame(double t_s, const std::optional<geometry::Pose2>& motion,
                                 int inliers, const Eigen::Matrix3d* covariance) {
  PredictTo(t_s);
  const double dt = t_s - t_clone_;
  if (motion && has_clone_ && inliers > 0 && dt > 0.0) {
    // h = the pose's change since the clone, in the clone's axes.
    const double thc = x_(kCloneTheta), c = std::cos(thc), s = std::sin(thc);
    const double dx = x_(kX) - x_(kCloneX), dy = x_(kY) - x_(kCloneY);
    const Eigen::Vector3d h(c * dx + s * dy, -s * dx + c * dy, x_(kTheta) - thc);
    Eigen::Matrix<double, 3, kN> H = Eigen::Matrix<double, 3, kN>::Zero();
    H(0, kX) = c;
    H(0, kY) = s;
    H(1, kX) = -s;
    H(1, kY) = c;
    H(0, kCloneX) = -c;
    H(0, kCloneY) = -s;
    H(1, kCloneX) = s;
    H(1, kCloneY) = -c;
    H(0, kCloneTheta) = -s * dx + c * dy;
    H(1, kCloneTheta) = -c * dx - s * dy;
    H(2, kTheta) = 1.0;
    H(2, kCloneTheta) = -1.0;
    Eigen::Vector3d innovation = Eigen::Vector3d(motion->x, motion->y, motion->yaw) - h;
    innovation(2) = geometry::WrapAngle(innovation(2));
    const double scale = options_.vo_reference_inliers / static_cast<double>(inliers);
    const double var_t = scale * std::pow(options_.vo_speed_std * dt, 2);
    const double var_r = scale * std::pow(options_.vo_yaw_rate_std * dt, 2);
    const Eigen::Matrix3d R =
        options_.vo_covariance_from_vo && covariance
            ? *covariance
            : Eigen::Matrix3d(Eigen::Vector3d(var_t, var_t, var_r).asDiagonal());
    Update<3>(innovation, H, R);
  }
  ClonePose();
  t_clone_ = t_s;
  has_clone_ = true;
}

}  // namespace trackbed::estimation
