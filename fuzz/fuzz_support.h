// What the fuzz targets share: reporting a finding (abort, so that libFuzzer keeps the
// input that caused it), a scratch folder per process for the parsers that read files,
// and writing an input into it.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace trackbed::fuzz {

/// Prints `target: FINDING: what` and aborts.
[[noreturn]] inline void Finding(const char* target, const std::string& what) {
  std::fprintf(stderr, "%s: FINDING: %s\n", target, what.c_str());
  std::abort();
}

/// The folder `trackbed_fuzz_NAME_PID` under the temporary folder: created at once,
/// removed with what it holds at exit. One per process, so that parallel jobs never
/// share files.
struct ScratchDir {
  explicit ScratchDir(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("trackbed_fuzz_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path path;
};

/// Writes `bytes` to `path` whole; a failure is the harness's, reported as `target`'s.
inline void WriteFile(const char* target, const std::filesystem::path& path,
                      const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
  if (!out.flush()) Finding(target, "cannot write " + path.string());
}

}  // namespace trackbed::fuzz
