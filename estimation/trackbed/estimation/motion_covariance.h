// How well a stereo pair's frame-to-frame motion is determined, from the geometry of its
// inliers: the covariance of the motion that RefineMotionReprojection found, and the
// motion and covariance after a gyro's rotation over the frame interval is added as a
// prior.
//
// The residual of correspondence i, r_i = Project(T · p_prev,i) − z_curr,i [px]
// (StereoReprojectionResidual), has two noise sources: the current observation z_curr
// (left u, v, right u), and the point p_prev, triangulated from the previous frame's
// observation z_prev. Each image coordinate has the same noise σ [px], independently;
// p_prev = Triangulate(z_prev) carries it into the residual through the triangulation's
// Jacobian, which grows as Z²/(fx·b) along the depth. Per point
//   S_i = I + A_i A_iᵀ,  A_i = ∂Project/∂p (at T·p_prev) · R · ∂Triangulate/∂z_prev,
// is the residual's covariance in units of σ². The refinement minimises the Huber cost
// of the plain residuals (weights w_i: 1 within its threshold, k/|r_i| beyond), so its
// motion's covariance is the sandwich of an M-estimator (Huber 1967):
//   Σ = σ² · N⁻¹ M N⁻¹,  N = Σ_i w_i J_iᵀJ_i,  M = Σ_i w_i² J_iᵀ S_i J_i
// (J_i = ∂r_i/∂δ, the left increment of ApplyIncrement). σ² is estimated from the same
// residuals (the a-posteriori variance of a least-squares fit,
// Σ_i r_iᵀ S_i⁻¹ r_i / (3n − 6)): no figure is assumed for the tracker's and the
// matcher's precision. A far point's depth is poorly known,
// so its S is large along the direction its depth error moves its projection: far
// points pin down the rotation and little else, and a motion seen only in far points
// has a large translational covariance.
//
// Errors every point shares. A rectification whose principal points or relative yaw
// are slightly off offsets every disparity by the same δ [px] (stereo_motion_estimation.h,
// MeasureDisparityOffset): it moves the motion without leaving a residual, so σ above
// cannot show it, and it is common to every frame of the run. Given the calibration's
// stated spread of δ, σ_δ, it enters as a consider parameter (Schmidt's): with
// b_i = ∂r_i/∂δ = e₃ − A_i e₃ (δ shifts the right image's column in both observations)
// and g = N⁻¹ Σ_i H_i-weighted J_iᵀ b_i the refined motion's sensitivity to it (H_i the
// Huber cost's Hessian in r_i, as in N), Σ gains σ_δ²·g gᵀ: along the translation's
// scale, growing with the points' depth.
//
// Frames as in stereo_motion_estimation.h.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "trackbed/common/stereo_camera.h"
#include "trackbed/estimation/stereo_motion_estimation.h"

namespace trackbed::estimation {

using MotionCovarianceMatrix = Eigen::Matrix<double, 6, 6>;

/// What EstimateMotionCovariance found.
struct MotionCovariance {
  /// Enough points (>= 3, more than 6 / 3 residual coordinates) and a full-rank
  /// information matrix.
  bool valid = false;
  /// Covariance of the left increment δ = (ρ, φ) [m, rad] of T_curr_prev
  /// (ApplyIncrement): the true motion is ApplyIncrement(δ, T_curr_prev) with δ of this
  /// covariance [m², m·rad, rad²]. Zero unless valid.
  MotionCovarianceMatrix covariance = MotionCovarianceMatrix::Zero();
  /// The information per unit image variance, (N⁻¹MN⁻¹)⁻¹ above: covariance =
  /// σ²·unit_information⁻¹.
  MotionCovarianceMatrix unit_information = MotionCovarianceMatrix::Zero();
  /// σ, the image noise the residuals show [px] (a-posteriori, see the file comment).
  double image_noise_px = 0.0;
  int points = 0;  ///< the points that entered (in front of both cameras)
};

/// The covariance of the motion T_curr_prev from the correspondences whose mask entry is
/// non-zero (all if the mask is empty), as the file comment says, for the refinement's
/// Huber threshold `huber_px` (MotionRefinementOptions; <= 0: no Huber weights). Points
/// behind the
/// current or the previous camera, or with a disparity <= 0 in the previous frame, are
/// left out. `disparity_offset_std_px` [px], >= 0: σ_δ of the rig's disparity offset as
/// its calibration states it, a consider parameter (file comment); 0: none. Throws
/// std::invalid_argument for a mask of the wrong size.
MotionCovariance EstimateMotionCovariance(const std::vector<MotionCorrespondence>& correspondences,
                                          const std::vector<unsigned char>& mask,
                                          const geometry::StereoCamera& camera,
                                          const Eigen::Isometry3d& T_curr_prev, double huber_px,
                                          double disparity_offset_std_px = 0.0);

/// A rotation of the camera over the frame interval from another sensor (a gyro's
/// integrated rate) and its spread.
struct RotationPrior {
  /// The camera's rotation since the previous frame, p_prev = R_prev_curr · p_curr.
  Eigen::Matrix3d R_prev_curr = Eigen::Matrix3d::Identity();
  /// Its standard deviation per axis [rad], > 0.
  double std_rad = 1e-3;
};

/// The motion and its covariance with the rotation prior added: the two estimates, the
/// motion with its covariance and the prior's rotation, combined in information form
/// (one Gauss–Newton step of δᵀΣ⁻¹δ + |e_R(δ)|²/std², with
/// e_R = Log(R_curr_prev · R_prev_curr_prior) the rotation's disagreement with the
/// prior), so that the rotation's correction moves the translation as their correlation
/// in `vo` says. `vo` must be valid; its covariance is
/// replaced by the posterior's and *T_curr_prev moved by the step.
void AddRotationPrior(const RotationPrior& prior, MotionCovariance* vo,
                      Eigen::Isometry3d* T_curr_prev);

/// A motion's covariance seen in another frame: a motion M in frame a that is off by
/// the left increment E (true = E·M) is, as T_ba·M·T_ba⁻¹ in frame b, off by
/// T_ba·E·T_ba⁻¹, whose (ρ, φ) is Ad·(ρ, φ) with Ad = [[R, [t]×R], [0, R]] (R, t of
/// T_ba). Returns Ad·Σ·Adᵀ.
MotionCovarianceMatrix TransformMotionCovariance(const MotionCovarianceMatrix& covariance,
                                                 const Eigen::Isometry3d& T_ba);

}  // namespace trackbed::estimation
