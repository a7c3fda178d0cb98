// `trackbed transfer` (see transfer_command.h).
#include "transfer_command.h"

#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "command_errors.h"
#include "trackbed/experiments/transfer_files.h"
#include "trackbed/experiments/transfer_study.h"

namespace trackbed::apps {
namespace {

struct TransferArguments {
  std::string real, sim, out_dir;
  std::string metric = "translation_error_pct";
  experiments::TransferOptions options;
};

void RunTransfer(const TransferArguments& args) {
  args.options.Validate();
  const experiments::OutcomeInput real = experiments::ReadOutcomes(args.real, args.metric);
  const experiments::OutcomeInput sim = experiments::ReadOutcomes(args.sim, args.metric);
  experiments::CheckSameSettings(real, sim);
  const experiments::TransferFigures figures =
      experiments::TransferStudy(real.table, sim.table, args.options);
  const std::filesystem::path out(args.out_dir);
  experiments::WriteTransferFiles(out, figures, args.metric);
  experiments::WriteOutcomeTable(out / "real_outcomes.csv", real.table, args.metric);
  experiments::WriteOutcomeTable(out / "sim_outcomes.csv", sim.table, args.metric);
  std::cout << experiments::FormatTransferFigures(figures, args.metric)
            << "outputs: " << out.string()
            << " (transfer.json, outcomes.csv, transfer.png, transfer_values.png)\n";
}

}  // namespace

void AddTransferCommand(CLI::App& app) {
  auto args = std::make_shared<TransferArguments>();
  CLI::App* cmd = app.add_subcommand(
      "transfer",
      "How well simulated outcomes of configurations rank them as real outcomes do: Spearman "
      "rho, Pearson r, MMRV, bootstrap intervals, the split-half ceiling; writes "
      "transfer.json, outcomes.csv and transfer.png");
  cmd->add_option("--real", args->real,
                  "Real outcomes: a table (CSV: config[,sequence][,frame],METRIC), a folder "
                  "of configuration folders with `trackbed vo` outputs, or a sweep folder")
      ->required();
  cmd->add_option("--sim", args->sim, "Simulated outcomes, as --real")->required();
  cmd->add_option("--out", args->out_dir, "Folder to write")->required();
  cmd->add_option("--metric", args->metric,
                  "The outcome's column: translation_error_pct (default), rotation_error_deg, "
                  "length_ratio, or a table's own");
  cmd->add_option("--resamples", args->options.resamples, "Bootstrap resamples (default 2000)");
  cmd->add_option("--seed", args->options.seed, "Bootstrap seed (default 1)");
  cmd->add_option("--block-frames", args->options.block_frames,
                  "Consecutive frames resampled and split together (default 5)");
  cmd->add_option("--near-best", args->options.near_best_factor,
                  "The near-best subset: real outcome within this factor of the best "
                  "(default 1.5)");
  cmd->add_flag("--higher-is-better", args->options.higher_is_better,
                "A higher outcome is better (success rates); default: lower (errors)");
  cmd->callback([args]() { RunCommand("transfer", [&] { RunTransfer(*args); }); });
}

}  // namespace trackbed::apps
