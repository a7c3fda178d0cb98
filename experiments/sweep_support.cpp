// See sweep_support.h.
#include "trackbed/experiments/sweep_support.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>
#include <iostream>
#include <stdexcept>

namespace trackbed::experiments {

namespace fs = std::filesystem;
using experiments::CellOutcome;
using experiments::CellStatus;
using experiments::SweepCell;

namespace {

// What cell.json keeps of a run's stderr.
constexpr std::size_t kTailLines = 20;
constexpr std::size_t kTailBytes = 4000;

std::string Seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f s", s);
  return buf;
}

}  // namespace

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

std::string Tail(const fs::path& file) {
  std::string text;
  try {
    text = experiments::ReadTextFile(file);
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

BlockedSignals::BlockedSignals() {
  sigemptyset(&set_);
  for (int s : {SIGCHLD, SIGINT, SIGTERM, SIGHUP}) sigaddset(&set_, s);
  ::pthread_sigmask(SIG_BLOCK, &set_, &old_);
}

BlockedSignals::~BlockedSignals() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

int BlockedSignals::Wait(double timeout_s) const {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(timeout_s);
  ts.tv_nsec = static_cast<long>((timeout_s - static_cast<double>(ts.tv_sec)) * 1e9);
  siginfo_t info{};
  const int sig = ::sigtimedwait(&set_, &info, &ts);
  return sig > 0 ? sig : 0;
}

int BlockedSignals::TakeInterrupt() const {
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

bool IsInterrupt(int sig) { return sig == SIGINT || sig == SIGTERM || sig == SIGHUP; }

std::optional<double> SecondsLeft(std::size_t finished, std::size_t remaining, double elapsed_s) {
  if (finished == 0) return std::nullopt;
  return elapsed_s / static_cast<double>(finished) * static_cast<double>(remaining);
}

std::string MinutesSeconds(double seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) return "-:--";
  const long s = std::lround(seconds);
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%ld:%02ld", s / 60, s % 60);
  return buf;
}

Progress::Progress(std::size_t total, std::size_t done, bool bar)
    : total_(total), done_(done), bar_(bar), start_(SweepClock::now()) {}

void Progress::Finished(const SweepCell& cell, const CellOutcome& o) {
  if (o.status != CellStatus::kInterrupted) {
    ++done_;
    ++finished_here_;
  }
  if (o.status == CellStatus::kOk) {
    ++ok_;
  } else if (o.status != CellStatus::kInterrupted) {
    ++bad_;
  }
  if (bar_ && o.status == CellStatus::kOk) return;
  char head[64];
  const int width = static_cast<int>(std::to_string(total_).size());
  std::snprintf(head, sizeof(head), "[%*zu/%zu] %-11s ", width, done_, total_,
                experiments::ToString(o.status));
  std::string line = head + cell.name;
  if (o.status != CellStatus::kFailed || o.exit_code) line += "  " + Seconds(o.wall_time_s);
  if (!o.reason.empty()) line += ": " + o.reason;
  Clear();
  std::cerr << line << std::endl;
  drawn_ = false;
}

void Progress::Message(const std::string& text) {
  Clear();
  std::cerr << text << std::endl;
  drawn_ = false;
}

void Progress::Refresh(std::size_t running) {
  if (!bar_) return;
  constexpr int kWidth = 30;
  const int filled =
      total_ ? static_cast<int>(kWidth * static_cast<double>(done_) / static_cast<double>(total_))
             : kWidth;
  const double elapsed = std::chrono::duration<double>(SweepClock::now() - start_).count();
  const std::optional<double> left = SecondsLeft(finished_here_, total_ - done_, elapsed);
  char buf[256];
  std::snprintf(buf, sizeof(buf),
                "\r\033[K[%s%s] %zu/%zu cells  %zu ok  %zu not ok  %zu running  %s  %s left",
                std::string(static_cast<std::size_t>(filled), '#').c_str(),
                std::string(static_cast<std::size_t>(kWidth - filled), '.').c_str(), done_, total_,
                ok_, bad_, running, MinutesSeconds(std::floor(elapsed)).c_str(),
                MinutesSeconds(left ? *left : -1.0).c_str());
  std::cerr << buf << std::flush;
  drawn_ = true;
}

void Progress::End() { Clear(); }

void Progress::Clear() {
  if (bar_ && drawn_) std::cerr << "\r\033[K" << std::flush;
  drawn_ = false;
}

FolderLock::FolderLock(const fs::path& dir) {
  const fs::path path = dir / ".sweep.lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error(path.string() + ": cannot open: " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    throw std::runtime_error(dir.string() + ": another `trackbed sweep` is running there");
  }
}

FolderLock::~FolderLock() { ::close(fd_); }

// Records a cell's outcome.
void WriteOutcome(const fs::path& dir, const SweepCell& cell, const CellOutcome& o) {
  fs::create_directories(experiments::CellDir(dir, cell));
  experiments::WriteFileAtomically(experiments::CellJsonPath(dir, cell),
                                   experiments::CellOutcomeJson(cell, o));
}

// cell.json of a finished run whose outcome was never recorded (the sweep stopped
// between the run's end and the record).
CellOutcome RecoverOutcome(const fs::path& dir, const SweepCell& cell) {
  CellOutcome o = experiments::OutcomeFromMetrics(
      experiments::ReadTextFile(experiments::CellMetricsPath(dir, cell)));
  o.host = Hostname();
  o.stderr_tail = Tail(experiments::CellDir(dir, cell) / "stderr.txt");
  WriteOutcome(dir, cell, o);
  return o;
}

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
    const std::optional<std::string> reason = experiments::ValidateCell(*cell);
    if (!reason) {
      valid.push_back(cell);
      continue;
    }
    fs::remove_all(experiments::CellDir(dir, *cell));
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
std::optional<fs::path> FindOnPath(const std::string& name) {
  if (name.find('/') != std::string::npos) {
    return ::access(name.c_str(), X_OK) == 0 ? std::optional<fs::path>(name) : std::nullopt;
  }
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  std::size_t begin = 0;
  while (begin <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', begin), dirs.size());
    const std::string dir = dirs.substr(begin, end - begin);
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
    begin = end + 1;
  }
  return std::nullopt;
}

namespace {

// The whole of an in-memory file written by a child.
std::string ReadBack(int fd) {
  std::string text;
  ::lseek(fd, 0, SEEK_SET);
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof(buf));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buf, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace

ProgramResult RunProgram(const std::vector<std::string>& argv) {
  if (argv.empty()) throw std::invalid_argument("RunProgram: empty command");
  // Output into memory files rather than pipes: no deadlock however much it writes,
  // and nothing left on disk.
  const int out = ::memfd_create("trackbed-out", MFD_CLOEXEC);
  const int err = ::memfd_create("trackbed-err", MFD_CLOEXEC);
  if (out < 0 || err < 0) {
    throw std::runtime_error("cannot run " + argv[0] + ": memfd_create: " + std::strerror(errno));
  }
  std::vector<std::string> args = argv;
  std::vector<char*> c_args;
  for (std::string& a : args) c_args.push_back(a.data());
  c_args.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&files, out, 1);
  posix_spawn_file_actions_adddup2(&files, err, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  // The caller may block signals (BlockedSignals); the program gets none blocked.
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, c_args[0], &files, &attr, c_args.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    ::close(out);
    ::close(err);
    throw std::runtime_error("cannot run " + argv[0] + ": " + std::strerror(rc));
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  ProgramResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = ReadBack(out);
  r.err = ReadBack(err);
  ::close(out);
  ::close(err);
  return r;
}

}  // namespace trackbed::experiments
