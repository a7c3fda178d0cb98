// The camera's frames as the stack receives them (after the lens, the shutter and the
// sensor; not rectified), saved for the run's bag (`outputs.mcap_images`,
// run_bag.h): camera/left/NNNNNN.png and camera/right/NNNNNN.png (8-bit grey, frames
// numbered from 0) and camera/times.txt (each frame's time [s], 6 decimals, one per
// line).
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>

#include "trackbed/common/gray_image.h"

namespace trackbed::runner {

class CameraFrameLog {
 public:
  /// Creates `dir` with its left/ and right/ folders and times.txt. Throws
  /// std::runtime_error naming what cannot be written.
  explicit CameraFrameLog(const std::filesystem::path& dir);

  /// Writes frame size(). Throws std::runtime_error naming the file it cannot write.
  void Add(double t_s, const GrayImage& left, const GrayImage& right);
  std::size_t size() const { return frames_; }
  /// Flushes times.txt; throws std::runtime_error if that fails.
  void Close();

 private:
  std::filesystem::path dir_;
  std::ofstream times_;
  std::size_t frames_ = 0;
};

}  // namespace trackbed::runner
