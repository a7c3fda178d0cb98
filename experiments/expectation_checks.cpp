// Checking a sweep's expectations (see expectation_checks.h).
#include "trackbed/experiments/expectation_checks.h"

#include <cmath>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "trackbed/experiments/sweep_support.h"

namespace trackbed::experiments {
namespace {

// The number at a dotted path of a run's metrics.json, if there is one.
std::optional<double> MetricAt(const nlohmann::json& metrics, const std::string& dotted) {
  const nlohmann::json* node = &metrics;
  std::stringstream path(dotted);
  for (std::string key; std::getline(path, key, '.');) {
    if (!node->is_object() || !node->contains(key)) return std::nullopt;
    node = &(*node)[key];
  }
  if (node->is_boolean()) return node->get<bool>() ? 1.0 : 0.0;
  if (!node->is_number()) return std::nullopt;
  return node->get<double>();
}

// The values an expectation reads from one run: the metric, or each ordered
// estimator's; nothing when one is missing (`missing` says which).
std::optional<std::vector<double>> Values(const SweepExpectation& e, const nlohmann::json& metrics,
                                          std::string* missing) {
  std::vector<std::string> paths;
  if (e.order.empty()) paths.push_back(e.metric);
  for (const std::string& name : e.order) paths.push_back("estimators." + name + "." + e.metric);
  std::vector<double> values;
  for (const std::string& p : paths) {
    const std::optional<double> v = MetricAt(metrics, p);
    if (!v || !std::isfinite(*v)) {
      *missing = "no number at " + p;
      return std::nullopt;
    }
    values.push_back(*v);
  }
  return values;
}

// Whether values pass the expectation, and what was measured.
bool Judge(const SweepExpectation& e, const std::vector<double>& v, std::string* detail) {
  if (e.order.empty()) {
    *detail = FormatMeasured(v[0]);
    if (e.min && v[0] < *e.min) *detail += " < " + FormatMeasured(*e.min);
    if (e.max && v[0] > *e.max) *detail += " > " + FormatMeasured(*e.max);
    return (!e.min || v[0] >= *e.min) && (!e.max || v[0] <= *e.max);
  }
  bool ok = true;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) *detail += v[i - 1] < v[i] ? " < " : " >= ";
    *detail += e.order[i] + " " + FormatMeasured(v[i]);
    if (i > 0 && !(v[i - 1] < v[i])) ok = false;
  }
  return ok;
}

std::string Xml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        // Control characters other than tab and newline are not allowed in XML 1.0.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') {
          out += ' ';
        } else {
          out += c;
        }
    }
  }
  return out;
}

}  // namespace

std::vector<ExpectationCheck> CheckExpectations(const SweepPlan& plan,
                                                const std::vector<CellResult>& cells) {
  std::vector<ExpectationCheck> checks;
  std::vector<nlohmann::json> metrics(cells.size());  // each ok cell's, parsed once
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const CellResult& r = cells[i];
    if (r.outcome.status == CellStatus::kOk && r.metrics_json) {
      metrics[i] = nlohmann::json::parse(*r.metrics_json, nullptr, false);
    }
  }
  for (std::size_t k = 0; k < plan.expect.size(); ++k) {
    const SweepExpectation& e = plan.expect[k];
    // Per cell, or the values of each group's ok cells gathered for their mean.
    std::map<std::string, std::vector<std::vector<double>>> groups;
    std::map<std::string, std::string> missing_in_group;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const CellResult& r = cells[i];
      if (!e.scenario.empty() && r.cell.scenario != e.scenario) continue;
      groups[r.cell.group];
      if (r.outcome.status != CellStatus::kOk || !r.metrics_json) continue;
      std::string missing;
      const std::optional<std::vector<double>> v = Values(e, metrics[i], &missing);
      if (e.over == "mean") {
        if (v) groups[r.cell.group].push_back(*v);
        if (!v) missing_in_group[r.cell.group] = r.cell.name + ": " + missing;
        continue;
      }
      ExpectationCheck c{k, r.cell.name, r.cell.group, false, missing};
      if (v) c.passed = Judge(e, *v, &c.detail);
      checks.push_back(c);
    }
    if (e.over != "mean") continue;
    for (const auto& [group, rows] : groups) {
      ExpectationCheck c{k, group, group, false, ""};
      if (missing_in_group.count(group)) {
        c.detail = missing_in_group[group];
      } else if (rows.empty()) {
        c.detail = "no ok cell";
      } else {
        std::vector<double> mean(rows[0].size(), 0.0);
        for (const auto& row : rows) {
          for (std::size_t i = 0; i < row.size(); ++i) mean[i] += row[i] / rows.size();
        }
        c.passed = Judge(e, mean, &c.detail);
        c.detail = "mean of " + std::to_string(rows.size()) + ": " + c.detail;
      }
      checks.push_back(c);
    }
  }
  return checks;
}

std::string JunitXml(const SweepPlan& plan, const std::vector<CellResult>& cells,
                     const std::vector<ExpectationCheck>& checks) {
  std::size_t errors = 0, failures = 0;
  std::ostringstream cases;
  for (const CellResult& r : cells) {
    cases << "    <testcase classname=\"" << Xml(plan.name + "." + r.cell.group) << "\" name=\""
          << Xml(r.cell.name + ": runs") << "\" time=\"" << FormatMeasured(r.outcome.wall_time_s)
          << "\"";
    if (r.outcome.status == CellStatus::kOk) {
      cases << "/>\n";
      continue;
    }
    ++errors;
    const std::string why = std::string(ToString(r.outcome.status)) +
                            (r.outcome.reason.empty() ? "" : ": " + r.outcome.reason);
    cases << ">\n      <error type=\"" << ToString(r.outcome.status) << "\" message=\"" << Xml(why)
          << "\">" << Xml(r.outcome.stderr_tail) << "</error>\n    </testcase>\n";
  }
  for (const ExpectationCheck& c : checks) {
    const SweepExpectation& e = plan.expect[c.expectation];
    cases << "    <testcase classname=\"" << Xml(plan.name + "." + c.group) << "\" name=\""
          << Xml(c.subject + ": " + e.Text()) << "\" time=\"0\"";
    if (c.passed) {
      cases << "/>\n";
      continue;
    }
    ++failures;
    cases << ">\n      <failure type=\"expectation\" message=\"" << Xml("measured " + c.detail)
          << "\">" << Xml(e.Text() + ": measured " + c.detail) << "</failure>\n    </testcase>\n";
  }
  const std::size_t tests = cells.size() + checks.size();
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<testsuites name=\"trackbed sweep\" tests=\"" << tests << "\" failures=\"" << failures
    << "\" errors=\"" << errors << "\">\n"
    << "  <testsuite name=\"" << Xml(plan.name) << "\" tests=\"" << tests << "\" failures=\""
    << failures << "\" errors=\"" << errors << "\" skipped=\"0\">\n"
    << cases.str() << "  </testsuite>\n</testsuites>\n";
  return x.str();
}

std::string ExpectationsMarkdown(const SweepPlan& plan,
                                 const std::vector<ExpectationCheck>& checks) {
  if (plan.expect.empty()) return "";
  std::ostringstream md;
  md << "## Expectations\n\nChecked on the cells that ran (`expect:` in the sweep file; "
        "JUnit XML in [junit.xml](junit.xml)).\n\n| expectation | checked | passed | failed |\n"
        "|---|---|---|---|\n";
  std::string failed_lines;
  for (std::size_t k = 0; k < plan.expect.size(); ++k) {
    std::size_t n = 0, passed = 0;
    for (const ExpectationCheck& c : checks) {
      if (c.expectation != k) continue;
      ++n;
      if (c.passed) {
        ++passed;
      } else {
        failed_lines +=
            "- " + c.subject + ": " + plan.expect[k].Text() + ": measured " + c.detail + "\n";
      }
    }
    md << "| " << plan.expect[k].Text() << " | " << n << " | " << passed << " | " << n - passed
       << " |\n";
  }
  if (!failed_lines.empty()) md << "\nFailed:\n\n" << failed_lines;
  return md.str() + "\n";
}

SweepVerdict ReportSweep(const std::filesystem::path& sweep_dir) {
  const std::filesystem::path dir = std::filesystem::absolute(sweep_dir).lexically_normal();
  const SweepPlan plan = ReadSweepPlan(dir);
  const std::vector<CellResult> cells = ReadSweepResults(dir, plan);
  const std::vector<ExpectationCheck> checks = CheckExpectations(plan, cells);
  SweepVerdict v;
  v.cells = WriteSweepReport(dir, plan, cells, ExpectationsMarkdown(plan, checks));
  WriteFileAtomically(dir / "junit.xml", JunitXml(plan, cells, checks));
  v.expectations.checked = checks.size();
  for (const ExpectationCheck& c : checks) {
    if (!c.passed) {
      v.expectations.failed.push_back(c.subject + ": " + plan.expect[c.expectation].Text() +
                                      ": measured " + c.detail);
    }
  }
  return v;
}

int SweepExitStatus(const SweepVerdict& verdict) {
  if (verdict.cells.ok != verdict.cells.total()) return kExitSomeFailed;
  return verdict.expectations.failed.empty() ? kExitAllOk : kExitExpectationFailed;
}

void PrintSweepResult(std::ostream& out, const std::string& name,
                      const std::filesystem::path& sweep_dir, const SweepVerdict& verdict) {
  const SweepCounts& n = verdict.cells;
  const ExpectationSummary& e = verdict.expectations;
  out << "trackbed sweep: " << name << ": " << n.ok << " ok, " << n.failed << " failed, "
      << n.timed_out << " timed out";
  if (e.checked > 0) {
    out << "; expectations: " << e.checked - e.failed.size() << " of " << e.checked << " held";
  }
  out << "; summary in " << (sweep_dir / "summary.csv").string() << ", report in "
      << (sweep_dir / "report.md").string();
  if (e.checked > 0) out << ", JUnit XML in " << (sweep_dir / "junit.xml").string();
  out << std::endl;
  for (const std::string& f : e.failed) out << "trackbed sweep: expectation failed: " << f << "\n";
  out.flush();
}

}  // namespace trackbed::experiments
