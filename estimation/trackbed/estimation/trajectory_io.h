// Reading and writing trajectories in the benchmark formats, and associating two
// trajectories pose by pose (`trackbed eval`; the formats and their pitfalls below).
//
//   TUM       `t x y z qx qy qz qw` per line, whitespace-separated, t in seconds, `#`
//             comments (TUM RGB-D benchmark). ORB-SLAM3 writes these columns with
//             nanosecond times: if the first pose's t > 1e12 the whole file's times are
//             taken as nanoseconds and converted to seconds (1e12 s is 31,700 years,
//             1e12 ns is 17 minutes after the epoch, so no real file is ambiguous).
//   KITTI     12 numbers per line, the row-major 3×4 [R | t] of the pose (KITTI odometry
//             devkit). No times: with a times file (one time [s] per line, KITTI's
//             times.txt) pose k gets line k's time; without one the trajectory is
//             `indexed`: t_s holds the pose's index k and poses are associated by index.
//   EuRoC     ASL csv: `#timestamp [ns], p_RS_R_x [m], p_RS_R_y, p_RS_R_z, q_RS_w [],
//             q_RS_x, q_RS_y, q_RS_z, …` — integer nanosecond times and the quaternion
//             **w first**; further columns (velocities, biases) are ignored.
//
// Quaternions are normalised on reading (files carry 4–9 digits); one whose norm is
// not within 10 % of 1 is an error, as it usually means misread columns.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "trackbed/estimation/trajectory.h"

namespace trackbed::estimation {

enum class TrajectoryFormat { kTum, kKitti, kEuroc };

/// "tum", "kitti", "euroc".
const char* FormatName(TrajectoryFormat format);
/// Inverse of FormatName (case-insensitive). Throws std::invalid_argument naming the
/// accepted names otherwise.
TrajectoryFormat ParseFormatName(const std::string& name);

/// A trajectory read from a file, with what association needs to know about it.
struct LoadedTrajectory {
  Trajectory poses;
  /// True when the file has no times (KITTI without a times file): poses[k].t_s = k and
  /// the trajectory can only be associated by index.
  bool indexed = false;
  TrajectoryFormat format = TrajectoryFormat::kTum;
  /// True when a TUM file's times were nanoseconds and have been converted to seconds.
  bool converted_from_ns = false;
};

/// Detects the format of `path` from its first data line (blank lines and `#`
/// comments skipped): comma-separated with ≥ 8 fields → EuRoC; 12 whitespace-separated
/// fields → KITTI; 8 → TUM. Throws std::runtime_error naming the file (and line) if it
/// cannot be read, has no data line, or the line fits none of these.
TrajectoryFormat DetectFormat(const std::filesystem::path& path);

/// A TUM file read pose by pose, in the memory of one line (a run folder's `.tum` files
/// of hours). The same checks and messages as ReadTrajectory's TUM reading.
class TumReader {
 public:
  /// Throws std::runtime_error naming the file if it cannot be opened.
  explicit TumReader(const std::filesystem::path& path);
  /// The next pose; false at the end of the file. Throws std::runtime_error with
  /// `file:line: reason` for a malformed line.
  bool Next(StampedPose* pose);
  /// True when the file's times are nanoseconds (converted to seconds).
  bool converted_from_ns() const { return converted_from_ns_; }

 private:
  std::filesystem::path path_;
  std::ifstream in_;
  std::size_t line_ = 0;
  bool first_ = true;
  bool converted_from_ns_ = false;
};

/// Reads a trajectory; `format` overrides detection. `times_path` (KITTI only) names a
/// times file with one time [s] per pose. Throws std::runtime_error with `file:line:
/// reason` for unreadable files, malformed lines (wrong field count, non-numeric or
/// non-finite values, a quaternion far from unit norm, a KITTI rotation that is not
/// one), a times file whose line count differs from the pose count, or a file without
/// poses; std::invalid_argument for a times file with a non-KITTI format.
LoadedTrajectory ReadTrajectory(const std::filesystem::path& path,
                                std::optional<TrajectoryFormat> format = std::nullopt,
                                const std::filesystem::path& times_path = {});

/// Writes TUM lines (FormatTumLine: t with 6 decimals, qw ≥ 0) with a `#` header.
/// Throws std::runtime_error naming the file if it cannot be written.
void WriteTum(const std::filesystem::path& path, const Trajectory& trajectory);

/// Writes KITTI pose lines (round-trip exact), and, when `times_path` is not empty, the
/// times [s] one per line (%.9e). Throws std::runtime_error naming the file on failure.
void WriteKitti(const std::filesystem::path& path, const Trajectory& trajectory,
                const std::filesystem::path& times_path = {});

/// Two trajectories paired pose by pose: gt[k] and est[k] belong together.
struct Association {
  Trajectory gt;
  Trajectory est;
  /// For each pair, the indices into the original (first, second) trajectories.
  std::vector<std::pair<std::size_t, std::size_t>> indices;
  bool by_index = false;  ///< paired by line number, not by time
};

/// Nearest-timestamp association like TUM's associate.py: every pair (i, j) with
/// |a_i.t − (b_j.t + offset_s)| ≤ max_dt_s is a candidate; candidates are taken in order
/// of increasing time difference (ties: lower i, then lower j), each pose used at most
/// once; the result is sorted by a's time. The est poses keep their own times. Throws
/// std::invalid_argument unless max_dt_s ≥ 0 and offset_s are finite.
Association Associate(const Trajectory& a, const Trajectory& b, double max_dt_s = 0.02,
                      double offset_s = 0.0);

/// Pairs a[k] with b[k] for k < min(a.size(), b.size()).
Association AssociateByIndex(const Trajectory& a, const Trajectory& b);

/// By index if either trajectory is `indexed` (KITTI without times), else by time.
Association Associate(const LoadedTrajectory& a, const LoadedTrajectory& b, double max_dt_s = 0.02,
                      double offset_s = 0.0);

}  // namespace trackbed::estimation
