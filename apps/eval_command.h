// `trackbed eval GT EST`: trajectory metrics like the evo tool and the KITTI devkit
// (README.md, "Commands"): ATE RMSE after alignment, the horizontal unaligned ATE, RPE, KITTI
// t_rel / r_rel, drift over 10 m and final error, as a table or JSON.
#pragma once

#include <iosfwd>
#include <string>

#include <CLI/CLI.hpp>

namespace trackbed::apps {

/// The command line of `trackbed eval` (empty strings: not given).
struct EvalArgs {
  std::string gt_path;
  std::string est_path;
  std::string format;                 ///< --format: both files (tum|kitti|euroc); empty: detect
  std::string gt_format;              ///< --gt-format: overrides --format for GT
  std::string est_format;             ///< --est-format: overrides --format for EST
  std::string times;                  ///< --times: times file for whichever of GT/EST is KITTI
  std::string gt_times;               ///< --gt-times: overrides --times for GT
  std::string est_times;              ///< --est-times: overrides --times for EST
  std::string align = "se3";          ///< --align: se3|sim3|none
  double max_dt_s = 0.02;             ///< --max-dt: association tolerance [s]
  double offset_s = 0.0;              ///< --t-offset: added to EST's times [s]
  double delta = 1.0;                 ///< --delta: RPE pair spacing
  std::string delta_unit = "frames";  ///< --delta-unit: frames|m
  bool json = false;                  ///< --json: JSON instead of the table
};

/// Reads, associates and evaluates GT and EST and writes the table (or JSON) to `out`.
/// Throws std::exception with a one-line reason on bad input (unreadable or malformed
/// files, unknown names, no associated poses, …).
void RunEval(const EvalArgs& args, std::ostream& out);

/// Registers the `eval` subcommand. It runs in its CLI11 callback, i.e. inside
/// app.parse(): on success it prints the result to stdout, on failure a one-line
/// `trackbed eval: <reason>` to stderr; either way it then ends parsing by throwing
/// CLI::RuntimeError carrying the exit status (0 on success, 2 on failure), which
/// CLI::App::exit() returns without printing anything more — so main's usual
/// `catch (const CLI::ParseError& e) { return app.exit(e); }` yields the status.
void AddEvalCommand(CLI::App& app);

}  // namespace trackbed::apps
