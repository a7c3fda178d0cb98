// `trackbed export-mcap RUN_DIR`: writes a finished run folder as a ROS 2 bag, run.mcap
// and metadata.yaml beside its files (runner/run_bag.h, docs/mcap.md), as a run with
// `outputs.mcap` does at its end.
#pragma once

#include <CLI/CLI.hpp>

namespace trackbed::apps {

/// Registers the `export-mcap` subcommand (exit 0 when written, 2 when the folder is not
/// a run folder or one of its files is missing or malformed); like AddEvalCommand it ends
/// parsing by throwing CLI::RuntimeError with the exit status.
void AddExportMcapCommand(CLI::App& app);

}  // namespace trackbed::apps
