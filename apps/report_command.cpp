// `trackbed report DIR` (see report_command.h).
#include "report_command.h"

#include <exception>
#include <iostream>
#include <memory>
#include <string>

#include "command_errors.h"
#include "trackbed/experiments/expectation_checks.h"

namespace trackbed::apps {

using namespace experiments;  // the sweep engine this command line drives

void AddReportCommand(CLI::App& app) {
  auto dir = std::make_shared<std::string>();
  CLI::App* report = app.add_subcommand(
      "report",
      "Rebuild a sweep folder's summary.csv, summary.json, aggregates.csv, report.md and plots "
      "from its cell files");
  report->add_option("dir", *dir, "Sweep folder (the --out of `trackbed sweep`)")->required();
  report->callback([dir]() {
    RunCommand("report", [&] {
      const experiments::SweepVerdict verdict = experiments::ReportSweep(*dir);
      const experiments::SweepCounts& n = verdict.cells;
      std::cout << "trackbed report: " << n.total() << " cells (" << n.ok << " ok, " << n.failed
                << " failed, " << n.timed_out << " timed out, " << n.interrupted << " interrupted, "
                << n.pending << " pending) -> " << *dir << "/report.md" << std::endl;
      for (const std::string& f : verdict.expectations.failed) {
        std::cout << "trackbed report: expectation failed: " << f << "\n";
      }
    });
  });
}

}  // namespace trackbed::apps
