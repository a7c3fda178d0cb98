// Image statistics per band of rows: how much a grey image offers a feature-based
// stack (corners, gradients, trackability) and how its content is spread over spatial
// frequencies (the power spectrum's slope), so that rendered images can be measured
// against real ones with one yardstick (docs/image_statistics.md).
//
// Bands: `bands` horizontal bands of ⌊H / bands⌋ rows each, from the top; the H mod
// bands bottom rows belong to no band (2 of KITTI 06's 370 rows for 4 bands). Per band:
//   fast_corners        cv::FastFeatureDetector (threshold 20, non-maximum suppression,
//                       TYPE_9_16) run on the whole image, corners counted by the band
//                       their row falls in (detecting on band crops instead loses the
//                       3-pixel border of every band: 4–6 % fewer per band on KITTI 06);
//   shi_tomasi_corners  cv::goodFeaturesToTrack on the whole image (at most 2000,
//                       quality 0.01, minimum distance 5 px, 3×3 block, no Harris),
//                       counted per band;
//   mean_gradient       mean over the band of sqrt(gx² + gy²), gx and gy the 3×3
//                       Sobel derivatives (unnormalised: a ramp of 1 grey level per
//                       pixel gives 8) of the whole image in float, borders reflected
//                       (BORDER_REFLECT_101);
//   spectrum_slope      least-squares slope of ln(power) against ln(frequency) of the
//                       band's radially averaged power spectrum: the band's mean
//                       subtracted, a 2-D Hann window applied (the outer product of the
//                       symmetric Hann windows 0.5 (1 − cos(2π i / (n − 1))) of its
//                       height and width; cv::createHanningWindow is the square root of
//                       that and reads 0.1 steeper on KITTI 06's sky), the DFT at the
//                       band's own size (no padding), power |F|², frequency
//                       f = sqrt((kx/W)² + (ky/H)²) [cycles/px]; the power averaged in
//                       `spectrum_bins` bins equally spaced in ln f over
//                       [spectrum_min_frequency, spectrum_max_frequency], each bin's mean
//                       power at the bin's centre in ln f (natural images: about −2; van
//                       der Schaaf & van Hateren 1996: 1.88 ± 0.43 for the exponent of
//                       amplitude squared);
//   grey_mean, grey_std the band's grey levels (population standard deviation);
//   track_share         the share of the band's FAST corners that pyramidal
//                       Lucas–Kanade (perception::FeatureTracker: cv::calcOpticalFlowPyrLK,
//                       21×21 window, 3 pyramid levels, 30 iterations or 0.01 px) tracks
//                       into the next image of the sequence with a forward–backward error
//                       of at most 1 px; NaN without a next image or without corners.
// A sequence's statistics are the means over the images measured (a track share over
// the images where it is defined).
#pragma once

#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

namespace trackbed::perception {

/// What the statistics measure and how (the defaults are the definitions above).
struct ImageStatisticsOptions {
  /// Horizontal bands of rows, top to bottom, [1, 64]; each ⌊H / bands⌋ rows.
  int bands = 4;
  /// FAST's intensity threshold [grey levels], [1, 255].
  int fast_threshold = 20;
  /// FAST with non-maximum suppression.
  bool fast_nonmax_suppression = true;
  /// Shi–Tomasi: at most this many corners in the whole image, >= 1.
  int shi_tomasi_max_corners = 2000;
  /// Shi–Tomasi quality level: the fraction of the strongest corner's minimum
  /// eigenvalue a corner needs, in (0, 1).
  double shi_tomasi_quality = 0.01;
  /// Shi–Tomasi minimum distance between corners [px], >= 0.
  double shi_tomasi_min_distance_px = 5.0;
  /// Spectrum: number of logarithmic frequency bins, >= 2.
  int spectrum_bins = 15;
  /// Spectrum: lowest frequency fitted [cycles/px], > 0.
  double spectrum_min_frequency = 1.0 / 64.0;
  /// Spectrum: highest frequency fitted [cycles/px], in (spectrum_min_frequency, 0.5].
  double spectrum_max_frequency = 0.25;
  /// Lucas–Kanade window side [px], odd, >= 5.
  int lk_window_px = 21;
  /// Lucas–Kanade pyramid levels above the image, [0, 8].
  int lk_pyramid_levels = 3;
  /// Largest forward–backward error of a tracked corner [px], > 0.
  double lk_max_forward_backward_px = 1.0;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The keys of these fields (`trackbed image-stats`' JSON output), read and written by
  /// the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("bands", &bands);
    a->Visit("fast_threshold", &fast_threshold);
    a->Visit("fast_nonmax_suppression", &fast_nonmax_suppression);
    a->Visit("shi_tomasi_max_corners", &shi_tomasi_max_corners);
    a->Visit("shi_tomasi_quality", &shi_tomasi_quality);
    a->Visit("shi_tomasi_min_distance_px", &shi_tomasi_min_distance_px);
    a->Visit("spectrum_bins", &spectrum_bins);
    a->Visit("spectrum_min_frequency", &spectrum_min_frequency);
    a->Visit("spectrum_max_frequency", &spectrum_max_frequency);
    a->Visit("lk_window_px", &lk_window_px);
    a->Visit("lk_pyramid_levels", &lk_pyramid_levels);
    a->Visit("lk_max_forward_backward_px", &lk_max_forward_backward_px);
  }
};

/// One band's statistics (of one image, or the means over a sequence's images).
struct BandStatistics {
  int row_begin = 0;  ///< first row of the band
  int row_end = 0;    ///< one past its last row
  double fast_corners = 0.0;
  double shi_tomasi_corners = 0.0;
  double mean_gradient = 0.0;   ///< [grey levels/px × 8] (unnormalised 3×3 Sobel)
  double spectrum_slope = 0.0;  ///< d ln(power) / d ln(frequency)
  double grey_mean = 0.0;       ///< [grey levels]
  double grey_std = 0.0;        ///< [grey levels]
  double track_share = 0.0;     ///< in [0, 1]; NaN where undefined
};

/// The rows [begin, end) of each band of an image `rows` high: ⌊rows / bands⌋ rows each
/// from the top. Throws std::invalid_argument when a band would have fewer than 8 rows.
std::vector<cv::Range> BandRows(int rows, int bands);

/// The statistics of `gray` per band (see the file comment). `next`: the sequence's
/// next image (the same size), or empty (track shares NaN). Throws std::invalid_argument
/// for an empty or non-CV_8UC1 image, a `next` of another size or type, or an image too
/// small for the bands; OptionError for invalid options.
std::vector<BandStatistics> MeasureImage(const cv::Mat& gray, const cv::Mat& next,
                                         const ImageStatisticsOptions& options = {});

/// The spectrum slope of one image or band (CV_8UC1, at least 8 × 8) as defined in the
/// file comment; NaN with fewer than 2 non-empty bins.
double SpectrumSlope(const cv::Mat& gray, const ImageStatisticsOptions& options = {});

/// Means of per-image band statistics over a sequence, image by image.
class SequenceStatistics {
 public:
  /// Adds one image's bands; every image must have the same bands (throws
  /// std::invalid_argument otherwise).
  void Add(const std::vector<BandStatistics>& image);
  /// Images added.
  std::size_t images() const { return images_; }
  /// The means per band (each field averaged over the images, a track share over the
  /// images where it is defined: NaN where none is); empty before the first Add.
  std::vector<BandStatistics> Mean() const;

 private:
  std::vector<BandStatistics> sums_;
  std::vector<int> track_share_images_;
  std::size_t images_ = 0;
};

}  // namespace trackbed::perception
