// Fuzzes the trajectory readers (trajectory_io.h): the input up to its first NUL byte is
// written to a temporary trajectory file (one per process, rewritten for each input) and
// read with format detection and with each format forced (TUM, KITTI, EuRoC); the part
// after the NUL byte, when there is one, is a KITTI times file read with the trajectory
// as KITTI (and, documented as an error, as TUM).
//
// Finding: a crash, a sanitizer report, a hang, or an exception other than the documented
// std::runtime_error (and std::invalid_argument for a times file with another format
// than KITTI); a trajectory read without error but with a non-finite pose.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

#include "fuzz_support.h"
#include "trackbed/estimation/trajectory_io.h"

namespace {

namespace fs = std::filesystem;
using trackbed::estimation::TrajectoryFormat;

void Write(const fs::path& path, const std::string& text) {
  trackbed::fuzz::WriteFile("trajectory_fuzz", path, text);
}

void Read(const fs::path& path, std::optional<TrajectoryFormat> format,
          const fs::path& times = {}) {
  try {
    const auto loaded = trackbed::estimation::ReadTrajectory(path, format, times);
    for (const auto& pose : loaded.poses) {
      if (!std::isfinite(pose.t_s) || !pose.T_world_body.matrix().allFinite()) {
        std::fprintf(stderr, "trajectory_fuzz: FINDING: a non-finite pose was read\n");
        std::abort();
      }
    }
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
    if (times.empty() || format == TrajectoryFormat::kKitti) throw;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const trackbed::fuzz::ScratchDir dir("trajectory");
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  const fs::path trajectory = dir.path / "trajectory.txt";
  Write(trajectory, input.substr(0, nul));
  Read(trajectory, std::nullopt);
  for (TrajectoryFormat f :
       {TrajectoryFormat::kTum, TrajectoryFormat::kKitti, TrajectoryFormat::kEuroc}) {
    Read(trajectory, f);
  }
  if (nul != std::string::npos) {
    const fs::path times = dir.path / "times.txt";
    Write(times, input.substr(nul + 1));
    Read(trajectory, TrajectoryFormat::kKitti, times);
    Read(trajectory, TrajectoryFormat::kTum, times);
  }
  return 0;
}
