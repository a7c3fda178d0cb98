// Image statistics over a folder of images (see image_sequence_statistics.h).
#include "trackbed/perception/image_sequence_statistics.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "trackbed/common/option_error.h"

namespace trackbed::perception {
namespace {

namespace fs = std::filesystem;

// The PNG files directly in `dir`, sorted by name; empty when `dir` is no folder.
std::vector<fs::path> PngsIn(const fs::path& dir) {
  std::vector<fs::path> pngs;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return pngs;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (e.is_regular_file() && ext == ".png") pngs.push_back(e.path());
  }
  std::sort(pngs.begin(), pngs.end());
  return pngs;
}

cv::Mat ReadGray(const fs::path& path, const cv::Size& expected) {
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
  if (image.empty() || image.type() != CV_8UC1) {
    throw std::runtime_error(path.string() + ": cannot be read as an 8-bit grey image");
  }
  if (!expected.empty() && image.size() != expected) {
    throw std::runtime_error(path.string() + ": " + std::to_string(image.cols) + " x " +
                             std::to_string(image.rows) + " px, the first image " +
                             std::to_string(expected.width) + " x " +
                             std::to_string(expected.height));
  }
  return image;
}

}  // namespace

void ImageSelection::Validate() const {
  option_check::AtLeast("first", first, 0);
  option_check::AtLeast("every", every, 1);
  option_check::AtLeast("count", count, 0);
}

std::vector<fs::path> FindImages(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw std::runtime_error(dir.string() + ": not a folder");
  for (const fs::path& where : {dir / "images" / "image_0", dir / "image_0", dir}) {
    std::vector<fs::path> pngs = PngsIn(where);
    if (!pngs.empty()) return pngs;
  }
  throw std::runtime_error(dir.string() +
                           ": no PNG image in images/image_0/ (a run folder), image_0/ (a KITTI "
                           "sequence) or the folder itself");
}

FolderStatistics MeasureFolder(const fs::path& dir, const ImageSelection& selection,
                               const ImageStatisticsOptions& options) {
  selection.Validate();
  options.Validate();
  const std::vector<fs::path> all = FindImages(dir);
  FolderStatistics result;
  SequenceStatistics sequence;
  cv::Mat next;  // the image after the current one, read for the track share
  std::size_t next_index = all.size();
  for (std::size_t i = static_cast<std::size_t>(selection.first); i < all.size();
       i += static_cast<std::size_t>(selection.every)) {
    if (selection.count > 0 && result.images.size() >= static_cast<std::size_t>(selection.count))
      break;
    const cv::Mat image =
        next_index == i ? next
                        : ReadGray(all[i], result.images.empty() ? cv::Size() : result.image_size);
    if (result.images.empty()) result.image_size = image.size();
    next = i + 1 < all.size() ? ReadGray(all[i + 1], result.image_size) : cv::Mat();
    next_index = i + 1;
    sequence.Add(MeasureImage(image, next, options));
    result.images.push_back(all[i]);
  }
  if (result.images.empty()) {
    throw std::runtime_error(dir.string() + ": the selection (first " +
                             std::to_string(selection.first) + " of " + std::to_string(all.size()) +
                             " images) holds no image");
  }
  result.bands = sequence.Mean();
  return result;
}

}  // namespace trackbed::perception
