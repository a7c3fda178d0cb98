// The Slurm backend of `trackbed sweep` (see slurm_backend.h, docs/sweeps.md).
#include "trackbed/experiments/slurm_backend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "trackbed/common/archive.h"
#include "trackbed/experiments/expectation_checks.h"
#include "trackbed/experiments/sweep_report.h"

namespace trackbed::experiments {
namespace {

namespace fs = std::filesystem;
using experiments::CellOutcome;
using experiments::CellStatus;
using experiments::SweepCell;
using experiments::SweepPlan;

// Slurm's default MaxArraySize is 1001 (task ids 0…1000): larger sweeps are split
// into several array jobs of at most this many tasks.
constexpr std::size_t kMaxArrayTasks = 1000;

// Starts the Slurm log's part of a cell's stderr_tail.
constexpr const char* kLogMark = "--- Slurm log ";

fs::path SlurmDir(const fs::path& dir) { return dir / "slurm"; }
fs::path JobsFile(const fs::path& dir) { return SlurmDir(dir) / "jobs.json"; }
fs::path LogDir(const fs::path& dir) { return SlurmDir(dir) / "logs"; }

/// jobs.json.
struct JobsFields {
  std::vector<SlurmSubmission> jobs;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("jobs", &jobs, archive::kRequired);
  }
};

std::vector<SlurmSubmission> ReadSubmissions(const fs::path& dir) {
  const fs::path file = JobsFile(dir);
  if (!fs::exists(file)) return {};
  return ParseSlurmJobs(experiments::ReadTextFile(file), file.string());
}

void WriteSubmissions(const fs::path& dir, const std::vector<SlurmSubmission>& subs) {
  experiments::WriteFileAtomically(JobsFile(dir), SlurmJobsJson(subs));
}

// PENDING, RUNNING and the other states of a task that has not ended.
bool IsActive(const std::string& state) {
  static const std::set<std::string> kActive = {
      "PENDING",   "RUNNING",     "CONFIGURING",  "COMPLETING", "SUSPENDED",
      "REQUEUED",  "REQUEUE_FED", "REQUEUE_HOLD", "RESIZING",   "SIGNALING",
      "STAGE_OUT", "STOPPED",     "RESV_DEL_HOLD"};
  return kActive.count(state) != 0;
}

std::vector<std::string> Split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, sep)) parts.push_back(part);
  return parts;
}

std::string Trim(const std::string& s) {
  const std::size_t b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

// Task id -> state for the array job `job_id`: squeue (every task it still holds,
// finished ones for MinJobAge), then sacct for the tasks squeue no longer has (on a
// cluster with accounting). Tasks neither knows are absent. Nothing when squeue fails
// for another reason than not knowing the job (slurmctld busy or down): the caller
// then asks again later rather than take the tasks for gone.
std::optional<std::map<std::size_t, SlurmTaskState>> QueryTasks(const std::string& job_id) {
  const ProgramResult q =
      RunProgram({"squeue", "-h", "-r", "-t", "all", "-j", job_id, "-o", "%K|%T|%r"});
  if (q.exit_code != 0 && q.err.find("Invalid job id") == std::string::npos) return std::nullopt;
  std::map<std::size_t, SlurmTaskState> tasks;
  if (q.exit_code == 0) tasks = ParseSqueueTasks(q.out);
  const ProgramResult a =
      RunProgram({"sacct", "-n", "-P", "-X", "-j", job_id, "-o", "JobID,State,Reason"});
  if (a.exit_code == 0) AddSacctTasks(a.out, &tasks);
  return tasks;
}

// The cells of `subs` that Slurm still has queued or running. Throws when Slurm
// cannot be asked: resubmitting blind could run a cell twice at once.
std::map<std::size_t, std::string> BusyCells(const std::vector<SlurmSubmission>& subs) {
  std::map<std::size_t, std::string> busy;  // cell -> job id
  for (const SlurmSubmission& s : subs) {
    const auto tasks = QueryTasks(s.job_id);
    if (!tasks) {
      throw std::runtime_error("squeue cannot tell whether job " + s.job_id +
                               " of this sweep still runs; try again when slurmctld answers");
    }
    for (const auto& [task, st] : *tasks) {
      if (task < s.cells.size() && IsActive(st.state)) busy[s.cells[task]] = s.job_id;
    }
  }
  return busy;
}

// Slurm's time format for a time limit of `timeout_s` plus a minute, in whole minutes.
std::string MinutesFor(double timeout_s) {
  return std::to_string(static_cast<long long>(std::ceil(timeout_s / 60.0)) + 1);
}

std::string ShellQuote(const std::string& s) { return "'" + ReplaceAll(s, "'", "'\\''") + "'"; }

// Writes submission `number`'s list and batch script; returns the script's path.
fs::path WriteBatchScript(const fs::path& dir, const SweepPlan& plan, const SlurmOptions& options,
                          std::size_t number, const std::vector<std::size_t>& cells) {
  const std::string stem = "submit-" + std::to_string(number);
  std::string list;
  for (std::size_t c : cells) list += std::to_string(c) + "\n";
  experiments::WriteFileAtomically(SlurmDir(dir) / (stem + ".cells"), list);

  const fs::path exe = fs::read_symlink("/proc/self/exe");
  // The tasks start the file at this path, not this process's image: if the file was
  // replaced (a rebuild) since this process started, the kernel names it "… (deleted)".
  const std::string deleted = " (deleted)";
  const std::string exe_name = exe.string();
  if (exe_name.size() > deleted.size() &&
      exe_name.compare(exe_name.size() - deleted.size(), deleted.size(), deleted) == 0) {
    throw std::runtime_error("the trackbed binary was replaced on disk since this sweep started (" +
                             exe_name +
                             "); Slurm tasks would run the new file: run the sweep again with it");
  }
  std::string array = "0-" + std::to_string(cells.size() - 1);
  if (options.max_parallel > 0) array += "%" + std::to_string(options.max_parallel);
  std::string time = options.time_limit;
  if (time.empty() && plan.timeout_s) time = MinutesFor(*plan.timeout_s);

  std::ostringstream s;
  s << "#!/bin/sh\n"
    << "# trackbed sweep " << plan.name << ", submission " << number << ": array task i runs\n"
    << "# the cell on line i of " << stem << ".cells (docs/sweeps.md, \"On a Slurm cluster\").\n"
    << "#SBATCH --job-name=trackbed-" << plan.name << "\n"
    << "#SBATCH --array=" << array << "\n"
    << "#SBATCH --ntasks=1\n"
    << "#SBATCH --cpus-per-task=1\n"
    << "#SBATCH --chdir=" << dir.string() << "\n"
    << "#SBATCH --output=" << (LogDir(dir) / "%A_%a.out").string() << "\n"
    << "#SBATCH --error=" << (LogDir(dir) / "%A_%a.err").string() << "\n";
  if (!time.empty()) s << "#SBATCH --time=" << time << "\n";
  if (!options.partition.empty()) s << "#SBATCH --partition=" << options.partition << "\n";
  s << "exec " << ShellQuote(exe.string()) << " sweep-cell " << ShellQuote(dir.string())
    << " \"$SLURM_ARRAY_TASK_ID\" --list "
    << ShellQuote((SlurmDir(dir) / (stem + ".cells")).string()) << "\n";
  const fs::path script = SlurmDir(dir) / (stem + ".sbatch");
  experiments::WriteFileAtomically(script, s.str());
  return script;
}

// The outcome to record for a cell whose task Slurm ended (or no longer knows) before
// the cell recorded a final result. The sweep-cell task itself (on SIGTERM) and the
// follower both word it here, so the reason reads the same whoever wrote it.
CellOutcome OutcomeFromSlurm(const std::optional<SlurmTaskState>& st, CellOutcome o) {
  if (!st) {
    o.status = CellStatus::kFailed;
    o.reason =
        "ended without a result, and Slurm no longer knows the task (past MinJobAge, no "
        "accounting); see its log";
    return o;
  }
  // While Slurm signals a task over its time limit, it is COMPLETING with reason
  // TimeLimit; once ended, TIMEOUT.
  const std::string state = st->reason == "TimeLimit" ? "TIMEOUT" : st->state;
  o.status = state == "TIMEOUT" ? CellStatus::kTimedOut : CellStatus::kFailed;
  o.reason = "stopped by Slurm: " + state;
  if (!st->reason.empty() && st->reason != "None") o.reason += " (" + st->reason + ")";
  if (state == "COMPLETED") o.reason = "the Slurm task completed without recording a result";
  return o;
}

// The Slurm log tail of task `task` of `job` appended to the run's stderr tail.
std::string WithSlurmLog(const fs::path& dir, const std::string& run_tail, const std::string& job,
                         std::size_t task) {
  const fs::path log = LogDir(dir) / (job + "_" + std::to_string(task) + ".err");
  const std::string slurm = Tail(log);
  if (slurm.empty()) return run_tail;
  return run_tail + (run_tail.empty() || run_tail.back() == '\n' ? "" : "\n") + kLogMark +
         fs::relative(log, dir).string() + " ---\n" + slurm;
}

// Follows `subs`' tasks of the cells in `watch` until none is queued or running.
// Returns the interrupting signal, or 0.
int Follow(const fs::path& dir, const SweepPlan& plan, const std::vector<SlurmSubmission>& subs,
           const std::set<std::size_t>& watch, const SlurmOptions& options,
           const BlockedSignals& signals, Progress& progress) {
  // cell -> (submission, task) of its latest submission.
  std::map<std::size_t, std::pair<const SlurmSubmission*, std::size_t>> where;
  for (const SlurmSubmission& s : subs) {
    for (std::size_t t = 0; t < s.cells.size(); ++t) where[s.cells[t]] = {&s, t};
  }
  std::set<std::size_t> open = watch;
  while (!open.empty()) {
    if (const int sig = signals.TakeInterrupt()) return sig;
    std::map<std::string, std::optional<std::map<std::size_t, SlurmTaskState>>> states;
    std::size_t running = 0;
    for (auto it = open.begin(); it != open.end();) {
      const std::size_t cell_index = *it;
      const auto [sub, task] = where.at(cell_index);
      if (!states.count(sub->job_id)) states[sub->job_id] = QueryTasks(sub->job_id);
      if (!states[sub->job_id]) {  // Slurm did not answer: ask again next round
        ++it;
        continue;
      }
      const auto& tasks = *states[sub->job_id];
      const auto found = tasks.find(task);
      const std::optional<SlurmTaskState> st =
          found == tasks.end() ? std::nullopt : std::optional<SlurmTaskState>(found->second);
      if (st && IsActive(st->state)) {
        if (st->state != "PENDING") ++running;
        ++it;
        continue;
      }
      const SweepCell& cell = plan.cells[cell_index];
      CellOutcome o = experiments::ReadCellOutcome(dir, cell);
      if (experiments::CellFinished(dir, cell) && o.status == CellStatus::kPending) {
        o = RecoverOutcome(dir, cell);
      } else if (o.status == CellStatus::kPending || o.status == CellStatus::kInterrupted) {
        // The task ended without a final record: Slurm stopped it, or it never ran.
        o = OutcomeFromSlurm(st, o);
        o.slurm_job = sub->job_id + "_" + std::to_string(task);
        o.stderr_tail = WithSlurmLog(dir, o.stderr_tail, sub->job_id, task);
        WriteOutcome(dir, cell, o);
      } else if (o.status != CellStatus::kOk && o.stderr_tail.find(kLogMark) == std::string::npos) {
        // Recorded by the task itself, which could not see what Slurm logged after it.
        o.stderr_tail = WithSlurmLog(dir, o.stderr_tail, sub->job_id, task);
        WriteOutcome(dir, cell, o);
      }
      progress.Finished(cell, o);
      it = open.erase(it);
    }
    progress.Refresh(running);
    if (open.empty()) break;
    const int sig = signals.Wait(options.poll_s);
    if (IsInterrupt(sig)) return sig;
  }
  return 0;
}

}  // namespace

std::string SlurmJobsJson(const std::vector<SlurmSubmission>& submissions) {
  return archive::ToJson(archive::Write(JobsFields{submissions})) + "\n";
}

std::vector<SlurmSubmission> ParseSlurmJobs(const std::string& json_text,
                                            const std::string& source_name) {
  JobsFields fields;
  try {
    // The sweep folder's brief wording, as cells.json and cell.json.
    archive::Read(archive::ParseJson(json_text), "", archive::Wording::kBrief, &fields);
  } catch (const archive::Error& e) {
    throw SweepError(source_name, e.path(), e.reason());
  }
  return fields.jobs;
}

void CheckSlurmAvailable() {
  std::vector<std::string> missing;
  for (const char* tool : {"sbatch", "squeue", "scontrol"}) {
    if (!FindOnPath(tool)) missing.emplace_back(tool);
  }
  if (missing.empty()) return;
  std::string names;
  for (const std::string& m : missing) names += (names.empty() ? "" : ", ") + m;
  throw std::runtime_error("--backend slurm: " + names +
                           " not found on PATH; is Slurm installed here (Debian: slurm-client)? "
                           "Without Slurm, leave out --backend to run the cells locally");
}

std::string CurrentSlurmJob() {
  const char* array = std::getenv("SLURM_ARRAY_JOB_ID");
  const char* task = std::getenv("SLURM_ARRAY_TASK_ID");
  if (array && task) return std::string(array) + "_" + task;
  const char* job = std::getenv("SLURM_JOB_ID");
  return job ? job : "";
}

std::optional<CellOutcome> SlurmStopOutcome() {
  // JOB_TASK names the one task; `show job` of an array's job id lists every task.
  const std::string job = CurrentSlurmJob();
  if (job.empty() || !FindOnPath("scontrol")) return std::nullopt;
  ProgramResult r;
  try {
    r = RunProgram({"scontrol", "-o", "show", "job", job});
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (r.exit_code != 0) return std::nullopt;
  const std::optional<SlurmTaskState> job_state = ParseScontrolJob(r.out);
  if (!job_state) return std::nullopt;
  const SlurmTaskState& st = *job_state;
  // Only a stop Slurm explains; anything else (a SIGTERM by hand) stays interrupted.
  if (st.reason != "TimeLimit" && IsActive(st.state)) return std::nullopt;
  return OutcomeFromSlurm(st, CellOutcome{});
}

std::optional<std::size_t> ParseIndex(const std::string& text) {
  const std::string t = Trim(text);
  if (t.empty() || t.size() > 19 || t.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  return static_cast<std::size_t>(std::stoull(t));
}

std::map<std::size_t, SlurmTaskState> ParseSqueueTasks(const std::string& out) {
  std::map<std::size_t, SlurmTaskState> tasks;
  for (const std::string& line : Split(out, '\n')) {
    const std::vector<std::string> f = Split(Trim(line), '|');
    if (f.size() < 3) continue;
    // A pending array's summary line has no task id (N/A, or a range such as 0-9).
    if (const std::optional<std::size_t> task = ParseIndex(f[0])) {
      tasks[*task] = SlurmTaskState{f[1], f[2]};
    }
  }
  return tasks;
}

void AddSacctTasks(const std::string& out, std::map<std::size_t, SlurmTaskState>* tasks) {
  for (const std::string& line : Split(out, '\n')) {
    const std::vector<std::string> f = Split(Trim(line), '|');
    if (f.size() < 2) continue;
    const std::size_t us = f[0].find('_');
    if (us == std::string::npos) continue;
    const std::optional<std::size_t> task = ParseIndex(f[0].substr(us + 1));
    if (!task || tasks->count(*task)) continue;
    // "CANCELLED by 0" -> "CANCELLED".
    const std::vector<std::string> words = Split(f[1], ' ');
    (*tasks)[*task] = SlurmTaskState{words.empty() ? f[1] : words[0], f.size() > 2 ? f[2] : ""};
  }
}

std::optional<SlurmTaskState> ParseScontrolJob(const std::string& out) {
  const std::vector<std::string> lines = Split(out, '\n');
  if (lines.empty()) return std::nullopt;
  std::map<std::string, std::string> fields;
  for (const std::string& word : Split(Trim(lines[0]), ' ')) {
    const std::size_t eq = word.find('=');
    if (eq != std::string::npos) fields[word.substr(0, eq)] = word.substr(eq + 1);
  }
  if (!fields.count("JobState")) return std::nullopt;
  return SlurmTaskState{fields["JobState"], fields["Reason"]};
}

std::size_t CellIndexFromList(const fs::path& list_file, std::size_t line) {
  const std::vector<std::string> lines = Split(experiments::ReadTextFile(list_file), '\n');
  if (line >= lines.size() || Trim(lines[line]).empty()) {
    throw std::runtime_error(list_file.string() + ": no line " + std::to_string(line) + " (" +
                             std::to_string(lines.size()) + " cells listed)");
  }
  if (const std::optional<std::size_t> index = ParseIndex(lines[line])) return *index;
  throw std::runtime_error(list_file.string() + ": line " + std::to_string(line) +
                           ": not a cell index: '" + lines[line] + "'");
}

int RunSlurmSweep(const fs::path& dir, const SweepPlan& plan, const SlurmOptions& options,
                  const BlockedSignals& signals) {
  if (options.max_parallel < 0) throw std::invalid_argument("--max-parallel must be >= 0");
  if (!(options.poll_s > 0)) throw std::invalid_argument("poll interval must be > 0");
  if (dir.string().find_first_of("% \t\n'\"") != std::string::npos) {
    throw std::invalid_argument(dir.string() +
                                ": the Slurm backend needs an --out path without spaces, "
                                "quotes or '%' (they would reach #SBATCH lines)");
  }
  fs::create_directories(LogDir(dir));
  std::vector<SlurmSubmission> subs = ReadSubmissions(dir);
  const std::map<std::size_t, std::string> busy = BusyCells(subs);

  std::vector<const SweepCell*> to_run;
  std::size_t finished = 0;
  std::set<std::string> busy_jobs;
  for (const SweepCell& cell : plan.cells) {
    if (experiments::CellFinished(dir, cell)) {
      if (!fs::exists(experiments::CellJsonPath(dir, cell))) RecoverOutcome(dir, cell);
      ++finished;
    } else if (busy.count(cell.index)) {
      busy_jobs.insert(busy.at(cell.index));
    } else {
      to_run.push_back(&cell);
    }
  }
  std::string busy_text;
  for (const std::string& j : busy_jobs) busy_text += (busy_text.empty() ? "" : ", ") + j;
  std::cerr << "trackbed sweep: " << plan.name << ": " << plan.cells.size() << " cells, "
            << finished << " finished already, " << busy.size()
            << " queued or running in Slurm job(s) " << (busy_text.empty() ? "-" : busy_text)
            << ", " << to_run.size() << " to submit -> " << dir.string() << std::endl;

  Progress progress(plan.cells.size(), finished, options.wait && UseBar());
  int interrupt = 0;
  const std::vector<const SweepCell*> valid =
      ValidateCells(dir, to_run, signals, progress, interrupt);
  if (interrupt != 0) return 128 + interrupt;

  std::set<std::size_t> watch;
  for (const auto& [cell, job] : busy) watch.insert(cell);
  for (std::size_t begin = 0; begin < valid.size(); begin += kMaxArrayTasks) {
    const std::size_t end = std::min(valid.size(), begin + kMaxArrayTasks);
    std::vector<std::size_t> cells;
    for (std::size_t k = begin; k < end; ++k) {
      cells.push_back(valid[k]->index);
      // A stale record must not pass for this submission's result.
      fs::remove_all(experiments::CellDir(dir, *valid[k]));
    }
    const std::size_t number = subs.size() + 1;
    const fs::path script = WriteBatchScript(dir, plan, options, number, cells);
    const ProgramResult r = RunProgram({"sbatch", "--parsable", script.string()});
    const std::string job_id = Split(Trim(r.out), ';').empty() ? "" : Split(Trim(r.out), ';')[0];
    if (r.exit_code != 0 || job_id.empty()) {
      throw std::runtime_error("sbatch " + script.string() + " failed (exit " +
                               std::to_string(r.exit_code) + "): " + LastLine(r.err));
    }
    SlurmSubmission sub{job_id, cells,
                        fs::relative(script, dir).replace_extension(".cells").string(), UtcNow()};
    subs.push_back(sub);
    WriteSubmissions(dir, subs);
    watch.insert(cells.begin(), cells.end());
    std::cout << "trackbed sweep: submitted " << cells.size()
              << (cells.size() == 1 ? " cell" : " cells") << " as Slurm array job " << job_id
              << " (" << fs::relative(script, dir).string() << ")" << std::endl;
  }

  if (!options.wait) {
    experiments::ReportSweep(dir);
    if (!watch.empty()) {
      std::cout << "trackbed sweep: follow it with the same command and --wait, or squeue; "
                   "`trackbed report "
                << dir.string() << "` gathers what has finished" << std::endl;
    }
    return kExitAllOk;
  }
  interrupt = Follow(dir, plan, subs, watch, options, signals, progress);
  progress.End();
  const experiments::SweepVerdict verdict = experiments::ReportSweep(dir);
  if (interrupt != 0) {
    std::cerr << "trackbed sweep: stopped following by " << SignalText(interrupt)
              << "; the Slurm job(s) go on: rerun with --wait to follow them" << std::endl;
    return 128 + interrupt;
  }
  experiments::PrintSweepResult(std::cout, plan.name, dir, verdict);
  return experiments::SweepExitStatus(verdict);
}

}  // namespace trackbed::experiments
