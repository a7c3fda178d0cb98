// A run's progress line (see run_progress.h).
#include "trackbed/runner/run_progress.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace trackbed::runner {

ProgressMode ParseProgressMode(const std::string& name) {
  if (name == "none") return ProgressMode::kNone;
  if (name == "lines") return ProgressMode::kLines;
  if (name == "bar") return ProgressMode::kBar;
  throw std::invalid_argument("unknown progress mode '" + name + "' (expected none, lines or bar)");
}

std::string FormatProgress(const ProgressFigures& f) {
  char left[32] = "?";
  if (f.wall_s > 0.0 && f.sim_s > 0.0) {
    const double seconds = std::max(0.0, f.total_s - f.sim_s) * f.wall_s / f.sim_s;
    const auto s = static_cast<long long>(std::llround(seconds));
    std::snprintf(left, sizeof(left), "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  }
  char rtf[32] = "?";
  if (f.wall_s > 0.0 && f.sim_s > 0.0) std::snprintf(rtf, sizeof(rtf), "%.3g", f.sim_s / f.wall_s);
  char distance[32];
  if (f.distance_m >= 10000.0) {
    std::snprintf(distance, sizeof(distance), "%.2f km", f.distance_m / 1000.0);
  } else {
    std::snprintf(distance, sizeof(distance), "%.1f m", f.distance_m);
  }
  const double pct = f.total_s > 0.0 ? std::min(100.0, 100.0 * f.sim_s / f.total_s) : 100.0;
  char line[192];
  std::snprintf(line, sizeof(line), "%7.1f / %.1f s (%.0f %%)  %sx real time  %s left  %s", f.sim_s,
                f.total_s, std::floor(pct), rtf, left, distance);
  return line;
}

RunProgress::RunProgress(ProgressMode mode, double total_s, std::FILE* out)
    : mode_(mode), total_s_(total_s), out_(out) {}

void RunProgress::Sample(double sim_s, const Eigen::Vector3d& true_position, double wall_s) {
  if (started_ && sim_s < last_sim_s_) {  // a second pass (teach & repeat) from t = 0
    started_ = false;
    last_tenth_ = 0;
    pass_start_wall_s_ = wall_s;
  }
  last_sim_s_ = sim_s;
  if (started_) distance_m_ += (true_position - last_position_).norm();
  started_ = true;
  last_position_ = true_position;
  if (mode_ == ProgressMode::kNone) return;
  const ProgressFigures f{sim_s, total_s_, wall_s - pass_start_wall_s_, distance_m_};
  if (mode_ == ProgressMode::kLines) {
    // One line per tenth of the duration reached (a tenth skipped is not caught up).
    const int tenth =
        total_s_ > 0.0 ? static_cast<int>(std::floor(10.0 * sim_s / total_s_ + 1e-9)) : 10;
    if (tenth <= last_tenth_) return;
    last_tenth_ = tenth;
    std::fprintf(out_, "trackbed run: %s\n", FormatProgress(f).c_str());
    std::fflush(out_);
    ++lines_;
    return;
  }
  if (last_bar_wall_s_ >= 0.0 && wall_s - last_bar_wall_s_ < 0.25) return;
  last_bar_wall_s_ = wall_s;
  const std::string line = FormatProgress(f);
  // Rewrite in place; spaces cover the end of a longer earlier line.
  const std::size_t pad = bar_width_ > line.size() ? bar_width_ - line.size() : 0;
  std::fprintf(out_, "\r%s%*s", line.c_str(), static_cast<int>(pad), "");
  std::fflush(out_);
  bar_width_ = line.size();
  ++lines_;
}

void RunProgress::Finish() {
  if (mode_ != ProgressMode::kBar || bar_width_ == 0) return;
  std::fprintf(out_, "\r%*s\r", static_cast<int>(bar_width_), "");
  std::fflush(out_);
  bar_width_ = 0;
}

}  // namespace trackbed::runner
