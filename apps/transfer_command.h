// `trackbed transfer --real REAL --sim SIM --out DIR [--metric NAME] [--resamples N]
// [--seed N] [--near-best F] [--higher-is-better]`: do the testbed's verdicts transfer?
// How well the simulated outcomes of many configurations rank them as their real
// outcomes do: Spearman's ρ, Pearson's r, the MMRV, their bootstrap intervals, the
// ceiling (the real outcomes' split-half correlation) and the same on the
// configurations near the best (docs/transfer.md).
//
// REAL and SIM: each an outcome table (CSV: config[,sequence][,frame],<metric>), a
// folder with one subfolder per configuration holding `trackbed vo` outputs, or a sweep
// folder (experiments/trackbed/experiments/transfer_files.h). Prints the figures and writes in
// DIR transfer.json, outcomes.csv, transfer.png, transfer_values.png and both sides as
// outcome tables (real_outcomes.csv, sim_outcomes.csv).
#pragma once

#include <CLI/CLI.hpp>

namespace trackbed::apps {

/// Registers the `transfer` subcommand (exit 0 when written; 2, after a one-line reason
/// on stderr, for a bad input: a configuration on one side only, a missing column, a
/// folder without `trackbed vo` outputs, different VO options on the two sides); like
/// AddVoCommand it ends parsing by throwing (CLI::Success or CLI::RuntimeError).
void AddTransferCommand(CLI::App& app);

}  // namespace trackbed::apps
