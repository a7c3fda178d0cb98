// Image statistics (image_statistics.h) over a folder of images: which images a folder
// holds, which of them are measured, and the means over them (`trackbed image-stats`,
// docs/image_statistics.md).
//
// A folder is read as, in this order:
//   a run folder        DIR/images/image_0/*.png (a run with outputs.save_images: kitti);
//   a KITTI sequence    DIR/image_0/*.png (the left camera's images);
//   a folder of images  DIR/*.png.
// The images are taken in the order of their file names. Of them, images first,
// first + every, first + 2·every, … are measured, at most `count` (0: all); each
// measured image's track share is into the image after it in the folder (the next
// frame, not the next one measured), and is undefined for the folder's last image.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

#include "trackbed/perception/image_statistics.h"

namespace trackbed::perception {

/// Which of a folder's images are measured.
struct ImageSelection {
  /// Index of the first image measured (in file-name order), >= 0.
  int first = 0;
  /// Measure every N-th image from `first`, >= 1.
  int every = 5;
  /// At most this many images measured, >= 0 (0: all there are).
  int count = 0;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The keys of these fields (`trackbed image-stats`' JSON output), read and written by
  /// the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("first", &first);
    a->Visit("every", &every);
    a->Visit("count", &count);
  }
};

/// The images of `dir` as the file comment reads it, in file-name order. Throws
/// std::runtime_error naming the folder when it is not a folder or holds no PNG image
/// in any of the three places.
std::vector<std::filesystem::path> FindImages(const std::filesystem::path& dir);

/// A folder's statistics: the images measured and the means over them.
struct FolderStatistics {
  std::vector<std::filesystem::path> images;  ///< the images measured, in order
  cv::Size image_size;                        ///< their size [px]
  std::vector<BandStatistics> bands;          ///< the means per band, top to bottom
};

/// Measures the selected images of `dir` (FindImages) as the file comment says. Throws
/// std::runtime_error naming the file for an image that cannot be read as an 8-bit grey
/// image (a colour image is converted to grey) or whose size differs from the first's,
/// and when the selection holds no image; OptionError for invalid options.
FolderStatistics MeasureFolder(const std::filesystem::path& dir, const ImageSelection& selection,
                               const ImageStatisticsOptions& options = {});

}  // namespace trackbed::perception
