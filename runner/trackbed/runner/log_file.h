// Run-folder files as they are written: a buffered text file that checks every
// write (a full disk is an error, not a short log). Whole files are written with
// trackbed/common/durable_file.h.
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace trackbed::runner {

/// A text file with a 64 KiB buffer, its header line first (unless empty); every write
/// is checked and a failure throws std::runtime_error naming the file. The buffer goes to
/// the file whole lines at a time, so a run killed at any point (SIGKILL, a power cut
/// aside) leaves files of complete lines: everything up to its last 64 KiB, readable.
class LogFile {
 public:
  LogFile(const std::filesystem::path& path, const std::string& header) : path_(path) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0) Fail("cannot create");
    buffer_.reserve(kCapacity);
    if (!header.empty()) Line(header.c_str());
  }
  LogFile(const LogFile&) = delete;
  LogFile& operator=(const LogFile&) = delete;
  ~LogFile() {
    if (fd_ >= 0) ::close(fd_);  // without Close(): an error path, nothing more to report
  }

  void Line(const char* text) {
    const std::size_t n = std::strlen(text);
    if (buffer_.size() + n + 1 > kCapacity) Flush();
    buffer_.append(text, n);
    buffer_ += '\n';
  }
  void Close() {
    Flush();
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) Fail("cannot close");
  }

 private:
  static constexpr std::size_t kCapacity = 1 << 16;
  // Writes the buffered lines (one write(2) unless the kernel takes less).
  void Flush() {
    std::size_t done = 0;
    while (done < buffer_.size()) {
      const ssize_t n = ::write(fd_, buffer_.data() + done, buffer_.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) Fail("cannot write");
      done += static_cast<std::size_t>(n);
    }
    buffer_.clear();
  }
  [[noreturn]] void Fail(const char* what) const {
    throw std::runtime_error(path_.string() + ": " + what + ": " + std::strerror(errno));
  }
  std::filesystem::path path_;
  int fd_ = -1;
  std::string buffer_;
};

}  // namespace trackbed::runner
