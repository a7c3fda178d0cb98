// `trackbed sweep` and `trackbed sweep-cell` (see sweep_command.h, docs/sweeps.md).
//
// Each cell is a child process of this same binary (`/proc/self/exe run …`: the very
// image this process runs, whatever its file holds by then), started
// with posix_spawn in a process group of its own, so that a timeout or an interrupt
// kills the whole run, and so that the terminal's Ctrl-C reaches only the sweep,
// which then stops its cells itself. The sweep blocks SIGCHLD, SIGINT, SIGTERM and
// SIGHUP and takes them with sigtimedwait: one thread, no handlers, no races. The
// wait is capped at one second (progress bar, deadlines), and every wake-up polls
// each child with waitpid(WNOHANG), so no exit can be missed.
#include "sweep_command.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <deque>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "trackbed/experiments/expectation_checks.h"
#include "trackbed/experiments/slurm_backend.h"
#include "trackbed/experiments/sweep.h"
#include "trackbed/experiments/sweep_report.h"
#include "trackbed/experiments/sweep_support.h"

namespace trackbed::apps {

using namespace experiments;  // the sweep engine this command line drives
namespace {

namespace fs = std::filesystem;
using Clock = SweepClock;
using experiments::CellOutcome;
using experiments::CellStatus;
using experiments::SweepCell;
using experiments::SweepPlan;

// Runs cells as child processes, `jobs` at a time.
class CellRunner {
 public:
  CellRunner(fs::path dir, std::size_t jobs, std::optional<double> timeout_s,
             const BlockedSignals& signals, Progress& progress)
      : dir_(std::move(dir)),
        exe_(fs::read_symlink("/proc/self/exe")),
        jobs_(std::max<std::size_t>(jobs, 1)),
        timeout_s_(timeout_s),
        signals_(signals),
        progress_(progress),
        host_(Hostname()),
        slurm_job_(CurrentSlurmJob()) {
    // The cells' environment: this one, and this sweep's pid (DieWithSweepIfCell).
    for (char** e = environ; *e != nullptr; ++e) {
      if (std::strncmp(*e, "TRACKBED_SWEEP_PID=", 19) != 0) env_text_.emplace_back(*e);
    }
    env_text_.push_back("TRACKBED_SWEEP_PID=" + std::to_string(::getpid()));
    for (std::string& e : env_text_) env_.push_back(e.data());
    env_.push_back(nullptr);
  }

  /// Runs `cells` in order; returns the interrupting signal, or 0. Interrupted cells get
  /// status interrupted; cells not started stay pending (no cell.json).
  int Run(const std::vector<const SweepCell*>& cells) {
    std::deque<const SweepCell*> queue(cells.begin(), cells.end());
    int stop = 0;
    while (!running_.empty() || (!queue.empty() && stop == 0)) {
      if (stop == 0) stop = signals_.TakeInterrupt();
      if (stop != 0) KillAll();
      while (stop == 0 && !queue.empty() && running_.size() < jobs_) {
        Launch(*queue.front());
        queue.pop_front();
      }
      progress_.Refresh(running_.size());
      if (running_.empty()) continue;
      const int sig = signals_.Wait(WaitSeconds());
      if (IsInterrupt(sig) && stop == 0) {
        stop = sig;
        KillAll();
      }
      Reap();
      EnforceDeadlines();
    }
    return stop;
  }

  CellOutcome last_outcome() const { return last_; }

 private:
  struct Child {
    const SweepCell* cell;
    pid_t pid;
    Clock::time_point start;
    std::string started_utc;
    bool timed_out = false;
    bool interrupted = false;
  };

  double WaitSeconds() const {
    double wait = 1.0;
    if (timeout_s_) {
      for (const Child& c : running_) {
        if (c.timed_out || c.interrupted) continue;
        const double left =
            *timeout_s_ - std::chrono::duration<double>(Clock::now() - c.start).count();
        wait = std::min(wait, std::max(left, 0.001));
      }
    }
    return wait;
  }

  void KillAll() {
    for (Child& c : running_) {
      if (c.interrupted) continue;
      c.interrupted = true;
      ::kill(-c.pid, SIGKILL);
    }
  }

  void EnforceDeadlines() {
    if (!timeout_s_) return;
    for (Child& c : running_) {
      if (c.timed_out || c.interrupted) continue;
      if (std::chrono::duration<double>(Clock::now() - c.start).count() >= *timeout_s_) {
        c.timed_out = true;
        ::kill(-c.pid, SIGKILL);  // the group: the run and anything it started
      }
    }
  }

  void Launch(const SweepCell& cell) {
    const fs::path cell_dir = experiments::CellDir(dir_, cell);
    fs::remove_all(cell_dir);
    fs::create_directories(cell_dir);
    std::vector<std::string> args = {exe_.string(),
                                     "run",
                                     cell.scenario_path.string(),
                                     "--out",
                                     experiments::CellRunDir(dir_, cell).string(),
                                     "--seed",
                                     std::to_string(cell.seed)};
    for (const scenario::Override& o : cell.overrides) {
      args.push_back("--set");
      args.push_back(o.key + "=" + o.value);
    }
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    const std::string out = (cell_dir / "stdout.txt").string();
    const std::string err = (cell_dir / "stderr.txt").string();
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&files, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    // Own process group (killed as one; the terminal's SIGINT goes to the sweep only),
    // no blocked signals, default dispositions.
    posix_spawnattr_setflags(
        &attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    posix_spawnattr_setpgroup(&attr, 0);
    sigset_t none, defaults;
    sigemptyset(&none);
    posix_spawnattr_setsigmask(&attr, &none);
    sigemptyset(&defaults);
    for (int s : {SIGCHLD, SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGQUIT}) sigaddset(&defaults, s);
    posix_spawnattr_setsigdefault(&attr, &defaults);

    Child child{&cell, 0, Clock::now(), UtcNow()};
    // The child execs /proc/self/exe, which before the exec is this process's own
    // image: the binary the sweep started with, even if its file has since been
    // replaced (a rebuild) or removed, so every cell of a sweep runs the same code.
    // argv[0] keeps the path, for ps and messages.
    const int rc =
        ::posix_spawn(&child.pid, "/proc/self/exe", &files, &attr, argv.data(), env_.data());
    posix_spawn_file_actions_destroy(&files);
    posix_spawnattr_destroy(&attr);
    if (rc != 0) {
      CellOutcome o;
      o.status = CellStatus::kFailed;
      o.reason = "cannot start " + exe_.string() + ": " + std::strerror(rc);
      o.host = host_;
      o.started_utc = child.started_utc;
      Record(cell, o);
      return;
    }
    running_.push_back(child);
  }

  void Reap() {
    for (auto it = running_.begin(); it != running_.end();) {
      int status = 0;
      const pid_t r = ::waitpid(it->pid, &status, WNOHANG);
      if (r == it->pid) {
        Finished(*it, status);
        it = running_.erase(it);
      } else {
        ++it;
      }
    }
  }

  void Finished(const Child& c, int wait_status) {
    const SweepCell& cell = *c.cell;
    const fs::path cell_dir = experiments::CellDir(dir_, cell);
    CellOutcome o;
    if (experiments::CellFinished(dir_, cell)) {
      // The run wrote its metrics: its own status decides, whatever happened after.
      o = experiments::OutcomeFromMetrics(
          experiments::ReadTextFile(experiments::CellMetricsPath(dir_, cell)));
    } else if (c.timed_out) {
      o.status = CellStatus::kTimedOut;
      char buf[96];
      std::snprintf(buf, sizeof(buf), "no result within timeout_s = %g s; killed", *timeout_s_);
      o.reason = buf;
    } else if (c.interrupted) {
      o.status = CellStatus::kInterrupted;
      o.reason = "the sweep was interrupted; the cell reruns on resume";
    } else if (WIFEXITED(wait_status)) {
      o.status = CellStatus::kFailed;
      const std::string last = LastLine(Tail(cell_dir / "stderr.txt"));
      o.reason = !last.empty() ? last
                               : "exit status " + std::to_string(WEXITSTATUS(wait_status)) +
                                     " without run/metrics.json";
    } else if (WIFSIGNALED(wait_status)) {
      o.status = CellStatus::kFailed;
      o.reason = "killed by " + SignalText(WTERMSIG(wait_status));
    } else {
      o.status = CellStatus::kFailed;
      o.reason = "ended with wait status " + std::to_string(wait_status);
    }
    if (WIFEXITED(wait_status)) o.exit_code = WEXITSTATUS(wait_status);
    // The scenario as the sweep file names it, so that reasons read the same anywhere.
    o.reason = ReplaceAll(o.reason, cell.scenario_path.string(), cell.scenario);
    o.stderr_tail = Tail(cell_dir / "stderr.txt");
    o.wall_time_s = std::chrono::duration<double>(Clock::now() - c.start).count();
    o.host = host_;
    o.started_utc = c.started_utc;
    Record(cell, o);
  }

  void Record(const SweepCell& cell, CellOutcome o) {
    o.slurm_job = slurm_job_;
    WriteOutcome(dir_, cell, o);
    last_ = o;
    progress_.Finished(cell, o);
  }

  fs::path dir_;
  fs::path exe_;
  std::vector<std::string> env_text_;
  std::vector<char*> env_;  // env_text_'s, for posix_spawn
  std::size_t jobs_;
  std::optional<double> timeout_s_;
  const BlockedSignals& signals_;
  Progress& progress_;
  std::string host_;
  std::string slurm_job_;  // the Slurm array task this runs in, recorded in cell.json
  std::vector<Child> running_;
  CellOutcome last_;
};

// Takes an exclusive lock on the sweep folder for the life of the object, so that two
// sweeps never write one folder.

}  // namespace

void DieWithSweepIfCell() {
  const char* text = std::getenv("TRACKBED_SWEEP_PID");
  if (text == nullptr) return;
  const long sweep = std::strtol(text, nullptr, 10);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  // The sweep may have ended between the spawn and the line above.
  if (static_cast<long>(::getppid()) != sweep) {
    std::cerr << "trackbed run: its sweep (pid " << sweep << ") is gone; not running\n";
    std::exit(137);
  }
}

int RunSweep(const SweepArgs& args) {
  const bool slurm = args.backend == "slurm";
  if (args.backend != "local" && !slurm) {
    throw std::invalid_argument("--backend " + args.backend + ": must be local or slurm");
  }
  if (args.jobs < 1) throw std::invalid_argument("--jobs must be >= 1");
  if (!slurm && (!args.slurm.partition.empty() || args.slurm.max_parallel != 0 ||
                 !args.slurm.time_limit.empty() || args.slurm.wait)) {
    throw std::invalid_argument(
        "--partition, --max-parallel, --time-limit and --wait are for --backend slurm");
  }
  if (slurm) CheckSlurmAvailable();  // at once, before anything is written
  const experiments::SweepSpec spec = experiments::LoadSweep(args.sweep_file);
  const SweepPlan plan = experiments::MakeSweepPlan(spec);
  const fs::path dir = fs::absolute(args.out_dir).lexically_normal();
  fs::create_directories(dir / "cells");
  const FolderLock lock(dir);
  if (fs::exists(dir / "cells.json")) {
    const std::string conflict = experiments::PlanConflict(experiments::ReadSweepPlan(dir), plan);
    if (!conflict.empty()) {
      throw std::runtime_error(dir.string() + " holds another sweep (" + conflict +
                               "); use another --out");
    }
  }
  experiments::WriteFileAtomically(dir / "sweep.yaml", experiments::SweepToYaml(spec));
  experiments::WriteFileAtomically(dir / "cells.json", experiments::SweepPlanJson(plan));

  const BlockedSignals signals;
  if (slurm) return RunSlurmSweep(dir, plan, args.slurm, signals);

  std::vector<const SweepCell*> to_run;
  std::size_t finished = 0;
  for (const SweepCell& cell : plan.cells) {
    if (experiments::CellFinished(dir, cell)) {
      if (!fs::exists(experiments::CellJsonPath(dir, cell))) RecoverOutcome(dir, cell);
      ++finished;
    } else {
      to_run.push_back(&cell);
    }
  }
  std::cerr << "trackbed sweep: " << plan.name << ": " << plan.cells.size() << " cells, "
            << finished << " finished already, " << to_run.size() << " to run, " << args.jobs
            << " at a time -> " << dir.string() << std::endl;

  Progress progress(plan.cells.size(), finished, UseBar());
  int interrupt = 0;
  const std::vector<const SweepCell*> valid =
      ValidateCells(dir, to_run, signals, progress, interrupt);
  if (interrupt == 0) {
    CellRunner runner(dir, static_cast<std::size_t>(args.jobs), plan.timeout_s, signals, progress);
    interrupt = runner.Run(valid);
  }
  progress.End();

  const experiments::SweepVerdict verdict = experiments::ReportSweep(dir);
  const experiments::SweepCounts& n = verdict.cells;
  if (interrupt != 0) {
    std::cerr << "trackbed sweep: interrupted by " << SignalText(interrupt) << ": " << n.ok
              << " ok, " << (n.failed + n.timed_out) << " not ok, " << (n.interrupted + n.pending)
              << " not finished; finished cells are kept: rerun the same command to resume"
              << std::endl;
    return 128 + interrupt;
  }
  experiments::PrintSweepResult(std::cout, plan.name, dir, verdict);
  return experiments::SweepExitStatus(verdict);
}

int RunSweepCell(const std::string& sweep_dir, std::size_t index, const std::string& list_file) {
  const fs::path dir = fs::absolute(sweep_dir).lexically_normal();
  const SweepPlan plan = experiments::ReadSweepPlan(dir);
  if (!list_file.empty()) index = CellIndexFromList(list_file, index);
  if (index >= plan.cells.size()) {
    throw std::invalid_argument("cell index " + std::to_string(index) + " out of range (" +
                                std::to_string(plan.cells.size()) + " cells)");
  }
  const SweepCell& cell = plan.cells[index];
  const BlockedSignals signals;
  Progress progress(1, 0, false);
  CellOutcome o;
  if (experiments::CellFinished(dir, cell)) {
    o = fs::exists(experiments::CellJsonPath(dir, cell)) ? experiments::ReadCellOutcome(dir, cell)
                                                         : RecoverOutcome(dir, cell);
    std::cerr << "trackbed sweep-cell: " << cell.name << " finished already ("
              << experiments::ToString(o.status) << ")" << std::endl;
    return o.status == CellStatus::kOk ? kExitAllOk : kExitSomeFailed;
  }
  int interrupt = 0;
  const std::vector<const SweepCell*> valid =
      ValidateCells(dir, {&cell}, signals, progress, interrupt);
  if (interrupt == 0 && !valid.empty()) {
    CellRunner runner(dir, 1, plan.timeout_s, signals, progress);
    interrupt = runner.Run(valid);
  }
  if (interrupt != 0) {
    // Under Slurm a SIGTERM is Slurm stopping the task: record why, in Slurm's words.
    o = experiments::ReadCellOutcome(dir, cell);
    if (o.status == CellStatus::kInterrupted) {
      if (const std::optional<CellOutcome> why = SlurmStopOutcome()) {
        o.status = why->status;
        o.reason = why->reason;
        o.slurm_job = CurrentSlurmJob();
        WriteOutcome(dir, cell, o);
        std::cerr << "trackbed sweep-cell: " << cell.name << ": " << o.reason << std::endl;
      }
    }
    return 128 + interrupt;
  }
  o = experiments::ReadCellOutcome(dir, cell);
  return o.status == CellStatus::kOk ? kExitAllOk : kExitSomeFailed;
}

void AddSweepCommand(CLI::App& app) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "Run every cell of a sweep file (scenarios x varied overrides x seeds), each a separate "
      "`trackbed run`, N at a time; resumable; writes summary.csv, aggregates.csv and report.md");
  sweep->add_option("sweep", args->sweep_file, "Sweep file (YAML; docs/sweeps.md)")->required();
  sweep->add_option("--out", args->out_dir, "Sweep folder to write (or resume)")->required();
  sweep->add_option("--jobs,-j", args->jobs, "Cells run at once")->capture_default_str();
  sweep
      ->add_option("--backend", args->backend,
                   "Where cells run: local (child processes, --jobs at a time) or slurm (one "
                   "sbatch array job; the folder must be on a filesystem the nodes share)")
      ->check(CLI::IsMember({"local", "slurm"}))
      ->capture_default_str();
  sweep->add_option("--partition", args->slurm.partition,
                    "slurm: partition to submit to (default: the cluster's default)");
  sweep
      ->add_option("--max-parallel", args->slurm.max_parallel,
                   "slurm: at most N array tasks at once (0: as Slurm schedules)")
      ->check(CLI::NonNegativeNumber);
  sweep->add_option("--time-limit", args->slurm.time_limit,
                    "slurm: time limit of each cell's task, as sbatch --time (minutes, H:MM:SS, "
                    "D-HH:MM); default timeout_s + 1 min when the sweep has one");
  sweep->add_flag("--wait", args->slurm.wait,
                  "slurm: follow the job until every cell has ended (progress as the local "
                  "backend's), then write the summary and report");
  sweep->footer(
      "Exit status: 0 every cell ok and every expectation held (slurm without --wait: "
      "submitted); 1 some cell failed or timed out; 2 bad input or Slurm refused the job; 3 "
      "every cell ran and an expectation failed; 130/143 interrupted by SIGINT/SIGTERM (rerun "
      "the same command to resume; a Slurm job goes on).");
  sweep->callback([args]() {
    int status = kExitBadInput;
    try {
      status = RunSweep(*args);
    } catch (const std::exception& e) {
      std::cerr << "trackbed sweep: " << e.what() << std::endl;
      throw CLI::RuntimeError(kExitBadInput);
    }
    throw CLI::RuntimeError(status);
  });

  auto cell_dir = std::make_shared<std::string>();
  auto cell_index = std::make_shared<std::size_t>(0);
  auto cell_list = std::make_shared<std::string>();
  CLI::App* cell = app.add_subcommand(
      "sweep-cell",
      "Run one cell of a sweep folder written by `trackbed sweep` (what a batch scheduler's "
      "array task runs); `trackbed report DIR` then gathers the results");
  cell->add_option("dir", *cell_dir, "Sweep folder (holds cells.json)")->required();
  cell->add_option("index", *cell_index, "Cell index (0-based, as in cells.json)")->required();
  cell->add_option("--list", *cell_list,
                   "Take the cell index from line INDEX (0-based) of this file (a Slurm "
                   "submission's DIR/slurm/submit-N.cells)");
  cell->callback([cell_dir, cell_index, cell_list]() {
    int status = kExitBadInput;
    try {
      status = RunSweepCell(*cell_dir, *cell_index, *cell_list);
    } catch (const std::exception& e) {
      std::cerr << "trackbed sweep-cell: " << e.what() << std::endl;
      throw CLI::RuntimeError(kExitBadInput);
    }
    throw CLI::RuntimeError(status);
  });
}

}  // namespace trackbed::apps
