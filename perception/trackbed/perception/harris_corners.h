// Harris corners (Harris & Stephens 1988) with an absolute response threshold.
//
// OpenCV's goodFeaturesToTrack thresholds at `qualityLevel` × the image's strongest
// response, so its counts are not comparable across images or scenes.
// Here R is computed on a fixed, documented scale and thresholded absolutely, so the
// number of corners says how much texture a scene has — which the fuzzy fusion uses.
//
// Scale of R. With I = gray / 255 ∈ [0, 1]:
//   Ix, Iy  = Sobel derivatives of aperture a divided by 2^(2a-3) (the sum of the
//             smoothing kernel times the derivative kernel's first moment), i.e. the
//             intensity slope per pixel: a ramp I = s·x gives Ix = s for a = 3, 5 and 7;
//   M       = weighted mean of [Ix² IxIy; IxIy Iy²] over a block_size × block_size
//             Gaussian window whose weights sum to 1 (σ = 0.3((block_size−1)/2 − 1) + 0.8,
//             OpenCV's default for that size), so M does not grow with the block; a
//             Gaussian rather than a box so that an ideal corner is one peak, not a
//             plateau as wide as block − aperture + 1;
//   R       = det M − k (trace M)²,  in [px⁻⁴] of normalised intensity.
// So R does not carry the kernels' raw sums (a ramp of slope s gives R = −k s⁴ for every
// block and aperture), and scales with contrast as c⁴: multiplying the image by c
// multiplies R by c⁴ (0.5 → 1/16). For reference, with the default 3/3 kernels an ideal
// step corner of contrast c (fraction of full scale) gives R ≈ 6.5e-3 c⁴ (an L corner)
// and a checkerboard X-junction R ≈ 5.6e-3 c⁴, so the default threshold 1e-4 keeps sharp
// corners of contrast ≳ 0.35; the real kitti06 left frames give ~270–470 corners at 1e-4
// and ~900 at 1e-5. Larger apertures give smaller R on sharp edges (the derivative is
// spread over more pixels). Borders are reflected (BORDER_REFLECT_101).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace trackbed::perception {

/// Options of the Harris detector. Sizes in pixels.
struct HarrisOptions {
  /// Neighbourhood for the structure tensor [px] (Gaussian window of this many taps per
  /// axis, see above), odd, >= 3.
  int block_size = 3;
  /// Sobel aperture [px]: 3, 5 or 7.
  int aperture_size = 3;
  /// Harris k, in (0, 0.25).
  double k = 0.04;
  /// Absolute threshold on R [px⁻⁴, image scaled to [0, 1]], >= 0; a corner needs R >
  /// min_response. See the file comment for the scale.
  double min_response = 1e-4;
  /// Non-maximum suppression radius [px], >= 1: no two corners closer than this in
  /// both x and y (a square window of side 2r+1); the stronger one is kept.
  int nms_radius_px = 3;
  /// Ignore corners closer than this to the image border [px], >= 0.
  int border_px = 8;
  /// Keep the strongest N corners (0 = all), >= 0.
  int max_corners = 0;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The keys of these fields (e.g. the scenario's `estimation.vo.harris.*`,
  /// docs/scenario_format.md), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("block_size", &block_size);
    a->Visit("aperture_size", &aperture_size);
    a->Visit("k", &k);
    a->Visit("min_response", &min_response);
    a->Visit("nms_radius_px", &nms_radius_px);
    a->Visit("border_px", &border_px);
    a->Visit("max_corners", &max_corners);
  }
};

/// A detected corner: sub-pixel position (OpenCV pixel coordinates, the centre of the
/// top-left pixel is (0, 0)) and its Harris response R (scale: see the file comment).
struct Corner {
  cv::Point2f position;
  float response = 0.0f;
};

/// Harris response map R (CV_32F, same size as `gray`) on the scale documented above.
/// `gray` must be a non-empty CV_8UC1 image (throws std::invalid_argument otherwise);
/// options are validated.
cv::Mat HarrisResponse(const cv::Mat& gray, const HarrisOptions& options);

/// Corners of an 8-bit grayscale image, strongest first (ties in raster order): local
/// maxima of R above min_response after non-maximum suppression, outside the border,
/// refined to sub-pixel by a parabola through R at the peak and its two neighbours along
/// each axis. Throws std::invalid_argument for an image that is not non-empty CV_8UC1,
/// OptionError for invalid options.
std::vector<Corner> DetectHarrisCorners(const cv::Mat& gray, const HarrisOptions& options);

/// Same, but spread over the image: the strongest `per_cell` corners in each cell of a
/// grid of `cols` x `rows` buckets (used by the visual odometry front end). A corner at
/// (x, y) is in cell (floor(x·cols/width), floor(y·rows/height)), clamped to the grid.
/// The candidates are those of DetectHarrisCorners with max_corners = 0; max_corners,
/// if > 0, then caps the total. Result strongest first. Throws std::invalid_argument
/// unless cols, rows, per_cell >= 1.
std::vector<Corner> DetectHarrisCornersBucketed(const cv::Mat& gray, const HarrisOptions& options,
                                                int cols, int rows, int per_cell);

}  // namespace trackbed::perception
