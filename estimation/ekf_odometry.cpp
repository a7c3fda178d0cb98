// EKF odometry baseline (see ekf_odometry.h).
#include "trackbed/estimation/ekf_odometry.h"

#include <cmath>

#include <Eigen/Cholesky>

#include "trackbed/common/option_error.h"

namespace trackbed::estimation {

void EkfOdometryOptions::Validate() const {
  option_check::Positive("accel_noise", accel_noise);
  option_check::Positive("yaw_accel_noise", yaw_accel_noise);
  option_check::NonNegative("gyro_bias_walk", gyro_bias_walk);
  option_check::Positive("wheel_speed_std", wheel_speed_std);
  option_check::Positive("wheel_yaw_rate_std", wheel_yaw_rate_std);
  option_check::Positive("gyro_std", gyro_std);
  option_check::Positive("vo_speed_std", vo_speed_std);
  option_check::Positive("vo_yaw_rate_std", vo_yaw_rate_std);
  option_check::Positive("vo_reference_inliers", vo_reference_inliers);
}

EkfOdometry::EkfOdometry(const EkfOdometryOptions& options, const Pose2& initial_pose)
    : options_(options) {
  options_.Validate();
  x_ << initial_pose.x, initial_pose.y, initial_pose.yaw, 0, 0, 0;
  // The start pose is known (design.md §3); speed, yaw rate and bias are not.
  P_.diagonal() << 1e-8, 1e-8, 1e-8, 0.1, 0.1, 1e-4;
}

void EkfOdometry::PredictTo(double t_s) {
  if (!started_) {
    started_ = true;
    t_ = t_s;
    return;
  }
  const double dt = t_s - t_;
  if (dt <= 0.0) return;
  const double th = x_(2), v = x_(3), w = x_(4);
  x_(0) += v * std::cos(th) * dt;
  x_(1) += v * std::sin(th) * dt;
  x_(2) += w * dt;
  Mat F = Mat::Identity();
  F(0, 2) = -v * std::sin(th) * dt;
  F(0, 3) = std::cos(th) * dt;
  F(1, 2) = v * std::cos(th) * dt;
  F(1, 3) = std::sin(th) * dt;
  F(2, 4) = dt;
  Mat Q = Mat::Zero();
  const double qa = options_.accel_noise * options_.accel_noise * dt;
  const double qw = options_.yaw_accel_noise * options_.yaw_accel_noise * dt;
  Q(3, 3) = qa;
  Q(4, 4) = qw;
  Q(5, 5) = options_.gyro_bias_walk * options_.gyro_bias_walk * dt;
  P_ = F * P_ * F.transpose() + Q;
  t_ = t_s;
}

template <int M>
void EkfOdometry::Update(const Eigen::Matrix<double, M, 1>& z, const Eigen::Matrix<double, M, 6>& H,
                         const Eigen::Matrix<double, M, M>& R) {
  const Eigen::Matrix<double, M, 1> innovation = z - H * x_;
  const Eigen::Matrix<double, M, M> S = H * P_ * H.transpose() + R;
  const Eigen::Matrix<double, 6, M> K = P_ * H.transpose() * S.inverse();
  x_ += K * innovation;
  // Joseph form keeps P symmetric positive definite.
  const Mat I_KH = Mat::Identity() - K * H;
  P_ = I_KH * P_ * I_KH.transpose() + K * R * K.transpose();
}

void EkfOdometry::AddWheelTwist(double t_s, double forward_mps, double yaw_rate_radps) {
  PredictTo(t_s);
  Eigen::Matrix<double, 2, 6> H = Eigen::Matrix<double, 2, 6>::Zero();
  H(0, 3) = 1.0;
  H(1, 4) = 1.0;
  const Eigen::Vector2d z(forward_mps, yaw_rate_radps);
  const Eigen::Matrix2d R =
      Eigen::Vector2d(options_.wheel_speed_std * options_.wheel_speed_std,
                      options_.wheel_yaw_rate_std * options_.wheel_yaw_rate_std)
          .asDiagonal();
  Update<2>(z, H, R);
}

void EkfOdometry::AddGyro(double t_s, double yaw_rate_radps) {
  PredictTo(t_s);
  Eigen::Matrix<double, 1, 6> H = Eigen::Matrix<double, 1, 6>::Zero();
  H(0, 4) = 1.0;
  H(0, 5) = 1.0;
  Eigen::Matrix<double, 1, 1> z, R;
  z << yaw_rate_radps;
  R << options_.gyro_std * options_.gyro_std;
  Update<1>(z, H, R);
}

void EkfOdometry::AddVisualTwist(double t_s, double forward_mps, double yaw_rate_radps,
                                 int inliers) {
  if (inliers <= 0) return;
  PredictTo(t_s);
  Eigen::Matrix<double, 2, 6> H = Eigen::Matrix<double, 2, 6>::Zero();
  H(0, 3) = 1.0;
  H(1, 4) = 1.0;
  const double scale = options_.vo_reference_inliers / static_cast<double>(inliers);
  const Eigen::Vector2d z(forward_mps, yaw_rate_radps);
  const Eigen::Matrix2d R =
      (scale * Eigen::Vector2d(options_.vo_speed_std * options_.vo_speed_std,
                               options_.vo_yaw_rate_std * options_.vo_yaw_rate_std))
          .asDiagonal();
  Update<2>(z, H, R);
}

}  // namespace trackbed::estimation
