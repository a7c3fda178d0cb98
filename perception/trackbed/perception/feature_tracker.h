// Pyramidal Lucas–Kanade feature tracking (Bouguet's implementation in OpenCV,
// cv::calcOpticalFlowPyrLK) from a previous to a current image, with the two checks
// OpenCV leaves to its caller:
//   - bounds: calcOpticalFlowPyrLK can report status 1 for a point it has moved
//     outside the image, so every tracked point is checked against the image;
//   - forward–backward consistency (Kalal et al. 2010): the tracked point is tracked
//     back to the previous image, starting where the forward track ended (shifted back
//     by the guess's displacement when a guess was given), and must land within
//     `max_forward_backward_px` of where it started; this
//     rejects tracks that slid along an edge, jumped to a similar-looking patch, or
//     went into an occluder.
// Pyramids are built once per image (TrackingPyramid) and reused: the current image's
// pyramid serves the forward track now, the backward track now, and the forward track
// of the next frame as the previous image.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace trackbed::perception {

/// Options of the Lucas–Kanade tracker. Sizes in pixels of the full-resolution image.
struct FeatureTrackerOptions {
  /// Side of the square LK integration window [px], odd, >= 5. (OpenCV's default is
  /// 21; 15 tracks as well on KITTI and 640×480 images at half the cost.)
  int window_px = 15;
  /// Pyramid levels above the full-resolution image (OpenCV's maxLevel), in [0, 8]. Each
  /// level doubles the capture range (about window_px/2 · 2^levels px).
  int pyramid_levels = 3;
  /// Gauss–Newton iterations per pyramid level, >= 1.
  int max_iterations = 20;
  /// Stop iterating when the update is smaller than this [px], > 0.
  double epsilon_px = 0.03;
  /// Minimum eigenvalue of the window's spatial gradient matrix divided by the window
  /// area (OpenCV's minEigThreshold, image scaled to [0, 1]), >= 0: flatter windows are
  /// lost rather than tracked.
  double min_eigenvalue = 1e-4;
  /// Forward–backward threshold [px], >= 0: a point tracked forward and back must return
  /// within this distance of its start. 0 disables the check.
  double max_forward_backward_px = 0.5;
  /// A tracked point must lie at least this far inside the image [px], >= 0: x in
  /// [border_px, width − 1 − border_px], likewise y (pixel centres at integers).
  double border_px = 0.0;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The keys of these fields (e.g. the scenario's `estimation.vo.tracker.*`,
  /// docs/scenario_format.md), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("window_px", &window_px);
    a->Visit("pyramid_levels", &pyramid_levels);
    a->Visit("max_iterations", &max_iterations);
    a->Visit("epsilon_px", &epsilon_px);
    a->Visit("min_eigenvalue", &min_eigenvalue);
    a->Visit("max_forward_backward_px", &max_forward_backward_px);
    a->Visit("border_px", &border_px);
  }
};

/// Outcome of tracking one point.
enum class TrackStatus : std::uint8_t {
  kTracked,          ///< tracked, inside the image, forward–backward consistent
  kLost,             ///< LK did not converge or the window was too flat (status 0)
  kOutOfImage,       ///< LK reported success but the point left the image (or its border)
  kForwardBackward,  ///< the backward track did not return to the start
};

/// Short lower-case name of a status ("tracked", "lost", "out_of_image",
/// "forward_backward").
const char* ToString(TrackStatus status);

/// An image pyramid for tracking (cv::buildOpticalFlowPyramid with derivatives, padded
/// for the window). Reuse one object per stream: its buffers are kept when the image
/// size does not change.
struct TrackingPyramid {
  std::vector<cv::Mat> levels;
  cv::Size image_size;  ///< size of level 0 [px]; empty until built
  bool empty() const { return levels.empty(); }
};

/// Tracks points from a previous to a current image. Holds scratch buffers only (no
/// state between calls affects the result); not copyable.
class FeatureTracker {
 public:
  /// Throws OptionError naming the invalid field.
  explicit FeatureTracker(const FeatureTrackerOptions& options = {});
  FeatureTracker(const FeatureTracker&) = delete;
  FeatureTracker& operator=(const FeatureTracker&) = delete;

  const FeatureTrackerOptions& options() const { return options_; }

  /// Builds the pyramid of `gray` (non-empty CV_8UC1; throws std::invalid_argument
  /// otherwise) into `pyramid`, reusing its buffers.
  void BuildPyramid(const cv::Mat& gray, TrackingPyramid* pyramid) const;

  /// Tracks `prev_points` (pixel coordinates in the previous image, centre of the
  /// top-left pixel at (0, 0)) into the current image. `curr_points` and `status` are
  /// resized to prev_points.size(); curr_points[i] is meaningful only where status[i] ==
  /// kTracked. With `use_initial_guess`, curr_points must hold one predicted position per
  /// point on input (e.g. from a motion prior): LK starts there instead of at the
  /// previous position. Returns the number of kTracked points. Throws
  /// std::invalid_argument for empty or differently sized pyramids, or a guess of the
  /// wrong size.
  int Track(const TrackingPyramid& prev, const TrackingPyramid& curr,
            const std::vector<cv::Point2f>& prev_points, std::vector<cv::Point2f>* curr_points,
            std::vector<TrackStatus>* status, bool use_initial_guess = false);

  /// Convenience for one image pair: builds both pyramids, then tracks as above.
  int Track(const cv::Mat& prev_gray, const cv::Mat& curr_gray,
            const std::vector<cv::Point2f>& prev_points, std::vector<cv::Point2f>* curr_points,
            std::vector<TrackStatus>* status);

 private:
  FeatureTrackerOptions options_;
  // Scratch, reused between calls to keep allocations out of the per-frame path.
  std::vector<unsigned char> lk_status_, back_status_;
  std::vector<std::size_t> fb_index_;
  std::vector<cv::Point2f> guess_shift_, fb_from_, back_points_;
  TrackingPyramid scratch_prev_, scratch_curr_;
};

}  // namespace trackbed::perception
