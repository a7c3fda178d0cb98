// `trackbed report DIR`: rebuilds a sweep folder's summary.csv, summary.json,
// aggregates.csv, report.md and plots/ from its cell files alone (docs/sweeps.md).
// Works on a finished, interrupted or still running sweep: cells without a result
// are listed as such.
#pragma once

#include <CLI/CLI.hpp>

namespace trackbed::apps {

/// Registers the `report` subcommand (exit 0 when written, 2 when DIR is not a sweep
/// folder or a file cannot be read or written); like AddEvalCommand it ends parsing by
/// throwing CLI::RuntimeError with the exit status.
void AddReportCommand(CLI::App& app);

}  // namespace trackbed::apps
