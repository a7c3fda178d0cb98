// Sweep files and sweep results without running anything: expansion order and
// cell names, the strict reader's messages, the folder's JSON round trips, the
// summary's column rules, and the statistics of the aggregates.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/experiments/slurm_backend.h"
#include "trackbed/experiments/sweep.h"
#include "trackbed/experiments/sweep_report.h"
#include "trackbed/experiments/sweep_support.h"

namespace trackbed::experiments {

using namespace scenario;  // the scenarios these tests run
namespace {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(TRACKBED_SOURCE_DIR) / "scenes";

SweepSpec Parse(const std::string& yaml) { return ParseSweep(yaml, "test.yaml", kScenes); }

std::string ErrorOf(const std::string& yaml) {
  try {
    Parse(yaml);
  } catch (const SweepError& e) {
    return e.what();
  }
  return "(no error)";
}

std::vector<std::string> Names(const std::vector<SweepCell>& cells) {
  std::vector<std::string> names;
  for (const SweepCell& c : cells) names.push_back(c.name);
  return names;
}

fs::path TempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("trackbed_sweep_test_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(SweepFileTest, ExpandsScenariosThenAxesThenSeedsWithStableNames) {
  const SweepSpec spec = Parse(R"(
name: order
scenarios: [nav_paper_left.yaml, nav_paper_right.yaml]
seeds: [3, 1]
set: ["duration_s=5"]
vary:
  - {key: navigation.method, values: [dwa, potential_field]}
  - {key: navigation.safety_radius_m, range: {from: 0.5, to: 1.0, step: 0.25}}
)");
  const std::vector<SweepCell> cells = ExpandSweep(spec);
  ASSERT_EQ(cells.size(), 2u * 2u * 3u * 2u);
  // Seeds fastest, then the last axis, then the first, then the scenario.
  EXPECT_EQ(cells[0].name, "nav_paper_left__method-dwa__safety_radius_m-0.5__seed-3");
  EXPECT_EQ(cells[1].name, "nav_paper_left__method-dwa__safety_radius_m-0.5__seed-1");
  EXPECT_EQ(cells[2].name, "nav_paper_left__method-dwa__safety_radius_m-0.75__seed-3");
  EXPECT_EQ(cells[5].name, "nav_paper_left__method-dwa__safety_radius_m-1__seed-1");
  EXPECT_EQ(cells[6].name, "nav_paper_left__method-potential_field__safety_radius_m-0.5__seed-3");
  EXPECT_EQ(cells[12].name, "nav_paper_right__method-dwa__safety_radius_m-0.5__seed-3");
  for (std::size_t i = 0; i < cells.size(); ++i) EXPECT_EQ(cells[i].index, i);
  EXPECT_EQ(cells[1].group, "nav_paper_left__method-dwa__safety_radius_m-0.5");
  EXPECT_EQ(cells[1].group, cells[0].group);
  EXPECT_NE(cells[2].group, cells[0].group);
  EXPECT_EQ(cells[12].scenario, "nav_paper_right.yaml");
  EXPECT_EQ(cells[12].scenario_path, kScenes / "nav_paper_right.yaml");
  EXPECT_EQ(cells[1].seed, 1u);
  // Fixed overrides first, then the varied ones in axis order.
  ASSERT_EQ(cells[2].overrides.size(), 3u);
  EXPECT_EQ(cells[2].overrides[0].key, "duration_s");
  EXPECT_EQ(cells[2].overrides[0].value, "5");
  EXPECT_EQ(cells[2].overrides[1].key, "navigation.method");
  EXPECT_EQ(cells[2].overrides[1].value, "dwa");
  EXPECT_EQ(cells[2].overrides[2].key, "navigation.safety_radius_m");
  EXPECT_EQ(cells[2].overrides[2].value, "0.75");
  ASSERT_EQ(cells[2].varied.size(), 2u);
  EXPECT_EQ(cells[2].varied[1].value, "0.75");
  // The same file expands to the same names.
  EXPECT_EQ(Names(ExpandSweep(Parse(R"(
name: order
scenarios: [nav_paper_left.yaml, nav_paper_right.yaml]
seeds: [3, 1]
set: ["duration_s=5"]
vary:
  - {key: navigation.method, values: [dwa, potential_field]}
  - {key: navigation.safety_radius_m, range: {from: 0.5, to: 1.0, step: 0.25}}
)"))),
            Names(cells));
}

TEST(SweepFileTest, RangesAndSeedRangesExpandInclusively) {
  const SweepSpec spec = Parse(R"(
scenarios: [nav_paper_left.yaml]
seeds: {from: 1, to: 10}
vary:
  - {key: navigation.field_seed, range: {from: 0, to: 4, step: 2}}
  - {key: navigation.safety_radius_m, range: {from: 0.1, to: 0.3, step: 0.1}}
)");
  EXPECT_EQ(spec.name, "test");  // the file's stem
  ASSERT_EQ(spec.seeds.size(), 10u);
  EXPECT_EQ(spec.seeds.front(), 1u);
  EXPECT_EQ(spec.seeds.back(), 10u);
  EXPECT_EQ(spec.vary[0].values, (std::vector<std::string>{"0", "2", "4"}));
  // 0.1 + 2 * 0.1 is not 0.3 in binary; the value text is.
  EXPECT_EQ(spec.vary[1].values, (std::vector<std::string>{"0.1", "0.2", "0.3"}));
  EXPECT_EQ(ExpandSweep(spec).size(), 10u * 3u * 3u);
}

TEST(SweepFileTest, ListValuesBecomeOneSetTokenAndSafeNames) {
  const SweepSpec spec = Parse(R"(
scenarios: [corridor.yaml]
seeds: [1]
vary:
  - key: drive.waypoints
    values:
      - [[0, 0], [5, 0]]
      - [[0, 0], [3, 0]]
  - {key: scene.terrain.default_material, values: ["hard floor?", grass]}
)");
  const std::vector<SweepCell> cells = ExpandSweep(spec);
  ASSERT_EQ(cells.size(), 4u);
  EXPECT_EQ(cells[0].varied[0].value, "[[0, 0], [5, 0]]");
  EXPECT_EQ(cells[0].varied[1].value, "hard floor?");
  const std::regex safe("[A-Za-z0-9._+-]+");
  for (const SweepCell& c : cells) EXPECT_TRUE(std::regex_match(c.name, safe)) << c.name;
  // Unsafe values keep a readable part and a hash of the original text.
  EXPECT_EQ(cells[0].name.rfind("corridor__waypoints-0_0_5_0-", 0), 0u) << cells[0].name;
  EXPECT_NE(cells[0].name.find("__default_material-hard_floor-"), std::string::npos)
      << cells[0].name;
  EXPECT_NE(cells[0].group, cells[2].group);
  EXPECT_EQ(cells[3].name, cells[3].group + "__seed-1");
}

TEST(SweepFileTest, ScenariosWithTheSameStemAreNamedByTheirPath) {
  const fs::path dir = TempDir("stems");
  for (const char* sub : {"a", "b"}) {
    fs::create_directories(dir / sub);
    fs::copy_file(kScenes / "nav_paper_left.yaml", dir / sub / "nav.yaml");
  }
  const std::vector<SweepCell> cells =
      ExpandSweep(ParseSweep("scenarios: [a/nav.yaml, b/nav.yaml]\nseeds: [1]\n", "s.yaml", dir));
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[0].name, "a-nav__seed-1");
  EXPECT_EQ(cells[1].name, "b-nav__seed-1");
}

TEST(SweepFileTest, ReplicateAxesAreLeftOutOfGroups) {
  const SweepSpec spec = Parse(R"(
scenarios: [nav_paper_left.yaml]
seeds: [1]
vary:
  - {key: navigation.method, values: [dwa, potential_field]}
  - {key: navigation.field_seed, range: {from: 0, to: 2}, replicate: true}
)");
  const SweepPlan plan = MakeSweepPlan(spec);
  ASSERT_EQ(plan.cells.size(), 6u);
  EXPECT_EQ(plan.cells[1].name, "nav_paper_left__method-dwa__field_seed-1__seed-1");
  EXPECT_EQ(plan.cells[1].group, "nav_paper_left__method-dwa");
  EXPECT_EQ(plan.cells[2].group, plan.cells[0].group);
  EXPECT_EQ(plan.replicate_keys, std::vector<std::string>{"navigation.field_seed"});
  EXPECT_EQ(plan.GroupKeys(), std::vector<std::string>{"navigation.method"});
}

struct BadSweep {
  std::string yaml;
  std::string message;
};

class SweepFileErrorTest : public ::testing::TestWithParam<BadSweep> {};

TEST_P(SweepFileErrorTest, NamesFileKeyAndReason) {
  EXPECT_EQ(ErrorOf(GetParam().yaml), GetParam().message);
}

const std::string kOk = "scenarios: [nav_paper_left.yaml]\nseeds: [1]\n";

INSTANTIATE_TEST_SUITE_P(
    Messages, SweepFileErrorTest,
    ::testing::Values(
        BadSweep{"- a\n", "test.yaml: expected a map of sweep keys, got a list"},
        BadSweep{kOk + "seed: 1\n",
                 "test.yaml: seed: unknown key (expected one of: name, base_dir, scenarios, "
                 "seeds, set, vary, timeout_s, expect)"},
        BadSweep{"seeds: [1]\n", "test.yaml: scenarios: missing (a list of scenario files)"},
        BadSweep{"scenarios: []\nseeds: [1]\n", "test.yaml: scenarios: must not be empty"},
        BadSweep{"scenarios: [nav_paper_left.yaml, ./nav_paper_left.yaml]\nseeds: [1]\n",
                 "test.yaml: scenarios[1]: listed twice (also scenarios[0])"},
        BadSweep{"scenarios: [nav_paper_left.yaml]\n",
                 "test.yaml: seeds: missing (a list of seeds or {from: A, to: B})"},
        BadSweep{"scenarios: [nav_paper_left.yaml]\nseeds: [1, -2]\n",
                 "test.yaml: seeds[1]: expected a non-negative integer, got '-2'"},
        BadSweep{"scenarios: [nav_paper_left.yaml]\nseeds: [1, 1.5]\n",
                 "test.yaml: seeds[1]: expected a non-negative integer, got '1.5'"},
        BadSweep{"scenarios: [nav_paper_left.yaml]\nseeds: [2, 2]\n",
                 "test.yaml: seeds[1]: duplicate seed 2"},
        BadSweep{"scenarios: [nav_paper_left.yaml]\nseeds: {from: 5, to: 1}\n",
                 "test.yaml: seeds.to: must be >= from"},
        BadSweep{"scenarios: [nav_paper_left.yaml]\nseeds: 3\n",
                 "test.yaml: seeds: expected a list of seeds or {from: A, to: B}, got a scalar"},
        BadSweep{kOk + "set: [duration_s]\n",
                 "test.yaml: set[0]: expected key=value, got 'duration_s'"},
        BadSweep{kOk + "set: [\"seed=3\"]\n",
                 "test.yaml: set[0]: the seed comes from `seeds`, not from an override"},
        BadSweep{kOk + "set: [\"duration_s=3\", \"duration_s=4\"]\n",
                 "test.yaml: set[1]: 'duration_s' is set twice"},
        BadSweep{kOk + "vary: [{key: duration_s, values: [1], range: {from: 1, to: 2}}]\n",
                 "test.yaml: vary[0]: give either `values` or `range`"},
        BadSweep{kOk + "vary: [{key: duration_s}]\n",
                 "test.yaml: vary[0]: give either `values` or `range`"},
        BadSweep{kOk + "vary: [{values: [1]}]\n", "test.yaml: vary[0]: missing `key`"},
        BadSweep{kOk + "vary: [{key: duration_s, value: [1]}]\n",
                 "test.yaml: vary[0].value: unknown key (expected one of: key, values, range, "
                 "replicate)"},
        BadSweep{kOk + "vary: [{key: duration_s, values: []}]\n",
                 "test.yaml: vary[0].values: must not be empty"},
        BadSweep{kOk + "vary: [{key: navigation.method, values: [dwa, dwa]}]\n",
                 "test.yaml: vary[0].values[1]: duplicate value 'dwa'"},
        BadSweep{kOk + "vary: [{key: duration_s, range: {from: 1, to: 3, step: 0}}]\n",
                 "test.yaml: vary[0].range.step: must be > 0"},
        BadSweep{kOk + "vary: [{key: duration_s, range: {from: 3, to: 1}}]\n",
                 "test.yaml: vary[0].range.to: must be >= from"},
        BadSweep{kOk + "vary: [{key: duration_s, range: {from: 1, to: x}}]\n",
                 "test.yaml: vary[0].range.to: expected a number, got 'x'"},
        BadSweep{kOk + "set: [\"duration_s=3\"]\nvary: [{key: duration_s, values: [1]}]\n",
                 "test.yaml: vary[0].key: 'duration_s' is also in `set`"},
        BadSweep{kOk + "vary: [{key: 'a..b', values: [1]}]\n",
                 "test.yaml: vary[0].key: 'a..b' is not a dotted scenario key"},
        BadSweep{kOk + "vary: [{key: duration_s, values: [1], replicate: maybe}]\n",
                 "test.yaml: vary[0].replicate: expected true or false, got 'maybe'"},
        BadSweep{kOk + "timeout_s: 0\n", "test.yaml: timeout_s: must be > 0"},
        BadSweep{kOk + "name: [a]\n", "test.yaml: name: expected a string, got a list"},
        BadSweep{kOk + "expect: []\n", "test.yaml: expect: must not be empty"},
        BadSweep{kOk + "expect: [{max: 1}]\n", "test.yaml: expect[0].metric: missing"},
        BadSweep{kOk + "expect: [{metric: m, maxx: 1}]\n",
                 "test.yaml: expect[0].maxx: unknown key (expected one of: metric, min, max, "
                 "over, order, scenario)"},
        BadSweep{kOk + "expect: [{metric: m}]\n",
                 "test.yaml: expect[0].min, max: a bound needs at least one (or give `order`)"},
        BadSweep{kOk + "expect: [{metric: m, min: 2, max: 1}]\n",
                 "test.yaml: expect[0].max: must be >= min"},
        BadSweep{kOk + "expect: [{metric: m, max: 1, over: group}]\n",
                 "test.yaml: expect[0].over: must be cell or mean (got 'group')"},
        BadSweep{kOk + "expect: [{metric: m, order: [fused]}]\n",
                 "test.yaml: expect[0].order: name at least two estimators"},
        BadSweep{kOk + "expect: [{metric: m, order: [fused, fused]}]\n",
                 "test.yaml: expect[0].order: 'fused' named twice"},
        BadSweep{kOk + "expect: [{metric: m, order: [a, b], max: 1}]\n",
                 "test.yaml: expect[0].order: an ordering takes no min or max"},
        BadSweep{kOk + "expect: [{metric: m, max: x}]\n",
                 "test.yaml: expect[0].max: expected a number, got 'x'"},
        BadSweep{kOk + "expect: [{metric: m, max: 1, scenario: other.yaml}]\n",
                 "test.yaml: expect[0].scenario: 'other.yaml' is not among the sweep's "
                 "scenarios"},
        // Found by fuzzing (tests/fuzz_corpus/sweep): a key that `--set` would split at
        // its '=', bytes the JSON files cannot hold, and crossed ranges of billions of
        // cells.
        BadSweep{kOk + "vary: [{key: 'robot.a=b', values: [1]}]\n",
                 "test.yaml: vary[0].key: 'robot.a=b' is not a dotted scenario key"},
        BadSweep{kOk + "name: a\xce b\n", "test.yaml: name: not UTF-8 text"},
        BadSweep{"scenarios: [nav_paper_left.yaml]\nseeds: {from: 0, to: 999}\n"
                 "vary: [{key: duration_s, range: {from: 1, to: 20}}]\n",
                 "test.yaml: vary: the sweep expands to more than 10000 cells (scenarios x "
                 "values of each varied key x seeds)"}));

// A seed range ending at the largest seed expands (the loop once wrapped and never
// ended: tests/fuzz_corpus/sweep).
TEST(SweepFileTest, ASeedRangeEndingAtTheLargestSeedEnds) {
  const SweepSpec spec = Parse(
      "scenarios: [nav_paper_left.yaml]\nseeds: {from: 18446744073709551614, to: "
      "18446744073709551615}\n");
  EXPECT_EQ(spec.seeds, (std::vector<std::uint64_t>{18446744073709551614u, 18446744073709551615u}));
}

TEST(SweepFileTest, MissingScenarioAndSyntaxErrorsNameTheFile) {
  const std::string missing = ErrorOf("scenarios: [nope.yaml]\nseeds: [1]\n");
  EXPECT_EQ(missing, "test.yaml: scenarios[0]: no such file: " + (kScenes / "nope.yaml").string());
  EXPECT_EQ(ErrorOf("scenarios: [a\n").rfind("test.yaml: YAML syntax error at line ", 0), 0u);
  try {
    LoadSweep(kScenes / "sweeps" / "no_such_sweep.yaml");
    FAIL() << "no error";
  } catch (const SweepError& e) {
    EXPECT_EQ(e.reason(), "cannot read file");
  }
}

// `trackbed sweep my.yaml` run in the sweep file's own folder: the file name has no
// directory part, and relative scenario paths resolve against the working directory.
TEST(SweepFileTest, ABareFileNameResolvesAgainstTheWorkingDirectory) {
  const fs::path before = fs::current_path();
  fs::current_path(kScenes / "sweeps");
  try {
    const SweepSpec spec = LoadSweep("corridor_vs_outdoor.yaml");
    fs::current_path(before);
    EXPECT_EQ(spec.base_dir, (kScenes / "sweeps").lexically_normal());
    EXPECT_EQ(MakeSweepPlan(spec).cells.size(), 20u);
  } catch (...) {
    fs::current_path(before);
    throw;
  }
}

TEST(SweepFileTest, ResolvedCopyAndCellListRoundTrip) {
  const SweepSpec spec = Parse(R"(
name: round trip
scenarios: [nav_paper_left.yaml]
seeds: {from: 1, to: 2}
set: ["navigation.obstacles=[]"]
vary:
  - {key: navigation.method, values: [dwa, potential_field]}
  - {key: navigation.field_seed, range: {from: 0, to: 1}, replicate: true}
timeout_s: 2.5
)");
  // The resolved copy lives elsewhere; base_dir keeps its scenario paths meaning the same.
  const SweepSpec again = ParseSweep(SweepToYaml(spec), "copy.yaml", TempDir("copy"));
  EXPECT_EQ(again.name, spec.name);
  EXPECT_EQ(again.base_dir, spec.base_dir);
  EXPECT_EQ(again.timeout_s, spec.timeout_s);
  EXPECT_EQ(SweepPlanJson(MakeSweepPlan(again)), SweepPlanJson(MakeSweepPlan(spec)));

  const SweepPlan plan = MakeSweepPlan(spec);
  const SweepPlan read = ParseSweepPlan(SweepPlanJson(plan), "cells.json");
  EXPECT_EQ(SweepPlanJson(read), SweepPlanJson(plan));
  EXPECT_EQ(read.cells[3].overrides.size(), 3u);
  EXPECT_EQ(PlanConflict(plan, read), "");
}

TEST(SweepFileTest, AFolderOfAnotherSweepIsRefused) {
  const SweepPlan before = MakeSweepPlan(Parse(kOk + "set: [\"duration_s=5\"]\n"));
  const SweepPlan after = MakeSweepPlan(Parse(kOk + "set: [\"duration_s=6\"]\n"));
  EXPECT_EQ(PlanConflict(before, after),
            "cell nav_paper_left__seed-1 was `nav_paper_left.yaml --seed 1 --set duration_s=5`, "
            "is now `nav_paper_left.yaml --seed 1 --set duration_s=6`");
  // More seeds: the old cells keep their meaning.
  const SweepPlan more = MakeSweepPlan(
      Parse("scenarios: [nav_paper_left.yaml]\nseeds: [1, 2]\nset: [\"duration_s=5\"]\n"));
  EXPECT_EQ(PlanConflict(before, more), "");
}

TEST(SweepCellTest, ValidationGivesTheScenarioErrorOfTheCell) {
  const std::vector<SweepCell> cells =
      ExpandSweep(Parse(kOk + "vary: [{key: navigation.method, values: [dwa, teleport]}]\n"));
  EXPECT_EQ(ValidateCell(cells[0]), std::nullopt);
  EXPECT_EQ(ValidateCell(cells[1]),
            "--set navigation.method=teleport: navigation.method: must be one of "
            "gauss_newton_subgoal, potential_field, dwa (got 'teleport')");
}

TEST(SweepCellTest, OutcomesRoundTripAndMetricsDecideFinishedRuns) {
  const SweepCell cell = ExpandSweep(Parse(kOk))[0];
  CellOutcome o;
  o.status = CellStatus::kTimedOut;
  o.reason = "no result";
  o.stderr_tail = "line 1\nline 2\n";
  o.wall_time_s = 1.25;
  o.host = "h";
  o.started_utc = "2024-01-01T00:00:00.000Z";
  const CellOutcome r = ParseCellOutcome(CellOutcomeJson(cell, o), "cell.json");
  EXPECT_EQ(r.status, CellStatus::kTimedOut);
  EXPECT_EQ(r.exit_code, std::nullopt);
  EXPECT_EQ(r.reason, o.reason);
  EXPECT_EQ(r.stderr_tail, o.stderr_tail);
  EXPECT_EQ(r.wall_time_s, 1.25);
  EXPECT_EQ(CellOutcomeJson(cell, r), CellOutcomeJson(cell, o));

  EXPECT_EQ(OutcomeFromMetrics(R"({"status": "completed"})").status, CellStatus::kOk);
  const CellOutcome stopped =
      OutcomeFromMetrics(R"({"status": "failed", "stop_reason": "robot tipped over"})");
  EXPECT_EQ(stopped.status, CellStatus::kFailed);
  EXPECT_EQ(stopped.reason, "run failed: robot tipped over");

  // A cut-short metrics.json is not a finished run.
  const fs::path dir = TempDir("finished");
  fs::create_directories(CellRunDir(dir, cell));
  EXPECT_FALSE(CellFinished(dir, cell));
  std::ofstream(CellMetricsPath(dir, cell)) << "{\"status\": \"comp";
  EXPECT_FALSE(CellFinished(dir, cell));
  WriteFileAtomically(CellMetricsPath(dir, cell), "{\"status\": \"completed\"}\n");
  EXPECT_TRUE(CellFinished(dir, cell));
}

TEST(SweepCellTest, FolderJsonIsReadAsStrictlyAsSweepFiles) {
  const SweepPlan plan = MakeSweepPlan(Parse(kOk + "set: [\"duration_s=5\"]\n"));
  std::string json = SweepPlanJson(plan);
  json.replace(json.find("\"group\""), 7, "\"grupo\"");
  try {
    ParseSweepPlan(json, "cells.json");
    FAIL() << "no error";
  } catch (const SweepError& e) {
    EXPECT_EQ(e.key(), "cells[0].grupo");
    EXPECT_EQ(e.reason().rfind("unknown key (expected one of: index, name, group, ", 0), 0u)
        << e.reason();
  }
  // A cell's name is its folder under cells/: one ExpandSweep could make, and once.
  for (const auto& [from, to, reason] : {std::tuple<std::string, std::string, std::string>{
           plan.cells[0].name, "../../escape",
           "not a cell name (1 to 200 of [A-Za-z0-9._+-], not . or ..): '../../escape'"}}) {
    std::string bad = SweepPlanJson(plan);
    bad.replace(bad.find("\"" + from + "\""), from.size() + 2, "\"" + to + "\"");
    try {
      ParseSweepPlan(bad, "cells.json");
      FAIL() << "no error for " << to;
    } catch (const SweepError& e) {
      EXPECT_EQ(e.key(), "cells[0].name");
      EXPECT_EQ(e.reason(), reason);
    }
  }
  const SweepCell cell = plan.cells[0];
  CellOutcome o;
  o.status = CellStatus::kOk;
  o.exit_code = 0;
  std::string outcome = CellOutcomeJson(cell, o);
  EXPECT_EQ(ParseCellOutcome(outcome, "cell.json").exit_code, 0);
  outcome.replace(outcome.find("\"exit_code\": 0"), 14, "\"exit_code\": \"0\"");
  try {
    ParseCellOutcome(outcome, "cell.json");
    FAIL() << "no error";
  } catch (const SweepError& e) {
    EXPECT_EQ(std::string(e.what()),
              "cell.json: exit_code: expected an integer, got the quoted string \"0\"");
  }
}

std::vector<SlurmSubmission> TwoSubmissions() {
  return {{"4711", {0, 1, 2}, "slurm/submit-1.cells", "2024-05-01T12:00:00Z"},
          {"4712_3", {18446744073709551615u}, "slurm/dir \"q\"\\x\t/submit-2.cells", ""}};
}

TEST(SweepProgressTest, TimeLeftIsTheRemainingCellsAtTheFinishedCellsPace) {
  using experiments::SecondsLeft;
  EXPECT_EQ(SecondsLeft(0, 10, 42.0), std::nullopt);  // nothing finished: no pace yet
  EXPECT_DOUBLE_EQ(*SecondsLeft(2, 8, 30.0), 120.0);  // 15 s a cell, 8 to go
  EXPECT_DOUBLE_EQ(*SecondsLeft(5, 0, 61.0), 0.0);
  // Two at once: four cells in 100 s, 25 s a cell, six to go.
  EXPECT_DOUBLE_EQ(*SecondsLeft(4, 6, 100.0), 150.0);
  EXPECT_EQ(experiments::MinutesSeconds(150.0), "2:30");
  EXPECT_EQ(experiments::MinutesSeconds(59.6), "1:00");
  EXPECT_EQ(experiments::MinutesSeconds(7325.0), "122:05");
  EXPECT_EQ(experiments::MinutesSeconds(-1.0), "-:--");
}

TEST(SlurmJobsTest, JobsJsonKeepsItsLayoutAndRoundTrips) {
  // The layout jobs.json has always had: keys sorted, two spaces per level.
  EXPECT_EQ(SlurmJobsJson(TwoSubmissions()), R"({
  "jobs": [
    {
      "cells": [
        0,
        1,
        2
      ],
      "job_id": "4711",
      "list": "slurm/submit-1.cells",
      "submitted_utc": "2024-05-01T12:00:00Z"
    },
    {
      "cells": [
        18446744073709551615
      ],
      "job_id": "4712_3",
      "list": "slurm/dir \"q\"\\x\t/submit-2.cells",
      "submitted_utc": ""
    }
  ]
}
)");
  EXPECT_EQ(SlurmJobsJson({}), "{\n  \"jobs\": []\n}\n");
  const std::vector<SlurmSubmission> read =
      ParseSlurmJobs(SlurmJobsJson(TwoSubmissions()), "jobs.json");
  ASSERT_EQ(read.size(), 2u);
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].job_id, TwoSubmissions()[i].job_id);
    EXPECT_EQ(read[i].cells, TwoSubmissions()[i].cells);
    EXPECT_EQ(read[i].list, TwoSubmissions()[i].list);
    EXPECT_EQ(read[i].submitted_utc, TwoSubmissions()[i].submitted_utc);
  }
}

// The message ParseSlurmJobs gives for `json` (empty when it reads).
std::string JobsErrorOf(const std::string& json) {
  try {
    ParseSlurmJobs(json, "slurm/jobs.json");
  } catch (const SweepError& e) {
    return e.what();
  }
  return "";
}

TEST(SlurmJobsTest, JobsJsonIsReadAsStrictlyAsTheOtherFolderFiles) {
  const std::string job = R"("job_id": "7", "list": "l", "submitted_utc": "t")";
  EXPECT_EQ(JobsErrorOf(R"({"jobs": [{"cells": [1], )" + job + "}]}"), "");
  EXPECT_EQ(JobsErrorOf(R"({"jobs": [{"cells": [1], "node": "a", )" + job + "}]}"),
            "slurm/jobs.json: jobs[0].node: unknown key (expected one of: cells, job_id, list, "
            "submitted_utc)");
  EXPECT_EQ(JobsErrorOf(R"({"jobs": [{"cells": [1, "2"], )" + job + "}]}"),
            "slurm/jobs.json: jobs[0].cells[1]: expected a non-negative integer, got the quoted "
            "string \"2\"");
  EXPECT_EQ(JobsErrorOf(R"({"jobs": [{"cells": [-1], )" + job + "}]}"),
            "slurm/jobs.json: jobs[0].cells[0]: expected a non-negative integer, got '-1'");
  EXPECT_EQ(JobsErrorOf(R"({"jobs": [{"cells": [1], "job_id": 7, "list": "l"}]})"),
            "slurm/jobs.json: jobs[0].submitted_utc: missing");
  EXPECT_EQ(JobsErrorOf(R"({"jobs": {}})"), "slurm/jobs.json: jobs: expected a list, got a map");
  EXPECT_EQ(JobsErrorOf("{}"), "slurm/jobs.json: jobs: missing");
  EXPECT_EQ(JobsErrorOf(R"({"jobs": [)").rfind("slurm/jobs.json: not valid JSON: ", 0), 0u);
}

// What squeue, sacct and scontrol print, as the backend reads it (real output's layout:
// `squeue -h -r -t all -o %K|%T|%r`, `sacct -n -P -X -o JobID,State,Reason`,
// `scontrol -o show job`).
TEST(SlurmOutputTest, SqueueSacctAndScontrolAreReadAsTheyPrint) {
  std::map<std::size_t, SlurmTaskState> tasks = ParseSqueueTasks(
      "0|COMPLETED|None\n2|TIMEOUT|TimeLimit\nN/A|PENDING|JobArrayTaskLimit\n"
      "3-9|PENDING|JobArrayTaskLimit\n-1|RUNNING|None\n12abc|RUNNING|None\n4|RUNNING\n");
  ASSERT_EQ(tasks.size(), 2u);  // summary lines, bad ids and short lines skipped
  EXPECT_EQ(tasks.at(2).state, "TIMEOUT");
  EXPECT_EQ(tasks.at(2).reason, "TimeLimit");
  AddSacctTasks("4711_0|FAILED|None\n4711_1|CANCELLED by 0|None\n4711_[4-9]|PENDING|None\n4711\n",
                &tasks);
  ASSERT_EQ(tasks.size(), 3u);
  EXPECT_EQ(tasks.at(0).state, "COMPLETED");  // squeue's word stands
  EXPECT_EQ(tasks.at(1).state, "CANCELLED");
  const auto job = ParseScontrolJob(
      "JobId=4713 ArrayJobId=4711 ArrayTaskId=2 JobState=TIMEOUT Reason=TimeLimit "
      "TimeLimit=00:01:00\nsecond line ignored JobState=RUNNING\n");
  ASSERT_TRUE(job.has_value());
  EXPECT_EQ(job->state, "TIMEOUT");
  EXPECT_EQ(job->reason, "TimeLimit");
  EXPECT_FALSE(ParseScontrolJob("slurm_load_jobs error: Invalid job id specified\n"));
  EXPECT_FALSE(ParseScontrolJob(""));
  EXPECT_EQ(ParseIndex(" 17\r"), std::optional<std::size_t>(17));
  for (const char* bad : {"", "-1", "12abc", "+3", "1 2", "99999999999999999999"}) {
    EXPECT_FALSE(ParseIndex(bad)) << bad;
  }
}

TEST(SlurmOutputTest, AListFileLineMustBeAnIndex) {
  const fs::path list = fs::path(::testing::TempDir()) / "slurm_output_test.cells";
  std::ofstream(list) << "4\n-1\n12abc\n";
  EXPECT_EQ(CellIndexFromList(list, 0), 4u);
  for (std::size_t line : {1u, 2u}) {
    try {
      CellIndexFromList(list, line);
      FAIL() << line;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(": not a cell index: '"), std::string::npos) << e.what();
    }
  }
}

// A sweep folder of three seeds of one cell, the last failed, built by hand.
struct FakeSweep {
  SweepPlan plan;
  std::vector<CellResult> cells;
};

FakeSweep MakeFakeSweep() {
  FakeSweep f;
  f.plan = MakeSweepPlan(
      Parse("scenarios: [nav_paper_left.yaml]\nseeds: [1, 2, 3]\nvary: [{key: navigation.method, "
            "values: [dwa]}]\n"));
  const char* metrics[] = {
      R"({"status": "completed", "sim_time_s": 1.5, "wall_time_s": 0.25, "real_time_factor": 6.0,
          "estimators": {"fused": {"ate_rmse_m": 0.1, "rpe_trans_pct": null}},
          "timing": {"render_s": 0.125}, "navigation": {"success": true, "method": "dwa"}})",
      R"({"status": "completed", "sim_time_s": 1.5, "wall_time_s": 0.5, "real_time_factor": 3.0,
          "estimators": {"fused": {"ate_rmse_m": 0.3, "rpe_trans_pct": null}},
          "timing": {"render_s": 0.25}, "navigation": {"success": false, "method": "dwa"}})"};
  for (std::size_t i = 0; i < 3; ++i) {
    CellResult r;
    r.cell = f.plan.cells[i];
    r.outcome.status = i < 2 ? CellStatus::kOk : CellStatus::kFailed;
    r.outcome.wall_time_s = 0.5;
    r.outcome.host = "host1";
    if (i < 2) {
      r.metrics_json = metrics[i];
    } else {
      r.outcome.reason = "invalid scenario: x, \"y\" in /abs/sweep/cells/z";
    }
    f.cells.push_back(r);
  }
  return f;
}

TEST(SweepSummaryTest, ColumnsFollowTheNamingRule) {
  EXPECT_EQ(SummaryColumnName({"estimators", "fused", "ate_rmse_m"}),
            "estimators_fused_ate_rmse_m");
  EXPECT_EQ(SummaryColumnName({"navigation", "success"}), "navigation_success");
  EXPECT_EQ(SummaryColumnName({"wall_time_s"}), "wall_time_s");
  EXPECT_EQ(SummaryColumnName({"real_time_factor"}), "wall_real_time_factor");
  EXPECT_EQ(SummaryColumnName({"timing", "render_s"}), "timing_render_s");
  EXPECT_EQ(SummaryColumnName({"localization", "timing", "vo_s"}),
            "timing_localization_timing_vo_s");
  EXPECT_EQ(SummaryColumnName({"peak_memory_mb"}), "mem_peak_memory_mb");
  EXPECT_EQ(SummaryColumnName({"slip", "by_material", "hard_floor", "samples"}),
            "slip_by_material_hard_floor_samples");
  EXPECT_TRUE(IsMachineDependentColumn("host"));
  EXPECT_TRUE(IsMachineDependentColumn("wall_cell_s"));
  EXPECT_FALSE(IsMachineDependentColumn("estimators_fused_ate_rmse_m"));

  const FakeSweep f = MakeFakeSweep();
  const SweepSummary s = BuildSweepSummary(f.plan, f.cells, "/abs/sweep");
  std::vector<std::string> names;
  for (const SummaryColumn& c : s.columns) names.push_back(c.name);
  EXPECT_EQ(names, (std::vector<std::string>{
                       "index", "cell", "group", "scenario", "seed", "vary_navigation_method",
                       "cell_status", "cell_reason", "status", "sim_time_s", "wall_time_s",
                       "wall_real_time_factor", "estimators_fused_ate_rmse_m",
                       "estimators_fused_rpe_trans_pct", "timing_render_s", "navigation_success",
                       "navigation_method", "wall_cell_s", "host"}));
  const std::string csv = SummaryCsv(s);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_EQ(header.rfind("index,cell,group,scenario,seed,vary_navigation_method,cell_status,", 0),
            0u);
  // Metric text as metrics.json wrote it; null is empty; reasons are quoted, and paths
  // under the sweep folder are relative to it.
  EXPECT_NE(csv.find(",ok,,completed,1.5,0.25,6.0,0.1,,0.125,true,dwa,0.5,host1\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find(",failed,\"invalid scenario: x, \"\"y\"\" in cells/z\",,,"), std::string::npos)
      << csv;
  const std::string json = SummaryJson(s);
  EXPECT_NE(json.find("\"navigation_success\": false"), std::string::npos);
  EXPECT_NE(json.find("\"seed\": 3"), std::string::npos);
}

TEST(SweepStatsTest, StudentTQuantilesMatchTables) {
  EXPECT_NEAR(StudentTQuantile(0.975, 1), 12.7062047, 1e-6);
  EXPECT_NEAR(StudentTQuantile(0.975, 2), 4.3026527, 1e-6);
  EXPECT_NEAR(StudentTQuantile(0.975, 9), 2.2621572, 1e-6);
  EXPECT_NEAR(StudentTQuantile(0.975, 29), 2.0452296, 1e-6);
  EXPECT_NEAR(StudentTQuantile(0.975, 1e7), 1.9599640, 1e-5);
  EXPECT_NEAR(StudentTQuantile(0.95, 4), 2.1318468, 1e-6);
  EXPECT_NEAR(StudentTQuantile(0.025, 9), -StudentTQuantile(0.975, 9), 1e-12);
}

TEST(SweepStatsTest, DescribeGivesMeanStdIntervalAndOrderStatistics) {
  const SampleStats s = Describe({4.0, 1.0, 3.0, 2.0, NAN});
  EXPECT_EQ(s.n, 4u);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_NEAR(s.std, std::sqrt(5.0 / 3.0), 1e-12);
  EXPECT_NEAR(s.ci95_half_width, 3.1824463 * std::sqrt(5.0 / 3.0) / 2.0, 1e-6);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  const SampleStats one = Describe({7.0});
  EXPECT_EQ(one.n, 1u);
  EXPECT_DOUBLE_EQ(one.median, 7.0);
  EXPECT_TRUE(std::isnan(one.std));
  EXPECT_TRUE(std::isnan(one.ci95_half_width));
  EXPECT_EQ(Describe({}).n, 0u);
}

TEST(SweepStatsTest, AggregatesAreTakenOverOkCellsAndSuccessIsARate) {
  const FakeSweep f = MakeFakeSweep();
  const SweepSummary s = BuildSweepSummary(f.plan, f.cells, "/abs/sweep");
  const std::vector<GroupStats> groups = AggregateSweep(f.plan, s);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].cells, 3u);
  EXPECT_EQ(groups[0].ok, 2u);
  const SampleStats* ate = groups[0].Find("estimators_fused_ate_rmse_m");
  ASSERT_NE(ate, nullptr);
  EXPECT_EQ(ate->n, 2u);
  EXPECT_DOUBLE_EQ(ate->mean, 0.2);
  const SampleStats* success = groups[0].Find("navigation_success");
  ASSERT_NE(success, nullptr);
  EXPECT_DOUBLE_EQ(success->mean, 0.5);
  EXPECT_EQ(groups[0].Find("estimators_fused_rpe_trans_pct"), nullptr);  // all null
  EXPECT_EQ(groups[0].Find("seed"), nullptr);
  const std::string csv = AggregatesCsv(f.plan, groups);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "group,scenario,vary_navigation_method,cells,ok,metric,n,mean,std,ci95_half_width,"
            "median,min,max");
  EXPECT_NE(csv.find("nav_paper_left__method-dwa,nav_paper_left.yaml,dwa,3,2,navigation_success,2,"
                     "0.5,"),
            std::string::npos)
      << csv;
  const std::string md = SweepReportMarkdown(f.plan, s, groups, {});
  EXPECT_NE(md.find("| nav_paper_left__method-dwa | nav_paper_left.yaml | dwa | 2/3 | 0.200 ± "
                    "0.141 | fused |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| 2/3 | 1/2 (50 %) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| nav_paper_left__method-dwa__seed-3 | failed |"), std::string::npos) << md;
}

TEST(SweepShippedTest, ShippedSweepsLoadAndEveryCellValidates) {
  int sweeps = 0;
  for (const auto& entry : fs::directory_iterator(kScenes / "sweeps")) {
    if (entry.path().extension() != ".yaml") continue;
    ++sweeps;
    const SweepPlan plan = MakeSweepPlan(LoadSweep(entry.path()));
    EXPECT_FALSE(plan.cells.empty()) << entry.path();
    for (const SweepCell& cell : plan.cells) {
      EXPECT_EQ(ValidateCell(cell), std::nullopt) << entry.path() << ": " << cell.name;
    }
  }
  EXPECT_GE(sweeps, 3);
  const SweepPlan cvo = MakeSweepPlan(LoadSweep(kScenes / "sweeps" / "corridor_vs_outdoor.yaml"));
  EXPECT_EQ(cvo.cells.size(), 20u);
  EXPECT_EQ(cvo.cells[0].name, "corridor__seed-1");
  EXPECT_EQ(cvo.cells[19].name, "outdoor__seed-10");
}

}  // namespace
}  // namespace trackbed::experiments
