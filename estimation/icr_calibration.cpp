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

// One window's mean encoder (y) and reference (x) yaw rate.
struct Window {
  double y = 0.0, x = 0.0;
};

constexpr int kJackknifeGroups = 20;

double Chi(double yy, double yx) { return yx != 0.0 ? yy / yx : 1.0; }

// Delete-a-group jackknife standard error of Σy² / Σyx over consecutive groups of windows.
double JackknifeStderr(const std::vector<Window>& windows, double yy, double yx) {
  const std::size_t n = windows.size();
  const std::size_t groups = std::min<std::size_t>(kJackknifeGroups, n);
  std::vector<double> estimates;
  for (std::size_t g = 0; g < groups; ++g) {
    double out_yy = 0.0, out_yx = 0.0;
    for (std::size_t i = n * g / groups; i < n * (g + 1) / groups; ++i) {
      out_yy += windows[i].y * windows[i].y;
      out_yx += windows[i].y * windows[i].x;
    }
    if (yx - out_yx == 0.0) return std::numeric_limits<double>::infinity();
    estimates.push_back(Chi(yy - out_yy, yx - out_yx));
  }
  double mean = 0.0;
  for (double e : estimates) mean += e / static_cast<double>(groups);
  double ss = 0.0;
  for (double e : estimates) ss += (e - mean) * (e - mean);
  return std::sqrt((static_cast<double>(groups) - 1.0) / static_cast<double>(groups) * ss);
}

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

IcrFit FitIcrExpansion(const std::vector<IcrSample>& samples, int window_samples,
                       double min_yaw_rate_radps) {
  if (window_samples < 1) throw std::invalid_argument("FitIcrExpansion: window_samples < 1");
  IcrFit fit;
  std::vector<Window> windows;
  double yy = 0.0, yx = 0.0;
  const auto n = static_cast<std::size_t>(window_samples);
  for (std::size_t start = 0; start + n <= samples.size(); start += n) {
    Window w;
    for (std::size_t i = start; i < start + n; ++i) {
      w.y += samples[i].encoder_yaw_rate_radps / window_samples;
      w.x += samples[i].reference_yaw_rate_radps / window_samples;
    }
    if (std::abs(w.y) < min_yaw_rate_radps) continue;
    windows.push_back(w);
    yy += w.y * w.y;
    yx += w.y * w.x;
  }
  fit.windows_used = static_cast<int>(windows.size());
  fit.samples_used = fit.windows_used * window_samples;
  if (!windows.empty()) {
    fit.chi = Chi(yy, yx);
    fit.turn_rms_radps = std::sqrt(yy / static_cast<double>(windows.size()));
    double sse = 0.0;
    for (const Window& w : windows) sse += (w.y - fit.chi * w.x) * (w.y - fit.chi * w.x);
    fit.rms_residual_radps = std::sqrt(sse / static_cast<double>(windows.size()));
    if (fit.windows_used >= 2) fit.chi_stderr = JackknifeStderr(windows, yy, yx);
  }
  fit.reason = WhyNotIdentified(fit, min_yaw_rate_radps);
  fit.identified = fit.reason.empty();
  return fit;
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
