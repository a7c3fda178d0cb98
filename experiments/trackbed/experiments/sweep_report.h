// The results of a sweep (docs/sweeps.md): one summary row per cell with
// every metric of its metrics.json, statistics per group (the cells that differ
// only in seed), and a Markdown report with PNG plots — all rebuilt from the
// sweep folder's files alone (`trackbed report DIR`).
//
// Column rule: a column whose value depends on the machine or the moment
// (wall-clock time, per-stage timing, memory, host) starts with `wall_`,
// `timing_`, `mem_` or `host`; every other column of a cell is the same bytes on
// any run of the same binary.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "trackbed/experiments/sweep.h"

namespace trackbed::experiments {

/// One value of the summary table.
struct SummaryValue {
  enum class Kind { kNull, kBool, kNumber, kText };
  Kind kind = Kind::kNull;
  double number = 0.0;  ///< kNumber; kBool as 0 or 1
  std::string text;     ///< as written to CSV: numbers as in metrics.json, true/false; "" for null
};

/// A column of the summary table.
struct SummaryColumn {
  std::string name;
  /// For metric columns, the key path in metrics.json (`{"estimators", "fused",
  /// "ate_rmse_m"}`); empty for the cell's own columns.
  std::vector<std::string> metric_path;
};

/// summary.csv / summary.json as a table: one row per cell in cell order.
///
/// Columns: `index, cell, group, scenario, seed`, one `vary_<key>` per varied key
/// (key with non-alphanumerics as `_`), `cell_status, cell_reason`, every metric of
/// the cells' metrics.json (in order of first appearance, nested keys joined by `_`:
/// `estimators_fused_ate_rmse_m`), then `wall_cell_s` and `host`.
struct SweepSummary {
  std::string sweep;
  std::vector<SummaryColumn> columns;
  std::vector<std::vector<SummaryValue>> rows;

  /// The column's position, or -1.
  int Column(const std::string& name) const;
};

/// A cell as read from its folder.
struct CellResult {
  SweepCell cell;
  CellOutcome outcome;
  std::optional<std::string> metrics_json;  ///< run/metrics.json when the cell finished
};

/// The summary column of a metric at `path` in metrics.json: the keys joined by `_`,
/// with machine-dependent metrics given their prefix (`real_time_factor` →
/// `wall_real_time_factor`; a key under `timing` → `timing_…`; memory → `mem_…`).
std::string SummaryColumnName(const std::vector<std::string>& path);

/// Whether a summary column depends on the machine: it starts with `wall_`,
/// `timing_`, `mem_` or `host`.
bool IsMachineDependentColumn(const std::string& name);

/// Builds the table. `sweep_dir` (absolute) is cut from paths in reasons and string
/// metrics, so that they read relative to the sweep folder.
SweepSummary BuildSweepSummary(const SweepPlan& plan, const std::vector<CellResult>& cells,
                               const std::filesystem::path& sweep_dir);

/// RFC 4180 CSV with a header row.
std::string SummaryCsv(const SweepSummary& summary);
/// `{"sweep": name, "columns": [...], "cells": [{column: value, …}, …]}`.
std::string SummaryJson(const SweepSummary& summary);

/// Statistics of a sample; NaN where undefined (std and CI need n >= 2).
struct SampleStats {
  std::size_t n = 0;
  double mean, std, ci95_half_width, median, min, max;
};
/// n, mean, sample standard deviation (n − 1), half-width of the 95 % confidence
/// interval of the mean (Student t, n − 1 degrees of freedom: t·s/√n), median, min,
/// max. Non-finite values are left out.
SampleStats Describe(std::vector<double> values);

/// Quantile `p` in (0, 1) of Student's t distribution with `dof` > 0 degrees of
/// freedom, from Boost.Math. Throws std::invalid_argument outside those ranges.
double StudentTQuantile(double p, double dof);

/// One group's statistics: per numeric summary column (metrics and `wall_cell_s`),
/// over the group's cells whose status is ok.
struct GroupStats {
  std::string group;
  std::string scenario;
  std::vector<scenario::Override> varied;
  std::size_t cells = 0;                                     ///< cells in the group
  std::size_t ok = 0;                                        ///< of which ok
  std::vector<std::pair<std::string, SampleStats>> metrics;  ///< column name, stats

  /// The statistics of a column, or nullptr.
  const SampleStats* Find(const std::string& column) const;
};

std::vector<GroupStats> AggregateSweep(const SweepPlan& plan, const SweepSummary& summary);

/// aggregates.csv: `group, scenario, vary_…, cells, ok, metric, n, mean, std,
/// ci95_half_width, median, min, max`, one row per group and metric.
std::string AggregatesCsv(const SweepPlan& plan, const std::vector<GroupStats>& groups);

/// Count of cells per status.
struct SweepCounts {
  std::size_t ok = 0, failed = 0, timed_out = 0, interrupted = 0, pending = 0;
  std::size_t total() const { return ok + failed + timed_out + interrupted + pending; }
};
SweepCounts CountOutcomes(const std::vector<CellResult>& cells);

/// Reads every cell of `plan` from `sweep_dir`. A cell whose run finished but whose
/// cell.json is missing (the sweep was killed in between) gets OutcomeFromMetrics; a
/// cell.json that says ok without a finished run reads as pending.
std::vector<CellResult> ReadSweepResults(const std::filesystem::path& sweep_dir,
                                         const SweepPlan& plan);

/// The Markdown report: cell counts, a table per scenario group of each estimator's
/// ATE (mean ± std over seeds, best-to-worst order), navigation success rates when
/// there are navigation metrics, the cells that did not succeed, and the plots in
/// `plots` (paths relative to the sweep folder).
std::string SweepReportMarkdown(const SweepPlan& plan, const SweepSummary& summary,
                                const std::vector<GroupStats>& groups,
                                const std::vector<std::string>& plots);

/// Reads the sweep folder (cells.json, cells/*/cell.json, cells/*/run/metrics.json)
/// and (re)writes summary.csv, summary.json, aggregates.csv, report.md and plots/
/// (box plots of each group's ATE per estimator; navigation success per group). The
/// report also links the run plots (trajectories, navigation map) of each group's
/// first ok cell.
/// Throws SweepError when `sweep_dir` is not a sweep folder.
SweepCounts WriteSweepReport(const std::filesystem::path& sweep_dir);
/// The same from the plan and results already read from `sweep_dir` (absolute), with
/// `section` (Markdown, may be empty) placed after the report's opening counts.
SweepCounts WriteSweepReport(const std::filesystem::path& sweep_dir, const SweepPlan& plan,
                             const std::vector<CellResult>& results, const std::string& section);

}  // namespace trackbed::experiments
