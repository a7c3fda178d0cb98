// Trajectory files and association (see trajectory_io.h).
#include "trackbed/estimation/trajectory_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "trackbed/perception/kitti_sequence.h"

namespace trackbed::estimation {

namespace {

namespace fs = std::filesystem;

// Times above this are nanoseconds (TUM columns written by ORB-SLAM3); see the header.
constexpr double kNanosecondThreshold = 1e12;

[[noreturn]] void Fail(const fs::path& path, std::size_t line, const std::string& reason) {
  throw std::runtime_error(path.string() + ":" + std::to_string(line) + ": " + reason);
}

std::string Trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

std::vector<std::string> SplitWhitespace(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  std::string token;
  while (in >> token) out.push_back(token);
  return out;
}

std::vector<std::string> SplitCommas(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = s.find(',', start);
    out.push_back(
        Trim(s.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// The whole token as a finite double, or nullopt.
std::optional<double> ToDouble(const std::string& token) {
  if (token.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(token.c_str(), &end);
  if (end != token.c_str() + token.size() || errno == ERANGE || !std::isfinite(v)) {
    return std::nullopt;
  }
  return v;
}

bool AllDigits(const std::string& token) {
  return !token.empty() && token.size() <= 18 &&
         std::all_of(token.begin(), token.end(),
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
}

// Nanoseconds in `token` as seconds; an integer token is split exactly into s + ns.
double NanosecondsToSeconds(const std::string& token, double value) {
  if (AllDigits(token)) {
    const std::int64_t ns = std::strtoll(token.c_str(), nullptr, 10);
    return static_cast<double>(ns / 1000000000) + static_cast<double>(ns % 1000000000) * 1e-9;
  }
  return value * 1e-9;
}

double Number(const fs::path& path, std::size_t line, const std::string& token, const char* what) {
  const std::optional<double> v = ToDouble(token);
  if (!v) Fail(path, line, std::string("bad ") + what + " '" + token + "' (not a finite number)");
  return *v;
}

Eigen::Isometry3d PoseFromPositionQuaternion(const fs::path& path, std::size_t line,
                                             const Eigen::Vector3d& p, double qw, double qx,
                                             double qy, double qz) {
  Eigen::Quaterniond q(qw, qx, qy, qz);
  const double norm = q.norm();
  if (!(norm > 0.9 && norm < 1.1)) {
    std::ostringstream s;
    s << "quaternion norm " << norm << " is not 1 (wrong columns?)";
    Fail(path, line, s.str());
  }
  q.coeffs() /= norm;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = p;
  return T;
}

// Calls f(line_number, trimmed_line) for every non-blank, non-`#` line. A callback
// that returns bool stops the walk by returning false.
template <typename F>
void ForEachDataLine(const fs::path& path, F&& f) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot open file");
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string t = Trim(line);
    if (t.empty() || t[0] == '#') continue;
    if constexpr (std::is_same_v<decltype(f(number, t)), bool>) {
      if (!f(number, t)) return;
    } else {
      f(number, t);
    }
  }
  if (in.bad()) throw std::runtime_error(path.string() + ": read error");
}

LoadedTrajectory ReadTum(const fs::path& path) {
  LoadedTrajectory out;
  out.format = TrajectoryFormat::kTum;
  TumReader reader(path);
  for (StampedPose pose; reader.Next(&pose);) out.poses.push_back(pose);
  out.converted_from_ns = reader.converted_from_ns();
  return out;
}

LoadedTrajectory ReadEuroc(const fs::path& path) {
  LoadedTrajectory out;
  out.format = TrajectoryFormat::kEuroc;
  bool first = true;
  ForEachDataLine(path, [&](std::size_t line, const std::string& text) {
    const std::vector<std::string> f = SplitCommas(text);
    // A header row without the leading `#` (some tools drop it).
    if (first && !f.empty() && !ToDouble(f[0])) {
      first = false;
      return;
    }
    first = false;
    if (f.size() < 8) {
      Fail(path, line,
           "expected at least 8 comma-separated fields `timestamp [ns], p_x, p_y, p_z, q_w, q_x, "
           "q_y, q_z` (EuRoC), got " +
               std::to_string(f.size()));
    }
    const double t_ns = Number(path, line, f[0], "timestamp");
    const Eigen::Vector3d p(Number(path, line, f[1], "p_x"), Number(path, line, f[2], "p_y"),
                            Number(path, line, f[3], "p_z"));
    StampedPose pose;
    pose.t_s = NanosecondsToSeconds(f[0], t_ns);
    // EuRoC: quaternion w first.
    pose.T_world_body = PoseFromPositionQuaternion(
        path, line, p, Number(path, line, f[4], "q_w"), Number(path, line, f[5], "q_x"),
        Number(path, line, f[6], "q_y"), Number(path, line, f[7], "q_z"));
    out.poses.push_back(pose);
  });
  return out;
}

LoadedTrajectory ReadKitti(const fs::path& path, const fs::path& times_path) {
  LoadedTrajectory out;
  out.format = TrajectoryFormat::kKitti;
  ForEachDataLine(path, [&](std::size_t line, const std::string& text) {
    StampedPose pose;
    try {
      pose.T_world_body = perception::ParseKittiPoseLine(text);
    } catch (const std::invalid_argument& e) {
      std::string reason = e.what();
      const std::string prefix = "ParseKittiPoseLine: ";
      if (reason.rfind(prefix, 0) == 0) reason = reason.substr(prefix.size());
      Fail(path, line, reason + " (KITTI: 12 numbers, the row-major 3x4 [R | t])");
    }
    pose.t_s = static_cast<double>(out.poses.size());
    out.poses.push_back(pose);
  });
  if (times_path.empty()) {
    out.indexed = true;
    return out;
  }
  std::size_t k = 0, last_line = 0;
  ForEachDataLine(times_path, [&](std::size_t line, const std::string& text) {
    const std::vector<std::string> f = SplitWhitespace(text);
    if (f.size() != 1) {
      Fail(times_path, line,
           "expected one time [s] per line, got " + std::to_string(f.size()) + " fields");
    }
    const double t = Number(times_path, line, f[0], "time");
    if (k < out.poses.size()) out.poses[k].t_s = t;
    ++k;
    last_line = line;
  });
  if (k != out.poses.size()) {
    Fail(times_path, last_line,
         "has " + std::to_string(k) + " times for " + std::to_string(out.poses.size()) +
             " poses in " + path.string());
  }
  return out;
}

}  // namespace

const char* FormatName(TrajectoryFormat format) {
  switch (format) {
    case TrajectoryFormat::kTum:
      return "tum";
    case TrajectoryFormat::kKitti:
      return "kitti";
    case TrajectoryFormat::kEuroc:
      return "euroc";
  }
  return "?";
}

TrajectoryFormat ParseFormatName(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (TrajectoryFormat f :
       {TrajectoryFormat::kTum, TrajectoryFormat::kKitti, TrajectoryFormat::kEuroc}) {
    if (lower == FormatName(f)) return f;
  }
  throw std::invalid_argument("unknown trajectory format '" + name +
                              "' (expected tum, kitti or euroc)");
}

TrajectoryFormat DetectFormat(const fs::path& path) {
  // The first data line decides.
  std::optional<TrajectoryFormat> format;
  ForEachDataLine(path, [&](std::size_t number, const std::string& t) {
    if (t.find(',') != std::string::npos) {
      const std::size_t fields = SplitCommas(t).size();
      if (fields < 8) {
        Fail(path, number,
             "cannot detect the format: " + std::to_string(fields) +
                 " comma-separated fields (EuRoC csv needs at least 8)");
      }
      format = TrajectoryFormat::kEuroc;
      return false;
    }
    const std::size_t fields = SplitWhitespace(t).size();
    if (fields == 8) {
      format = TrajectoryFormat::kTum;
    } else if (fields == 12) {
      format = TrajectoryFormat::kKitti;
    } else {
      Fail(path, number,
           "cannot detect the format: " + std::to_string(fields) +
               " fields (TUM has 8, KITTI 12, EuRoC csv is comma-separated)");
    }
    return false;
  });
  if (!format) throw std::runtime_error(path.string() + ": no poses (the file has no data lines)");
  return *format;
}

TumReader::TumReader(const fs::path& path) : path_(path), in_(path) {
  if (!in_) throw std::runtime_error(path.string() + ": cannot open file");
}

bool TumReader::Next(StampedPose* pose) {
  std::string text;
  for (std::string raw; text.empty();) {
    if (!std::getline(in_, raw)) {
      if (in_.bad()) throw std::runtime_error(path_.string() + ": read error");
      return false;
    }
    ++line_;
    text = Trim(raw);
    if (!text.empty() && text[0] == '#') text.clear();
  }
  const std::size_t line = line_;
  const fs::path& path = path_;
  const std::vector<std::string> f = SplitWhitespace(text);
  if (f.size() != 8) {
    Fail(path, line,
         "expected 8 fields `t x y z qx qy qz qw` (TUM), got " + std::to_string(f.size()));
  }
  const double t = Number(path, line, f[0], "time");
  const bool ns = t > kNanosecondThreshold;
  if (first_) {
    converted_from_ns_ = ns;
    first_ = false;
  } else if (ns != converted_from_ns_) {
    Fail(path, line,
         "time " + f[0] + " mixes nanosecond and second timestamps (first pose's time was in " +
             (converted_from_ns_ ? "ns" : "s") + ")");
  }
  const Eigen::Vector3d p(Number(path, line, f[1], "x"), Number(path, line, f[2], "y"),
                          Number(path, line, f[3], "z"));
  pose->t_s = ns ? NanosecondsToSeconds(f[0], t) : t;
  pose->T_world_body = PoseFromPositionQuaternion(
      path, line, p, Number(path, line, f[7], "qw"), Number(path, line, f[4], "qx"),
      Number(path, line, f[5], "qy"), Number(path, line, f[6], "qz"));
  return true;
}

LoadedTrajectory ReadTrajectory(const fs::path& path, std::optional<TrajectoryFormat> format,
                                const fs::path& times_path) {
  const TrajectoryFormat f = format ? *format : DetectFormat(path);
  if (!times_path.empty() && f != TrajectoryFormat::kKitti) {
    throw std::invalid_argument("a times file (" + times_path.string() +
                                ") applies to KITTI trajectories only, but " + path.string() +
                                " is " + FormatName(f));
  }
  LoadedTrajectory out;
  switch (f) {
    case TrajectoryFormat::kTum:
      out = ReadTum(path);
      break;
    case TrajectoryFormat::kKitti:
      out = ReadKitti(path, times_path);
      break;
    case TrajectoryFormat::kEuroc:
      out = ReadEuroc(path);
      break;
  }
  if (out.poses.empty()) throw std::runtime_error(path.string() + ": no poses");
  return out;
}

void WriteTum(const fs::path& path, const Trajectory& trajectory) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot open for writing");
  out << "# t x y z qx qy qz qw\n";
  for (const StampedPose& p : trajectory) out << FormatTumLine(p) << '\n';
  out.flush();
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

void WriteKitti(const fs::path& path, const Trajectory& trajectory, const fs::path& times_path) {
  {
    std::ofstream out(path);
    if (!out) throw std::runtime_error(path.string() + ": cannot open for writing");
    for (const StampedPose& p : trajectory) {
      out << perception::FormatKittiPoseLine(p.T_world_body) << '\n';
    }
    out.flush();
    if (!out) throw std::runtime_error(path.string() + ": write failed");
  }
  if (times_path.empty()) return;
  std::ofstream out(times_path);
  if (!out) throw std::runtime_error(times_path.string() + ": cannot open for writing");
  char buf[64];
  for (const StampedPose& p : trajectory) {
    std::snprintf(buf, sizeof(buf), "%.9e", p.t_s);
    out << buf << '\n';
  }
  out.flush();
  if (!out) throw std::runtime_error(times_path.string() + ": write failed");
}

Association Associate(const Trajectory& a, const Trajectory& b, double max_dt_s, double offset_s) {
  if (!(std::isfinite(max_dt_s) && max_dt_s >= 0.0)) {
    throw std::invalid_argument("Associate: max_dt_s must be finite and >= 0 (got " +
                                std::to_string(max_dt_s) + ")");
  }
  if (!std::isfinite(offset_s)) {
    throw std::invalid_argument("Associate: offset_s must be finite");
  }
  // b's indices sorted by (shifted) time, so each a_i finds its candidates by binary search.
  std::vector<std::size_t> order(b.size());
  for (std::size_t j = 0; j < b.size(); ++j) order[j] = j;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return b[x].t_s < b[y].t_s; });
  std::vector<double> tb(b.size());
  for (std::size_t k = 0; k < order.size(); ++k) tb[k] = b[order[k]].t_s + offset_s;

  struct Candidate {
    double dt;
    std::size_t i, j;
  };
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = a[i].t_s;
    auto it = std::lower_bound(tb.begin(), tb.end(), t - max_dt_s);
    for (; it != tb.end() && *it <= t + max_dt_s; ++it) {
      const double dt = std::abs(t - *it);
      if (dt <= max_dt_s) {
        candidates.push_back({dt, i, order[static_cast<std::size_t>(it - tb.begin())]});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    if (x.dt != y.dt) return x.dt < y.dt;
    if (x.i != y.i) return x.i < y.i;
    return x.j < y.j;
  });
  std::vector<bool> used_a(a.size(), false), used_b(b.size(), false);
  std::vector<std::pair<std::size_t, std::size_t>> matches;
  for (const Candidate& c : candidates) {
    if (used_a[c.i] || used_b[c.j]) continue;
    used_a[c.i] = used_b[c.j] = true;
    matches.emplace_back(c.i, c.j);
  }
  std::sort(matches.begin(), matches.end(), [&](const auto& x, const auto& y) {
    if (a[x.first].t_s != a[y.first].t_s) return a[x.first].t_s < a[y.first].t_s;
    return x.first < y.first;
  });
  Association out;
  for (const auto& [i, j] : matches) {
    out.gt.push_back(a[i]);
    out.est.push_back(b[j]);
  }
  out.indices = std::move(matches);
  return out;
}

Association AssociateByIndex(const Trajectory& a, const Trajectory& b) {
  Association out;
  out.by_index = true;
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t k = 0; k < n; ++k) {
    out.gt.push_back(a[k]);
    out.est.push_back(b[k]);
    out.indices.emplace_back(k, k);
  }
  return out;
}

Association Associate(const LoadedTrajectory& a, const LoadedTrajectory& b, double max_dt_s,
                      double offset_s) {
  if (a.indexed || b.indexed) return AssociateByIndex(a.poses, b.poses);
  return Associate(a.poses, b.poses, max_dt_s, offset_s);
}

}  // namespace trackbed::estimation
