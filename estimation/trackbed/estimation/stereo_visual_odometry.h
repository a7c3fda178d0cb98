// Stereo visual odometry, frame to frame (Nistér et al. 2006; Ham et al. 2012 §3.2):
// Harris corners, pyramidal Lucas–Kanade tracking from the previous to the current left
// image, depth from stereo disparity, and the motion from the resulting 3-D–3-D
// correspondences by RANSAC with Horn's absolute orientation (1987) and a refinement of
// the inliers' reprojection error in the current left and right images — the last two
// in stereo_motion_estimation.h, which also says why the image-space error.
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
//      with the refined motion and a second refinement (steps 3–4: EstimateStereoMotion);
//   4b. vet the motion: within the platform's per-frame bounds, and within its dynamics
//      bounds around the constant-velocity prediction (or a gyro's rotation, if given);
//      a consensus that breaks the dynamics bounds gives way to the consensus of the
//      remaining correspondences, if that one keeps within them;
//   5. keep the inliers as features and replenish the grid cells that have too few with
//      new Harris corners (stereo-matched for the next frame); with
//      estimate_disparity_offset, update the rig's disparity offset from the inliers
//      (stereo_motion_estimation.h, MeasureDisparityOffset).
// Fewer than min_inliers inliers is a failure: no motion (identity), inliers = 0, a
// status and a reason that say why (a run folder logs each frame's status,
// docs/run_folder.md), and all features are detected afresh so that the next frame can
// recover.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "trackbed/estimation/motion_covariance.h"
#include "trackbed/estimation/stereo_motion_estimation.h"
#include "trackbed/perception/feature_tracker.h"
#include "trackbed/perception/harris_corners.h"
#include "trackbed/perception/stereo_matcher.h"

namespace trackbed::estimation {

/// HarrisOptions{} with min_response = 2e-6: the VO's default detector.
inline perception::HarrisOptions DefaultVoHarrisOptions() {
  perception::HarrisOptions h;
  h.min_response = 2e-6;
  return h;
}

/// Options of StereoVisualOdometry. Nested structs carry their own documentation.
struct StereoVisualOdometryOptions {
  /// Harris detector for new features (absolute threshold: see harris_corners.h for
  /// the scale of min_response; the VO default 2e-6 keeps sharp corners of contrast
  /// ≳ 0.13; 1e-5, ≳ 0.2, left 8–17 inliers a frame on the simulated outdoor route's
  /// sandy stretch, docs/localization.md).
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
  /// RANSAC options (threshold in px of reprojection error; it also re-selects the
  /// inliers after the refinement).
  MotionRansacOptions ransac;
  /// Seed of the RANSAC generator (random::Generator); the same seed and images give the
  /// same result.
  std::uint64_t seed = 1;
  /// Fewer inliers than this is a failure (see the file comment), >= 3.
  int min_inliers = 6;
  /// Per-frame motion bounds of the platform: a frame whose estimated motion moves the
  /// camera farther [m], > 0, or turns it more [deg], in [0.001, 180], is a failure
  /// (kImplausibleMotion), not a motion — one wrong consensus would otherwise turn the
  /// whole trajectory. Defaults leave room for a car at 100 km/h and 10 Hz (KittiCar());
  /// the tracked robot's are tighter (TrackedRobot()).
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
  /// platform's true accelerations rejects it (TrackedRobot(): 8 m/s²). Defaults leave
  /// room for a car braking at 3 g (KittiCar()). [m/s²], [deg/s²], > 0.
  double max_acceleration_mps2 = 30.0;
  double max_angular_acceleration_dps2 = 1000.0;
  /// With a rotation prior (a gyro's rotation over the frame interval, passed to
  /// Process), the frame's rotation is held to the prior instead, to within this [deg],
  /// > 0, also right after a failed frame; the angular acceleration bound is then not
  /// used. Unless rotation_prior_in_estimate, the prior only vets consensuses. (With
  /// a right consensus VO's rotation error stayed under 0.6 deg per frame in the
  /// simulated outdoor runs of seeds 3 and 6.)
  double max_rotation_prior_error_deg = 2.0;
  /// Add the rotation prior to the refined motion (AddRotationPrior, motion_covariance.h:
  /// the motion with its covariance from the inliers' geometry and the prior's rotation
  /// combined in information form), so that where the images pin the rotation down
  /// poorly the gyro's rotation — and with it the sideways motion it is tied to — takes
  /// over. Off: the motion is the images' alone (Ham et al. 2012's VO).
  bool rotation_prior_in_estimate = false;
  /// The prior's spread per axis over a frame interval dt is
  /// √((rotation_prior_bias_std_radps·dt)² + rotation_prior_noise_density²·dt) [rad]:
  /// an unestimated gyro bias [rad/s], >= 0, and the gyro's white noise
  /// [rad/s/√Hz], >= 0, not both 0. Defaults: the turn-on bias σ of every realism
  /// profile's IMU, 1e-3 rad/s, and the largest gyro white noise among them, ideal's
  /// 1.6968e-4 rad/s/√Hz (docs/calibration.md, "The IMU's noise").
  double rotation_prior_bias_std_radps = 1e-3;
  double rotation_prior_noise_density = 1.6968e-4;
  /// Reprojection refinement after the inlier refit.
  MotionRefinementOptions refinement;
  /// Start LK at the position the last motion predicts (constant velocity), rather than
  /// at the previous position: large image motions stay within LK's capture range.
  bool use_motion_prior = true;
  /// Estimate the rig's disparity offset (MeasureDisparityOffset) and triangulate with
  /// it: after every frame with a motion, its inliers' measurement updates a scalar
  /// Kalman filter — the offset a constant of the rig that may wander slowly (a
  /// calibration's error, a rig that warms up) — and every point is triangulated from
  /// its measured disparity plus the estimate. Off: the disparities as measured.
  bool estimate_disparity_offset = false;
  /// The filter's prior spread [px] (rectification errors are fractions of a pixel) and
  /// its random walk per frame [px], both > 0.
  double disparity_offset_prior_std_px = 1.0;
  double disparity_offset_walk_px = 0.005;
  /// Fold the rig's disparity offset into each frame's covariance as a consider
  /// parameter (motion_covariance.h, "Errors every point shares"): its spread is the
  /// offset filter's own where `estimate_disparity_offset`, else
  /// `calibration_disparity_offset_std_px`. Off: the pixels' noise alone.
  bool covariance_disparity_offset = false;
  /// The spread of the disparity offset the given calibration states [px], >= 0. No key:
  /// a scenario's run sets it from the calibration's stated spreads
  /// (runner/localization_options.h); 0 elsewhere.
  double calibration_disparity_offset_std_px = 0.0;

  /// Throws OptionError naming the first invalid field (dotted for nested structs,
  /// e.g. "tracker.window_px").
  void Validate() const;

  /// KITTI's car (`trackbed vo`, the KITTI twin): the in-class defaults.
  static StereoVisualOdometryOptions KittiCar() { return {}; }
  /// The tracked robot (a scenario's `estimation.vo`): the defaults with the motion and
  /// dynamics bounds of a robot that tops out at 1.5 m/s and whose camera runs at
  /// 10 Hz: 0.5 m and 20 deg per frame, and 8 m/s² (docs/localization.md: the camera's
  /// true translation changes by under 4 cm from one frame to the next outdoors, 4 m/s²;
  /// with a few dozen inliers VO's consensus can be 0.12 m off (seed 7), which 8 m/s²,
  /// 0.08 m at 10 Hz, rejects, where 30 let it through). The angular bound stays the
  /// default 1000 deg/s²: it applies only to frames without gyro samples, and the
  /// robot's rotation changes by up to 5.6 deg per 0.1 s when it starts or stops a turn
  /// on the spot (ClosedLoopNavigationTest's run).
  static StereoVisualOdometryOptions TrackedRobot() {
    StereoVisualOdometryOptions o;
    o.max_translation_per_frame_m = 0.5;
    o.max_rotation_per_frame_deg = 20.0;
    o.max_acceleration_mps2 = 8.0;
    return o;
  }

  /// The keys of these fields (e.g. the scenario's `estimation.vo.*`,
  /// docs/scenario_format.md), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("harris", &harris);
    a->Visit("grid_cols", &grid_cols);
    a->Visit("grid_rows", &grid_rows);
    a->Visit("features_per_cell", &features_per_cell);
    a->Visit("exhausted_cell_retry_frames", &exhausted_cell_retry_frames);
    a->Visit("min_feature_distance_px", &min_feature_distance_px);
    a->Visit("tracker", &tracker);
    a->Visit("matcher", &matcher);
    a->Visit("max_depth_m", &max_depth_m);
    a->Visit("ransac", &ransac);
    a->Visit("seed", &seed);
    a->Visit("min_inliers", &min_inliers);
    a->Visit("max_translation_per_frame_m", &max_translation_per_frame_m);
    a->Visit("max_rotation_per_frame_deg", &max_rotation_per_frame_deg);
    a->Visit("max_acceleration_mps2", &max_acceleration_mps2);
    a->Visit("max_angular_acceleration_dps2", &max_angular_acceleration_dps2);
    a->Visit("max_rotation_prior_error_deg", &max_rotation_prior_error_deg);
    a->Visit("rotation_prior_in_estimate", &rotation_prior_in_estimate);
    a->Visit("rotation_prior_bias_std_radps", &rotation_prior_bias_std_radps);
    a->Visit("rotation_prior_noise_density", &rotation_prior_noise_density);
    a->Visit("refinement", &refinement);
    a->Visit("use_motion_prior", &use_motion_prior);
    a->Visit("estimate_disparity_offset", &estimate_disparity_offset);
    a->Visit("disparity_offset_prior_std_px", &disparity_offset_prior_std_px);
    a->Visit("disparity_offset_walk_px", &disparity_offset_walk_px);
    a->Visit("covariance_disparity_offset", &covariance_disparity_offset);
  }
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
  kNotProcessed,        ///< the frame was set aside before VO saw it (LocalizationStack)
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
  /// The motion's covariance from its inliers' geometry (motion_covariance.h): of the
  /// left increment δ = (ρ, φ) [m, rad] of T_prev_curr⁻¹ (curr from prev), in the
  /// current camera's axes; with rotation_prior_in_estimate and a prior, the combined
  /// motion's. Valid only when ok and covariance_valid.
  MotionCovarianceMatrix covariance = MotionCovarianceMatrix::Zero();
  bool covariance_valid = false;
  /// The image noise the inliers' residuals show [px] (MotionCovariance::image_noise_px).
  double image_noise_px = 0.0;
  /// Whether the rotation prior entered the motion (rotation_prior_in_estimate).
  bool rotation_prior_applied = false;
  /// Whether RANSAC's consensus broke the dynamics bounds and the motion is the
  /// consensus of the other correspondences instead.
  bool dynamics_constrained = false;
  /// The disparity offset estimated so far [px], on every frame, failed ones too (0
  /// unless estimate_disparity_offset).
  double disparity_offset_px = 0.0;
  bool ok() const { return status == VoStatus::kOk; }
};

/// Frame-to-frame stereo visual odometry (see the file comment). Stateful; not
/// copyable.
class StereoVisualOdometry {
 public:
  /// `camera`: the calibrated, rectified pair the images come from. Throws OptionError
  /// for invalid options or an invalid camera (geometry::StereoCamera::Validate).
  StereoVisualOdometry(const geometry::StereoCamera& camera,
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

  const geometry::StereoCamera& camera() const { return camera_; }
  const StereoVisualOdometryOptions& options() const { return options_; }
  const Eigen::Isometry3d& T_world_cam() const { return T_world_cam_; }
  /// The rig's disparity offset estimated so far [px] (0 unless estimate_disparity_offset).
  double disparity_offset_px() const { return disparity_offset_px_; }

 private:
  struct Features {
    std::vector<cv::Point2f> points;     // left image [px]
    std::vector<Eigen::Vector3d> p_cam;  // 3-D in that frame's left camera [m]
    std::vector<float> disparity;        // as measured in that frame [px]
    void clear() {
      points.clear();
      p_cam.clear();
      disparity.clear();
    }
    std::size_t size() const { return points.size(); }
  };
  /// One frame's input, as Process received it.
  struct Frame {
    const cv::Mat& left;
    const cv::Mat& right;
    double t_s;
    const Eigen::Matrix3d* R_prev_curr_prior;  // may be null
  };
  /// Why a frame has no motion.
  struct Failure {
    VoStatus status;
    std::string reason;
  };

  // Process's steps, in order. Each works on the per-frame scratch below.
  /// Throws std::invalid_argument for the input Process rejects.
  void CheckInput(const cv::Mat& left, const cv::Mat& right, double t_s) const;
  /// 1. LK-tracks prev_ into tracked_points_/track_status_ (from the constant-velocity
  ///    prediction when use_motion_prior); returns the number tracked.
  int TrackFeatures(const cv::Size& image_size);
  /// 2. Stereo-matches the tracked points into correspondences_ (and new_points_, their
  ///    left image positions); returns their number.
  int MatchTrackedFeatures(const cv::Mat& left, const cv::Mat& right);
  /// 3–4. EstimateStereoMotion on correspondences_ into motion_; why not, if it failed.
  std::optional<Failure> EstimateMotion(int matched);
  /// 4b. Holds motion_ to the per-frame and dynamics bounds; replaces a consensus that
  ///     breaks the dynamics bounds by the other correspondences' one where that keeps
  ///     within them (result->dynamics_constrained). Why not, if it fails.
  std::optional<Failure> VetMotion(const Frame& frame, VoFrameResult* result);
  /// Why T moves more in one frame than max_*_per_frame allow, if it does.
  std::optional<std::string> ExceedsFrameBounds(const Eigen::Isometry3d& T) const;
  /// Why T departs from the rotation prior or, after a frame with a motion, from the
  /// constant-velocity prediction `predicted` beyond the dynamics bounds, if it does.
  std::optional<std::string> BreaksDynamics(const Eigen::Isometry3d& T, const Frame& frame,
                                            const Eigen::Isometry3d& predicted) const;
  /// The motion's covariance from its inliers, and the rotation prior added to the
  /// motion (rotation_prior_in_estimate), into result.
  void EstimateCovariance(const Frame& frame, VoFrameResult* result);
  /// Takes motion_ as this frame's motion: result, pose, constant-velocity state.
  void AcceptMotion(const Frame& frame, VoFrameResult* result);
  /// 5. Moves motion_'s inliers into curr_, the next frame's features.
  void CarryInliers();
  /// A first frame: features detected everywhere, pose identity.
  VoFrameResult StartAfresh(const Frame& frame, VoFrameResult* result);
  /// A failed frame: no motion, features detected everywhere.
  VoFrameResult Fail(const Frame& frame, Failure failure, VoFrameResult* result);
  /// Hands curr_ and the pyramid on to the next frame; completes and returns *result.
  VoFrameResult Finish(const Frame& frame, VoFrameResult* result);

  /// Adds Harris corners in under-filled cells of `left` (stereo-matched in the pair)
  /// to `features`.
  void Replenish(const cv::Mat& left, const cv::Mat& right, Features* features);
  bool UsablePoint(const Eigen::Vector3d& p) const;
  /// The point at left pixel (u, v) with measured disparity d, corrected by the offset.
  Eigen::Vector3d TriangulateCorrected(double u, double v, double d) const {
    return camera_.Triangulate(u, v, d + disparity_offset_px_);
  }
  /// Updates the disparity offset from this frame's inliers (estimate_disparity_offset).
  void UpdateDisparityOffset();
  double PriorOffsetVariance() const {
    return options_.disparity_offset_prior_std_px * options_.disparity_offset_prior_std_px;
  }

  geometry::StereoCamera camera_;
  StereoVisualOdometryOptions options_;
  StereoMotionOptions motion_options_;  // options_'s ransac, refinement, min_inliers
  perception::FeatureTracker tracker_;
  perception::StereoMatcher matcher_;
  random::Generator rng_;

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
  double disparity_offset_px_ = 0.0;
  double disparity_offset_var_px2_ = 0.0;

  // Per-frame scratch (kept to avoid allocations).
  std::vector<cv::Point2f> tracked_points_, new_points_;
  std::vector<perception::TrackStatus> track_status_;
  std::vector<perception::StereoMatch> matches_;
  std::vector<MotionCorrespondence> correspondences_;
  std::vector<int> correspondence_feature_;    // correspondence → index into prev_
  StereoMotionResult motion_;                  // of correspondences_
  std::vector<unsigned char> candidate_mask_;  // outside an inconsistent consensus
  std::vector<int> cell_count_;
  std::vector<std::int64_t> cell_retry_frame_;  // frame index from which a cell is searched
  std::int64_t frame_index_ = 0;                // frames processed since construction
  cv::Mat occupancy_;
};

}  // namespace trackbed::estimation
