// Summary, aggregates and report of a sweep folder (see sweep_report.h and
// docs/sweeps.md). Numbers keep the text metrics.json gave them, so a summary
// rebuilt from the same files is the same bytes; statistics are printed in their
// shortest exact form.
#include "trackbed/experiments/sweep_report.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

#include <boost/math/distributions/students_t.hpp>
#include <nlohmann/json.hpp>

#include "trackbed/experiments/sweep_support.h"
#include "trackbed/plot/plots.h"

namespace trackbed::experiments {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Estimators in the order the report lists them; others follow in order of appearance.
const std::vector<std::string> kEstimatorOrder = {"wheel_odometry", "wheel_odometry_noslip",
                                                  "visual_odometry", "fused", "ekf"};

std::string Underscored(const std::string& s) {
  std::string out;
  for (char c : s) out.push_back(std::isalnum(static_cast<unsigned char>(c)) ? c : '_');
  return out;
}

bool StartsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

// Shortest text that reads back as exactly `x`; "" for NaN.
std::string Shortest(double x) {
  if (!std::isfinite(x)) return "";
  char buf[64];
  char* end = std::to_chars(buf, buf + sizeof(buf), x).ptr;
  return std::string(buf, end);
}

SummaryValue Text(const std::string& s) {
  SummaryValue v;
  v.kind = SummaryValue::Kind::kText;
  v.text = s;
  return v;
}

SummaryValue Number(double x, const std::string& text) {
  SummaryValue v;
  v.kind = SummaryValue::Kind::kNumber;
  v.number = x;
  v.text = text;
  return v;
}

// Every leaf of a metrics.json document with its key path.
void Flatten(const Json& j, std::vector<std::string>& path, const std::string& strip,
             std::vector<std::pair<std::vector<std::string>, SummaryValue>>& out) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      path.push_back(key);
      Flatten(value, path, strip, out);
      path.pop_back();
    }
    return;
  }
  if (j.is_array()) {
    for (std::size_t k = 0; k < j.size(); ++k) {
      path.push_back(std::to_string(k));
      Flatten(j[k], path, strip, out);
      path.pop_back();
    }
    return;
  }
  SummaryValue v;
  if (j.is_boolean()) {
    v.kind = SummaryValue::Kind::kBool;
    v.number = j.get<bool>() ? 1.0 : 0.0;
    v.text = j.get<bool>() ? "true" : "false";
  } else if (j.is_number()) {
    v = Number(j.get<double>(), j.dump());
  } else if (j.is_string()) {
    v = Text(ReplaceAll(j.get<std::string>(), strip, ""));
  }
  out.emplace_back(path, v);
}

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  return "\"" + ReplaceAll(s, "\"", "\"\"") + "\"";
}

std::string MarkdownCell(const std::string& s) {
  return ReplaceAll(ReplaceAll(ReplaceAll(s, "|", "\\|"), "\n", " "), "\r", " ");
}

// "0.490 ± 0.012": the mean to 3 significant digits (at most 6 decimals), the std to
// as many decimals; just the mean when n < 2.
std::string MeanStd(const SampleStats& s) {
  const double a = std::abs(s.mean);
  const int decimals =
      a > 0 ? std::clamp(2 - static_cast<int>(std::floor(std::log10(a))), 0, 6) : 3;
  char buf[96];
  if (s.n >= 2) {
    std::snprintf(buf, sizeof(buf), "%.*f ± %.*f", decimals, s.mean, decimals, s.std);
  } else {
    std::snprintf(buf, sizeof(buf), "%.*f", decimals, s.mean);
  }
  return buf;
}

std::vector<std::string> EstimatorsOf(const SweepSummary& summary) {
  std::vector<std::string> found;
  for (const SummaryColumn& c : summary.columns) {
    if (c.metric_path.size() == 3 && c.metric_path[0] == "estimators" &&
        c.metric_path[2] == "ate_rmse_m") {
      found.push_back(c.metric_path[1]);
    }
  }
  std::vector<std::string> ordered;
  for (const std::string& e : kEstimatorOrder) {
    if (std::find(found.begin(), found.end(), e) != found.end()) ordered.push_back(e);
  }
  for (const std::string& e : found) {
    if (std::find(ordered.begin(), ordered.end(), e) == ordered.end()) ordered.push_back(e);
  }
  return ordered;
}

std::string AteColumn(const SweepSummary& summary, const std::string& estimator) {
  for (const SummaryColumn& c : summary.columns) {
    if (c.metric_path == std::vector<std::string>{"estimators", estimator, "ate_rmse_m"}) {
      return c.name;
    }
  }
  return "";
}

std::string ColumnOfPath(const SweepSummary& summary, const std::vector<std::string>& path) {
  for (const SummaryColumn& c : summary.columns) {
    if (c.metric_path == path) return c.name;
  }
  return "";
}

std::string VaryColumn(const std::string& key) { return "vary_" + Underscored(key); }

// The values of `column` over the ok cells of `group`.
std::vector<double> GroupValues(const SweepSummary& summary, const std::string& group,
                                const std::string& column) {
  std::vector<double> values;
  const int g = summary.Column("group"), s = summary.Column("cell_status"),
            c = summary.Column(column);
  if (g < 0 || s < 0 || c < 0) return values;
  for (const std::vector<SummaryValue>& row : summary.rows) {
    const SummaryValue& v = row[static_cast<std::size_t>(c)];
    if (row[static_cast<std::size_t>(g)].text != group ||
        row[static_cast<std::size_t>(s)].text != "ok") {
      continue;
    }
    if (v.kind == SummaryValue::Kind::kNumber || v.kind == SummaryValue::Kind::kBool) {
      values.push_back(v.number);
    }
  }
  return values;
}

}  // namespace

int SweepSummary::Column(const std::string& name) const {
  for (std::size_t k = 0; k < columns.size(); ++k) {
    if (columns[k].name == name) return static_cast<int>(k);
  }
  return -1;
}

const SampleStats* GroupStats::Find(const std::string& column) const {
  for (const auto& [name, stats] : metrics) {
    if (name == column) return &stats;
  }
  return nullptr;
}

std::string SummaryColumnName(const std::vector<std::string>& path) {
  std::string flat;
  for (const std::string& p : path) flat += (flat.empty() ? "" : "_") + Underscored(p);
  if (IsMachineDependentColumn(flat)) return flat;
  if (flat == "real_time_factor") return "wall_real_time_factor";
  for (const std::string& p : path) {
    if (StartsWith(p, "timing")) return "timing_" + flat;
  }
  for (const std::string& p : path) {
    if (StartsWith(p, "wall") || p.find("real_time_factor") != std::string::npos) {
      return "wall_" + flat;
    }
  }
  for (const std::string& p : path) {
    if (StartsWith(p, "mem") || p.find("memory") != std::string::npos ||
        p.find("rss") != std::string::npos) {
      return "mem_" + flat;
    }
  }
  for (const std::string& p : path) {
    if (StartsWith(p, "host")) return "host_" + flat;
  }
  return flat;
}

bool IsMachineDependentColumn(const std::string& name) {
  return StartsWith(name, "wall_") || StartsWith(name, "timing_") || StartsWith(name, "mem_") ||
         StartsWith(name, "host");
}

SweepSummary BuildSweepSummary(const SweepPlan& plan, const std::vector<CellResult>& cells,
                               const fs::path& sweep_dir) {
  const std::string strip = sweep_dir.empty() ? "" : (sweep_dir / "").string();
  SweepSummary t;
  t.sweep = plan.name;
  for (const char* c : {"index", "cell", "group", "scenario", "seed"}) t.columns.push_back({c, {}});
  for (const std::string& k : plan.vary_keys) t.columns.push_back({VaryColumn(k), {}});
  t.columns.push_back({"cell_status", {}});
  t.columns.push_back({"cell_reason", {}});
  std::set<std::string> used = {"wall_cell_s", "host"};
  for (const SummaryColumn& c : t.columns) used.insert(c.name);

  // Metric columns in order of first appearance.
  std::map<std::vector<std::string>, std::size_t> column_of_path;
  std::vector<std::vector<std::pair<std::vector<std::string>, SummaryValue>>> flat(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (!cells[i].metrics_json) continue;
    Json j;
    try {
      j = Json::parse(*cells[i].metrics_json);
    } catch (const nlohmann::json::exception&) {
      continue;  // the cell's status already says its metrics.json is unreadable
    }
    std::vector<std::string> path;
    Flatten(j, path, strip, flat[i]);
    for (const auto& [p, value] : flat[i]) {
      if (column_of_path.count(p)) continue;
      std::string name = SummaryColumnName(p);
      while (used.count(name)) name = "run_" + name;
      used.insert(name);
      column_of_path[p] = t.columns.size();
      t.columns.push_back({name, p});
    }
  }
  t.columns.push_back({"wall_cell_s", {}});
  t.columns.push_back({"host", {}});

  for (std::size_t i = 0; i < cells.size(); ++i) {
    const SweepCell& cell = cells[i].cell;
    const CellOutcome& o = cells[i].outcome;
    std::vector<SummaryValue> row(t.columns.size());
    std::size_t k = 0;
    row[k++] = Number(static_cast<double>(cell.index), std::to_string(cell.index));
    row[k++] = Text(cell.name);
    row[k++] = Text(cell.group);
    row[k++] = Text(cell.scenario);
    row[k++] = Number(static_cast<double>(cell.seed), std::to_string(cell.seed));
    for (const std::string& key : plan.vary_keys) {
      SummaryValue v;
      for (const scenario::Override& o2 : cell.varied) {
        if (o2.key == key) v = Text(o2.value);
      }
      row[k++] = v;
    }
    row[k++] = Text(ToString(o.status));
    row[k++] = Text(ReplaceAll(o.reason, strip, ""));
    for (const auto& [p, value] : flat[i]) row[column_of_path.at(p)] = value;
    if (o.status != CellStatus::kPending) {
      row[t.columns.size() - 2] = Number(o.wall_time_s, Json(o.wall_time_s).dump());
      row[t.columns.size() - 1] = Text(o.host);
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::string SummaryCsv(const SweepSummary& summary) {
  std::string out;
  for (std::size_t k = 0; k < summary.columns.size(); ++k) {
    out += (k ? "," : "") + CsvField(summary.columns[k].name);
  }
  out += "\n";
  for (const std::vector<SummaryValue>& row : summary.rows) {
    for (std::size_t k = 0; k < row.size(); ++k) out += (k ? "," : "") + CsvField(row[k].text);
    out += "\n";
  }
  return out;
}

std::string SummaryJson(const SweepSummary& summary) {
  Json j;
  j["sweep"] = summary.sweep;
  Json columns = Json::array();
  for (const SummaryColumn& c : summary.columns) columns.push_back(c.name);
  j["columns"] = columns;
  Json rows = Json::array();
  for (const std::vector<SummaryValue>& row : summary.rows) {
    Json r = Json::object();
    for (std::size_t k = 0; k < row.size(); ++k) {
      const SummaryValue& v = row[k];
      switch (v.kind) {
        case SummaryValue::Kind::kNull:
          r[summary.columns[k].name] = nullptr;
          break;
        case SummaryValue::Kind::kBool:
          r[summary.columns[k].name] = v.number != 0.0;
          break;
        case SummaryValue::Kind::kNumber:
          r[summary.columns[k].name] = Json::parse(v.text);  // integers stay integers
          break;
        case SummaryValue::Kind::kText:
          r[summary.columns[k].name] = v.text;
          break;
      }
    }
    rows.push_back(r);
  }
  j["cells"] = rows;
  return j.dump(2) + "\n";
}

SampleStats Describe(std::vector<double> values) {
  values.erase(
      std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
      values.end());
  SampleStats s{0, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
  s.n = values.size();
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  double sum = 0.0;
  for (double v : values) sum += v;
  const double n = static_cast<double>(values.size());
  s.mean = sum / n;
  s.min = values.front();
  s.max = values.back();
  const std::size_t h = values.size() / 2;
  s.median = values.size() % 2 ? values[h] : 0.5 * (values[h - 1] + values[h]);
  if (values.size() >= 2) {
    double ss = 0.0;
    for (double v : values) ss += (v - s.mean) * (v - s.mean);
    s.std = std::sqrt(ss / (n - 1.0));
    s.ci95_half_width = StudentTQuantile(0.975, n - 1.0) * s.std / std::sqrt(n);
  }
  return s;
}

double StudentTQuantile(double p, double dof) {
  if (!(p > 0.0 && p < 1.0) || !(dof > 0.0)) {
    throw std::invalid_argument("StudentTQuantile: need 0 < p < 1 and dof > 0");
  }
  return boost::math::quantile(boost::math::students_t_distribution<double>(dof), p);
}

std::vector<GroupStats> AggregateSweep(const SweepPlan& plan, const SweepSummary& summary) {
  std::vector<GroupStats> groups;
  std::map<std::string, std::size_t> index_of;
  const int status = summary.Column("cell_status");
  for (std::size_t i = 0; i < plan.cells.size(); ++i) {
    const SweepCell& cell = plan.cells[i];
    auto [it, fresh] = index_of.emplace(cell.group, groups.size());
    if (fresh) {
      GroupStats g;
      g.group = cell.group;
      g.scenario = cell.scenario;
      const std::vector<std::string> keys = plan.GroupKeys();
      for (const scenario::Override& o : cell.varied) {
        if (std::find(keys.begin(), keys.end(), o.key) != keys.end()) g.varied.push_back(o);
      }
      groups.push_back(g);
    }
    GroupStats& g = groups[it->second];
    ++g.cells;
    if (status >= 0 && i < summary.rows.size() &&
        summary.rows[i][static_cast<std::size_t>(status)].text == "ok") {
      ++g.ok;
    }
  }
  static const std::set<std::string> kNotMetrics = {
      "index", "cell", "group", "scenario", "seed", "cell_status", "cell_reason", "host"};
  for (GroupStats& g : groups) {
    for (const SummaryColumn& c : summary.columns) {
      if (kNotMetrics.count(c.name) || StartsWith(c.name, "vary_")) continue;
      const std::vector<double> values = GroupValues(summary, g.group, c.name);
      if (values.empty()) continue;
      g.metrics.emplace_back(c.name, Describe(values));
    }
  }
  return groups;
}

std::string AggregatesCsv(const SweepPlan& plan, const std::vector<GroupStats>& groups) {
  const std::vector<std::string> keys = plan.GroupKeys();
  std::string out = "group,scenario";
  for (const std::string& k : keys) out += "," + CsvField(VaryColumn(k));
  out += ",cells,ok,metric,n,mean,std,ci95_half_width,median,min,max\n";
  for (const GroupStats& g : groups) {
    std::string head = CsvField(g.group) + "," + CsvField(g.scenario);
    for (const std::string& k : keys) {
      std::string value;
      for (const scenario::Override& o : g.varied) {
        if (o.key == k) value = o.value;
      }
      head += "," + CsvField(value);
    }
    head += "," + std::to_string(g.cells) + "," + std::to_string(g.ok);
    for (const auto& [name, s] : g.metrics) {
      out += head + "," + CsvField(name) + "," + std::to_string(s.n) + "," + Shortest(s.mean) +
             "," + Shortest(s.std) + "," + Shortest(s.ci95_half_width) + "," + Shortest(s.median) +
             "," + Shortest(s.min) + "," + Shortest(s.max) + "\n";
    }
  }
  return out;
}

SweepCounts CountOutcomes(const std::vector<CellResult>& cells) {
  SweepCounts n;
  for (const CellResult& c : cells) {
    switch (c.outcome.status) {
      case CellStatus::kOk:
        ++n.ok;
        break;
      case CellStatus::kFailed:
        ++n.failed;
        break;
      case CellStatus::kTimedOut:
        ++n.timed_out;
        break;
      case CellStatus::kInterrupted:
        ++n.interrupted;
        break;
      case CellStatus::kPending:
        ++n.pending;
        break;
    }
  }
  return n;
}

std::vector<CellResult> ReadSweepResults(const fs::path& sweep_dir, const SweepPlan& plan) {
  std::vector<CellResult> results;
  for (const SweepCell& cell : plan.cells) {
    CellResult r;
    r.cell = cell;
    r.outcome = ReadCellOutcome(sweep_dir, cell);
    if (CellFinished(sweep_dir, cell)) {
      r.metrics_json = ReadTextFile(CellMetricsPath(sweep_dir, cell));
      if (r.outcome.status == CellStatus::kPending) {
        // The run finished but the sweep stopped before it recorded the outcome.
        r.outcome = OutcomeFromMetrics(*r.metrics_json);
      }
    } else if (r.outcome.status == CellStatus::kOk) {
      r.outcome = CellOutcome{};
      r.outcome.reason = "run/metrics.json is missing: the cell reruns on resume";
    }
    results.push_back(std::move(r));
  }
  return results;
}

namespace {

// The title, the cell counts by status and where the report's data lives.
std::string ReportIntroduction(const SweepPlan& plan, const SweepSummary& summary) {
  std::map<std::string, std::size_t> by_status;
  const int status = summary.Column("cell_status");
  for (const std::vector<SummaryValue>& row : summary.rows) {
    ++by_status[row[static_cast<std::size_t>(status)].text];
  }
  std::string md = "# Sweep `" + plan.name + "`\n\n";
  md += std::to_string(summary.rows.size()) + " cells:";
  bool first = true;
  for (const char* s : {"ok", "failed", "timed_out", "interrupted", "pending"}) {
    if (!by_status[s]) continue;
    md += std::string(first ? " " : ", ") + std::to_string(by_status[s]) + " " + s;
    first = false;
  }
  md +=
      ". Every cell's metrics are in [summary.csv](summary.csv) ([summary.json](summary.json)); "
      "statistics per group (the cells that differ only in seed";
  if (!plan.replicate_keys.empty()) {
    md += " and ";
    for (std::size_t k = 0; k < plan.replicate_keys.size(); ++k) {
      md += (k ? ", " : "") + std::string("`") + plan.replicate_keys[k] + "`";
    }
  }
  md +=
      ": n, mean, std, 95 % confidence interval, median, min, max) in "
      "[aggregates.csv](aggregates.csv); each cell's run folder in `cells/<cell>/run/`.\n";
  return md;
}

// The group columns both tables start with: group, scenario, then each varied key.
std::string GroupHeader(const std::vector<std::string>& keys) {
  std::string h = "| group | scenario |";
  for (const std::string& k : keys) h += " " + MarkdownCell(k) + " |";
  return h;
}

// One group's cells under GroupHeader (empty for a key the group does not vary).
std::string GroupCells(const std::vector<std::string>& keys, const GroupStats& g) {
  std::string r = "| " + MarkdownCell(g.group) + " | " + MarkdownCell(g.scenario) + " |";
  for (const std::string& k : keys) {
    std::string value;
    for (const scenario::Override& o : g.varied) {
      if (o.key == k) value = o.value;
    }
    r += " " + MarkdownCell(value) + " |";
  }
  return r;
}

// A table's header rule for `columns` columns.
std::string TableRule(std::size_t columns) {
  std::string r = "|";
  for (std::size_t k = 0; k < columns; ++k) r += "---|";
  return r + "\n";
}

// ATE per estimator and group, with the estimators ranked; "" without estimators.
std::string LocalizationSection(const SweepPlan& plan, const SweepSummary& summary,
                                const std::vector<GroupStats>& groups) {
  const std::vector<std::string> estimators = EstimatorsOf(summary);
  if (estimators.empty()) return "";
  const std::vector<std::string> keys = plan.GroupKeys();
  std::string md = "\n## Localization: ATE [m] per estimator\n\n";
  md +=
      "Horizontal RMS position error against ground truth, without alignment "
      "(`estimators.<name>.ate_rmse_m`), mean ± sample standard deviation over the group's "
      "seeds (ok cells only); the last column orders the estimators by mean ATE, best "
      "first.\n\n";
  md += GroupHeader(keys) + " ok |";
  for (const std::string& e : estimators) md += " " + e + " |";
  md += " best → worst |\n";
  md += TableRule(2 + keys.size() + 1 + estimators.size() + 1);
  for (const GroupStats& g : groups) {
    md += GroupCells(keys, g) + " " + std::to_string(g.ok) + "/" + std::to_string(g.cells) + " |";
    std::vector<std::pair<double, std::string>> ranking;
    for (const std::string& e : estimators) {
      const SampleStats* s = g.Find(AteColumn(summary, e));
      md += " " + (s ? MeanStd(*s) : std::string("–")) + " |";
      if (s) ranking.emplace_back(s->mean, e);
    }
    std::stable_sort(ranking.begin(), ranking.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::string order;
    for (const auto& [mean, e] : ranking) order += (order.empty() ? "" : " < ") + e;
    md += " " + order + " |\n";
  }
  return md;
}

// Success rate and navigation means per group; "" when no cell reports navigation.
std::string NavigationSection(const SweepPlan& plan, const SweepSummary& summary,
                              const std::vector<GroupStats>& groups) {
  const std::string success = ColumnOfPath(summary, {"navigation", "success"});
  if (success.empty()) return "";
  const std::vector<std::string> keys = plan.GroupKeys();
  std::string md = "\n## Navigation\n\n";
  md +=
      "Success rate over the group's ok cells; the other columns are means ± std over "
      "them (`navigation.*` in metrics.json).\n\n";
  const std::vector<std::pair<std::string, std::vector<std::string>>> extra = {
      {"time to goal [s]", {"navigation", "time_to_goal_s"}},
      {"path length [m]", {"navigation", "path_length_m"}},
      {"final error [m]", {"navigation", "final_position_error_m"}},
      {"min clearance [m]", {"navigation", "min_clearance_m"}},
      {"collisions", {"navigation", "collisions"}}};
  md += GroupHeader(keys) + " ok | success |";
  for (const auto& [title, path] : extra) md += " " + title + " |";
  md += "\n" + TableRule(2 + keys.size() + 2 + extra.size());
  for (const GroupStats& g : groups) {
    md += GroupCells(keys, g) + " " + std::to_string(g.ok) + "/" + std::to_string(g.cells) + " |";
    const SampleStats* s = g.Find(success);
    if (s) {
      char buf[64];
      const long wins = std::lround(s->mean * static_cast<double>(s->n));
      std::snprintf(buf, sizeof(buf), "%ld/%zu (%.0f %%)", wins, s->n, 100.0 * s->mean);
      md += std::string(" ") + buf + " |";
    } else {
      md += " – |";
    }
    for (const auto& [title, path] : extra) {
      const SampleStats* e = g.Find(ColumnOfPath(summary, path));
      md += " " + (e ? MeanStd(*e) : std::string("–")) + " |";
    }
    md += "\n";
  }
  return md;
}

// Every cell whose status is not ok, with its reason; "" when all are ok.
std::string CellsWithoutResultSection(const SweepSummary& summary) {
  const int status = summary.Column("cell_status");
  const int reason = summary.Column("cell_reason"), cell = summary.Column("cell");
  std::string md;
  for (const std::vector<SummaryValue>& row : summary.rows) {
    if (row[static_cast<std::size_t>(status)].text == "ok") continue;
    if (md.empty())
      md += "\n## Cells without a result\n\n| cell | status | reason |\n|---|---|---|\n";
    md += "| " + MarkdownCell(row[static_cast<std::size_t>(cell)].text) + " | " +
          row[static_cast<std::size_t>(status)].text + " | " +
          MarkdownCell(row[static_cast<std::size_t>(reason)].text) + " |\n";
  }
  return md;
}

// The sweep's plots as images; "" without plots.
std::string PlotsSection(const std::vector<std::string>& plots) {
  if (plots.empty()) return "";
  std::string md = "\n## Plots\n\n";
  for (const std::string& p : plots) {
    md += "![" + fs::path(p).stem().string() + "](" + p + ")\n\n";
  }
  return md;
}

}  // namespace

std::string SweepReportMarkdown(const SweepPlan& plan, const SweepSummary& summary,
                                const std::vector<GroupStats>& groups,
                                const std::vector<std::string>& plots) {
  return ReportIntroduction(plan, summary) + LocalizationSection(plan, summary, groups) +
         NavigationSection(plan, summary, groups) + CellsWithoutResultSection(summary) +
         PlotsSection(plots);
}

SweepCounts WriteSweepReport(const fs::path& sweep_dir) {
  const fs::path dir = fs::absolute(sweep_dir).lexically_normal();
  const SweepPlan plan = ReadSweepPlan(dir);
  return WriteSweepReport(dir, plan, ReadSweepResults(dir, plan), "");
}

SweepCounts WriteSweepReport(const fs::path& dir, const SweepPlan& plan,
                             const std::vector<CellResult>& results, const std::string& section) {
  const SweepSummary summary = BuildSweepSummary(plan, results, dir);
  const std::vector<GroupStats> groups = AggregateSweep(plan, summary);

  const fs::path plot_dir = dir / "plots";
  fs::remove_all(plot_dir);
  fs::create_directories(plot_dir);
  std::vector<std::string> plots;
  const std::vector<std::string> estimators = EstimatorsOf(summary);
  for (const GroupStats& g : groups) {
    std::vector<plot::BoxSeries> boxes;
    double lo = 1e300, hi = 0.0;
    bool any = false;
    for (const std::string& e : estimators) {
      plot::BoxSeries b{e, GroupValues(summary, g.group, AteColumn(summary, e))};
      for (double v : b.values) {
        if (!(v > 0) || !std::isfinite(v)) continue;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        any = true;
      }
      boxes.push_back(std::move(b));
    }
    if (!any) continue;
    const std::string name = "plots/ate_" + g.group + ".png";
    plot::WriteBoxPlot(dir / name,
                       "ATE per estimator: " + g.group + " (" + std::to_string(g.ok) + " ok cells)",
                       "ATE [m]", boxes, hi / lo > 30.0);
    plots.push_back(name);
  }
  const std::string success = ColumnOfPath(summary, {"navigation", "success"});
  if (!success.empty()) {
    std::vector<plot::BarValue> bars;
    for (const GroupStats& g : groups) {
      const SampleStats* s = g.Find(success);
      if (!s) continue;
      const long wins = std::lround(s->mean * static_cast<double>(s->n));
      bars.push_back({g.group, s->mean, std::to_string(wins) + "/" + std::to_string(s->n)});
    }
    if (!bars.empty()) {
      plot::WriteBarPlot(dir / "plots/navigation_success.png", "Navigation success rate per group",
                         "success rate", bars, 1.0);
      plots.push_back("plots/navigation_success.png");
    }
  }

  WriteFileAtomically(dir / "summary.csv", SummaryCsv(summary));
  WriteFileAtomically(dir / "summary.json", SummaryJson(summary));
  WriteFileAtomically(dir / "aggregates.csv", AggregatesCsv(plan, groups));
  // One run of each group as an example: its own plots (trajectories over the true
  // path, the navigation map), from the first ok cell.
  std::string examples;
  for (const GroupStats& g : groups) {
    for (const CellResult& r : results) {
      if (r.cell.group != g.group || r.outcome.status != CellStatus::kOk) continue;
      for (const char* png : {"trajectories.png", "navigation.png"}) {
        const fs::path p = fs::path("cells") / r.cell.name / "run" / png;
        if (!fs::exists(dir / p)) continue;
        examples += "![" + r.cell.name + "](" + p.string() + ")\n\n";
      }
      break;
    }
  }
  std::string md = SweepReportMarkdown(plan, summary, groups, plots);
  const std::size_t first_section = md.find("\n## ");
  md.insert(first_section == std::string::npos ? md.size() : first_section + 1, section);
  if (!examples.empty()) {
    if (md.size() < 2 || md.compare(md.size() - 2, 2, "\n\n") != 0) md += "\n";
    md += "## Example runs\n\nThe first ok cell of each group, with its run's own plots.\n\n" +
          examples;
  }
  WriteFileAtomically(dir / "report.md", md);
  return CountOutcomes(results);
}

}  // namespace trackbed::experiments
