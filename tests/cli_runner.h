// Running the `trackbed` binary from tests: the command in the source folder, both
// output streams captured in files, the exit status decoded. Shared by the tests that
// drive the command line (TRACKBED_BINARY and TRACKBED_SOURCE_DIR come from CMake).
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace trackbed::testing_cli {

struct CliResult {
  int exit_code = -1;
  std::string stdout_text, stderr_text;
};

/// The whole file as bytes ("" when it cannot be read).
inline std::string Slurp(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

/// An empty folder `prefix_name` in the system's temporary folder.
inline std::filesystem::path FreshTempDir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() / (prefix + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

/// Runs `trackbed ARGS` from the source folder; stdout and stderr go to `io`/out and
/// `io`/err and are returned.
inline CliResult RunTrackbed(const std::string& args, const std::filesystem::path& io) {
  std::filesystem::create_directories(io);
  const std::string cmd = std::string("cd '") + TRACKBED_SOURCE_DIR + "' && '" + TRACKBED_BINARY +
                          "' " + args + " >'" + (io / "out").string() + "' 2>'" +
                          (io / "err").string() + "'";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.stdout_text = Slurp(io / "out");
  r.stderr_text = Slurp(io / "err");
  return r;
}

// summary.csv without its machine-dependent columns (wall_, timing_, mem_, host…).
inline std::string DeterministicColumns(const std::filesystem::path& csv) {
  std::istringstream in(Slurp(csv));
  std::string line, out;
  std::vector<bool> keep;
  // The summary's text fields here hold no commas inside quotes except reasons, which
  // come before any machine-dependent column; split on commas outside quotes.
  const auto split = [](const std::string& l) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (char c : l) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted) {
        fields.emplace_back();
      } else {
        fields.back().push_back(c);
      }
    }
    return fields;
  };
  bool header = true;
  while (std::getline(in, line)) {
    const std::vector<std::string> fields = split(line);
    if (header) {
      for (const std::string& f : fields) {
        keep.push_back(!(f.rfind("wall_", 0) == 0 || f.rfind("timing_", 0) == 0 ||
                         f.rfind("mem_", 0) == 0 || f.rfind("host", 0) == 0));
      }
      header = false;
    }
    EXPECT_EQ(fields.size(), keep.size()) << line;
    for (std::size_t k = 0; k < fields.size() && k < keep.size(); ++k) {
      if (keep[k]) out += fields[k] + ",";
    }
    out += "\n";
  }
  return out;
}

}  // namespace trackbed::testing_cli
