// PNG plots (see plots.h). A small plotting canvas on cv::Mat: data bounds
// to pixels, "nice" ticks, axes, lines, bars, legend.
#include "trackbed/plot/plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace trackbed::plot {
namespace {

const cv::Scalar kColors[] = {{0, 0, 0},      {200, 80, 20}, {30, 140, 30},   {20, 20, 210},
                              {170, 40, 170}, {0, 150, 220}, {120, 120, 120}, {90, 60, 20}};
const cv::Scalar kAxis(60, 60, 60), kGrid(225, 225, 225);

cv::Scalar Color(std::size_t k) { return kColors[k % (sizeof(kColors) / sizeof(kColors[0]))]; }

// Tick step of about `span / target` rounded to 1, 2 or 5 × 10^k.
double NiceStep(double span, int target) {
  const double raw = span / std::max(target, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (raw <= m * mag) return m * mag;
  }
  return 10.0 * mag;
}

// The multiples of `step` in [lo, hi + 1e-9], at most 64 of them: a span too narrow
// for the values' floating-point resolution would otherwise never reach its end.
std::vector<double> Ticks(double lo, double hi, double step) {
  std::vector<double> ticks;
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 && ticks.size() < 64; v += step) {
    ticks.push_back(v);
    if (v + step == v) break;
  }
  return ticks;
}

// Widens [lo, hi] about its centre to `span` where it is narrower than `at_least`.
void Widen(double& lo, double& hi, double at_least, double span) {
  if (hi - lo >= at_least) return;
  const double c = (lo + hi) / 2;
  lo = c - span / 2;
  hi = c + span / 2;
}

std::string Format(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

// A rectangle of the image mapped to data bounds.
struct Axes {
  cv::Rect area;
  double x0, x1, y0, y1;

  cv::Point Map(double x, double y) const {
    const double u = area.x + (x - x0) / (x1 - x0) * area.width;
    const double v = area.y + area.height - (y - y0) / (y1 - y0) * area.height;
    return {static_cast<int>(std::lround(u)), static_cast<int>(std::lround(v))};
  }

  void Draw(cv::Mat& img, const std::string& x_label, const std::string& y_label) const {
    for (double x : Ticks(x0, x1, NiceStep(x1 - x0, 8))) {
      cv::line(img, Map(x, y0), Map(x, y1), kGrid, 1);
      const cv::Point p = Map(x, y0);
      cv::putText(img, Format(x), {p.x - 12, p.y + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kAxis, 1,
                  cv::LINE_AA);
    }
    for (double y : Ticks(y0, y1, NiceStep(y1 - y0, 6))) {
      cv::line(img, Map(x0, y), Map(x1, y), kGrid, 1);
      const cv::Point p = Map(x0, y);
      cv::putText(img, Format(y), {p.x - 48, p.y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kAxis, 1,
                  cv::LINE_AA);
    }
    cv::rectangle(img, area, kAxis, 1);
    cv::putText(img, x_label, {area.x + area.width / 2 - 30, area.y + area.height + 38},
                cv::FONT_HERSHEY_SIMPLEX, 0.45, kAxis, 1, cv::LINE_AA);
    cv::putText(img, y_label, {area.x - 48, area.y - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kAxis, 1,
                cv::LINE_AA);
  }
};

void Legend(cv::Mat& img, const cv::Point& at, const std::vector<std::string>& names,
            int first_color = 0) {
  for (std::size_t k = 0; k < names.size(); ++k) {
    const cv::Point p(at.x, at.y + static_cast<int>(k) * 18);
    cv::line(img, p, {p.x + 24, p.y}, Color(k + first_color), 2, cv::LINE_AA);
    cv::putText(img, names[k], {p.x + 30, p.y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kAxis, 1,
                cv::LINE_AA);
  }
}

void Title(cv::Mat& img, const std::string& title) {
  cv::putText(img, title, {20, 26}, cv::FONT_HERSHEY_SIMPLEX, 0.6, kAxis, 1, cv::LINE_AA);
}

void Save(const std::filesystem::path& png, const cv::Mat& img) {
  if (!cv::imwrite(png.string(), img)) {
    throw std::runtime_error(png.string() + ": cannot write plot");
  }
}

void Polyline(cv::Mat& img, const Axes& axes, const std::vector<Eigen::Vector2d>& pts,
              const cv::Scalar& color) {
  std::vector<cv::Point> line;
  line.reserve(pts.size());
  for (const Eigen::Vector2d& p : pts) {
    if (p.allFinite()) line.push_back(axes.Map(p.x(), p.y()));
  }
  if (line.size() >= 2) cv::polylines(img, line, false, color, 1, cv::LINE_AA);
}

}  // namespace

void WriteTrajectoryPlot(const std::filesystem::path& png, const std::string& title,
                         const std::vector<PlotSeries>& series) {
  WriteMapPlot(png, title, series, {}, {});
}

void WriteMapPlot(const std::filesystem::path& png, const std::string& title,
                  const std::vector<PlotSeries>& series, const std::vector<PlotCircle>& circles,
                  const std::vector<PlotMarker>& markers) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  const auto grow = [&](const Eigen::Vector2d& p, double r) {
    if (!p.allFinite() || !std::isfinite(r)) return;
    x0 = std::min(x0, p.x() - r);
    x1 = std::max(x1, p.x() + r);
    y0 = std::min(y0, p.y() - r);
    y1 = std::max(y1, p.y() + r);
  };
  for (const PlotSeries& s : series) {
    for (const Eigen::Vector2d& p : s.points) grow(p, 0.0);
  }
  for (const PlotCircle& c : circles) grow(c.centre, c.radius_m);
  for (const PlotMarker& m : markers) grow(m.position, 0.0);
  if (!(x1 > x0)) x1 = x0 + 1;
  if (!(y1 > y0)) y1 = y0 + 1;
  // A path within a millimetre (a robot turning in place) is drawn on a metre.
  if (std::max(x1 - x0, y1 - y0) < 1e-3) {
    Widen(x0, x1, 1e-3, 1.0);
    Widen(y0, y1, 1e-3, 1.0);
  }
  // Equal scales: grow the shorter span about its centre.
  const cv::Rect area(80, 50, 720, 620);
  const double scale = std::max((x1 - x0) / area.width, (y1 - y0) / area.height) * 1.05;
  const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  const Axes axes{area, cx - scale * area.width / 2, cx + scale * area.width / 2,
                  cy - scale * area.height / 2, cy + scale * area.height / 2};
  cv::Mat img(720, 1040, CV_8UC3, cv::Scalar(255, 255, 255));
  Title(img, title);
  axes.Draw(img, "x [m]", "y [m]");
  for (const PlotCircle& c : circles) {
    const int r = static_cast<int>(std::lround(c.radius_m / scale));
    const cv::Point p = axes.Map(c.centre.x(), c.centre.y());
    if (c.filled) {
      cv::circle(img, p, std::max(r, 2), cv::Scalar(150, 150, 150), cv::FILLED, cv::LINE_AA);
    } else {
      cv::circle(img, p, r, cv::Scalar(190, 190, 190), 1, cv::LINE_AA);
    }
  }
  std::vector<std::string> names;
  for (std::size_t k = 0; k < series.size(); ++k) {
    Polyline(img, axes, series[k].points, Color(k));
    names.push_back(series[k].name);
  }
  for (const PlotMarker& m : markers) {
    const cv::Point p = axes.Map(m.position.x(), m.position.y());
    cv::drawMarker(img, p, kColors[3], cv::MARKER_TILTED_CROSS, 10, 2, cv::LINE_AA);
    cv::putText(img, m.label, {p.x + 7, p.y - 7}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kAxis, 1,
                cv::LINE_AA);
  }
  Legend(img, {820, 70}, names);
  Save(png, img);
}

void WriteHistogramPlot(const std::filesystem::path& png, const std::string& title,
                        const std::string& x_label, const std::vector<double>& edges,
                        const std::vector<HistogramSeries>& series, int first_color) {
  if (edges.size() < 2) throw std::invalid_argument("WriteHistogramPlot: needs two edges");
  double top = 0.0;
  for (const HistogramSeries& s : series) {
    for (double c : s.counts) top = std::max(top, c);
  }
  const cv::Rect area(80, 50, 720, 560);
  const Axes axes{area, edges.front(), edges.back(), 0.0, top > 0 ? top * 1.1 : 1.0};
  cv::Mat img(660, 1120, CV_8UC3, cv::Scalar(255, 255, 255));
  Title(img, title);
  axes.Draw(img, x_label, "fraction of poses");
  const std::size_t n = std::max<std::size_t>(series.size(), 1);
  std::vector<std::string> names;
  for (std::size_t k = 0; k < series.size(); ++k) {
    names.push_back(series[k].name);
    for (std::size_t b = 0; b + 1 < edges.size() && b < series[k].counts.size(); ++b) {
      const double w = (edges[b + 1] - edges[b]) / static_cast<double>(n);
      const double left = edges[b] + w * static_cast<double>(k);
      const cv::Point p0 = axes.Map(left, 0.0), p1 = axes.Map(left + w, series[k].counts[b]);
      cv::rectangle(img, cv::Rect(p0, p1), Color(k + first_color), cv::FILLED);
    }
  }
  Legend(img, {820, 70}, names, first_color);
  Save(png, img);
}

void WriteTimePlot(const std::filesystem::path& png, const std::string& title,
                   const std::vector<TimePanel>& panels) {
  const int panel_h = 220, top = 50, gap = 60;
  cv::Mat img(top + static_cast<int>(panels.size()) * (panel_h + gap), 1040, CV_8UC3,
              cv::Scalar(255, 255, 255));
  Title(img, title);
  double t0 = 1e300, t1 = -1e300;
  for (const TimePanel& p : panels) {
    for (const PlotSeries& s : p.series) {
      for (const Eigen::Vector2d& q : s.points) {
        t0 = std::min(t0, q.x());
        t1 = std::max(t1, q.x());
      }
    }
  }
  if (!(t1 > t0)) t1 = t0 + 1;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    double y0 = 1e300, y1 = -1e300;
    for (const PlotSeries& s : panels[i].series) {
      for (const Eigen::Vector2d& q : s.points) {
        if (!std::isfinite(q.y())) continue;
        y0 = std::min(y0, q.y());
        y1 = std::max(y1, q.y());
      }
    }
    if (!(y1 > y0)) {
      y0 -= 0.5;
      y1 += 0.5;
    }
    // A span of a few units in the last place is a constant to the eye.
    Widen(y0, y1, 1e-12 * std::max(std::abs(y0), std::abs(y1)), 1.0);
    const double pad = 0.05 * (y1 - y0);
    const cv::Rect area(80, top + static_cast<int>(i) * (panel_h + gap), 720, panel_h);
    const Axes axes{area, t0, t1, y0 - pad, y1 + pad};
    axes.Draw(img, "t [s]", panels[i].y_label);
    std::vector<std::string> names;
    for (std::size_t k = 0; k < panels[i].series.size(); ++k) {
      Polyline(img, axes, panels[i].series[k].points, Color(k));
      names.push_back(panels[i].series[k].name);
    }
    Legend(img, {820, area.y + 20}, names);
  }
  Save(png, img);
}

namespace {

// Quantile q of sorted values, linear between order statistics (R's type 7).
double SortedQuantile(const std::vector<double>& sorted, double q) {
  const double h = (static_cast<double>(sorted.size()) - 1.0) * q;
  const std::size_t lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

void CenteredText(cv::Mat& img, const std::string& text, cv::Point centre, double scale) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  cv::putText(img, text, {centre.x - size.width / 2, centre.y}, cv::FONT_HERSHEY_SIMPLEX, scale,
              kAxis, 1, cv::LINE_AA);
}

}  // namespace

void WriteBoxPlot(const std::filesystem::path& png, const std::string& title,
                  const std::string& y_label, const std::vector<BoxSeries>& boxes, bool log_y,
                  int first_color) {
  // The samples in axis units (log10 of the value on a log axis), sorted.
  std::vector<std::vector<double>> samples(boxes.size());
  double lo = 1e300, hi = -1e300;
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    for (double v : boxes[k].values) {
      if (!std::isfinite(v) || (log_y && !(v > 0))) continue;
      const double u = log_y ? std::log10(v) : v;
      samples[k].push_back(u);
      lo = std::min(lo, u);
      hi = std::max(hi, u);
    }
    std::sort(samples[k].begin(), samples[k].end());
  }
  if (!(hi >= lo)) {
    lo = 0.0;
    hi = 1.0;
  }
  if (hi - lo < 1e-12) {
    const double pad = log_y ? 0.5 : std::max(std::abs(lo) * 0.1, 0.5);
    lo -= pad;
    hi += pad;
  }
  const double pad = 0.08 * (hi - lo);
  const cv::Rect area(90, 70, 800, 420);
  const Axes axes{area, 0.0, static_cast<double>(std::max<std::size_t>(boxes.size(), 1)), lo - pad,
                  hi + pad};
  cv::Mat img(580, 940, CV_8UC3, cv::Scalar(255, 255, 255));
  Title(img, title);
  // Value axis: nice steps, or decades (with 2 and 5 between when the span is short).
  std::vector<std::pair<double, std::string>> ticks;
  if (log_y) {
    const bool fine = axes.y1 - axes.y0 < 2.5;
    for (int e = static_cast<int>(std::floor(axes.y0)); e <= static_cast<int>(std::ceil(axes.y1));
         ++e) {
      for (double m : fine ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
        const double u = e + std::log10(m);
        if (u >= axes.y0 && u <= axes.y1) ticks.emplace_back(u, Format(m * std::pow(10.0, e)));
      }
    }
  } else {
    const double step = NiceStep(axes.y1 - axes.y0, 6);
    for (double y = std::ceil(axes.y0 / step) * step; y <= axes.y1 + 1e-9; y += step) {
      ticks.emplace_back(y, Format(y));
    }
  }
  for (const auto& [u, label] : ticks) {
    const cv::Point a = axes.Map(axes.x0, u), b = axes.Map(axes.x1, u);
    cv::line(img, a, b, kGrid, 1);
    cv::putText(img, label, {a.x - 56, a.y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kAxis, 1,
                cv::LINE_AA);
  }
  cv::rectangle(img, area, kAxis, 1);
  cv::putText(img, y_label + (log_y ? " (log scale)" : ""), {area.x - 56, area.y - 12},
              cv::FONT_HERSHEY_SIMPLEX, 0.45, kAxis, 1, cv::LINE_AA);

  const double slot_px = static_cast<double>(area.width) / std::max<double>(boxes.size(), 1);
  const int half_w = static_cast<int>(std::min(slot_px * 0.25, 40.0));
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const double x = static_cast<double>(k) + 0.5;
    const int cx = axes.Map(x, 0.0).x;
    const cv::Scalar color = Color(k + static_cast<std::size_t>(first_color));
    // Labels alternate between two rows when a slot is narrower than its label.
    int baseline = 0;
    const int text_w =
        cv::getTextSize(boxes[k].name, cv::FONT_HERSHEY_SIMPLEX, 0.42, 1, &baseline).width;
    const int row = (text_w > slot_px - 6 && k % 2 == 1) ? 1 : 0;
    CenteredText(img, boxes[k].name, {cx, area.y + area.height + 20 + 18 * row}, 0.42);
    const std::vector<double>& s = samples[k];
    CenteredText(img, "n=" + std::to_string(s.size()), {cx, area.y + area.height + 58}, 0.38);
    if (s.empty()) continue;
    const double q1 = SortedQuantile(s, 0.25), q3 = SortedQuantile(s, 0.75);
    const double median = SortedQuantile(s, 0.5), iqr = q3 - q1;
    double whisker_lo = q1, whisker_hi = q3;
    for (double u : s) {
      if (u >= q1 - 1.5 * iqr) whisker_lo = std::min(whisker_lo, u);
      if (u <= q3 + 1.5 * iqr) whisker_hi = std::max(whisker_hi, u);
    }
    const int y_q1 = axes.Map(x, q1).y, y_q3 = axes.Map(x, q3).y;
    const int y_lo = axes.Map(x, whisker_lo).y, y_hi = axes.Map(x, whisker_hi).y;
    cv::line(img, {cx, y_q1}, {cx, y_lo}, color, 1, cv::LINE_AA);
    cv::line(img, {cx, y_q3}, {cx, y_hi}, color, 1, cv::LINE_AA);
    cv::line(img, {cx - half_w / 2, y_lo}, {cx + half_w / 2, y_lo}, color, 1, cv::LINE_AA);
    cv::line(img, {cx - half_w / 2, y_hi}, {cx + half_w / 2, y_hi}, color, 1, cv::LINE_AA);
    cv::rectangle(img, cv::Point(cx - half_w, y_q3), cv::Point(cx + half_w, y_q1), color, 2,
                  cv::LINE_AA);
    const int y_med = axes.Map(x, median).y;
    cv::line(img, {cx - half_w, y_med}, {cx + half_w, y_med}, color, 3, cv::LINE_AA);
    for (double u : s) {
      if (u < whisker_lo || u > whisker_hi) {
        cv::circle(img, axes.Map(x, u), 3, color, 1, cv::LINE_AA);
      }
    }
  }
  Save(png, img);
}

void WriteBarPlot(const std::filesystem::path& png, const std::string& title,
                  const std::string& x_label, const std::vector<BarValue>& bars, double x_max) {
  if (!(x_max > 0)) throw std::invalid_argument("WriteBarPlot: x_max must be > 0");
  int label_w = 60;
  for (const BarValue& b : bars) {
    int baseline = 0;
    label_w = std::max(
        label_w, cv::getTextSize(b.label, cv::FONT_HERSHEY_SIMPLEX, 0.42, 1, &baseline).width);
  }
  label_w = std::min(label_w, 520);
  const int row_h = 24, top = 50;
  const int rows = static_cast<int>(std::max<std::size_t>(bars.size(), 1));
  const cv::Rect area(label_w + 30, top, 420, rows * row_h);
  const Axes axes{area, 0.0, x_max, 0.0, static_cast<double>(rows)};
  cv::Mat img(top + rows * row_h + 60, area.x + area.width + 110, CV_8UC3,
              cv::Scalar(255, 255, 255));
  Title(img, title);
  const double step = NiceStep(x_max, 5);
  for (double x = 0.0; x <= x_max + 1e-9; x += step) {
    const cv::Point a = axes.Map(x, 0.0), b = axes.Map(x, rows);
    cv::line(img, a, b, kGrid, 1);
    CenteredText(img, Format(x), {a.x, a.y + 18}, 0.4);
  }
  cv::rectangle(img, area, kAxis, 1);
  CenteredText(img, x_label, {area.x + area.width / 2, area.y + area.height + 40}, 0.45);
  for (std::size_t k = 0; k < bars.size(); ++k) {
    const double row = static_cast<double>(rows) - static_cast<double>(k);  // first on top
    const cv::Point p0 = axes.Map(0.0, row - 0.2);
    const cv::Point p1 = axes.Map(std::clamp(bars[k].value, 0.0, x_max), row - 0.8);
    if (p1.x > p0.x) cv::rectangle(img, cv::Rect(p0, p1), Color(1), cv::FILLED);
    const int y = axes.Map(0.0, row - 0.5).y + 5;
    cv::putText(img, bars[k].label, {20, y}, cv::FONT_HERSHEY_SIMPLEX, 0.42, kAxis, 1, cv::LINE_AA);
    cv::putText(img, bars[k].annotation, {std::max(p0.x, p1.x) + 6, y}, cv::FONT_HERSHEY_SIMPLEX,
                0.4, kAxis, 1, cv::LINE_AA);
  }
  Save(png, img);
}

void WriteScatterPlot(const std::filesystem::path& png, const std::string& title,
                      const std::string& x_label, const std::string& y_label,
                      const std::vector<ScatterPoint>& points,
                      const std::vector<std::string>& group_names, bool diagonal) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const ScatterPoint& p : points) {
    if (!p.position.allFinite()) continue;
    x0 = std::min(x0, p.position.x());
    x1 = std::max(x1, p.position.x());
    y0 = std::min(y0, p.position.y());
    y1 = std::max(y1, p.position.y());
  }
  if (x0 > x1) x0 = y0 = 0.0, x1 = y1 = 1.0;
  if (diagonal) x0 = y0 = std::min(x0, y0), x1 = y1 = std::max(x1, y1);
  const double px = std::max(0.08 * (x1 - x0), 1e-9), py = std::max(0.08 * (y1 - y0), 1e-9);
  const Axes axes{cv::Rect(80, 50, 760, 620), x0 - px, x1 + px, y0 - py, y1 + py};
  cv::Mat img(740, 1080, CV_8UC3, cv::Scalar(255, 255, 255));
  Title(img, title);
  axes.Draw(img, x_label, y_label);
  if (diagonal) {
    const double lo = std::max(axes.x0, axes.y0), hi = std::min(axes.x1, axes.y1);
    cv::line(img, axes.Map(lo, lo), axes.Map(hi, hi), kGrid * 0.8, 1, cv::LINE_AA);
  }
  for (const ScatterPoint& p : points) {
    if (!p.position.allFinite()) continue;
    const cv::Point at = axes.Map(p.position.x(), p.position.y());
    cv::circle(img, at, 4, Color(p.group + 1), cv::FILLED, cv::LINE_AA);
    cv::putText(img, p.label, {at.x + 6, at.y - 4}, cv::FONT_HERSHEY_SIMPLEX, 0.33,
                Color(p.group + 1), 1, cv::LINE_AA);
  }
  for (std::size_t k = 0; k < group_names.size(); ++k) {
    const cv::Point p(860, 70 + static_cast<int>(k) * 18);
    cv::circle(img, p, 4, Color(k + 1), cv::FILLED, cv::LINE_AA);
    cv::putText(img, group_names[k], {p.x + 10, p.y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.42, kAxis, 1,
                cv::LINE_AA);
  }
  Save(png, img);
}

}  // namespace trackbed::plot
