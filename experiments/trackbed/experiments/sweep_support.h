// What both sweep backends (local processes, Slurm array jobs; sweep_command.h,
// slurm_backend.h) share: signals taken with sigtimedwait, the progress display, the
// folder lock, recording cell outcomes, validating cells before anything runs, and
// running a helper program (sbatch, squeue, …) with its output captured.
#pragma once

#include <signal.h>

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "trackbed/experiments/sweep.h"

namespace trackbed::experiments {

using SweepClock = std::chrono::steady_clock;

// Exit statuses of `trackbed sweep` and `sweep-cell` (sweep_command.h).
constexpr int kExitAllOk = 0;
constexpr int kExitSomeFailed = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitExpectationFailed = 3;  ///< every cell ok, an expectation failed

/// This machine's host name ("" when unknown).
std::string Hostname();

/// The current time as ISO 8601 UTC with milliseconds, e.g. 2026-12-01T18:45:04.123Z.
std::string UtcNow();

/// `s` with every `from` replaced by `to`.
std::string ReplaceAll(std::string s, const std::string& from, const std::string& to);

/// The last 20 lines of a file, at most 4000 bytes ("" when it cannot be read): what
/// cell.json keeps of a run's stderr.
std::string Tail(const std::filesystem::path& file);

/// The last non-empty line of `text`.
std::string LastLine(const std::string& text);

/// "signal 9 (Killed)".
std::string SignalText(int sig);

/// Blocks SIGCHLD, SIGINT, SIGTERM and SIGHUP for its lifetime, so that a sweep takes
/// them with sigtimedwait: one thread, no handlers, no races.
class BlockedSignals {
 public:
  BlockedSignals();
  ~BlockedSignals();
  BlockedSignals(const BlockedSignals&) = delete;
  BlockedSignals& operator=(const BlockedSignals&) = delete;

  /// Waits up to `timeout_s` [s] for one of the signals; returns it, or 0. SIGCHLD is
  /// returned as such (the caller reaps).
  int Wait(double timeout_s) const;

  /// A pending SIGINT, SIGTERM or SIGHUP (taken), or 0.
  int TakeInterrupt() const;

 private:
  sigset_t set_, old_;
};

/// SIGINT, SIGTERM or SIGHUP.
bool IsInterrupt(int sig);

/// The time a sweep has left [s]: the cells `remaining` at the pace of those it
/// `finished` in `elapsed_s` (their mean wall time over the cells run at once, as the
/// sweep measured it); nullopt before the first has finished.
std::optional<double> SecondsLeft(std::size_t finished, std::size_t remaining, double elapsed_s);

/// Minutes and seconds, "m:ss" ("12:05"); a negative or non-finite time as "-:--".
std::string MinutesSeconds(double seconds);

/// Progress on stderr: a one-line bar on a terminal, else one line per finished cell.
/// The bar: cells done of all, ok, not ok, running, the time elapsed and the time left
/// (SecondsLeft; "-:-- left" before the first cell has finished).
class Progress {
 public:
  /// `total` cells, `done` of them finished before this sweep started.
  Progress(std::size_t total, std::size_t done, bool bar);

  /// A cell ended (an interrupted one is not done: it reruns on resume).
  void Finished(const experiments::SweepCell& cell, const experiments::CellOutcome& o);
  /// A line of its own (the bar is redrawn after it).
  void Message(const std::string& text);
  /// Redraws the bar (no-op without one); `running` cells are under way.
  void Refresh(std::size_t running);
  /// Clears the bar.
  void End();

 private:
  void Clear();

  std::size_t total_, done_, ok_ = 0, bad_ = 0;
  std::size_t finished_here_ = 0;  // cells finished since this sweep started
  bool bar_;
  bool drawn_ = false;
  SweepClock::time_point start_;
};

/// True when stderr is a terminal that can draw the progress bar.
bool UseBar();

/// An exclusive lock on a sweep folder (DIR/.sweep.lock) for the life of the object,
/// so that two sweeps never write one folder. Throws std::runtime_error when another
/// holds it.
class FolderLock {
 public:
  explicit FolderLock(const std::filesystem::path& dir);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

/// Records a cell's outcome: DIR/cells/NAME/cell.json, atomically.
void WriteOutcome(const std::filesystem::path& dir, const experiments::SweepCell& cell,
                  const experiments::CellOutcome& o);

/// cell.json of a finished run whose outcome was never recorded (the sweep stopped
/// between the run's end and the record), rebuilt from its metrics.json and written.
experiments::CellOutcome RecoverOutcome(const std::filesystem::path& dir,
                                        const experiments::SweepCell& cell);

/// Loads every cell's scenario with its overrides and seed; cells that do not load are
/// recorded failed (without a process) and reported to `progress`. Returns the cells
/// that load. Stops early, setting `interrupt`, when SIGINT/SIGTERM/SIGHUP arrives.
std::vector<const experiments::SweepCell*> ValidateCells(
    const std::filesystem::path& dir, const std::vector<const experiments::SweepCell*>& cells,
    const BlockedSignals& signals, Progress& progress, int& interrupt);

/// What a helper program did.
struct ProgramResult {
  int exit_code = -1;  ///< its exit status; -1 when it was killed by a signal
  std::string out;     ///< what it wrote to stdout
  std::string err;     ///< what it wrote to stderr
};

/// The program `name` on PATH (as the shell would find it), or nothing.
std::optional<std::filesystem::path> FindOnPath(const std::string& name);

/// Runs `argv` (argv[0] looked up on PATH) with stdin from /dev/null and waits for it.
/// Throws std::runtime_error when it cannot be started.
ProgramResult RunProgram(const std::vector<std::string>& argv);

}  // namespace trackbed::experiments
