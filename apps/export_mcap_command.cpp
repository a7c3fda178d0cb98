// `trackbed export-mcap RUN_DIR` (see export_mcap_command.h).
#include "export_mcap_command.h"

#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "command_errors.h"
#include "trackbed/runner/run_bag.h"

namespace trackbed::apps {

void AddExportMcapCommand(CLI::App& app) {
  auto dir = std::make_shared<std::string>();
  CLI::App* exporter = app.add_subcommand(
      "export-mcap", "Write a finished run folder as a ROS 2 bag: run.mcap and metadata.yaml");
  exporter->add_option("run_dir", *dir, "Run folder (the --out of `trackbed run`)")->required();
  exporter->callback([dir]() {
    RunCommand("export-mcap", [&] {
      if (!std::filesystem::exists(std::filesystem::path(*dir) / "scenario.yaml")) {
        throw std::runtime_error(*dir + ": not a run folder (no scenario.yaml)");
      }
      const runner::RunBagSummary s = runner::WriteRunBag(*dir);
      std::cout << "trackbed export-mcap: " << s.messages << " messages on "
                << s.messages_per_topic.size() << " topics -> " << *dir << "/run.mcap" << std::endl;
    });
  });
}

}  // namespace trackbed::apps
