// Processes started and watched by the tests that interrupt, kill and time out
// `trackbed` (sweep_cli_test.cpp, crash_recovery_test.cpp): started without a shell so
// that a signal reaches the program itself; every wait is a bounded poll for something
// the program does, never a sleep for a set time.
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.h"

extern char** environ;

namespace trackbed::testing_process {

namespace fs = std::filesystem;
using trackbed::testing_cli::Slurp;

// Starts `trackbed ARGS...` (the binary at `binary`) without a shell so that the test
// can signal it.
inline pid_t Spawn(const std::vector<std::string>& args, const fs::path& io,
                   const std::string& binary = TRACKBED_BINARY) {
  fs::create_directories(io);
  std::vector<std::string> all = {binary};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string out = (io / "out").string(), err = (io / "err").string();
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, binary.c_str(), &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  EXPECT_EQ(rc, 0);
  return pid;
}

// Polls for `file` while `pid` runs; false if the process ended first or the file has
// not appeared after 10 minutes of polling (a hang, not a timing judgement).
inline bool WaitForFile(const fs::path& file, pid_t pid) {
  for (int polls = 0; polls < 120000; ++polls) {
    if (fs::exists(file)) return true;
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

// The pids of the processes whose command line mentions `text` (none for zombies,
// whose command line is empty).
inline std::vector<pid_t> ProcessesMentioning(const std::string& text) {
  std::vector<pid_t> pids;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = Slurp(entry.path() / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find(text) != std::string::npos) pids.push_back(std::stoi(name));
  }
  return pids;
}

// Polls `done` every 5 ms for up to `limit`; whether it came true.
template <class F>
bool Within(std::chrono::seconds limit, F done) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

}  // namespace trackbed::testing_process
