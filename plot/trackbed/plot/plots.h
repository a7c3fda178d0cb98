// PNG plots of a run (Ham et al. 2012, figs. 8–11): estimated trajectories over
// the true path, histograms of each estimator's distance to the true path, and
// the fusion weight and slip (true vs estimated) over time; box plots, bar charts and
// labelled scatter plots of many runs. Drawn with OpenCV.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace trackbed::plot {

/// One named curve: points (x, y) in data units.
struct PlotSeries {
  std::string name;
  std::vector<Eigen::Vector2d> points;
};

/// x–y plot with equal axis scales (metres), one colour per series, a legend.
void WriteTrajectoryPlot(const std::filesystem::path& png, const std::string& title,
                         const std::vector<PlotSeries>& series);

/// A circle on a map plot [m]: filled grey for an obstacle's body, a thin outline for
/// a safety circle.
struct PlotCircle {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
  bool filled = true;
};
/// A labelled point on a map plot (start, goal, sub-goals).
struct PlotMarker {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  std::string label;
};
/// A trajectory plot with circles and markers drawn under the series (Jung & Kim 2014,
/// figs. 5–8: the path among obstacles, their safety circles and the sub-goals).
void WriteMapPlot(const std::filesystem::path& png, const std::string& title,
                  const std::vector<PlotSeries>& series, const std::vector<PlotCircle>& circles,
                  const std::vector<PlotMarker>& markers);

/// Grouped bar chart: counts per bin for each series (bins between `edges`).
struct HistogramSeries {
  std::string name;
  std::vector<double> counts;  ///< edges.size() − 1 values (fractions or counts)
};
/// `first_color` offsets the palette so that series keep the colours they have in a
/// trajectory plot that starts with the ground truth.
void WriteHistogramPlot(const std::filesystem::path& png, const std::string& title,
                        const std::string& x_label, const std::vector<double>& edges,
                        const std::vector<HistogramSeries>& series, int first_color = 0);

/// Panels stacked vertically, sharing the time axis; each panel has its series.
struct TimePanel {
  std::string y_label;
  std::vector<PlotSeries> series;  ///< points are (t, value)
};
void WriteTimePlot(const std::filesystem::path& png, const std::string& title,
                   const std::vector<TimePanel>& panels);

/// One box of a box plot: a label and the sample it summarises.
struct BoxSeries {
  std::string name;
  std::vector<double> values;  ///< non-finite values are left out
};
/// Tukey box plot, one box per series (e.g. the ATE of each estimator over seeds): the
/// box spans the first to the third quartile with a line at the median, whiskers reach
/// the farthest values within 1.5 interquartile ranges of the box, values beyond are
/// drawn as circles, and n is written under each box. With `log_y` the value axis is
/// logarithmic (decades labelled; values <= 0 are left out). `first_color` offsets the
/// palette as in WriteHistogramPlot.
void WriteBoxPlot(const std::filesystem::path& png, const std::string& title,
                  const std::string& y_label, const std::vector<BoxSeries>& boxes,
                  bool log_y = false, int first_color = 1);

/// One bar of a horizontal bar chart.
struct BarValue {
  std::string label;       ///< written left of the bar
  double value = 0.0;      ///< bar length in data units
  std::string annotation;  ///< written right of the bar (e.g. "9/10")
};
/// Horizontal bars, one row per value, on an axis from 0 to `x_max` (e.g. the success
/// rate of each scenario group); rows stay readable with many or long labels.
void WriteBarPlot(const std::filesystem::path& png, const std::string& title,
                  const std::string& x_label, const std::vector<BarValue>& bars, double x_max);

/// One labelled point of a scatter plot.
struct ScatterPoint {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< data units; non-finite: left out
  std::string label;                                   ///< written beside the point
  std::size_t group = 0;                               ///< index into the group names
};
/// Points in data units, coloured by group (a legend names the groups), each labelled;
/// with `diagonal` the line y = x (where x and y share a unit, e.g. an outcome measured
/// in simulation against the same outcome measured on real data).
void WriteScatterPlot(const std::filesystem::path& png, const std::string& title,
                      const std::string& x_label, const std::string& y_label,
                      const std::vector<ScatterPoint>& points,
                      const std::vector<std::string>& group_names, bool diagonal = false);

}  // namespace trackbed::plot
