// Fuzzes what the Slurm backend reads (slurm_backend.h): the input as slurm/jobs.json
// text (ParseSlurmJobs; what parses is written with SlurmJobsJson and must read back to
// the same submissions), as a submission's list file, written to a temporary file (one
// per process) and read line by line with CellIndexFromList, and as the output of
// squeue, sacct and scontrol (ParseSqueueTasks, AddSacctTasks, ParseScontrolJob).
//
// Finding: a crash, a sanitizer report, a hang, any exception from the programs' output
// parsers (they must take whatever a program prints), an exception other than SweepError
// from ParseSlurmJobs or std::runtime_error from CellIndexFromList, or jobs.json that does
// not read back.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "trackbed/experiments/slurm_backend.h"

namespace {

namespace fs = std::filesystem;
namespace ex = trackbed::experiments;

[[noreturn]] void Finding(const std::string& what) { trackbed::fuzz::Finding("slurm_fuzz", what); }

void FuzzJobs(const std::string& text) {
  std::vector<ex::SlurmSubmission> jobs;
  try {
    jobs = ex::ParseSlurmJobs(text, "jobs.json");
  } catch (const ex::SweepError&) {
    return;
  }
  try {
    const std::vector<ex::SlurmSubmission> again =
        ex::ParseSlurmJobs(ex::SlurmJobsJson(jobs), "written.json");
    bool same = again.size() == jobs.size();
    for (std::size_t k = 0; same && k < jobs.size(); ++k) {
      same = again[k].job_id == jobs[k].job_id && again[k].cells == jobs[k].cells &&
             again[k].list == jobs[k].list && again[k].submitted_utc == jobs[k].submitted_utc;
    }
    if (!same) Finding("jobs.json reads back differently");
  } catch (const ex::SweepError& e) {
    Finding(std::string("written jobs.json does not read back: ") + e.what());
  }
}

// squeue's, sacct's and scontrol's output: parsed without throwing, whatever it is.
void FuzzProgramOutput(const std::string& text) {
  try {
    std::map<std::size_t, ex::SlurmTaskState> tasks = ex::ParseSqueueTasks(text);
    ex::AddSacctTasks(text, &tasks);
    ex::ParseScontrolJob(text);
    ex::ParseIndex(text);
  } catch (const std::exception& e) {
    Finding(std::string("a program output parser threw: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const trackbed::fuzz::ScratchDir dir("slurm");
  static const fs::path list = dir.path / "submit.cells";
  const std::string text(reinterpret_cast<const char*>(data), size);
  FuzzJobs(text);
  FuzzProgramOutput(text);
  trackbed::fuzz::WriteFile("slurm_fuzz", list, text);
  for (std::size_t line = 0; line < 4; ++line) {
    try {
      ex::CellIndexFromList(list, line);
    } catch (const std::runtime_error&) {
    }
  }
  return 0;
}
