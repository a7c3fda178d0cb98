// `trackbed sweep … --backend slurm` (docs/sweeps.md, "On a Slurm cluster"):
// the sweep folder is prepared as for the local backend, and the cells to run are
// handed to Slurm as an array job (`sbatch --array`) whose task i runs
// `trackbed sweep-cell DIR i --list LIST` — cell LIST[i] — on whatever node Slurm
// picks, writing into DIR/cells/… on the shared filesystem. No scheduling of our own.
//
// The folder gets DIR/slurm/: `submit-N.cells` (the cell indices of submission N, one
// per line: array task i runs line i), `submit-N.sbatch` (the batch script, which
// `sbatch` can take again by hand), `jobs.json` (every submission: job id and cells;
// SlurmJobsJson)
// and `logs/JOB_TASK.out|err` (the array tasks' own output, Slurm's messages among it).
//
// Slurm's view of a task comes from `squeue -t all` (finished tasks stay there for the
// cluster's MinJobAge) and, where the cluster keeps accounting, `sacct`; without
// either, the cell's own cell.json is all there is. A cell that Slurm stops (time
// limit, scancel, node failure) is recorded with Slurm's state as its reason — by the
// task itself when it gets SIGTERM, else by `--wait` — and reruns on resubmission.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "trackbed/common/archive.h"
#include "trackbed/experiments/sweep.h"
#include "trackbed/experiments/sweep_support.h"

namespace trackbed::experiments {

/// The Slurm options of `trackbed sweep`.
struct SlurmOptions {
  std::string partition;   ///< `sbatch --partition`; empty: the cluster's default
  int max_parallel = 0;    ///< array throttle (`--array=…%N`), >= 0; 0: Slurm decides
  std::string time_limit;  ///< `sbatch --time` in Slurm's format (minutes, H:MM:SS, D-HH:MM);
                           ///< empty: timeout_s + 1 min when the sweep has one, else the
                           ///< partition's default
  bool wait = false;       ///< follow the job(s) until every submitted cell has ended
  double poll_s = 2.0;     ///< how often `wait` asks squeue [s], > 0
};

/// One `sbatch` of a sweep: an array job and the cell each of its tasks runs. The sweep
/// folder's slurm/jobs.json lists every submission (SlurmJobsJson).
struct SlurmSubmission {
  std::string job_id;              ///< Slurm's array job id
  std::vector<std::size_t> cells;  ///< task i runs cell cells[i]
  std::string list;                ///< the list file, relative to the sweep folder
  std::string submitted_utc;       ///< ISO 8601 time of the submission

  /// jobs.json's keys for these fields, read and written by the config archive
  /// (trackbed/common/archive.h). In alphabetical order: the file's layout since its
  /// first version, which wrote its keys sorted.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("cells", &cells, archive::kRequired);
    a->Visit("job_id", &job_id, archive::kRequired);
    a->Visit("list", &list, archive::kRequired);
    a->Visit("submitted_utc", &submitted_utc, archive::kRequired);
  }
};

/// DIR/slurm/jobs.json: `{"jobs": [...]}`, one entry per submission, in order.
std::string SlurmJobsJson(const std::vector<SlurmSubmission>& submissions);
/// Reads jobs.json as strictly as cells.json (unknown keys, wrong types and missing
/// keys by dotted path). Throws SweepError (source: `source_name`) on malformed text.
std::vector<SlurmSubmission> ParseSlurmJobs(const std::string& json_text,
                                            const std::string& source_name);

/// Throws std::runtime_error, saying what is missing, unless sbatch, squeue and
/// scontrol are on PATH. Called before anything is written.
void CheckSlurmAvailable();

/// Submits the unfinished cells of the prepared sweep folder `dir` (cells.json written)
/// that no earlier submission still has queued or running; cells whose scenario does
/// not load are recorded failed and not submitted. Prints the job id(s) to stdout.
/// With `options.wait`, follows every job with cells of this sweep until they have
/// ended (progress as the local backend's), writes the summary and report, and returns
/// 0 when every cell is ok, else 1 (128 + signal when the follower is interrupted; the
/// jobs go on). Without it, returns 0 once submitted. Throws std::runtime_error when
/// sbatch refuses the job (its message included).
int RunSlurmSweep(const std::filesystem::path& dir, const experiments::SweepPlan& plan,
                  const SlurmOptions& options, const BlockedSignals& signals);

/// Inside a Slurm job (SLURM_JOB_ID set): "ARRAYJOB_TASK" (or the job id of a job
/// that is not an array), else "".
std::string CurrentSlurmJob();

/// Why Slurm is stopping the job this process runs in (called on SIGTERM): the status
/// and reason to record, e.g. timed_out, "stopped by Slurm: TimeLimit (time limit
/// 00:01:00)". Nothing outside Slurm or when Slurm does not say.
std::optional<experiments::CellOutcome> SlurmStopOutcome();

/// The cell index on line `line` (0-based) of a submission's list file. Throws
/// std::runtime_error naming the file when it cannot be read, has no such line or the
/// line is not a decimal index.
std::size_t CellIndexFromList(const std::filesystem::path& list_file, std::size_t line);

/// A whole decimal number (surrounding blanks allowed, no sign), or nothing.
std::optional<std::size_t> ParseIndex(const std::string& text);

/// What Slurm says of one array task.
struct SlurmTaskState {
  std::string state;   ///< PENDING, RUNNING, COMPLETED, TIMEOUT, CANCELLED, …
  std::string reason;  ///< squeue's %r: TimeLimit, JobArrayTaskLimit, None, …
};

/// Task id -> state from `squeue -h -r -t all -o %K|%T|%r` output; lines without a task
/// id (a pending array's summary) or with too few fields are skipped.
std::map<std::size_t, SlurmTaskState> ParseSqueueTasks(const std::string& out);

/// Adds the tasks of `sacct -n -P -X -o JobID,State,Reason` output (JobID
/// `ARRAYJOB_TASK`; "CANCELLED by 0" read as CANCELLED) that `tasks` lacks.
void AddSacctTasks(const std::string& out, std::map<std::size_t, SlurmTaskState>* tasks);

/// The job's state and reason from `scontrol -o show job` output (its first line's
/// JobState= and Reason=), or nothing without a JobState.
std::optional<SlurmTaskState> ParseScontrolJob(const std::string& out);

}  // namespace trackbed::experiments
