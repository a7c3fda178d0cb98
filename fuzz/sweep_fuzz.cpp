// Fuzzes sweep files (sweep.h): ParseSweep on the input as YAML text, as if the file were
// in scenes/sweeps/ (so the shipped sweeps' relative scenario paths resolve); where it
// parses, ExpandSweep and MakeSweepPlan, cells.json written and read back, the resolved
// sweep (SweepToYaml) read back, and the first cell's scenario with its overrides loaded
// (ValidateCell) when that scenario is one of the shipped scenes.
//
// Finding: a crash, a sanitizer report, a hang or an out-of-memory, an exception other
// than SweepError (ValidateCell throws none), or a resolved sweep or cells.json that does
// not read back.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "trackbed/experiments/sweep.h"

namespace {

namespace ex = trackbed::experiments;

[[noreturn]] void Finding(const std::string& what) { trackbed::fuzz::Finding("sweep_fuzz", what); }

// A scenario path a cell may load: a shipped scene, never whatever file the input names.
bool IsShippedScene(const std::filesystem::path& p) {
  static const std::string scenes =
      std::filesystem::path(TRACKBED_SOURCE_DIR "/scenes/").lexically_normal().string();
  const std::string s = p.lexically_normal().string();
  return s.compare(0, scenes.size(), scenes) == 0 && p.extension() == ".yaml";
}

void CheckPlan(const ex::SweepSpec& spec) {
  const ex::SweepPlan plan = ex::MakeSweepPlan(spec);
  const std::string json = ex::SweepPlanJson(plan);
  try {
    const ex::SweepPlan again = ex::ParseSweepPlan(json, "cells.json");
    const std::string conflict = ex::PlanConflict(plan, again);
    if (!conflict.empty()) Finding("cells.json reads back differently: " + conflict);
  } catch (const ex::SweepError& e) {
    Finding(std::string("cells.json does not read back: ") + e.what());
  }
  if (!plan.cells.empty() && IsShippedScene(plan.cells[0].scenario_path)) {
    ex::ValidateCell(plan.cells[0]);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::filesystem::path dir = TRACKBED_SOURCE_DIR "/scenes/sweeps";
  ex::SweepSpec spec;
  try {
    spec = ex::ParseSweep(text, "fuzz.yaml", dir);
  } catch (const ex::SweepError&) {
    return 0;
  }
  std::size_t cells = 0;
  try {
    cells = ex::ExpandSweep(spec).size();
  } catch (const ex::SweepError&) {
    return 0;  // cells sharing a folder name, or a name too long: said, not crashed
  }
  CheckPlan(spec);
  const std::string resolved = ex::SweepToYaml(spec);
  try {
    const ex::SweepSpec again = ex::ParseSweep(resolved, "fuzz.yaml", dir);
    if (ex::ExpandSweep(again).size() != cells) Finding("resolved sweep expands differently");
  } catch (const ex::SweepError& e) {
    Finding(std::string("resolved sweep does not read back: ") + e.what() + "\n" + resolved);
  }
  return 0;
}
