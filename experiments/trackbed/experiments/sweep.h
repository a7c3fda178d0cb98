// Scenario sweeps (docs/sweeps.md): a sweep file names scenario files,
// seeds, fixed `--set` overrides and overrides to vary; it expands to cells, each
// one `trackbed run` of one scenario with one seed and one combination of the
// varied values, in a fixed order and under a stable, filesystem-safe name.
//
// The sweep folder (`trackbed sweep … --out DIR`):
//   DIR/sweep.yaml               resolved copy of the sweep file (ranges expanded)
//   DIR/cells.json               the cell list (SweepPlanJson)
//   DIR/cells/NAME/cell.json     the cell's outcome (CellOutcomeJson), written atomically
//   DIR/cells/NAME/run/          the cell's run folder; run/metrics.json marks it finished
//   DIR/cells/NAME/stdout.txt, stderr.txt   what `trackbed run` printed
//   DIR/summary.csv, summary.json, aggregates.csv, report.md, plots/   (sweep_report.h)
//
// Everything here is pure or plain file I/O: launching processes is the command
// line's business (apps/sweep_command.cpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "trackbed/common/durable_file.h"
#include "trackbed/experiments/sweep_expectation.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::experiments {

/// A sweep file (or sweep folder) that cannot be read. Message
/// `source: key: reason`, or `source: reason` when `key` is empty, like ScenarioError.
class SweepError : public std::runtime_error {
 public:
  SweepError(std::string source, std::string key, std::string reason);

  const std::string& source() const { return source_; }  ///< file path
  const std::string& key() const { return key_; }        ///< dotted key, e.g. `vary[1].range.step`
  const std::string& reason() const { return reason_; }

 private:
  std::string source_, key_, reason_;
};

/// One varied scenario key and its values.
struct SweepAxis {
  std::string key;                  ///< dotted scenario key, as for `--set`
  std::vector<std::string> values;  ///< each value as YAML text (what follows `key=`)
  /// The values are replicates, like seeds (e.g. `navigation.field_seed`): a group's
  /// statistics are taken across them, and group names leave them out.
  bool replicate = false;
};

/// A parsed sweep file. Cells are scenarios × axes (in file order) × seeds.
struct SweepSpec {
  /// The sweep file, as named to LoadSweep (for messages).
  std::string source;
  /// Name shown in reports (default: the sweep file's stem).
  std::string name;
  /// Absolute folder that relative `scenarios` are resolved against: `base_dir` of the
  /// file when given (itself relative to the file's folder), else the file's folder.
  std::filesystem::path base_dir;
  /// Scenario files as written in the sweep file; this spelling labels the cells.
  std::vector<std::string> scenarios;
  /// Seeds, passed to every cell's `trackbed run --seed`.
  std::vector<std::uint64_t> seeds;
  /// Fixed overrides applied to every cell, before the varied ones.
  std::vector<scenario::Override> set;
  /// Varied keys; their values are crossed with each other, the scenarios and the seeds.
  std::vector<SweepAxis> vary;
  /// Wall-clock limit of one cell [s]; none: no limit.
  std::optional<double> timeout_s;
  /// What the cells' metrics must show (sweep_expectation.h).
  std::vector<SweepExpectation> expect;
};

/// Reads and validates a sweep file: unknown keys, wrong types, empty or duplicate
/// lists, missing scenario files, bad override syntax, `seed` among the overrides and
/// a key both fixed and varied are rejected. Throws SweepError. Scenario values are
/// not checked here (they are checked per cell: ValidateCell).
SweepSpec LoadSweep(const std::filesystem::path& path);

/// As LoadSweep, from YAML text; `source_name` names it in errors and `file_dir` is
/// the folder relative paths in it are relative to.
SweepSpec ParseSweep(const std::string& yaml_text, const std::string& source_name,
                     const std::filesystem::path& file_dir);

/// The resolved sweep as YAML: absolute `base_dir`, explicit seed and value lists.
/// ParseSweep of it expands to the same cells.
std::string SweepToYaml(const SweepSpec& spec);

/// One run of a sweep.
struct SweepCell {
  std::size_t index = 0;  ///< position in the expansion order (0-based)
  /// Folder name under `cells/`: `<scenario>__<key>-<value>…__seed-<seed>`, only
  /// [A-Za-z0-9._+-] and unique within the sweep.
  std::string name;
  /// The name without the seed and replicate parts: the cells a group's statistics
  /// are taken over.
  std::string group;
  std::string scenario;                       ///< scenario file as written in the sweep file
  std::filesystem::path scenario_path;        ///< the scenario file, absolute
  std::uint64_t seed = 0;                     ///< `trackbed run --seed`
  std::vector<scenario::Override> varied;     ///< one per axis, in axis order
  std::vector<scenario::Override> overrides;  ///< the `--set` list: fixed, then varied
};

/// The cells of `spec` in expansion order: scenarios (file order), then each axis in
/// file order (the first axis varies slowest), then seeds (fastest). Throws SweepError
/// when two cells would get the same name.
std::vector<SweepCell> ExpandSweep(const SweepSpec& spec);

/// What DIR/cells.json holds: enough to run any cell without the sweep file
/// (`trackbed sweep-cell DIR i`) and to build the report.
struct SweepPlan {
  std::string name;
  std::optional<double> timeout_s;
  std::vector<std::string> vary_keys;
  std::vector<std::string> replicate_keys;  ///< the vary_keys whose axes are replicates
  std::vector<SweepCell> cells;
  std::vector<SweepExpectation> expect;

  /// vary_keys without replicate_keys: what tells groups of one scenario apart.
  std::vector<std::string> GroupKeys() const;
};

SweepPlan MakeSweepPlan(const SweepSpec& spec);
std::string SweepPlanJson(const SweepPlan& plan);
/// Throws SweepError (source: `source_name`) on malformed text.
SweepPlan ParseSweepPlan(const std::string& json_text, const std::string& source_name);
/// Reads DIR/cells.json. Throws SweepError.
SweepPlan ReadSweepPlan(const std::filesystem::path& sweep_dir);

/// Why `before` (a sweep folder's cells.json) cannot be resumed with `after`: a cell of
/// the same name with another scenario, seed or overrides. Empty when compatible.
std::string PlanConflict(const SweepPlan& before, const SweepPlan& after);

/// Folder layout of a sweep (see the file comment).
std::filesystem::path CellDir(const std::filesystem::path& sweep_dir, const SweepCell& cell);
std::filesystem::path CellRunDir(const std::filesystem::path& sweep_dir, const SweepCell& cell);
std::filesystem::path CellJsonPath(const std::filesystem::path& sweep_dir, const SweepCell& cell);
std::filesystem::path CellMetricsPath(const std::filesystem::path& sweep_dir,
                                      const SweepCell& cell);

/// A cell is finished when its run wrote metrics.json (atomically, last): such cells
/// are skipped on resume; any other cell folder is cleared and the cell rerun.
bool CellFinished(const std::filesystem::path& sweep_dir, const SweepCell& cell);

/// The cell's scenario with its overrides and seed, as `trackbed run` would load it.
/// Returns the one-line reason it is invalid (with the scenario path as written in
/// the sweep file), or nothing when it loads.
std::optional<std::string> ValidateCell(const SweepCell& cell);

/// The outcome of a cell.
enum class CellStatus {
  kPending,      ///< not run (yet): no cell.json
  kOk,           ///< the run completed
  kFailed,       ///< invalid scenario, non-zero exit, crash, or a run that stopped early
  kTimedOut,     ///< killed after timeout_s
  kInterrupted,  ///< killed because the sweep was interrupted (SIGINT/SIGTERM)
};
/// "pending", "ok", "failed", "timed_out", "interrupted".
const char* ToString(CellStatus status);

/// DIR/cells/NAME/cell.json.
struct CellOutcome {
  CellStatus status = CellStatus::kPending;
  std::optional<int> exit_code;  ///< `trackbed run`'s exit status; none if it did not exit
  std::string reason;            ///< one line; empty when ok
  std::string stderr_tail;       ///< the last lines `trackbed run` wrote to stderr
  double wall_time_s = 0.0;      ///< launch to exit [s]
  std::string host;              ///< machine that ran it
  std::string started_utc;       ///< ISO 8601 launch time
  std::string slurm_job;         ///< the Slurm array task that ran it (`JOB_TASK`); "" locally
};

std::string CellOutcomeJson(const SweepCell& cell, const CellOutcome& outcome);
/// Throws SweepError on malformed text.
CellOutcome ParseCellOutcome(const std::string& json_text, const std::string& source_name);
/// The cell's cell.json, or a pending outcome when there is none. Throws SweepError.
CellOutcome ReadCellOutcome(const std::filesystem::path& sweep_dir, const SweepCell& cell);

/// The status and reason a finished run's metrics.json implies: ok when its `status`
/// is `completed`, else failed with `run failed: <stop_reason>`. Both the sweep and the
/// recovery of a cell whose cell.json was never written use it, so they agree.
CellOutcome OutcomeFromMetrics(const std::string& metrics_json_text);

/// Writes `text` to `path` whole and on disk before it is visible
/// (trackbed/common/durable_file.h).
using ::trackbed::WriteFileAtomically;

/// The file's contents. Throws std::runtime_error when it cannot be read.
std::string ReadTextFile(const std::filesystem::path& path);

}  // namespace trackbed::experiments
