// Checking a sweep's closed-loop expectations (sweep_expectation.h) on the cells that
// ran, reported in report.md and in JUnit XML (junit.xml) that CI services display.
// `trackbed sweep` exits 3 when every cell ran and an expectation failed.
#pragma once

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "trackbed/experiments/sweep.h"
#include "trackbed/experiments/sweep_report.h"

namespace trackbed::experiments {

/// One expectation checked on one cell or group.
struct ExpectationCheck {
  std::size_t expectation = 0;  ///< index in the plan's list
  std::string subject;          ///< the cell's name (over cell) or the group's
  std::string group;            ///< the subject's group
  bool passed = false;
  /// What was measured: `0.0812`, `fused 0.31 >= visual_odometry 0.22`, `no number at
  /// estimators.fused.ate_rmse_m`.
  std::string detail;
};

/// Every expectation of `plan` on every ok cell (over cell) or on every group with a
/// cell (over mean; a group without an ok cell fails it). Cells that did not succeed
/// are not checked: they fail as cells.
std::vector<ExpectationCheck> CheckExpectations(const SweepPlan& plan,
                                                const std::vector<CellResult>& cells);

/// JUnit XML: one test suite for the sweep, a test case per cell (an error when it did
/// not succeed) and per expectation checked (a failure with what was measured).
std::string JunitXml(const SweepPlan& plan, const std::vector<CellResult>& cells,
                     const std::vector<ExpectationCheck>& checks);

/// What the expectations' checks found.
struct ExpectationSummary {
  std::size_t checked = 0;
  std::vector<std::string> failed;  ///< one line per failed check: `subject: text: measured …`
};

/// A sweep's outcome once its cells ran: the cells' counts and the expectations'.
struct SweepVerdict {
  SweepCounts cells;
  ExpectationSummary expectations;
};

/// Reads the sweep folder once, checks its expectations on its cells, writes the report
/// (WriteSweepReport, with the "Expectations" section) and junit.xml. Throws SweepError
/// when `sweep_dir` is not a sweep folder.
SweepVerdict ReportSweep(const std::filesystem::path& sweep_dir);

/// `trackbed sweep`'s exit status for a sweep whose cells all ran (not interrupted): 0
/// when every cell is ok and every expectation held, 1 when a cell did not succeed
/// (expectations are checked on the others all the same), 3 when every cell is ok and
/// an expectation failed.
int SweepExitStatus(const SweepVerdict& verdict);

/// The result lines `trackbed sweep` prints: the counts, where the summary and report
/// are, and each failed expectation.
void PrintSweepResult(std::ostream& out, const std::string& name,
                      const std::filesystem::path& sweep_dir, const SweepVerdict& verdict);

/// report.md's "Expectations" section (empty without expectations).
std::string ExpectationsMarkdown(const SweepPlan& plan,
                                 const std::vector<ExpectationCheck>& checks);

}  // namespace trackbed::experiments
