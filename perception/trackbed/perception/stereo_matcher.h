// Sparse stereo matching on a rectified pair: for given points of the left image, the
// corresponding point of the right image on the same row, as a disparity
// d = u_left − u_right [px] (so that depth Z = fx · baseline / d).
//
// Method: block matching by zero-mean normalised cross-correlation (ZNCC, insensitive
// to the gain and offset differences of two cameras) of a window_px × window_px patch
// over the integer disparities [min_disparity_px, max_disparity_px]. Patches are
// sampled bilinearly at the point's sub-pixel position, so the integer disparity grid
// is exact for sub-pixel points. The peak is located by a parabola through the scores
// at d−1, d, d+1 and then refined by a few Gauss–Newton steps of 1-D Lucas–Kanade with
// gain and offset (the photometric model ZNCC is invariant to). A match is accepted when
//   - the left patch has texture (standard deviation >= min_texture, gray levels),
//   - the peak score is >= min_zncc and the peak is not at either end of the range,
//   - it is unique: the best other local maximum has a cost (1 − ZNCC) at least
//     (1 + uniqueness_ratio) times the peak's (costs floored at 0.01), and
//   - left–right consistent: matching the right point back into the left image gives
//     the same disparity within max_left_right_px.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace trackbed::perception {

/// Options of the sparse stereo matcher. Sizes and disparities in pixels.
struct StereoMatcherOptions {
  /// Side of the square matching window [px], odd, >= 3.
  int window_px = 11;
  /// Smallest disparity searched [px], >= 0.
  int min_disparity_px = 0;
  /// Largest disparity searched [px], >= min_disparity_px + 2. Sets the nearest depth:
  /// Z_min = fx · baseline / max_disparity_px.
  int max_disparity_px = 128;
  /// Minimum ZNCC of the best match, in [−1, 1].
  double min_zncc = 0.8;
  /// Uniqueness margin, >= 0: the second-best local maximum must have a cost (1 − ZNCC)
  /// >= (1 + uniqueness_ratio) × the best cost, costs below 0.01 counting as 0.01 (so
  /// that copies of a repeated pattern that all match almost perfectly are ambiguous).
  double uniqueness_ratio = 0.2;
  /// Left–right consistency tolerance [px], >= 0; 0 disables the check (halving the
  /// cost of matching).
  double max_left_right_px = 1.0;
  /// Minimum standard deviation of the left patch [gray levels of 0..255], >= 0.
  double min_texture = 2.0;
  /// Gauss–Newton iterations of the sub-pixel refinement after the parabola (1-D
  /// Lucas–Kanade with gain and offset), >= 0; 0 keeps the parabola's estimate, which is
  /// biased towards integers ("pixel locking", up to a few hundredths of a pixel).
  int refinement_iterations = 5;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The keys of these fields (e.g. the scenario's `estimation.vo.matcher.*`,
  /// docs/scenario_format.md), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("window_px", &window_px);
    a->Visit("min_disparity_px", &min_disparity_px);
    a->Visit("max_disparity_px", &max_disparity_px);
    a->Visit("min_zncc", &min_zncc);
    a->Visit("uniqueness_ratio", &uniqueness_ratio);
    a->Visit("max_left_right_px", &max_left_right_px);
    a->Visit("min_texture", &min_texture);
    a->Visit("refinement_iterations", &refinement_iterations);
  }
};

/// Outcome of matching one point.
enum class StereoMatchStatus : std::uint8_t {
  kMatched,            ///< disparity valid
  kOutOfImage,         ///< the left window does not fit in the image (or no disparity fits)
  kLowTexture,         ///< the left patch is too flat (min_texture)
  kWeak,               ///< best ZNCC below min_zncc
  kAtRangeLimit,       ///< best disparity at the end of the searched range
  kAmbiguous,          ///< another local maximum nearly as good (uniqueness_ratio)
  kLeftRightMismatch,  ///< the right-to-left match disagrees (max_left_right_px)
};

/// Short lower-case name of a status ("matched", "out_of_image", …).
const char* ToString(StereoMatchStatus status);

/// One stereo match of a left-image point.
struct StereoMatch {
  float disparity_px = 0.0f;  ///< u_left − u_right [px] (valid only when matched)
  float zncc = 0.0f;          ///< score of the best match, in [−1, 1]
  StereoMatchStatus status = StereoMatchStatus::kOutOfImage;
  bool valid() const { return status == StereoMatchStatus::kMatched; }
};

/// Matches left-image points into the right image of a rectified pair. Holds scratch
/// buffers only; not copyable.
class StereoMatcher {
 public:
  /// Throws OptionError naming the invalid field.
  explicit StereoMatcher(const StereoMatcherOptions& options = {});
  StereoMatcher(const StereoMatcher&) = delete;
  StereoMatcher& operator=(const StereoMatcher&) = delete;

  const StereoMatcherOptions& options() const { return options_; }

  /// Matches every point (left-image pixel coordinates, centre of the top-left pixel at
  /// (0, 0)); `matches` is resized to points.size(). `left` and `right` must be non-empty
  /// CV_8UC1 images of one size (throws std::invalid_argument otherwise). Returns the
  /// number of valid matches.
  int Match(const cv::Mat& left, const cv::Mat& right, const std::vector<cv::Point2f>& points,
            std::vector<StereoMatch>* matches);

  /// One point; same contract.
  StereoMatch Match(const cv::Mat& left, const cv::Mat& right, const cv::Point2f& point);

 private:
  struct Search {
    float disparity = 0.0f;
    float zncc = 0.0f;
    StereoMatchStatus status = StereoMatchStatus::kOutOfImage;
  };
  /// Searches `other` for the patch of `ref` at (u, v) at columns u + sign·d; with
  /// `refine`, the sub-pixel refinement follows the parabola.
  Search SearchRow(const cv::Mat& ref, const cv::Mat& other, float u, float v, int sign,
                   bool refine);
  /// Where one row search samples: the reference window and the disparities searched.
  struct RowWindow {
    int x0 = 0, y0 = 0;  ///< top-left pixel of the reference window
    /// u − ⌊u⌋ and v − ⌊v⌋: one set of bilinear weights serves every sample of the
    /// window and of the strip.
    float fx = 0.0f, fy = 0.0f;
    int d_lo = 0, d_hi = 0;  ///< disparities whose window lies inside `other`
    int candidates() const { return d_hi - d_lo + 1; }
  };
  /// SearchRow's geometry; false when the window leaves `ref` or fewer than 3
  /// disparities fit in `other` (kOutOfImage).
  bool PlanRowWindow(const cv::Mat& ref, const cv::Mat& other, float u, float v, int sign,
                     RowWindow* window) const;
  /// The reference patch into patch_, at zero mean, and its norm; false when it is too
  /// flat to match (kLowTexture).
  bool SampleReferencePatch(const cv::Mat& ref, const RowWindow& window, double* patch_norm);
  /// The ZNCC of every candidate disparity into scores_ (candidate k: disparity d_hi − k
  /// for sign < 0, d_lo + k for sign > 0).
  void ScoreCandidates(const cv::Mat& other, const RowWindow& window, int sign, double patch_norm);
  /// Σ patch_·window into scores_ for each of the `nd` candidate windows of strip_.
  void CrossCorrelateStrip(int strip_cols, int nd);
  /// Divides scores_ by the norms of the patch and of each zero-mean candidate window.
  void NormaliseToZncc(int strip_cols, int nd, double patch_norm);
  StereoMatch MatchOne(const cv::Mat& left, const cv::Mat& right, const cv::Point2f& point);
  /// Sub-pixel refinement of disparity d0 of the patch in patch_ (zero mean).
  float RefineDisparity(const cv::Mat& other, float u, float v, int sign, float d0);

  StereoMatcherOptions options_;
  // Scratch, reused between calls.
  std::vector<float> patch_, strip_, scores_, col_sum_, col_sum_sq_, grad_strip_;
  std::vector<float> rows_;  // RefineDisparity's rows, interpolated vertically
};

}  // namespace trackbed::perception
