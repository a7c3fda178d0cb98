// Fuzzes what a sweep folder holds besides the sweep file (sweep.h): the input as JSON
// text goes to ParseSweepPlan (cells.json), ParseCellOutcome (cells/NAME/cell.json) and
// OutcomeFromMetrics (a run's metrics.json). A plan that parses is written again
// (SweepPlanJson), read back and compared with PlanConflict; an outcome that parses is
// written again (CellOutcomeJson) and read back.
//
// Finding: a crash, a sanitizer report, a hang, an exception other than SweepError from
// the two parsers, any exception from OutcomeFromMetrics (it reports unreadable text as a
// failed outcome), or a plan or outcome that does not read back.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "fuzz_support.h"
#include "trackbed/experiments/sweep.h"

namespace {

namespace ex = trackbed::experiments;

[[noreturn]] void Finding(const std::string& what) {
  trackbed::fuzz::Finding("sweep_plan_fuzz", what);
}

void FuzzPlan(const std::string& text) {
  ex::SweepPlan plan;
  try {
    plan = ex::ParseSweepPlan(text, "cells.json");
  } catch (const ex::SweepError&) {
    return;
  }
  plan.GroupKeys();
  try {
    const ex::SweepPlan again = ex::ParseSweepPlan(ex::SweepPlanJson(plan), "written.json");
    const std::string conflict = ex::PlanConflict(plan, again);
    if (!conflict.empty()) Finding("cells.json reads back differently: " + conflict);
  } catch (const ex::SweepError& e) {
    Finding(std::string("written cells.json does not read back: ") + e.what());
  }
}

void FuzzOutcome(const std::string& text) {
  ex::CellOutcome outcome;
  try {
    outcome = ex::ParseCellOutcome(text, "cell.json");
  } catch (const ex::SweepError&) {
    return;
  }
  ex::SweepCell cell;
  cell.name = "fuzz";
  try {
    const ex::CellOutcome again =
        ex::ParseCellOutcome(ex::CellOutcomeJson(cell, outcome), "written.json");
    if (again.status != outcome.status || again.reason != outcome.reason ||
        again.exit_code != outcome.exit_code) {
      Finding("cell.json reads back differently");
    }
  } catch (const ex::SweepError& e) {
    Finding(std::string("written cell.json does not read back: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  FuzzPlan(text);
  FuzzOutcome(text);
  ex::OutcomeFromMetrics(text);
  return 0;
}
