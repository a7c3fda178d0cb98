// The Slurm backend's tests need a Slurm cluster to submit to: `scripts/slurm_local.sh
// start` makes a one-node cluster on this machine and prints the SLURM_CONF to export
// (.ci/run does both). Without a reachable cluster the tests skip, saying so, unless
// TRACKBED_REQUIRE_SLURM=1 (as .ci/run sets): then they fail, so that CI cannot pass
// them unseen.
#pragma once

#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

namespace trackbed::testing_cli {

/// Why no Slurm cluster can take jobs from here, or "" when one can.
inline std::string SlurmUnavailable() {
  if (std::system("command -v sbatch >/dev/null 2>&1") != 0) return "sbatch is not installed";
  if (std::system("sinfo -h -o %T 2>/dev/null | grep -Eq 'idle|mixed|allocated'") != 0) {
    return "no Slurm node takes jobs (sinfo); start one with `scripts/slurm_local.sh start` and "
           "export the SLURM_CONF it prints";
  }
  return "";
}

inline bool SlurmRequired() {
  const char* v = std::getenv("TRACKBED_REQUIRE_SLURM");
  return v && std::string(v) == "1";
}

}  // namespace trackbed::testing_cli

/// Skips the test (or fails it, with TRACKBED_REQUIRE_SLURM=1) without a Slurm cluster.
#define TRACKBED_NEEDS_SLURM()                                                       \
  do {                                                                               \
    const std::string why = trackbed::testing_cli::SlurmUnavailable();               \
    if (!why.empty()) {                                                              \
      if (trackbed::testing_cli::SlurmRequired()) FAIL() << "Slurm needed: " << why; \
      GTEST_SKIP() << "no Slurm cluster: " << why;                                   \
    }                                                                                \
  } while (false)
