// The transfer study's files (docs/transfer.md): outcome tables and folders read into an
// OutcomeTable, and the figures written.
//
// An outcome table is CSV with a header: a `config` column, optionally `sequence` and
// `frame` columns, and the metric's column (any name, chosen by the caller); one row per
// frame (or one per configuration and sequence, without frames). A folder holds one
// subfolder per configuration, named as the configuration; in it, every folder with a
// `vo_frame_errors.csv` (a `trackbed vo` output with ground truth) is one sequence of it,
// named by its path inside the configuration's folder. Such outputs also carry the VO's
// options (vo_metrics.json), which must be the same for every sequence of a
// configuration, and on both sides (CheckSameSettings). A sweep folder (`trackbed
// sweep`'s, with summary.csv and cells.json) reads as a table whose configurations are
// the groups (a cell's name without its seed), whose sequences are the seeds and whose
// metric is a summary.csv column (`estimators_visual_odometry_ate_rmse_m`): one value
// per cell, no frames; a cell that did not finish is an error.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "trackbed/experiments/transfer_study.h"

namespace trackbed::experiments {

/// One side's outcomes and, for folders of `trackbed vo` outputs, each configuration's
/// VO options (compact JSON).
struct OutcomeInput {
  OutcomeTable table;
  std::map<std::string, std::string> settings;
};

/// Reads a CSV table, a folder or a sweep folder (see the file comment), the values of `metric`
/// (a column name: translation_error_pct, rotation_error_deg or length_ratio for
/// `trackbed vo`'s outputs). Throws std::runtime_error naming the file, the line or the
/// folder and the reason.
OutcomeInput ReadOutcomes(const std::filesystem::path& path, const std::string& metric);

/// Throws std::runtime_error naming the first configuration whose real and simulated
/// runs had different options, and the first key that differs (configurations without
/// settings on either side are not checked).
void CheckSameSettings(const OutcomeInput& real, const OutcomeInput& sim);

/// Writes `table` as an outcome table (config,sequence,frame,<metric>).
void WriteOutcomeTable(const std::filesystem::path& csv, const OutcomeTable& table,
                       const std::string& metric);

/// Writes in `out_dir`: transfer.json (every figure), outcomes.csv (each configuration's
/// real and simulated outcome, their ranks with 1 the best, and whether it is near the
/// best), transfer.png (the rank in simulation against the rank on real data, each
/// configuration labelled) and transfer_values.png (the outcomes, likewise).
void WriteTransferFiles(const std::filesystem::path& out_dir, const TransferFigures& figures,
                        const std::string& metric);

/// The figures as the lines `trackbed transfer` prints.
std::string FormatTransferFigures(const TransferFigures& figures, const std::string& metric);

}  // namespace trackbed::experiments
