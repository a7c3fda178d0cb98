// Trajectory metrics against ground truth, as the evo tool and the KITTI odometry
// devkit compute them, plus the run-folder figures of docs/run_folder.md.
//
// Every function takes *associated* trajectories: gt[k] and est[k] are the same instant
// (see Associate in trajectory_io.h); they throw std::invalid_argument (message starting
// with the function's name) if the two differ in size or are empty. Poses are
// T_world_body; positions in metres, angles as the names say. Pure functions returning
// values.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "trackbed/estimation/absolute_orientation.h"
#include "trackbed/estimation/trajectory.h"

namespace trackbed::estimation {

// ---------------------------------------------------------------------------------------
// Alignment

enum class AlignmentMode {
  kNone,  ///< compare as given
  kSe3,   ///< rigid: rotation + translation
  kSim3,  ///< similarity: rotation + translation + scale (monocular estimates)
};

/// "none", "se3", "sim3".
const char* AlignmentModeName(AlignmentMode mode);
/// Inverse of AlignmentModeName; throws std::invalid_argument for anything else.
AlignmentMode ParseAlignmentMode(const std::string& name);

struct Alignment {
  AlignmentMode mode = AlignmentMode::kNone;
  /// Maps the estimate's world frame into the ground truth's: p_gt ≈ s·R·p_est + t.
  SimilarityTransform T_gt_est;
  /// False when the positions are degenerate (fewer than 3, collinear — a straight run —
  /// or coincident): the transform is then one of several equally good ones (the
  /// residual errors are still minimal; the rotation about the line is arbitrary).
  bool unique = true;
};

/// Fits T_gt_est on the positions by Horn's method (HornAbsoluteOrientationAnyMinimizer),
/// minimising Σ |p_gt − (s R p_est + t)|², like evo's `-a` / `-as` (Umeyama alignment).
/// kNone gives the identity.
Alignment Align(const Trajectory& gt, const Trajectory& est, AlignmentMode mode);

/// The estimate moved by `T`: each pose (R_e, p_e) ↦ (R·R_e, s·R·p_e + t) (the scale acts
/// on positions only).
Trajectory ApplyAlignment(const SimilarityTransform& T, const Trajectory& est);

// ---------------------------------------------------------------------------------------
// Statistics and absolute errors

/// Summary statistics of a set of non-negative errors (all 0 when empty).
struct ErrorStats {
  std::size_t count = 0;
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double std = 0.0;  ///< population standard deviation (as evo)
  double min = 0.0;
  double max = 0.0;
};
ErrorStats ComputeStats(std::vector<double> values);

/// evo's APE (translation part): |p_gt,k − p_est,k| [m] per pose, after moving est by
/// Align(gt, est, mode). With kSe3 its rmse is metrics.json's `ate3d_se3_rmse_m`.
struct AbsoluteError {
  Alignment alignment;
  ErrorStats error_m;
};
AbsoluteError AbsoluteTrajectoryError(const Trajectory& gt, const Trajectory& est,
                                      AlignmentMode mode);

/// metrics.json's `ate_rmse_m` (docs/run_folder.md): the RMS horizontal (x, y) position
/// error [m], without any alignment (every estimator starts at the true initial pose;
/// the papers compare on the ground plane).
double HorizontalAteRmse(const Trajectory& gt, const Trajectory& est);

/// Error at the last associated pose, without alignment.
struct FinalError {
  double horizontal_m = 0.0;      ///< |(x, y)_est − (x, y)_gt| at the end (final_error_m)
  double error_3d_m = 0.0;        ///< the same in 3-D
  double gt_path_length_m = 0.0;  ///< PathLength(gt) of the associated poses
  /// 100 · horizontal_m / gt_path_length_m (as final_error_pct); NaN (n/a) on a path
  /// shorter than kMinPathForPerDistanceM (per_distance.h).
  double pct = 0.0;
};
FinalError ComputeFinalError(const Trajectory& gt, const Trajectory& est);

// ---------------------------------------------------------------------------------------
// Relative pose error (evo_rpe)

enum class DeltaUnit {
  kFrames,  ///< delta counts poses
  kMeters,  ///< delta is a length of the ground-truth path [m]
};

struct RpeOptions {
  double delta = 1.0;                   ///< spacing of the pose pairs, in `unit`; > 0
  DeltaUnit unit = DeltaUnit::kFrames;  ///< frames (integer delta ≥ 1) or metres of path
  /// False (evo's default): consecutive, non-overlapping pairs (0, j1), (j1, j2), …;
  /// true: a pair starting at every pose.
  bool all_pairs = false;
  void Validate() const;  ///< throws OptionError naming the field
};

/// For the pairs (i, j): E = (Q_i⁻¹ Q_j)⁻¹ (P_i⁻¹ P_j) with Q ground truth and P the
/// estimate; translation error |t(E)| [m], rotation error = angle of R(E) [deg]. In
/// metres, j is the first pose whose ground-truth path length from i reaches delta.
struct RpeResult {
  RpeOptions options;
  ErrorStats trans_m;
  ErrorStats rot_deg;
};
RpeResult RelativePoseError(const Trajectory& gt, const Trajectory& est,
                            const RpeOptions& options = {});

/// Frame-to-frame error of an odometry, the measure that compares a simulated camera's
/// odometry with a real one's on equal terms (docs/localization.md): for each pair of
/// consecutive poses whose true motion is at least min_motion_m, E as in
/// RelativePoseError; the translation error |t(E)| as a percentage of the true motion,
/// the rotation error [deg], and the length ratio |t(P_i⁻¹ P_i+1)| / |t(Q_i⁻¹ Q_i+1)|
/// (above 1: the odometry sees the frame's motion as longer than it was).
struct FrameMotionError {
  ErrorStats trans_pct;
  ErrorStats rot_deg;
  ErrorStats length_ratio;
  /// Whole paths: the estimate's path length over the ground truth's; NaN (n/a) when
  /// the ground truth's is under kMinPathForPerDistanceM (per_distance.h).
  double path_length_ratio = 0.0;
};
FrameMotionError FrameToFrameError(const Trajectory& gt, const Trajectory& est,
                                   double min_motion_m = 0.01);

/// One pair of consecutive poses of FrameToFrameError: `frame` is the index i of the
/// pair (i, i + 1).
struct FrameMotionSample {
  std::size_t frame = 0;
  double trans_pct = 0.0;     ///< |t(E)| over the true motion [%]
  double rot_deg = 0.0;       ///< angle of R(E) [deg]
  double length_ratio = 0.0;  ///< estimated over true motion
};
/// The per-pair values FrameToFrameError summarises, in frame order (pairs whose true
/// motion is under min_motion_m left out).
std::vector<FrameMotionSample> FrameToFrameErrors(const Trajectory& gt, const Trajectory& est,
                                                  double min_motion_m = 0.01);

// ---------------------------------------------------------------------------------------
// Drift over path segments (KITTI odometry devkit, evaluate_odometry.cpp)

struct SegmentDriftOptions {
  /// Segment lengths along the ground-truth path [m]; each > 0.
  std::vector<double> lengths_m = {100, 200, 300, 400, 500, 600, 700, 800};
  int step_frames = 10;   ///< a segment starts at every step_frames-th pose; ≥ 1
  void Validate() const;  ///< throws OptionError naming the field
};

/// Per segment from pose i of length L: j = the first pose whose ground-truth path
/// distance from i exceeds L; E = (Q_i⁻¹ Q_j)⁻¹ (P_i⁻¹ P_j); t_err = |t(E)| / L,
/// r_err = acos(clamp((tr R(E) − 1)/2, −1, 1)) / L (the devkit's formula). The figures
/// are means over all segments of all lengths, as the devkit's averages.
struct SegmentDrift {
  std::size_t segments = 0;         ///< 0 when the path is shorter than every length
  double t_rel_pct = 0.0;           ///< mean t_err × 100 [%]
  double r_rel_deg_per_100m = 0.0;  ///< mean r_err [rad/m] × 180/π × 100 [°/100 m]
  struct ByLength {
    double length_m = 0.0;
    std::size_t segments = 0;
    double t_rel_pct = 0.0;
    double r_rel_deg_per_100m = 0.0;
  };
  std::vector<ByLength> by_length;  ///< one entry per option length (segments may be 0)
};
SegmentDrift SegmentDriftError(const Trajectory& gt, const Trajectory& est,
                               const SegmentDriftOptions& options = {});

/// The KITTI benchmark's t_rel / r_rel: SegmentDriftError with the defaults (100…800 m,
/// every 10 frames). Needs a ground-truth path longer than 100 m (else segments == 0).
SegmentDrift KittiOdometryError(const Trajectory& gt, const Trajectory& est);

/// metrics.json's `rpe_trans_pct` (docs/run_folder.md): the mean translational drift
/// over 10 m segments of the ground-truth path (a segment starting at every pose), in %
/// of the segment length; std::nullopt when the path is shorter than 10 m.
std::optional<double> RpeTransPct(const Trajectory& gt, const Trajectory& est);

// ---------------------------------------------------------------------------------------
// Distance to a reference path (Ham et al. 2012, figs. 8–11)

/// For each estimated position, the distance [m] to the nearest point of the polyline
/// through the reference positions (segments between consecutive poses; a single pose
/// is a point). `horizontal`: in the (x, y) plane (z ignored), else in 3-D. The
/// trajectories need not be associated. Throws std::invalid_argument if reference is
/// empty. O(|estimate| · |reference|).
std::vector<double> DistancesToPath(const Trajectory& estimate, const Trajectory& reference,
                                    bool horizontal = true);

/// A histogram of DistancesToPath. Bin k counts distances in [edges_m[k], edges_m[k+1]),
/// the last bin is closed; distances below the first edge are counted in `below`, above
/// the last in `above`, so Σ counts + below + above = the number of estimated poses.
struct DistanceHistogram {
  std::vector<double> edges_m;
  std::vector<std::size_t> counts;  ///< edges_m.size() − 1 bins
  std::size_t below = 0;
  std::size_t above = 0;
  ErrorStats distance_m;  ///< of all distances
  std::size_t total() const;
};
/// Throws std::invalid_argument unless edges_m has ≥ 2 finite, strictly increasing values.
DistanceHistogram DistanceErrorHistogram(const Trajectory& estimate, const Trajectory& reference,
                                         const std::vector<double>& edges_m,
                                         bool horizontal = true);

// ---------------------------------------------------------------------------------------
// Everything at once (`trackbed eval`)

struct EvaluationOptions {
  AlignmentMode align = AlignmentMode::kSe3;  ///< for the ATE, RPE and segment drift
  RpeOptions rpe;                             ///< RPE pairs
  SegmentDriftOptions kitti;                  ///< KITTI t_rel / r_rel segments
  void Validate() const;
};

struct TrajectoryEvaluation {
  std::size_t pairs = 0;
  double gt_path_length_m = 0.0;
  double est_path_length_m = 0.0;       ///< of the estimate as given (before any scale)
  AbsoluteError ate;                    ///< 3-D, after `align`
  double ate_rmse_m = 0.0;              ///< horizontal, unaligned (docs/run_folder.md)
  RpeResult rpe;                        ///< on the aligned estimate
  SegmentDrift kitti;                   ///< on the aligned estimate; segments 0 if < 100 m
  std::optional<double> rpe_trans_pct;  ///< docs/run_folder.md; on the aligned estimate
  FinalError final_error;               ///< unaligned (docs/run_folder.md)
  double final_error_aligned_m = 0.0;   ///< 3-D, after `align`
};

/// All of the above for one associated pair of trajectories. The RPE, segment drift and
/// rpe_trans_pct use the aligned estimate (only a Sim(3) scale changes them: rigid
/// motions cancel in relative poses).
TrajectoryEvaluation EvaluateTrajectory(const Trajectory& gt, const Trajectory& est,
                                        const EvaluationOptions& options = {});

}  // namespace trackbed::estimation
