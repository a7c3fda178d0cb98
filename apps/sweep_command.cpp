// `trackbed sweep` and `trackbed sweep-cell` (see sweep_command.h, docs/sweeps.md).
//
// Each cell is a child process of this same binary (`/proc/self/exe run …`), started
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

#include "trackbed/scenes/sweep.h"
#include "trackbed/scenes/sweep_report.h"

namespace trackbed::apps {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using scenes::CellOutcome;
using scenes::CellStatus;
using scenes::SweepCell;
using scenes::SweepPlan;

// Exit statuses (sweep_command.h).
constexpr int kExitAllOk = 0;
constexpr int kExitSomeFailed = 1;
constexpr int kExitBadInput = 2;

// What cell.json keeps of a run's stderr.
constexpr std::size_t kTailLines = 20;
constexpr std::size_t kTailBytes = 4000;

std::string Hostname() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof(buf) - 1) != 0) return "";
  return buf;
}

std::string UtcNow() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[64];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%S", &tm);
  char out[80];
  std::snprintf(out, sizeof(out), "%s.%03lldZ", buf, static_cast<long long>(ms));
  return out;
}

std::string ReplaceAll(std::string s, const std::string& from, const std::string& to) {
  if (from.empty()) return s;
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
  }
  return s;
}

// The last `kTailLines` lines of a file, at most `kTailBytes`.
std::string Tail(const fs::path& file) {
  std::string text;
  try {
    text = scenes::ReadTextFile(file);
  } catch (const std::exception&) {
    return "";
  }
  if (text.size() > kTailBytes) text = text.substr(text.size() - kTailBytes);
  std::size_t start = text.size(), lines = 0;
  while (start > 0) {
    const std::size_t nl = text.rfind('\n', start - 1);
    if (nl == std::string::npos) {
      start = 0;
      break;
    }
    if (nl + 1 < text.size() && ++lines > kTailLines) break;
    start = nl;
  }
  if (start < text.size() && text[start] == '\n') ++start;
  return text.substr(start);
}

std::string LastLine(const std::string& text) {
  std::size_t end = text.size();
  while (end > 0 && (text[end - 1] == '\n' || text[end - 1] == '\r')) --end;
  const std::size_t nl = text.rfind('\n', end == 0 ? 0 : end - 1);
  return text.substr(nl == std::string::npos || end == 0 ? 0 : nl + 1,
                     end - (nl == std::string::npos || end == 0 ? 0 : nl + 1));
}

std::string SignalText(int sig) {
  const char* name = ::strsignal(sig);
  return "signal " + std::to_string(sig) + (name ? std::string(" (") + name + ")" : "");
}

std::string Seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f s", s);
  return buf;
}

// Blocks the signals the sweep takes with sigtimedwait for its lifetime.
class BlockedSignals {
 public:
  BlockedSignals() {
    sigemptyset(&set_);
    for (int s : {SIGCHLD, SIGINT, SIGTERM, SIGHUP}) sigaddset(&set_, s);
    ::pthread_sigmask(SIG_BLOCK, &set_, &old_);
  }
  ~BlockedSignals() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  BlockedSignals(const BlockedSignals&) = delete;
  BlockedSignals& operator=(const BlockedSignals&) = delete;

  const sigset_t& set() const { return set_; }

  /// Waits up to `timeout_s` for one of the signals; returns it, or 0. SIGCHLD is
  /// returned as such (the caller reaps).
  int Wait(double timeout_s) const {
    timespec ts{};
    ts.tv_sec = static_cast<time_t>(timeout_s);
    ts.tv_nsec = static_cast<long>((timeout_s - static_cast<double>(ts.tv_sec)) * 1e9);
    siginfo_t info{};
    const int sig = ::sigtimedwait(&set_, &info, &ts);
    return sig > 0 ? sig : 0;
  }

  /// A pending SIGINT, SIGTERM or SIGHUP (taken), or 0.
  int TakeInterrupt() const {
    sigset_t pending;
    sigemptyset(&pending);
    ::sigpending(&pending);
    for (int s : {SIGINT, SIGTERM, SIGHUP}) {
      if (sigismember(&pending, s)) {
        sigset_t one;
        sigemptyset(&one);
        sigaddset(&one, s);
        timespec zero{};
        ::sigtimedwait(&one, nullptr, &zero);
        return s;
      }
    }
    return 0;
  }

 private:
  sigset_t set_, old_;
};

bool IsInterrupt(int sig) { return sig == SIGINT || sig == SIGTERM || sig == SIGHUP; }

// Progress on stderr: a one-line bar on a terminal, else one line per finished cell.
class Progress {
 public:
  Progress(std::size_t total, std::size_t done, bool bar)
      : total_(total), done_(done), bar_(bar), start_(Clock::now()) {}

  void Finished(const SweepCell& cell, const CellOutcome& o) {
    // An interrupted cell is not done: it reruns on resume.
    if (o.status != CellStatus::kInterrupted) ++done_;
    if (o.status == CellStatus::kOk) {
      ++ok_;
    } else if (o.status != CellStatus::kInterrupted) {
      ++bad_;
    }
    if (bar_ && o.status == CellStatus::kOk) return;
    char head[64];
    const int width = static_cast<int>(std::to_string(total_).size());
    std::snprintf(head, sizeof(head), "[%*zu/%zu] %-11s ", width, done_, total_,
                  scenes::ToString(o.status));
    std::string line = head + cell.name;
    if (o.status != CellStatus::kFailed || o.exit_code) line += "  " + Seconds(o.wall_time_s);
    if (!o.reason.empty()) line += ": " + o.reason;
    Clear();
    std::cerr << line << std::endl;
    drawn_ = false;
  }

  void Message(const std::string& text) {
    Clear();
    std::cerr << text << std::endl;
    drawn_ = false;
  }

  void Refresh(std::size_t running) {
    if (!bar_) return;
    constexpr int kWidth = 30;
    const int filled =
        total_ ? static_cast<int>(kWidth * static_cast<double>(done_) / static_cast<double>(total_))
               : kWidth;
    const long elapsed =
        std::chrono::duration_cast<std::chrono::seconds>(Clock::now() - start_).count();
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "\r\033[K[%s%s] %zu/%zu cells  %zu ok  %zu not ok  %zu running  %ld:%02ld",
                  std::string(static_cast<std::size_t>(filled), '#').c_str(),
                  std::string(static_cast<std::size_t>(kWidth - filled), '.').c_str(), done_,
                  total_, ok_, bad_, running, elapsed / 60, elapsed % 60);
    std::cerr << buf << std::flush;
    drawn_ = true;
  }

  void End() { Clear(); }

 private:
  void Clear() {
    if (bar_ && drawn_) std::cerr << "\r\033[K" << std::flush;
    drawn_ = false;
  }

  std::size_t total_, done_, ok_ = 0, bad_ = 0;
  bool bar_;
  bool drawn_ = false;
  Clock::time_point start_;
};

// Records a cell's outcome.
void WriteOutcome(const fs::path& dir, const SweepCell& cell, const CellOutcome& o) {
  fs::create_directories(scenes::CellDir(dir, cell));
  scenes::WriteFileAtomically(scenes::CellJsonPath(dir, cell), scenes::CellOutcomeJson(cell, o));
}

// cell.json of a finished run whose outcome was never recorded (the sweep stopped
// between the run's end and the record).
CellOutcome RecoverOutcome(const fs::path& dir, const SweepCell& cell) {
  CellOutcome o =
      scenes::OutcomeFromMetrics(scenes::ReadTextFile(scenes::CellMetricsPath(dir, cell)));
  o.host = Hostname();
  o.stderr_tail = Tail(scenes::CellDir(dir, cell) / "stderr.txt");
  WriteOutcome(dir, cell, o);
  return o;
}

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
        host_(Hostname()) {}

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
    const fs::path cell_dir = scenes::CellDir(dir_, cell);
    fs::remove_all(cell_dir);
    fs::create_directories(cell_dir);
    std::vector<std::string> args = {exe_.string(),
                                     "run",
                                     cell.scenario_path.string(),
                                     "--out",
                                     scenes::CellRunDir(dir_, cell).string(),
                                     "--seed",
                                     std::to_string(cell.seed)};
    for (const scenes::Override& o : cell.overrides) {
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
    const int rc = ::posix_spawn(&child.pid, exe_.c_str(), &files, &attr, argv.data(), environ);
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
    const fs::path cell_dir = scenes::CellDir(dir_, cell);
    CellOutcome o;
    if (scenes::CellFinished(dir_, cell)) {
      // The run wrote its metrics: its own status decides, whatever happened after.
      o = scenes::OutcomeFromMetrics(scenes::ReadTextFile(scenes::CellMetricsPath(dir_, cell)));
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

  void Record(const SweepCell& cell, const CellOutcome& o) {
    WriteOutcome(dir_, cell, o);
    last_ = o;
    progress_.Finished(cell, o);
  }

  fs::path dir_;
  fs::path exe_;
  std::size_t jobs_;
  std::optional<double> timeout_s_;
  const BlockedSignals& signals_;
  Progress& progress_;
  std::string host_;
  std::vector<Child> running_;
  CellOutcome last_;
};

// Takes an exclusive lock on the sweep folder for the life of the object, so that two
// sweeps never write one folder.
class FolderLock {
 public:
  explicit FolderLock(const fs::path& dir) {
    const fs::path path = dir / ".sweep.lock";
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw std::runtime_error(path.string() + ": cannot open: " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      throw std::runtime_error(dir.string() + ": another `trackbed sweep` is running there");
    }
  }
  ~FolderLock() { ::close(fd_); }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

bool UseBar() {
  const char* term = std::getenv("TERM");
  return ::isatty(STDERR_FILENO) && !(term && std::string(term) == "dumb");
}

// Cells whose scenario does not load fail here, without a process.
std::vector<const SweepCell*> ValidateCells(const fs::path& dir,
                                            const std::vector<const SweepCell*>& cells,
                                            const BlockedSignals& signals, Progress& progress,
                                            int& interrupt) {
  std::vector<const SweepCell*> valid;
  const std::string host = Hostname();
  for (const SweepCell* cell : cells) {
    if ((interrupt = signals.TakeInterrupt()) != 0) return {};
    const std::optional<std::string> reason = scenes::ValidateCell(*cell);
    if (!reason) {
      valid.push_back(cell);
      continue;
    }
    fs::remove_all(scenes::CellDir(dir, *cell));
    CellOutcome o;
    o.status = CellStatus::kFailed;
    o.reason = "invalid scenario: " + *reason;
    o.host = host;
    o.started_utc = UtcNow();
    WriteOutcome(dir, *cell, o);
    progress.Finished(*cell, o);
  }
  return valid;
}

}  // namespace

int RunSweep(const SweepArgs& args) {
  if (args.backend != "local") {
    throw std::invalid_argument("--backend " + args.backend +
                                ": not available (only `local` so far)");
  }
  if (args.jobs < 1) throw std::invalid_argument("--jobs must be >= 1");
  const scenes::SweepSpec spec = scenes::LoadSweep(args.sweep_file);
  const SweepPlan plan = scenes::MakeSweepPlan(spec);
  const fs::path dir = fs::absolute(args.out_dir).lexically_normal();
  fs::create_directories(dir / "cells");
  const FolderLock lock(dir);
  if (fs::exists(dir / "cells.json")) {
    const std::string conflict = scenes::PlanConflict(scenes::ReadSweepPlan(dir), plan);
    if (!conflict.empty()) {
      throw std::runtime_error(dir.string() + " holds another sweep (" + conflict +
                               "); use another --out");
    }
  }
  scenes::WriteFileAtomically(dir / "sweep.yaml", scenes::SweepToYaml(spec));
  scenes::WriteFileAtomically(dir / "cells.json", scenes::SweepPlanJson(plan));

  const BlockedSignals signals;
  std::vector<const SweepCell*> to_run;
  std::size_t finished = 0;
  for (const SweepCell& cell : plan.cells) {
    if (scenes::CellFinished(dir, cell)) {
      if (!fs::exists(scenes::CellJsonPath(dir, cell))) RecoverOutcome(dir, cell);
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

  const scenes::SweepCounts n = scenes::WriteSweepReport(dir);
  if (interrupt != 0) {
    std::cerr << "trackbed sweep: interrupted by " << SignalText(interrupt) << ": " << n.ok
              << " ok, " << (n.failed + n.timed_out) << " not ok, " << (n.interrupted + n.pending)
              << " not finished; finished cells are kept: rerun the same command to resume"
              << std::endl;
    return 128 + interrupt;
  }
  std::cout << "trackbed sweep: " << plan.name << ": " << n.ok << " ok, " << n.failed << " failed, "
            << n.timed_out << " timed out; summary in " << (dir / "summary.csv").string()
            << ", report in " << (dir / "report.md").string() << std::endl;
  return n.ok == n.total() ? kExitAllOk : kExitSomeFailed;
}

int RunSweepCell(const std::string& sweep_dir, std::size_t index) {
  const fs::path dir = fs::absolute(sweep_dir).lexically_normal();
  const SweepPlan plan = scenes::ReadSweepPlan(dir);
  if (index >= plan.cells.size()) {
    throw std::invalid_argument("cell index " + std::to_string(index) + " out of range (" +
                                std::to_string(plan.cells.size()) + " cells)");
  }
  const SweepCell& cell = plan.cells[index];
  const BlockedSignals signals;
  Progress progress(1, 0, false);
  CellOutcome o;
  if (scenes::CellFinished(dir, cell)) {
    o = fs::exists(scenes::CellJsonPath(dir, cell)) ? scenes::ReadCellOutcome(dir, cell)
                                                    : RecoverOutcome(dir, cell);
    std::cerr << "trackbed sweep-cell: " << cell.name << " finished already ("
              << scenes::ToString(o.status) << ")" << std::endl;
    return o.status == CellStatus::kOk ? kExitAllOk : kExitSomeFailed;
  }
  int interrupt = 0;
  const std::vector<const SweepCell*> valid =
      ValidateCells(dir, {&cell}, signals, progress, interrupt);
  if (interrupt == 0 && !valid.empty()) {
    CellRunner runner(dir, 1, plan.timeout_s, signals, progress);
    interrupt = runner.Run(valid);
  }
  if (interrupt != 0) return 128 + interrupt;
  o = scenes::ReadCellOutcome(dir, cell);
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
  sweep->add_option("--backend", args->backend, "Where cells run: local")->capture_default_str();
  sweep->footer(
      "Exit status: 0 every cell ok; 1 some cell failed or timed out; 2 bad input; "
      "130/143 interrupted by SIGINT/SIGTERM (rerun the same command to resume).");
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
  CLI::App* cell = app.add_subcommand(
      "sweep-cell",
      "Run one cell of a sweep folder written by `trackbed sweep` (what a batch scheduler's "
      "array task runs); `trackbed report DIR` then gathers the results");
  cell->add_option("dir", *cell_dir, "Sweep folder (holds cells.json)")->required();
  cell->add_option("index", *cell_index, "Cell index (0-based, as in cells.json)")->required();
  cell->callback([cell_dir, cell_index]() {
    int status = kExitBadInput;
    try {
      status = RunSweepCell(*cell_dir, *cell_index);
    } catch (const std::exception& e) {
      std::cerr << "trackbed sweep-cell: " << e.what() << std::endl;
      throw CLI::RuntimeError(kExitBadInput);
    }
    throw CLI::RuntimeError(status);
  });
}

}  // namespace trackbed::apps
