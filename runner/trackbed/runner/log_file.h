// Run-folder files as they are written: a buffered text file that checks every
// write (a full disk is an error, not a short log). Whole files are written with
// trackbed/common/durable_file.h.
#pragma once

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace trackbed::runner {

/// A text file with a large buffer, its header line first (unless empty); every write
/// is checked and a failure throws std::runtime_error naming the file.
class LogFile {
 public:
  LogFile(const std::filesystem::path& path, const std::string& header) : path_(path) {
    file_.rdbuf()->pubsetbuf(buffer_, sizeof(buffer_));
    file_.open(path, std::ios::out | std::ios::trunc);
    if (!file_) Fail("cannot create");
    if (!header.empty()) Line(header.c_str());
  }
  LogFile(const LogFile&) = delete;
  LogFile& operator=(const LogFile&) = delete;

  void Line(const char* text) {
    file_ << text << '\n';
    if (!file_) Fail("cannot write");
  }
  void Close() {
    file_.close();
    if (!file_) Fail("cannot close");
  }

 private:
  [[noreturn]] void Fail(const char* what) const {
    throw std::runtime_error(path_.string() + ": " + what + ": " + std::strerror(errno));
  }
  std::filesystem::path path_;
  char buffer_[1 << 16];
  std::ofstream file_;
};

}  // namespace trackbed::runner
