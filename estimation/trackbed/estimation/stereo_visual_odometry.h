// Stereo visual odometry, frame to frame (Nistér et al. 2006; Ham et al. 2012 §3.2):
// Harris corners, pyramidal Lucas–Kanade tracking from the previous to the current left
// image, depth from stereo disparity, RANSAC over minimal 3-point samples solved by
// Horn's closed-form absolute orientation (1987), a refit on the inliers, and a few
// Gauss–Newton/Levenberg–Marquardt iterations that minimise the inliers' reprojection
// error in the current left and right images.
//
// Why the reprojection refinement: with a short baseline, depth Z = fx·b/d is noisy and
// the noise grows as Z² (σ_Z ≈ Z²σ_d/(fx·b)), so a fit that minimises 3-D distances is
// dominated by far points; the image-space error is what the measurements actually
// constrain, with the same noise for near and far points (as in libviso2, Geiger et al.
// 2011).
//
// Frames: cameras follow OpenCV (x right, y down, z forward). T_a_b maps b coordinates
// to a (p_a = T_a_b · p_b). "prev"/"curr" are the left cameras of the previous and the
// current frame; "world" is the left camera of the first frame.
//
// Per frame (StereoVisualOdometry::Process):
//   1. track the previous frame's features (with their 3-D points p_prev) into the
//      current left image (LK, forward–backward check), starting from where the last
//      motion predicts them;
//   2. stereo-match the tracked points in the current pair: p_curr, and the observation
//      z = (u_left, v, u_right);
//   3. RANSAC: 3 random correspondences → Horn (p_prev → p_curr) → T_curr_prev; inliers
//      by reprojection error of T_curr_prev·p_prev in the current left and right images;
//   4. Horn refit on the inliers (weights 1/(Z_prev⁴ + Z_curr⁴), the inverse variance
//      of stereo depth), then reprojection refinement, a re-selection of the inliers
//      with the refined motion and a second refinement;
//   4b. vet the motion: within the platform's per-frame bounds, and within its dynamics
//      bounds around the constant-velocity prediction (or a gyro's rotation, if given);
//      a consensus that breaks the dynamics bounds gives way to the consensus of the
//      remaining correspondences, if that one keeps within them;
//   5. keep the inliers as features and replenish the grid cells that have too few with
//      new Harris corners (stereo-matched for the next frame).
// Fewer than min_inliers inliers is a failure (docs/localization.md): no motion (identity),
// inliers = 0, a status that says why, and all features are detected afresh so that
// the next frame can recover.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "trackbed/perception/feature_tracker.h"
#include "trackbed/perception/harris_corners.h"
#include "trackbed/perception/kitti_sequence.h"
#include "trackbed/perception/stereo_matcher.h"

namespace trackbed::estimation {

/// Rectified pinhole stereo pair: both cameras share fx, fy, cx, cy; the right camera
/// sits baseline_m along the left camera's +x axis.
struct StereoCamera {
  double fx = 0.0;          ///< focal length along x [px], > 0
  double fy = 0.0;          ///< focal length along y [px], > 0
  double cx = 0.0;          ///< principal point x [px]
  double cy = 0.0;          ///< principal point y [px]
  double baseline_m = 0.0;  ///< [m], > 0

  /// From a KITTI-form calibration (P0, P1). Throws std::invalid_argument unless fx, fy,
  /// baseline > 0 and cx, cy finite.
  static StereoCamera FromCalibration(const perception::StereoCalibration& calibration);

  /// Point in the left camera frame [m] from a left pixel (u, v) [px] and disparity
  /// d = u_left − u_right [px] > 0: Z = fx·b/d, X = (u − cx)·Z/fx, Y = (v − cy)·Z/fy.
  Eigen::Vector3d Triangulate(double u, double v, double disparity_px) const;

  /// Projection of a point p (left camera frame, Z > 0) into the pair: (u_left, v,
  /// u_right) [px], u_right = fx·(X − b)/Z + cx.
  Eigen::Vector3d Project(const Eigen::Vector3d& p) const;
};

/// One 3-D–3-D correspondence between consecutive frames.
struct MotionCorrespondence {
  Eigen::Vector3d p_prev = Eigen::Vector3d::Zero();  ///< point in the previous left camera [m]
  Eigen::Vector3d p_curr = Eigen::Vector3d::Zero();  ///< same point from the current pair [m]
  /// Its observation in the current pair: (u_left, v, u_right) [px].
  Eigen::Vector3d z_curr = Eigen::Vector3d::Zero();
};

/// A 6-DoF increment δ = (ρ, φ) [m, rad] applied on the left:
/// T ← (Exp(φ), ρ) ∘ T, i.e. R ← Exp(φ)·R, t ← Exp(φ)·t + ρ.
using MotionIncrement = Eigen::Matrix<double, 6, 1>;
Eigen::Isometry3d ApplyIncrement(const MotionIncrement& delta, const Eigen::Isometry3d& T);

/// Stereo reprojection residual r = Project(T_curr_prev · p_prev) − z_curr [px] (u_left,
/// v, u_right), and, if J is not null, its Jacobian ∂r/∂δ (3×6) at δ = 0 for the
/// increment of ApplyIncrement. The point must be in front of the camera (Z > 0).
Eigen::Vector3d StereoReprojectionResidual(const StereoCamera& camera,
                                           const Eigen::Isometry3d& T_curr_prev,
                                           const MotionCorrespondence& c,
                                           Eigen::Matrix<double, 3, 6>* J = nullptr);

/// True when p_prev, moved by T_curr_prev, lies in front of the current camera and
/// reprojects within threshold_px of z_curr in both the left (u, v) and the right (u, v)
/// image.
bool IsReprojectionInlier(const StereoCamera& camera, const Eigen::Isometry3d& T_curr_prev,
                          const MotionCorrespondence& c, double threshold_px);

/// RANSAC over minimal samples of 3 correspondences.
struct MotionRansacOptions {
  /// Upper bound on hypotheses, >= 1.
  int max_iterations = 300;
  /// Stop early once a hypothesis with inlier ratio ε has been found and
  /// 1 − (1 − ε³)^k >= confidence after k hypotheses; in (0, 1).
  double confidence = 0.999;
  /// Inlier threshold [px] on the reprojection error in the current left and in the
  /// right image (each), > 0. Reprojection error is depth-aware by construction: the
  /// same pixel tolerance allows metres of depth error far away and millimetres near.
  double threshold_px = 2.0;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;
};

struct MotionRansacResult {
  bool success = false;  ///< a non-degenerate hypothesis was found
  /// Best hypothesis refitted on its inliers by Horn (weights 1/(Z_prev⁴ + Z_curr⁴)),
  /// unless the refit has fewer inliers than the hypothesis. Identity when !success.
  Eigen::Isometry3d T_curr_prev = Eigen::Isometry3d::Identity();
  int inliers = 0;                         ///< inliers of T_curr_prev
  int iterations = 0;                      ///< hypotheses drawn
  std::vector<unsigned char> inlier_mask;  ///< one per correspondence, 1 = inlier
};

/// RANSAC with Horn's absolute orientation (p_prev → p_curr) on 3-point samples, inliers
/// by IsReprojectionInlier. `rng` is the only source of randomness. Writes into `result`
/// (its mask buffer is reused). Needs >= 3 correspondences for success. Options are
/// validated (OptionError).
void EstimateMotionRansac(const std::vector<MotionCorrespondence>& correspondences,
                          const StereoCamera& camera, const MotionRansacOptions& options,
                          std::mt19937_64& rng, MotionRansacResult* result);

/// Levenberg–Marquardt on the stereo reprojection error.
struct MotionRefinementOptions {
  /// Maximum LM iterations, >= 0 (0 = no refinement).
  int max_iterations = 10;
  /// Huber threshold [px] on a correspondence's residual norm, > 0: errors beyond it
  /// count linearly (robust to inliers that are slightly off).
  double huber_px = 1.0;
  /// Stop when the increment's norm (metres and radians together) is below this, > 0.
  double min_step = 1e-9;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;
};

struct MotionRefinementResult {
  Eigen::Isometry3d T_curr_prev = Eigen::Isometry3d::Identity();
  int iterations = 0;
  double initial_rms_px = 0.0;  ///< RMS residual (per image coordinate) before
  double final_rms_px = 0.0;    ///< and after
  /// Stopped because the step became negligible (min_step) or no step lowers the cost,
  /// rather than on max_iterations.
  bool converged = false;
};

/// Minimises Σ Huber(|StereoReprojectionResidual|) over the correspondences whose mask
/// entry is non-zero (all if the mask is empty) by Levenberg–Marquardt on the 6-DoF
/// increment, starting from T_init. Steps that raise the cost are rejected (damping
/// grows); points that fall behind the camera are skipped. Throws
/// std::invalid_argument for a mask of the wrong size; OptionError for bad options.
MotionRefinementResult RefineMotionReprojection(
    const std::vector<MotionCorrespondence>& correspondences,
    const std::vector<unsigned char>& mask, const StereoCamera& camera,
    const Eigen::Isometry3d& T_init, const MotionRefinementOptions& options);

/// HarrisOptions{} with min_response = 2e-6: the VO's default detector.
inline perception::HarrisOptions DefaultVoHarrisOptions() {
  perception::HarrisOptions h;
  h.min_response = 2e-6;
  return h;
}

/// Options of StereoVisualOdometry. Nested structs carry their own documentation.
struct StereoVisualOdometryOptions {
  /// Harris detector for new features (absolute threshold: see harris_corners.h for
  /// the scale of min_response; the VO default 2e-6 keeps corners of contrast ≳ 0.13).
  perception::HarrisOptions harris = DefaultVoHarrisOptions();
  /// Bucketing grid for new features: cols × rows cells over the image, >= 1 each.
  int grid_cols = 12;
  int grid_rows = 4;
  /// Target number of features per cell, >= 1; cells with fewer get new corners.
  int features_per_cell = 8;
  /// A cell whose search for corners left it under-filled (little texture, or every
  /// corner already taken) is searched again only this many frames later, >= 1 (1 =
  /// every frame). Saves the Harris response of sky, blank walls and plain floors.
  int exhausted_cell_retry_frames = 4;
  /// A new corner must be at least this far from every kept feature in x or y [px]
  /// (Chebyshev distance, rounded up to whole pixels), >= 0.
  double min_feature_distance_px = 8.0;
  /// Lucas–Kanade tracking options.
  perception::FeatureTrackerOptions tracker;
  /// Stereo matching options (the disparity range sets the nearest depth).
  perception::StereoMatcherOptions matcher;
  /// Points farther than this [m] are not used, > 0.
  double max_depth_m = 200.0;
  /// RANSAC options (threshold in px of reprojection error).
  MotionRansacOptions ransac;
  /// Seed of the RANSAC generator (std::mt19937_64); the same seed and images give the
  /// same result.
  std::uint64_t seed = 1;
  /// Fewer inliers than this is a failure (docs/localization.md), >= 3.
  int min_inliers = 6;
  /// Per-frame motion bounds of the platform: a frame whose estimated motion moves the
  /// camera farther [m] or turns it more [deg] is a failure (kImplausibleMotion), not a
  /// motion — one wrong consensus would otherwise turn the whole trajectory. Defaults
  /// leave room for a car at 100 km/h and 10 Hz; a slow robot may tighten them. > 0.
  double max_translation_per_frame_m = 3.0;
  double max_rotation_per_frame_deg = 30.0;
  /// Dynamics bounds of the platform: its velocity cannot change faster than this, so a
  /// frame's motion cannot depart from the constant-velocity prediction (the last
  /// frame's motion, scaled to this frame's interval dt) by more than
  /// max_acceleration_mps2·dt² [m] or max_angular_acceleration_dps2·dt² [deg]. Such a
  /// consensus is a wrong one (features on a moving object, a repeated texture); the
  /// frame then runs RANSAC again on the correspondences outside it and takes the
  /// second consensus, refined like any other, if it has min_inliers inliers and keeps
  /// within the bounds, and fails (kInconsistentMotion) otherwise.
  /// Checked only when the last frame had a motion (for a rotation prior, see below).
  /// With a few dozen inliers a short-baseline rig's consensus can be 0.1 m off where
  /// the true translations differ by 1 cm from frame to frame: a bound just above the
  /// platform's true accelerations rejects it (the tracked robot's scenarios use
  /// 8 m/s², scenario/trackbed/scenario/scenario.h). Defaults leave room for a car braking at 3 g.
  /// > 0.
  double max_acceleration_mps2 = 30.0;
  double max_angular_acceleration_dps2 = 1000.0;
  /// With a rotation prior (a gyro's rotation over the frame interval, passed to
  /// Process), the frame's rotation is held to the prior instead, to within this [deg],
  /// > 0, also right after a failed frame; the angular acceleration bound is then not
  /// used. The prior only vets consensuses: it never enters the motion estimate.
  double max_rotation_prior_error_deg = 2.0;
  /// Reprojection refinement after the inlier refit.
  MotionRefinementOptions refinement;
  /// Start LK at the position the last motion predicts (constant velocity), rather than
  /// at the previous position: large image motions stay within LK's capture range.
  bool use_motion_prior = true;

  /// Throws OptionError naming the first invalid field (dotted for nested structs,
  /// e.g. "tracker.window_px").
  void Validate() const;
};

/// Outcome of one frame.
enum class VoStatus {
  kOk,                  ///< motion estimated
  kFirstFrame,          ///< first frame (or after Reset): features initialised, no motion
  kTooFewFeatures,      ///< fewer than min_inliers 3-D–3-D correspondences
  kTooFewInliers,       ///< RANSAC found fewer than min_inliers inliers
  kRansacFailed,        ///< every sample was degenerate
  kImplausibleMotion,   ///< the motion exceeds the per-frame bounds (a wrong consensus)
  kInconsistentMotion,  ///< breaks the dynamics bounds, as does the second consensus
};

/// "ok", "first_frame", "too_few_features", "too_few_inliers", "ransac_failed",
/// "implausible_motion", "inconsistent_motion".
const char* ToString(VoStatus status);

/// Result of StereoVisualOdometry::Process for one frame.
struct VoFrameResult {
  double t_s = 0.0;  ///< frame time [s]
  VoStatus status = VoStatus::kFirstFrame;
  std::string reason;  ///< why it failed (empty when ok or first frame)
  /// Motion of the left camera from the previous frame to this one, expressed in the
  /// previous camera frame: p_prev = T_prev_curr · p_curr. Identity unless ok.
  Eigen::Isometry3d T_prev_curr = Eigen::Isometry3d::Identity();
  /// Accumulated pose of the current left camera in the first camera's frame.
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  int tracked = 0;  ///< features tracked by LK from the previous frame (checks passed)
  int matched = 0;  ///< of those, with a stereo match: 3-D–3-D correspondences
  /// Inliers of the final motion: the "number of features" fusion uses (Ham et al.
  /// 2012); 0 on failure.
  int inliers = 0;
  int features = 0;                  ///< features carried to the next frame (inliers + new corners)
  double reprojection_rms_px = 0.0;  ///< inliers' RMS residual after refinement
  /// Whether RANSAC's consensus broke the dynamics bounds and the motion is the
  /// consensus of the other correspondences instead.
  bool dynamics_constrained = false;
  bool ok() const { return status == VoStatus::kOk; }
};

/// Frame-to-frame stereo visual odometry (see the file comment). Stateful; not
/// copyable.
class StereoVisualOdometry {
 public:
  /// Throws OptionError for invalid options, std::invalid_argument for a calibration
  /// without positive fx, fy, baseline.
  StereoVisualOdometry(const perception::StereoCalibration& calibration,
                       const StereoVisualOdometryOptions& options = {});
  StereoVisualOdometry(const StereoVisualOdometry&) = delete;
  StereoVisualOdometry& operator=(const StereoVisualOdometry&) = delete;

  /// Processes one rectified pair taken at t_s [s]. Images: non-empty CV_8UC1, left and
  /// right of one size, the same size for every frame; t_s finite and not decreasing.
  /// Throws std::invalid_argument otherwise (the state is then unchanged).
  /// `R_prev_curr_prior`: where known, the rotation of the left camera since the last
  /// frame (p_prev = R · p_curr, as T_prev_curr's), e.g. from a gyro; see
  /// max_rotation_prior_error_deg.
  VoFrameResult Process(const cv::Mat& left, const cv::Mat& right, double t_s,
                        const Eigen::Matrix3d* R_prev_curr_prior = nullptr);

  /// Forgets all features and the pose: the next frame is a first frame again.
  void Reset();

  const StereoCamera& camera() const { return camera_; }
  const StereoVisualOdometryOptions& options() const { return options_; }
  const Eigen::Isometry3d& T_world_cam() const { return T_world_cam_; }

 private:
  struct Features {
    std::vector<cv::Point2f> points;     // left image [px]
    std::vector<Eigen::Vector3d> p_cam;  // 3-D in that frame's left camera [m]
    void clear() {
      points.clear();
      p_cam.clear();
    }
    std::size_t size() const { return points.size(); }
  };

  /// Adds Harris corners in under-filled cells of `left` (stereo-matched in the pair)
  /// to `features`.
  void Replenish(const cv::Mat& left, const cv::Mat& right, Features* features);
  bool UsablePoint(const Eigen::Vector3d& p) const;

  StereoCamera camera_;
  StereoVisualOdometryOptions options_;
  perception::FeatureTracker tracker_;
  perception::StereoMatcher matcher_;
  std::mt19937_64 rng_;

  // State carried between frames.
  bool has_previous_ = false;
  double last_t_s_ = 0.0;
  cv::Size image_size_;
  perception::TrackingPyramid prev_pyramid_, curr_pyramid_;
  Features prev_, curr_;
  Eigen::Isometry3d T_world_cam_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d last_T_curr_prev_ = Eigen::Isometry3d::Identity();
  double last_motion_dt_s_ = 0.0;  // the interval last_T_curr_prev_ spans
  bool last_motion_valid_ = false;

  // Per-frame scratch (kept to avoid allocations).
  std::vector<cv::Point2f> tracked_points_, new_points_;
  std::vector<perception::TrackStatus> track_status_;
  std::vector<perception::StereoMatch> matches_;
  std::vector<MotionCorrespondence> correspondences_;
  std::vector<int> correspondence_feature_;  // correspondence → index into prev_
  MotionRansacResult ransac_;
  std::vector<unsigned char> inlier_mask_;
  std::vector<MotionCorrespondence> rest_;  // outside an inconsistent consensus
  std::vector<int> rest_index_;             // rest_ → index into correspondences_
  std::vector<unsigned char> rest_mask_;    // a consensus of rest_, over correspondences_
  std::vector<int> cell_count_;
  std::vector<std::int64_t> cell_retry_frame_;  // frame index from which a cell is searched
  std::int64_t frame_index_ = 0;                // frames processed since construction
  cv::Mat occupancy_;
};

}  // namespace trackbed::estimation
