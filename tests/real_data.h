// Real data for tests (KITTI frames, benchmark trajectories with published figures),
// found through one setting: the CMake cache variable TRACKBED_DATA_DIR. A clone
// without it skips the tests that need it, saying where it looked; with
// TRACKBED_REQUIRE_DATA=1 in the environment (as .ci/run sets) they fail instead, so
// that CI, which has the data, cannot pass them unseen. Such tests carry `RealData` in
// their suite's name: tests/CMakeLists.txt labels them `realdata`.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace trackbed::testing_data {

/// `sub` under the real-data folder (TRACKBED_DATA_DIR).
inline std::filesystem::path RealData(const std::string& sub) {
  return std::filesystem::path(TRACKBED_DATA_DIR) / sub;
}

inline bool RealDataRequired() {
  const char* v = std::getenv("TRACKBED_REQUIRE_DATA");
  return v && std::string(v) == "1";
}

}  // namespace trackbed::testing_data

/// Skips the test (or fails it, with TRACKBED_REQUIRE_DATA=1) where `where` is absent.
#define TRACKBED_NEEDS_REAL_DATA(where)                                                     \
  do {                                                                                      \
    const std::filesystem::path needed = (where);                                           \
    if (!std::filesystem::exists(needed)) {                                                 \
      if (trackbed::testing_data::RealDataRequired()) {                                     \
        FAIL() << "real data needed (TRACKBED_REQUIRE_DATA=1) and not found at " << needed; \
      }                                                                                     \
      GTEST_SKIP() << "real data not found at " << needed << ": set TRACKBED_DATA_DIR";     \
    }                                                                                       \
  } while (false)
