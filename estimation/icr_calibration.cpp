// ICR expansion factor fit (see icr_calibration.h).
#include "trackbed/estimation/icr_calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace trackbed::estimation {

namespace {

// Most groups of consecutive windows the jackknife keeps; when a run fills them, pairs
// merge (kMaxGroups / 2 groups of twice the windows), so a run of any length keeps
// between kMaxGroups / 2 and kMaxGroups groups once it has that many windows.
constexpr std::size_t kMaxGroups = 40;

double Chi(double yy, double yx) { return yx != 0.0 ? yy / yx : 1.0; }

std::string Figure(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, value);
  return buf;
}

// IcrIdentification's rules, in order; "" when they hold.
std::string WhyNotIdentified(const IcrFit& fit, double min_yaw_rate_radps) {
  using I = IcrIdentification;
  if (fit.windows_used < I::kMinWindows) {
    // No comma: the reason is a field of a sweep's summary.csv that scripts split.
    return "too little turning: " + std::to_string(fit.windows_used) + " window(s) above " +
           Figure("%g", min_yaw_rate_radps) + " rad/s (fewer than " +
           std::to_string(I::kMinWindows) + ")";
  }
  if (fit.turn_rms_radps < I::kMinTurnRmsRadps) {
    return "turning too gentle: RMS encoder yaw rate " + Figure("%.3f", fit.turn_rms_radps) +
           " rad/s < " + Figure("%.2f", I::kMinTurnRmsRadps) + " rad/s";
  }
  if (!(fit.chi_stderr <= I::kMaxStderr)) {
    return "standard error " + Figure("%.3f", fit.chi_stderr) + " > " +
           Figure("%.2f", I::kMaxStderr);
  }
  return "";
}

}  // namespace

void RunningIcrFit::Sums::Add(const Sums& o) {
  yy += o.yy;
  yx += o.yx;
  xx += o.xx;
  windows += o.windows;
}

RunningIcrFit::RunningIcrFit(int window_samples, double min_yaw_rate_radps)
    : window_samples_(window_samples), min_yaw_rate_radps_(min_yaw_rate_radps) {
  if (window_samples < 1) throw std::invalid_argument("RunningIcrFit: window_samples < 1");
}

void RunningIcrFit::Add(const IcrSample& s) {
  window_y_ += s.encoder_yaw_rate_radps / window_samples_;
  window_x_ += s.reference_yaw_rate_radps / window_samples_;
  if (++in_window_ < window_samples_) return;
  const double y = window_y_, x = window_x_;
  window_y_ = window_x_ = 0.0;
  in_window_ = 0;
  if (std::abs(y) < min_yaw_rate_radps_) return;
  const Sums window{y * y, y * x, x * x, 1};
  total_.Add(window);
  if (groups_.empty() || groups_.back().windows == windows_per_group_) {
    if (groups_.size() == kMaxGroups) {
      for (std::size_t g = 0; g < kMaxGroups / 2; ++g) {
        groups_[g] = groups_[2 * g];
        groups_[g].Add(groups_[2 * g + 1]);
      }
      groups_.resize(kMaxGroups / 2);
      windows_per_group_ *= 2;
    }
    if (groups_.empty() || groups_.back().windows == windows_per_group_) groups_.push_back({});
  }
  groups_.back().Add(window);
}

// Delete-a-group jackknife of Σy² / Σy·x over the groups of consecutive windows.
double RunningIcrFit::JackknifeStderr() const {
  const auto g = static_cast<double>(groups_.size());
  std::vector<double> estimates;
  for (const Sums& out : groups_) {
    if (total_.yx - out.yx == 0.0) return std::numeric_limits<double>::infinity();
    estimates.push_back(Chi(total_.yy - out.yy, total_.yx - out.yx));
  }
  double mean = 0.0;
  for (double e : estimates) mean += e / g;
  double ss = 0.0;
  for (double e : estimates) ss += (e - mean) * (e - mean);
  return std::sqrt((g - 1.0) / g * ss);
}

IcrFit RunningIcrFit::Fit() const {
  IcrFit fit;
  fit.windows_used = total_.windows;
  fit.samples_used = total_.windows * window_samples_;
  if (total_.windows > 0) {
    const auto n = static_cast<double>(total_.windows);
    fit.chi = Chi(total_.yy, total_.yx);
    fit.turn_rms_radps = std::sqrt(total_.yy / n);
    // Σ (y − χx)² = Σy² − 2χ·Σyx + χ²·Σx².
    const double sse = total_.yy - 2.0 * fit.chi * total_.yx + fit.chi * fit.chi * total_.xx;
    fit.rms_residual_radps = std::sqrt(std::max(sse, 0.0) / n);
    if (groups_.size() >= 2) fit.chi_stderr = JackknifeStderr();
  }
  fit.reason = WhyNotIdentified(fit, min_yaw_rate_radps_);
  fit.identified = fit.reason.empty();
  return fit;
}

IcrFit FitIcrExpansion(const std::vector<IcrSample>& samples, int window_samples,
                       double min_yaw_rate_radps) {
  if (window_samples < 1) throw std::invalid_argument("FitIcrExpansion: window_samples < 1");
  RunningIcrFit fit(window_samples, min_yaw_rate_radps);
  for (const IcrSample& s : samples) fit.Add(s);
  return fit.Fit();
}

double RigidPlasticIcrExpansion(const std::vector<double>& station_x_m, double half_track_m) {
  const double c = half_track_m;
  if (!(c > 0.0)) throw std::invalid_argument("RigidPlasticIcrExpansion: half_track_m must be > 0");
  double max_x = 0.0;
  for (double x : station_x_m) max_x = std::max(max_x, std::abs(x));
  if (max_x == 0.0) {
    throw std::invalid_argument("RigidPlasticIcrExpansion: needs a station off the axle");
  }
  // The moment Σ (c e − x²)/√(e² + x²) rises monotonically in e from −Σ|x| at 0
  // to +Σ c at infinity; its root lies in (0, max x² / c]. Bisection to 1e-15.
  auto moment = [&](double e) {
    double m = 0.0;
    for (double x : station_x_m) m += (c * e - x * x) / std::hypot(e, x);
    return m;
  };
  double lo = 0.0, hi = max_x * max_x / c;
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (moment(mid) > 0.0 ? hi : lo) = mid;
  }
  return (c + 0.5 * (lo + hi)) / c;
}

}  // namespace trackbed::estimation
