// Two-view geometry and patch matching for visual teach & repeat (Diosi et al. 2007, as
// Choi & Ha 2011 §III describe it): pure functions on value types.
//
// * Two-view reconstruction (ReconstructTwoView). The essential matrix between two
//   images of a calibrated camera (p_bᵀ E p_a = 0 on normalised coordinates, Choi & Ha
//   eq. 3) by Nistér's 5-point algorithm inside RANSAC (cv::findEssentialMat), the
//   motion by cv::recoverPose (the one of the four decompositions that puts the points
//   in front of both cameras), refitted on all inliers (Levenberg–Marquardt on the
//   Sampson error; RANSAC's answer is that of one minimal sample), linear (DLT)
//   triangulation, and the mean reprojection
//   error of the triangulated inliers in both images — the number that ends a 3D
//   milestone (Choi & Ha: 0.1 px). recoverPose's translation has unit norm: the caller
//   supplies the scale (odometry in teach; ScaleRatio in repeat).
// * Scale (ScaleRatio). Two reconstructions of the same points in the same camera frame
//   differ by a scale only; Choi & Ha make the repeat's reconstruction consistent with
//   the milestone's by "the ratio of corresponding 3-D coordinates". We take the median
//   of |p_reference| / |p_unscaled| over the points: the ratio of their distances from
//   the common camera centre, robust to a few bad points.
// * Patches (Zncc, SearchPatch). Zero-mean normalised cross-correlation of a stored
//   patch with the image around a predicted position (the feature recovery of Diosi et
//   al.): invariant to gain and offset of the brightness, in [−1, 1].
// * Path offsets (ComputePathOffset). The camera's lateral and heading offset from the
//   taught segment between a milestone's first and last camera, for steering.
//
// Frames: OpenCV cameras (x right, y down, z forward); T_a_b maps b coordinates to a.
// The "horizontal plane" is the camera's x–z plane: the camera is assumed level (its y
// axis vertical), as on the robot; a small pitch only scales offsets by cos(pitch).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "trackbed/teach_repeat/teach_map.h"

namespace trackbed::teach_repeat {

/// Options of ReconstructTwoView.
struct TwoViewOptions {
  /// RANSAC inlier threshold of cv::findEssentialMat: distance of a point from its
  /// epipolar line [px], > 0.
  double ransac_threshold_px = 1.0;
  /// RANSAC confidence, in (0, 1).
  double confidence = 0.999;
  /// RANSAC iterations at most, >= 1.
  int max_iterations = 1000;
  /// Fewer inliers (in front of both cameras) than this is a failure, >= 5.
  int min_inliers = 8;
  /// Refit the motion on all RANSAC inliers (Levenberg–Marquardt on the Sampson error)
  /// before triangulating: RANSAC returns the model of its best minimal sample.
  bool refine = true;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `teach_repeat.milestones.two_view`, `teach_repeat.localizer_3d.two_view`), read
  /// and written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("ransac_threshold_px", &ransac_threshold_px);
    a->Visit("confidence", &confidence);
    a->Visit("max_iterations", &max_iterations);
    a->Visit("min_inliers", &min_inliers);
    a->Visit("refine", &refine);
  }
};

/// Result of ReconstructTwoView.
struct TwoViewGeometry {
  bool ok = false;
  std::string reason;  ///< why not ok
  /// Pose of camera b in camera a's frame (p_a = T_a_b · p_b); |translation| = the given
  /// scale. Identity unless ok.
  Eigen::Isometry3d T_a_b = Eigen::Isometry3d::Identity();
  /// Triangulated points in a's frame at the same scale, one per input (zero where not an
  /// inlier).
  std::vector<Eigen::Vector3d> p_a;
  std::vector<unsigned char> inlier;  ///< RANSAC inlier, in front of both cameras
  int inliers = 0;
  /// Mean over the inliers of the pixel distance between a point's reprojection and its
  /// measurement, averaged over both images [px].
  double reprojection_error_px = 0.0;
  /// Median image motion |b_i − a_i| over all input pairs [px] (computed even when !ok).
  double median_parallax_px = 0.0;
};

/// Relative pose and structure from correspondences a[i] ↔ b[i] (pixel coordinates) of
/// one camera. `scale_m` > 0 sets |translation| (and the points' scale); <= 0 leaves it
/// 1. Deterministic (OpenCV's RANSAC uses a fixed seed). Throws std::invalid_argument if
/// a and b differ in size; OptionError for bad options or intrinsics.
TwoViewGeometry ReconstructTwoView(const geometry::PinholeCamera& camera,
                                   const std::vector<cv::Point2f>& a,
                                   const std::vector<cv::Point2f>& b, double scale_m,
                                   const TwoViewOptions& options);

/// Linear (DLT) triangulation of one point seen at normalised image coordinates x_a, x_b
/// (x/z, y/z) by cameras a (identity) and b with p_b = T_b_a · p_a. Returns the point
/// in a's frame.
Eigen::Vector3d TriangulateLinear(const Eigen::Vector2d& x_a, const Eigen::Vector2d& x_b,
                                  const Eigen::Isometry3d& T_b_a);

/// Median of |reference[i]| / |unscaled[i]| over the i with mask[i] != 0 (all if the
/// mask is empty) and both norms > 0; std::nullopt if there is none. Throws
/// std::invalid_argument for vectors (or a mask) of different sizes.
std::optional<double> ScaleRatio(const std::vector<Eigen::Vector3d>& reference,
                                 const std::vector<Eigen::Vector3d>& unscaled,
                                 const std::vector<unsigned char>& mask = {});

/// The pixel of a point in the camera frame [m]; std::nullopt unless Z > min_depth_m.
std::optional<cv::Point2d> ProjectPoint(const geometry::PinholeCamera& camera,
                                        const Eigen::Vector3d& p_cam, double min_depth_m = 1e-3);

/// ZNCC of `patch` (odd square CV_8UC1) with the equally sized window of `image`
/// (CV_8UC1) centred on the integer pixel `centre`. 0 when the patch or the window has a
/// standard deviation below min_stddev grey levels (a flat occluder or a blank wall
/// matches nothing); std::nullopt when the window leaves the image.
std::optional<double> Zncc(const cv::Mat& patch, const cv::Mat& image, cv::Point centre,
                           double min_stddev);

/// Best match of a patch near a predicted position.
struct PatchMatch {
  bool found = false;    ///< some window inside the image was compared
  cv::Point2f position;  ///< centre of the best window, sub-pixel [px]
  double score = -1.0;   ///< its ZNCC
};

/// Compares `patch` with the windows of `image` centred on every integer pixel within
/// `radius_px` (Chebyshev) of round(predicted); the best is refined to sub-pixel by a
/// parabola through the scores of its neighbours along each axis. Windows leaving the
/// image are skipped. Ties keep the first in raster order.
PatchMatch SearchPatch(const cv::Mat& image, const cv::Mat& patch, cv::Point2f predicted,
                       int radius_px, double min_stddev);

/// The translation that best aligns image `from` to image `to` (both CV_8UC1 of one
/// size), by phase correlation (cv::phaseCorrelate with a Hann window): a point at p in
/// `from` appears near p + shift in `to`. For a first guess where KLT must find features
/// of a key image in an image taken from a somewhat different pose (a yaw of a few
/// degrees moves the whole image by fx·tan(yaw)). Throws std::invalid_argument for
/// images of different sizes or types.
cv::Point2f EstimateImageShift(const cv::Mat& from, const cv::Mat& to);

/// The camera's offset from a taught segment, in the horizontal plane (see the file
/// comment).
struct PathOffset {
  /// Signed distance of the camera centre from the line through the first and the last
  /// camera centre [m]; > 0 when the camera is left of the taught direction.
  double lateral_m = 0.0;
  /// Camera heading minus the taught heading [rad], wrapped; > 0 when turned left (CCW
  /// seen from above). The taught heading is interpolated linearly in `progress` from
  /// the first camera's (0) to the last camera's.
  double heading_rad = 0.0;
  /// Along-track position: 0 at the first camera centre, 1 at the last (not clamped).
  double progress = 0.0;
  /// Length of the taught segment [m].
  double segment_length_m = 0.0;
};

/// Offsets of the camera T_first_cam from the segment from the first camera (identity) to
/// T_first_last, both in the milestone's first camera frame. A segment shorter than
/// 1 mm is taken along the first camera's optical axis, with progress 0.
PathOffset ComputePathOffset(const Eigen::Isometry3d& T_first_cam,
                             const Eigen::Isometry3d& T_first_last);

/// Heading of a camera in the horizontal plane of frame `a` [rad]: the angle of its
/// optical axis from a's z axis, > 0 toward a's −x (left).
double CameraHeading(const Eigen::Matrix3d& R_a_cam);

}  // namespace trackbed::teach_repeat
