// Fuzzes KITTI-layout sequence folders (kitti_sequence.h). The input is split at NUL bytes
// into calib.txt, times.txt and poses.txt (absent when the input has fewer than two NUL
// bytes) of a temporary sequence folder (one per process, its text files rewritten for
// each input); the constructor counts and reads the images, so image_0/ and image_1/ hold
// three small frames written once at start-up. Every line of the poses part also goes to
// ParseKittiPoseLine, and a pose it accepts must come back bit for bit through
// FormatKittiPoseLine (the header's promise).
//
// Finding: a crash, a sanitizer report, a hang, an exception other than std::runtime_error
// from KittiSequence or std::invalid_argument from ParseKittiPoseLine, a sequence read
// without error whose times or poses are not finite or whose times decrease, or a pose
// line that does not round-trip.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "fuzz_support.h"
#include "trackbed/perception/kitti_sequence.h"

namespace {

namespace fs = std::filesystem;
namespace perception = trackbed::perception;

[[noreturn]] void Finding(const std::string& what) {
  trackbed::fuzz::Finding("kitti_sequence_fuzz", what);
}

// This process's sequence folder with its images, removed at exit.
struct SequenceDir : trackbed::fuzz::ScratchDir {
  SequenceDir() : ScratchDir("kitti") {
    const cv::Mat image(8, 16, CV_8UC1, cv::Scalar(128));
    for (const char* folder : {"image_0", "image_1"}) {
      fs::create_directories(path / folder);
      for (const char* name : {"000000.png", "000001.png", "000002.png"}) {
        if (!cv::imwrite((path / folder / name).string(), image)) Finding("cannot write images");
      }
    }
  }
};

void Write(const fs::path& path, const std::string& text) {
  trackbed::fuzz::WriteFile("kitti_sequence_fuzz", path, text);
}

void CheckPoseLines(const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    Eigen::Isometry3d T;
    try {
      T = perception::ParseKittiPoseLine(line);
    } catch (const std::invalid_argument&) {
      continue;
    }
    const std::string formatted = perception::FormatKittiPoseLine(T);
    try {
      if (!(perception::ParseKittiPoseLine(formatted).matrix() == T.matrix())) {
        Finding("pose line does not round-trip: " + formatted);
      }
    } catch (const std::invalid_argument& e) {
      Finding("formatted pose line does not parse: " + formatted + ": " + e.what());
    }
  }
}

void CheckSequence(const perception::KittiSequence& s) {
  const std::vector<double>& t = s.times_s();
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!std::isfinite(t[k]) || (k > 0 && t[k] < t[k - 1])) Finding("bad time accepted");
  }
  for (const Eigen::Isometry3d& T : s.poses()) {
    if (!T.matrix().allFinite()) Finding("non-finite pose accepted");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const SequenceDir dir;
  const std::string input(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (int k = 0; k < 2; ++k) {
    const std::size_t nul = input.find('\0', begin);
    if (nul == std::string::npos) break;
    parts.push_back(input.substr(begin, nul - begin));
    begin = nul + 1;
  }
  parts.push_back(input.substr(begin));
  Write(dir.path / "calib.txt", parts[0]);
  Write(dir.path / "times.txt", parts.size() > 1 ? parts[1] : "");
  std::error_code ec;
  if (parts.size() > 2) {
    Write(dir.path / "poses.txt", parts[2]);
    CheckPoseLines(parts[2]);
  } else {
    fs::remove(dir.path / "poses.txt", ec);
  }
  try {
    CheckSequence(perception::KittiSequence(dir.path));
  } catch (const std::runtime_error&) {
  }
  return 0;
}
