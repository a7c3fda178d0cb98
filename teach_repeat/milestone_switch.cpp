// When a milestone is passed: the error minimum, the progress fit and the 2D milestone
// switch (see milestone_switch.h).
#include "trackbed/teach_repeat/milestone_switch.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "trackbed/common/option_error.h"

namespace trackbed::teach_repeat {

ErrorMinimumDetector::ErrorMinimumDetector(double hysteresis) : hysteresis_(hysteresis) {
  if (!(hysteresis >= 0.0 && std::isfinite(hysteresis))) {
    throw std::invalid_argument("ErrorMinimumDetector: hysteresis must be finite and >= 0");
  }
  Reset();
}

void ErrorMinimumDetector::Reset() {
  minimum_ = std::numeric_limits<double>::infinity();
  passed_ = false;
}

bool ErrorMinimumDetector::Update(double error) {
  if (passed_) return true;
  if (!std::isfinite(error)) return false;
  minimum_ = std::min(minimum_, error);
  passed_ = error > minimum_ + hysteresis_;
  return passed_;
}

void MilestoneProgressOptions::Validate() const {
  option_check::Positive("min_flow_spread_px", min_flow_spread_px);
  option_check::Positive("outlier_px", outlier_px);
  option_check::AtLeast("min_features", min_features, 3);
}

namespace {

/// One feature's taught flow F and current displacement D, x in bearing pixels.
struct FlowSample {
  double fx, fy, dx, dy;
};

/// Least squares of D = p·F + (c, b) over `samples` with weights `use`
/// (funnel_lane_controller.h, "Progress"): the offsets eliminated,
/// p = Σ(F − F̄)·(D − D̄) / Σ|F − F̄|².
bool FitProgress(const std::vector<FlowSample>& samples, const std::vector<bool>& use,
                 double min_spread_px, MilestoneProgress* out) {
  double n = 0.0, mfx = 0.0, mfy = 0.0, mdx = 0.0, mdy = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!use[i]) continue;
    const FlowSample& s = samples[i];
    n += 1.0;
    mfx += s.fx;
    mfy += s.fy;
    mdx += s.dx;
    mdy += s.dy;
  }
  if (n < 3.0) return false;
  mfx /= n;
  mfy /= n;
  mdx /= n;
  mdy /= n;
  double sff = 0.0, sfd = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!use[i]) continue;
    const FlowSample& s = samples[i];
    sff += (s.fx - mfx) * (s.fx - mfx) + (s.fy - mfy) * (s.fy - mfy);
    sfd += (s.fx - mfx) * (s.dx - mdx) + (s.fy - mfy) * (s.dy - mdy);
  }
  if (!(std::sqrt(sff / n) >= min_spread_px)) return false;
  out->progress = sfd / sff;
  out->heading_px = mdx - out->progress * mfx;
  out->pitch_px = mdy - out->progress * mfy;
  out->features = static_cast<int>(n);
  return true;
}

double Residual(const FlowSample& s, const MilestoneProgress& p) {
  return std::hypot(s.dx - p.progress * s.fx - p.heading_px, s.dy - p.progress * s.fy - p.pitch_px);
}

}  // namespace

MilestoneProgress EstimateMilestoneProgress(const geometry::PinholeCamera& camera,
                                            const Milestone& m,
                                            const std::vector<cv::Point2f>& current_px,
                                            const std::vector<bool>& tracked,
                                            const MilestoneProgressOptions& options) {
  if (current_px.size() != m.features.size() || tracked.size() != m.features.size()) {
    throw std::invalid_argument(
        "EstimateMilestoneProgress: one current position and flag per milestone feature");
  }
  // Cylindrical coordinates in pixels at the centre: azimuth fx·atan(x/fx), which a yaw
  // shifts alike everywhere, and fy·tan(elevation), which a yaw leaves alone (the image
  // y of a point off the centre changes with a yaw, by ~y·x·yaw/fx: with features on one
  // side that would read as progress).
  const auto cylinder = [&camera](const cv::Point2f& q) {
    const double x = (static_cast<double>(q.x) - camera.cx) / camera.fx;
    const double y = static_cast<double>(q.y) - camera.cy;
    return cv::Point2d(camera.fx * std::atan(x), y / std::sqrt(1.0 + x * x));
  };
  std::vector<FlowSample> samples;
  samples.reserve(m.features.size());
  for (std::size_t i = 0; i < m.features.size(); ++i) {
    if (!tracked[i]) continue;
    const MilestoneFeature& f = m.features[i];
    const cv::Point2d a = cylinder(f.first_px), b = cylinder(f.last_px),
                      c = cylinder(current_px[i]);
    samples.push_back({b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y});
  }
  MilestoneProgress result;
  if (static_cast<int>(samples.size()) < options.min_features) return result;
  std::vector<bool> use(samples.size(), true);
  MilestoneProgress first;
  if (!FitProgress(samples, use, options.min_flow_spread_px, &first)) return result;
  // Second fit without the features far from the first (a KLT track slid onto an
  // occluder, a feature on a moving object).
  std::vector<double> residuals;
  for (const FlowSample& s : samples) residuals.push_back(Residual(s, first));
  std::vector<double> sorted = residuals;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const double bound = std::max(options.outlier_px, 3.0 * sorted[sorted.size() / 2]);
  for (std::size_t i = 0; i < samples.size(); ++i) use[i] = residuals[i] <= bound;
  MilestoneProgress second;
  if (!FitProgress(samples, use, options.min_flow_spread_px, &second) ||
      second.features < options.min_features) {
    return result;
  }
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (use[i]) sum_sq += Residual(samples[i], second) * Residual(samples[i], second);
  }
  second.rms_px = std::sqrt(sum_sq / second.features);
  second.valid = true;
  return second;
}

namespace detail {

MilestoneSwitch::MilestoneSwitch(double hysteresis_px, SwitchError mode, bool remove_rotation)
    : detector_(hysteresis_px), mode_(mode), remove_rotation_(remove_rotation) {}

void MilestoneSwitch::Reset() {
  detector_.Reset();
  fresh_ = true;
  common_ = 0.0;
  accumulated_ = 0.0;
  last_error_.clear();
  last_outward_.clear();
}

double MilestoneSwitch::Term(double error, double outward, double common) const {
  const double e = error - common;
  return mode_ == SwitchError::kMeanAbsolute ? std::abs(e) : outward * e;
}

bool MilestoneSwitch::Update(const FunnelFrame& frame) {
  const std::vector<double>& e = frame.error_px;
  if (fresh_ || last_error_.size() != e.size()) {
    // The start values, over every tracked feature.
    double sum = 0.0;
    int n = 0;
    for (double v : e) {
      if (std::isfinite(v)) {
        sum += v;
        ++n;
      }
    }
    if (n > 0) {
      common_ = remove_rotation_ ? sum / n : 0.0;
      double terms = 0.0;
      for (std::size_t i = 0; i < e.size(); ++i) {
        if (std::isfinite(e[i])) terms += Term(e[i], frame.outward[i], common_);
      }
      accumulated_ = terms / n;
      fresh_ = false;
    }
  } else {
    // Changes over the features tracked in both frames only.
    double shift = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < e.size(); ++i) {
      if (std::isfinite(e[i]) && std::isfinite(last_error_[i])) {
        shift += e[i] - last_error_[i];
        ++n;
      }
    }
    if (n > 0) {
      const double common = remove_rotation_ ? common_ + shift / n : 0.0;
      double change = 0.0;
      for (std::size_t i = 0; i < e.size(); ++i) {
        if (std::isfinite(e[i]) && std::isfinite(last_error_[i])) {
          change += Term(e[i], frame.outward[i], common) -
                    Term(last_error_[i], last_outward_[i], common_);
        }
      }
      accumulated_ += change / n;
      common_ = common;
    }
  }
  last_error_ = e;
  last_outward_ = frame.outward;
  if (fresh_) return false;
  return detector_.Update(error_px());
}

double MilestoneSwitch::error_px() const {
  return mode_ == SwitchError::kMeanAbsolute ? accumulated_ : std::abs(accumulated_);
}

}  // namespace detail
}  // namespace trackbed::teach_repeat
