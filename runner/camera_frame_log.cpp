// The camera's frames for the run's bag (see camera_frame_log.h).
#include "trackbed/runner/camera_frame_log.h"

#include <cstdio>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "trackbed/perception/opencv_views.h"

namespace trackbed::runner {

CameraFrameLog::CameraFrameLog(const std::filesystem::path& dir) : dir_(dir) {
  std::filesystem::create_directories(dir / "left");
  std::filesystem::create_directories(dir / "right");
  times_.open(dir / "times.txt");
  if (!times_) throw std::runtime_error((dir / "times.txt").string() + ": cannot write");
}

void CameraFrameLog::Add(double t_s, const GrayImage& left, const GrayImage& right) {
  char name[16];
  std::snprintf(name, sizeof(name), "%06zu.png", frames_);
  // Compression level 1, as the KITTI export: a fast write, a file a third larger.
  const std::vector<int> png = {cv::IMWRITE_PNG_COMPRESSION, 1};
  for (const auto& [side, image] : {std::pair{"left", &left}, {"right", &right}}) {
    const std::filesystem::path path = dir_ / side / name;
    bool ok = false;
    try {
      ok = cv::imwrite(path.string(), perception::AsCvMat(*image), png);
    } catch (const cv::Exception&) {
      ok = false;
    }
    if (!ok) throw std::runtime_error(path.string() + ": cannot write");
  }
  char line[32];
  std::snprintf(line, sizeof(line), "%.6f\n", t_s);
  times_ << line;
  ++frames_;
}

void CameraFrameLog::Close() {
  times_.flush();
  if (!times_) throw std::runtime_error((dir_ / "times.txt").string() + ": write failed");
  times_.close();
}

}  // namespace trackbed::runner
