// `trackbed sweep SWEEP.yaml --out DIR [--jobs N]`: many closed-loop runs, each a
// separate `trackbed run` process, N at a time, resumable (docs/sweeps.md); and
// `trackbed sweep-cell DIR INDEX`, which runs one cell of a prepared sweep folder —
// what a batch scheduler's array task runs; `--backend slurm` submits the cells
// as one Slurm array job of such tasks (slurm_backend.h).
//
// Exit status of `sweep`: 0 when every cell is ok and every expectation held; 1 when
// some cell failed or timed out (the summary and report are written all the same); 3
// when every cell is ok and an expectation failed (expectation_checks.h); 2 on bad input (sweep
// file, command line, a sweep folder holding another sweep); 128 + signal (130 for SIGINT, 143 for
// SIGTERM) when interrupted — finished cells are kept and a rerun resumes.
#pragma once

#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

#include "trackbed/experiments/slurm_backend.h"

namespace trackbed::apps {

/// The command line of `trackbed sweep`.
struct SweepArgs {
  std::string sweep_file;
  std::string out_dir;
  int jobs = 1;                     ///< local: cells run at once, >= 1
  std::string backend = "local";    ///< local (child processes) or slurm (an array job)
  experiments::SlurmOptions slurm;  ///< with backend slurm
};

/// A sweep's cell (`trackbed run` started by a local sweep, whose pid the environment's
/// TRACKBED_SWEEP_PID names) dies with its sweep, even a sweep killed with SIGKILL: the
/// kernel sends the cell SIGKILL when its parent ends (PR_SET_PDEATHSIG); a cell whose
/// sweep is already gone exits at once. Does nothing outside a sweep.
void DieWithSweepIfCell();

/// Runs the sweep and writes the summary and report; returns the exit status. Prints
/// progress to stderr (a bar on a terminal, else one line per finished cell) and the
/// result to stdout. Throws std::exception with a one-line reason on bad input.
int RunSweep(const SweepArgs& args);

/// Runs cell `index` of the sweep folder `sweep_dir` (unless it is finished) and
/// records its cell.json; does not write the summary (`trackbed report` does). With a
/// `list_file` (a Slurm submission's cell list), the cell is the one on line `index`.
/// Returns 0 when the cell is ok, 1 when not, 128 + signal when interrupted (under
/// Slurm, the cell is then recorded with Slurm's reason for stopping it).
int RunSweepCell(const std::string& sweep_dir, std::size_t index,
                 const std::string& list_file = "");

/// Registers the `sweep` and `sweep-cell` subcommands; like AddEvalCommand, they run in
/// their CLI11 callbacks and end parsing by throwing CLI::RuntimeError with the exit
/// status.
void AddSweepCommand(CLI::App& app);

}  // namespace trackbed::apps
