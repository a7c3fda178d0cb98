// The independent MCAP readers from C++ tests: runs tests/mcap/check_mcap.mjs (the
// reference TypeScript reader, the CRCs recomputed, every message decoded by Foxglove's
// ROS 2 parser and CDR decoder) on a file and returns what it printed as JSON. The npm
// packages are installed into TRACKBED_MCAP_READERS_DIR by the ctest fixture
// `mcap_readers`; a test that uses this requires the fixture.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace trackbed::testing_mcap {

/// The readers' report on `path` (null after a test failure when they cannot run).
inline nlohmann::json ReadWithIndependentReaders(const std::string& path) {
  const std::string npm_dir = TRACKBED_MCAP_READERS_DIR;
  if (!std::filesystem::exists(npm_dir + "/node_modules/@mcap/core")) {
    ADD_FAILURE() << "the MCAP readers are not installed in " << npm_dir
                  << " (the ctest fixture mcap_readers installs them with npm)";
    return {};
  }
  const std::string command = "TRACKBED_NPM_DIR='" + npm_dir +
                              "' node '" TRACKBED_SOURCE_DIR "/tests/mcap/check_mcap.mjs' '" +
                              path + "' 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[65536];
  for (std::size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << out.substr(0, 4000);
  try {
    return nlohmann::json::parse(out);
  } catch (const nlohmann::json::exception&) {
    ADD_FAILURE() << "the readers printed no JSON: " << out.substr(0, 4000);
    return {};
  }
}

}  // namespace trackbed::testing_mcap
