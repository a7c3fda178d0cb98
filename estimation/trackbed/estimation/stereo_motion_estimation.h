// The motion of a rectified stereo pair between two frames, from 3-D–3-D point
// correspondences: RANSAC over minimal 3-point samples solved by Horn's closed-form
// absolute orientation (1987) and refitted on the inliers, then Levenberg–Marquardt
// refinement of the inliers' reprojection error in the current left and right images
// with a re-selection of the inliers (Nistér et al. 2006; libviso2, Geiger et al. 2011).
//
// A unit of its own so that it can be tested on synthetic correspondences with a known
// motion, apart from feature tracking and stereo matching: value types and free
// functions, no state between calls, and the caller's generator the only randomness.
// StereoVisualOdometry (stereo_visual_odometry.h) runs it once per frame.
//
// Why the reprojection refinement: with a short baseline, depth Z = fx·b/d is noisy and
// the noise grows as Z² (σ_Z ≈ Z²σ_d/(fx·b)), so a fit that minimises 3-D distances is
// dominated by far points; the image-space error is what the measurements actually
// constrain, with the same noise for near and far points.
//
// Frames: cameras follow OpenCV (x right, y down, z forward). T_a_b maps b coordinates
// to a (p_a = T_a_b · p_b); "prev"/"curr" are the left cameras of the previous and the
// current frame.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "trackbed/common/random.h"
#include "trackbed/common/stereo_camera.h"

namespace trackbed::estimation {

/// One 3-D–3-D correspondence between consecutive frames.
struct MotionCorrespondence {
  Eigen::Vector3d p_prev = Eigen::Vector3d::Zero();  ///< point in the previous left camera [m]
  Eigen::Vector3d p_curr = Eigen::Vector3d::Zero();  ///< same point from the current pair [m]
  /// Its observation in the current pair: (u_left, v, u_right) [px].
  Eigen::Vector3d z_curr = Eigen::Vector3d::Zero();
  /// Its observation in the previous pair, from which p_prev was triangulated
  /// (MeasureDisparityOffset reads it).
  Eigen::Vector3d z_prev = Eigen::Vector3d::Zero();
};

/// A stereo rig's disparity offset δ [px] as one frame's motion shows it. A
/// rectification that got a principal point or the cameras' relative yaw slightly wrong
/// offsets every disparity by the same amount: the true disparity is d + δ for a measured
/// d. A point's depth is then off by the factor (d + δ) / d — little for near points,
/// much for far ones — so the translation's scale comes out wrong by a fraction that
/// grows as the motion rests on far points (at speed, near points leave LK's reach), and
/// points at different depths tell δ and the scale apart.
///
/// One Gauss–Newton step of the stereo reprojection error jointly over the motion and δ,
/// at T_curr_prev and δ = 0 (the caller's correspondences already corrected by its
/// current estimate: p_prev triangulated from z_prev, whose right coordinate is
/// u_left − (d + δ_current), likewise z_curr), with the Huber weights of the refinement,
/// marginalised to δ by the Schur complement: the step in δ and its variance (the
/// residuals' mean square per coordinate over δ's marginal information). Not valid with
/// fewer than kMinDisparityOffsetPoints points or no information on δ (no translation).
struct DisparityOffsetMeasurement {
  bool valid = false;
  double offset_px = 0.0;     ///< the step in δ [px]
  double variance_px2 = 0.0;  ///< its variance [px²]
  /// δ's marginal information per unit residual variance [-]: how strongly the points
  /// and the motion pin δ down (none without translation).
  double information = 0.0;
};
inline constexpr int kMinDisparityOffsetPoints = 10;
DisparityOffsetMeasurement MeasureDisparityOffset(
    const std::vector<MotionCorrespondence>& correspondences,
    const std::vector<unsigned char>& mask, const geometry::StereoCamera& camera,
    const Eigen::Isometry3d& T_curr_prev, double huber_px);

/// A 6-DoF increment δ = (ρ, φ) [m, rad] applied on the left:
/// T ← (Exp(φ), ρ) ∘ T, i.e. R ← Exp(φ)·R, t ← Exp(φ)·t + ρ.
using MotionIncrement = Eigen::Matrix<double, 6, 1>;
Eigen::Isometry3d ApplyIncrement(const MotionIncrement& delta, const Eigen::Isometry3d& T);

/// Stereo reprojection residual r = Project(T_curr_prev · p_prev) − z_curr [px] (u_left,
/// v, u_right), and, if J is not null, its Jacobian ∂r/∂δ (3×6) at δ = 0 for the
/// increment of ApplyIncrement. The point must be in front of the camera (Z > 0).
Eigen::Vector3d StereoReprojectionResidual(const geometry::StereoCamera& camera,
                                           const Eigen::Isometry3d& T_curr_prev,
                                           const MotionCorrespondence& c,
                                           Eigen::Matrix<double, 3, 6>* J = nullptr);

/// True when p_prev, moved by T_curr_prev, lies in front of the current camera and
/// reprojects within threshold_px of z_curr in both the left (u, v) and the right (u, v)
/// image.
bool IsReprojectionInlier(const geometry::StereoCamera& camera,
                          const Eigen::Isometry3d& T_curr_prev, const MotionCorrespondence& c,
                          double threshold_px);

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

  /// The keys of these fields (e.g. the scenario's `estimation.vo.ransac.*`,
  /// docs/scenario_format.md), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("max_iterations", &max_iterations);
    a->Visit("confidence", &confidence);
    a->Visit("threshold_px", &threshold_px);
  }
};

/// What EstimateMotionRansac found.
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
                          const geometry::StereoCamera& camera, const MotionRansacOptions& options,
                          random::Generator& rng, MotionRansacResult* result);

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

  /// The keys of these fields (e.g. the scenario's `estimation.vo.refinement.*`,
  /// docs/scenario_format.md), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("max_iterations", &max_iterations);
    a->Visit("huber_px", &huber_px);
    a->Visit("min_step", &min_step);
  }
};

/// What RefineMotionReprojection did.
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
    const std::vector<unsigned char>& mask, const geometry::StereoCamera& camera,
    const Eigen::Isometry3d& T_init, const MotionRefinementOptions& options);

/// Options of EstimateStereoMotion: RANSAC, the refinement, and how many inliers make a
/// motion.
struct StereoMotionOptions {
  /// RANSAC over 3-point samples. Its threshold_px [px] also re-selects the inliers
  /// after each refinement, so that the consensus and the final inliers mean the same.
  MotionRansacOptions ransac;
  /// Reprojection refinement after RANSAC's refit.
  MotionRefinementOptions refinement;
  /// Fewest inliers [correspondences] of a motion, >= 3: fewer in RANSAC's consensus or
  /// after the refinement is a failure. Also the fewest candidates RANSAC is run on.
  int min_inliers = 6;

  /// Throws OptionError naming the first invalid field (dotted for nested structs,
  /// e.g. "ransac.threshold_px").
  void Validate() const;

  /// The keys of these fields, read and written by the config archive
  /// (trackbed/common/archive.h). (StereoVisualOdometryOptions holds the same three
  /// fields itself, under the same keys.)
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("ransac", &ransac);
    a->Visit("refinement", &refinement);
    a->Visit("min_inliers", &min_inliers);
  }
};

/// Outcome of EstimateStereoMotion.
enum class StereoMotionStatus {
  kOk,                      ///< motion estimated, with >= min_inliers inliers
  kTooFewCorrespondences,   ///< fewer than min_inliers candidates: RANSAC was not run
  kDegenerate,              ///< every RANSAC sample was degenerate (e.g. collinear points)
  kTooFewConsensusInliers,  ///< RANSAC's consensus has fewer than min_inliers inliers
  kTooFewRefinedInliers,    ///< the refined motion keeps fewer, or is not finite
};

/// "ok", "too_few_correspondences", "degenerate", "too_few_consensus_inliers",
/// "too_few_refined_inliers".
const char* ToString(StereoMotionStatus status);

/// What EstimateStereoMotion found: the motion, its inliers, and how it got there.
struct StereoMotionResult {
  StereoMotionStatus status = StereoMotionStatus::kTooFewCorrespondences;
  /// The refined motion (p_curr = T_curr_prev · p_prev), its rotation re-orthonormalised.
  /// Identity unless ok.
  Eigen::Isometry3d T_curr_prev = Eigen::Isometry3d::Identity();
  /// Inliers of T_curr_prev among all correspondences: one entry per correspondence,
  /// 1 = inlier. Set once the refinement ran (ok, kTooFewRefinedInliers), else empty.
  std::vector<unsigned char> inlier_mask;
  int inliers = 0;     ///< the 1s of inlier_mask (0 before the refinement)
  int candidates = 0;  ///< correspondences RANSAC drew its samples from
  /// RANSAC's consensus before the refinement: its motion, inliers and hypotheses drawn;
  /// its inlier_mask has one entry per correspondence (0 for non-candidates). Empty (no
  /// success, no inliers, no mask) when RANSAC was not run (kTooFewCorrespondences).
  MotionRansacResult ransac;
  /// The last reprojection refinement (iterations, RMS residual before and after).
  MotionRefinementResult refinement;

  bool ok() const { return status == StereoMotionStatus::kOk; }
};

/// The motion between two frames of a stereo pair from their correspondences:
///   1. RANSAC (EstimateMotionRansac) on the candidates — all correspondences when
///      `candidates` is empty, else those whose entry is non-zero (one entry per
///      correspondence) — if there are at least min_inliers of them;
///   2. RefineMotionReprojection from the consensus on its inliers, a re-selection of
///      the inliers among all correspondences, and, if at least min_inliers remain, a
///      second refinement on them and a second re-selection.
/// Restricting the candidates lets a caller look for a second consensus among the
/// correspondences outside a first one (a moving object's points, say) while the
/// refinement may still take any correspondence that fits. The same inputs and `rng`
/// state give the same result; rng advances only when RANSAC runs. Writes into `result`
/// (its buffers are reused); `candidates` must not be one of them. Throws OptionError for
/// invalid options, std::invalid_argument for a candidates mask of the wrong size.
void EstimateStereoMotion(const std::vector<MotionCorrespondence>& correspondences,
                          const std::vector<unsigned char>& candidates,
                          const geometry::StereoCamera& camera, const StereoMotionOptions& options,
                          random::Generator& rng, StereoMotionResult* result);

}  // namespace trackbed::estimation
