// Durable files (see durable_file.h).
#include "trackbed/common/durable_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace trackbed {
namespace {

namespace fs = std::filesystem;

DurableStepHook step_hook = nullptr;

void Step(const char* step, const fs::path& path) {
  if (step_hook) step_hook(step, path);
}

// The kill point of durable_file.h: POINT:SUFFIX from the environment.
void KillPoint(const char* point, const fs::path& path) {
  static const char* const spec = std::getenv(kKillAtVariable);
  if (!spec) return;
  const std::string s(spec), target = path.string();
  const std::size_t colon = s.find(':');
  if (colon == std::string::npos || s.compare(0, colon, point) != 0) return;
  const std::string suffix = s.substr(colon + 1);
  if (target.size() < suffix.size() ||
      target.compare(target.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return;
  }
  ::kill(::getpid(), SIGKILL);
}

[[noreturn]] void Fail(const fs::path& path, const char* what) {
  throw std::runtime_error(path.string() + ": cannot " + what + ": " + std::strerror(errno));
}

// fsync of a file or folder opened read-only (Linux syncs either); a path gone since
// it was listed is no error.
void Sync(const fs::path& path, bool folder) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | (folder ? O_DIRECTORY : 0));
  if (fd < 0) {
    if (errno == ENOENT) return;
    Fail(path, "open to sync");
  }
  const int status = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (status != 0) {
    errno = error;
    Fail(path, "sync");
  }
  Step("sync", path);
}

}  // namespace

void WriteFileAtomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) Fail(tmp, "create");
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      Fail(tmp, "write");
    }
    done += static_cast<std::size_t>(n);
  }
  // On disk before the rename makes it visible: a power loss leaves the old file or
  // the whole new one.
  if (::fsync(fd) != 0) {
    ::close(fd);
    Fail(tmp, "sync");
  }
  Step("sync", tmp);
  if (::close(fd) != 0) Fail(tmp, "close");
  KillPoint("before_rename", path);
  fs::rename(tmp, path);
  Step("rename", path);
  KillPoint("after_rename", path);
  Sync(path.parent_path().empty() ? fs::path(".") : path.parent_path(), true);
}

void SyncFolder(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw std::runtime_error(dir.string() + ": cannot sync: not a folder");
  }
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::file_status status = it->symlink_status(ec);
    if (ec) break;
    if (fs::is_regular_file(status)) Sync(it->path(), false);
    if (fs::is_directory(status)) Sync(it->path(), true);
  }
  if (ec && ec != std::errc::no_such_file_or_directory) {
    throw std::runtime_error(dir.string() + ": cannot list to sync: " + ec.message());
  }
  Sync(dir, true);
}

void SetDurableStepHookForTesting(DurableStepHook hook) { step_hook = hook; }

}  // namespace trackbed
