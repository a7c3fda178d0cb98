// `trackbed sweep`, `sweep-cell` and `report` end to end, on cells that take well
// under a second (the paper's kinematic navigation scene; the corridor and the
// park for 3 simulated seconds): a failing cell among good ones, resume after lost
// cells, an interrupted sweep, and reports rebuilt from the files. Synchronisation
// is by polling for files the sweep writes, never by sleeping for a set time.
#include <fcntl.h>
#include <pty.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "process_control.h"

namespace {

namespace fs = std::filesystem;

const fs::path kSource = TRACKBED_SOURCE_DIR;

using Result = trackbed::testing_cli::CliResult;
using trackbed::testing_cli::DeterministicColumns;
using trackbed::testing_cli::Slurp;
using trackbed::testing_process::ProcessesMentioning;
using trackbed::testing_process::Spawn;
using trackbed::testing_process::WaitForFile;
using trackbed::testing_process::Within;

fs::path TempDir(const std::string& name) {
  return trackbed::testing_cli::FreshTempDir("trackbed_sweep_cli_test_", name);
}

// Runs `trackbed ARGS` from the source folder, capturing both streams.
Result Trackbed(const std::string& args, const fs::path& io) {
  return trackbed::testing_cli::RunTrackbed(args, io);
}

nlohmann::json CellJson(const fs::path& sweep, const std::string& cell) {
  return nlohmann::json::parse(Slurp(sweep / "cells" / cell / "cell.json"));
}

// A sweep of the paper's navigation scene over `methods` (by default four, one of them
// unknown), written to dir/NAME.yaml.
fs::path WriteNavigationSweep(
    const fs::path& dir, const std::string& name = "nav",
    const std::string& methods = "gauss_newton_subgoal, potential_field, teleport, dwa") {
  const fs::path file = dir / (name + ".yaml");
  std::ofstream(file) << "name: " << name << "\n"
                      << "scenarios: [" << (kSource / "scenes/nav_paper_left.yaml").string()
                      << "]\n"
                      << "seeds: [1]\n"
                      << "set: [\"duration_s=30\"]\n"
                      << "vary:\n"
                      << "  - {key: navigation.method, values: [" << methods << "]}\n";
  return file;
}

const char* kBadCell = "nav_paper_left__method-teleport__seed-1";
const std::vector<std::string> kGoodCells = {"nav_paper_left__method-gauss_newton_subgoal__seed-1",
                                             "nav_paper_left__method-potential_field__seed-1",
                                             "nav_paper_left__method-dwa__seed-1"};

TEST(SweepCliTest, AFailingCellIsReportedAndTheOthersFinish) {
  const fs::path dir = TempDir("failing");
  const fs::path out = dir / "sweep";
  const Result r = Trackbed(
      "sweep " + WriteNavigationSweep(dir).string() + " --out " + out.string() + " --jobs 2",
      dir / "io");
  EXPECT_EQ(r.exit_code, 1) << r.stderr_text;  // some cell failed
  EXPECT_NE(r.stdout_text.find("nav: 3 ok, 1 failed, 0 timed out"), std::string::npos)
      << r.stdout_text;
  const nlohmann::json bad = CellJson(out, kBadCell);
  EXPECT_EQ(bad["status"], "failed");
  EXPECT_EQ(bad["reason"],
            "invalid scenario: --set navigation.method=teleport: navigation.method: must be one "
            "of gauss_newton_subgoal, potential_field, dwa (got 'teleport')");
  for (const std::string& c : kGoodCells) {
    EXPECT_EQ(CellJson(out, c)["status"], "ok") << c;
    EXPECT_EQ(CellJson(out, c)["exit_code"], 0) << c;
    EXPECT_TRUE(fs::exists(out / "cells" / c / "run" / "metrics.json")) << c;
  }
  for (const char* f : {"sweep.yaml", "cells.json", "summary.csv", "summary.json", "aggregates.csv",
                        "report.md", "plots/navigation_success.png"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  const std::string summary = Slurp(out / "summary.csv");
  EXPECT_EQ(std::count(summary.begin(), summary.end(), '\n'), 5);
  EXPECT_NE(summary.find(",navigation_success,"), std::string::npos);
  EXPECT_NE(summary.find(",teleport,failed,\"invalid scenario: "), std::string::npos);
  const std::string report = Slurp(out / "report.md");
  EXPECT_NE(report.find("| " + std::string(kBadCell) + " | failed | invalid scenario: "),
            std::string::npos)
      << report;
  // The scenario as the sweep file names it.
  EXPECT_NE(report.find("| nav_paper_left__method-gauss_newton_subgoal | " +
                        (kSource / "scenes/nav_paper_left.yaml").string() + " |"),
            std::string::npos)
      << report;
}

TEST(SweepCliTest, ResumeRunsOnlyTheLostCellsAndGivesTheSameSummary) {
  const fs::path dir = TempDir("resume");
  const fs::path out = dir / "sweep";
  const std::string sweep =
      "sweep " + WriteNavigationSweep(dir).string() + " --out " + out.string() + " --jobs 2";
  ASSERT_EQ(Trackbed(sweep, dir / "io1").exit_code, 1);
  const std::string first = DeterministicColumns(out / "summary.csv");
  const std::string kept_before = Slurp(out / "cells" / kGoodCells[0] / "cell.json");

  // One cell's folder lost entirely, another's run cut short (no metrics.json).
  fs::remove_all(out / "cells" / kGoodCells[1]);
  fs::remove(out / "cells" / kGoodCells[2] / "run" / "metrics.json");
  const Result again = Trackbed(sweep, dir / "io2");
  EXPECT_EQ(again.exit_code, 1);
  // The failed cell has no result either and runs again (and fails again).
  EXPECT_NE(again.stderr_text.find("4 cells, 1 finished already, 3 to run"), std::string::npos)
      << again.stderr_text;
  // The finished cell was not touched; the lost ones ran again.
  EXPECT_EQ(Slurp(out / "cells" / kGoodCells[0] / "cell.json"), kept_before);
  EXPECT_EQ(CellJson(out, kGoodCells[1])["status"], "ok");
  EXPECT_EQ(CellJson(out, kGoodCells[2])["status"], "ok");
  EXPECT_EQ(DeterministicColumns(out / "summary.csv"), first);

  // Nothing left to do: nothing runs, but the failed cell is retried.
  const Result third = Trackbed(sweep, dir / "io3");
  EXPECT_NE(third.stderr_text.find("4 cells, 3 finished already, 1 to run"), std::string::npos)
      << third.stderr_text;
  EXPECT_EQ(Slurp(out / "cells" / kGoodCells[0] / "cell.json"), kept_before);
}

TEST(SweepCliTest, ReportRebuildsTheSameFilesFromTheCells) {
  const fs::path dir = TempDir("report");
  const fs::path out = dir / "sweep";
  ASSERT_EQ(Trackbed("sweep " + WriteNavigationSweep(dir).string() + " --out " + out.string(),
                     dir / "io1")
                .exit_code,
            1);
  const std::vector<std::string> files = {"summary.csv", "summary.json", "aggregates.csv",
                                          "report.md", "plots/navigation_success.png"};
  std::vector<std::string> before;
  for (const std::string& f : files) {
    before.push_back(Slurp(out / f));
    fs::remove(out / f);
  }
  const Result r = Trackbed("report " + out.string(), dir / "io2");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stdout_text.find("4 cells (3 ok, 1 failed"), std::string::npos) << r.stdout_text;
  for (std::size_t k = 0; k < files.size(); ++k) {
    EXPECT_EQ(Slurp(out / files[k]), before[k]) << files[k] << " differs";
  }

  // `sweep-cell DIR i` (a batch scheduler's task) reruns one lost cell; the report then
  // reads as before.
  fs::remove_all(out / "cells" / kGoodCells[1]);
  const Result cell = Trackbed("sweep-cell " + out.string() + " 1", dir / "io3");
  EXPECT_EQ(cell.exit_code, 0) << cell.stderr_text;
  EXPECT_EQ(CellJson(out, kGoodCells[1])["status"], "ok");
  EXPECT_EQ(Trackbed("sweep-cell " + out.string() + " 2", dir / "io4").exit_code, 1);
  ASSERT_EQ(Trackbed("report " + out.string(), dir / "io5").exit_code, 0);
  EXPECT_EQ(Slurp(out / "report.md"), before[3]);
  const Result no_folder = Trackbed("report " + (dir / "nothing").string(), dir / "io6");
  EXPECT_EQ(no_folder.exit_code, 2);
  EXPECT_NE(no_folder.stderr_text.find("not a sweep folder"), std::string::npos);
}

TEST(SweepCliTest, BadSweepFilesAndFoldersStopBeforeAnythingRuns) {
  const fs::path dir = TempDir("bad");
  std::ofstream(dir / "bad.yaml") << "scenarios: [nowhere.yaml]\nseeds: [1]\n";
  const Result r = Trackbed(
      "sweep " + (dir / "bad.yaml").string() + " --out " + (dir / "out").string(), dir / "io1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.stderr_text, "trackbed sweep: " + (dir / "bad.yaml").string() +
                               ": scenarios[0]: no such file: " + (dir / "nowhere.yaml").string() +
                               "\n");

  // A folder holding another sweep (other fixed overrides) is refused.
  const fs::path out = dir / "sweep";
  const fs::path nav = WriteNavigationSweep(dir);
  ASSERT_EQ(Trackbed("sweep " + nav.string() + " --out " + out.string(), dir / "io2").exit_code, 1);
  std::string text = Slurp(nav);
  text.replace(text.find("duration_s=30"), 13, "duration_s=31");
  std::ofstream(nav) << text;
  const Result other = Trackbed("sweep " + nav.string() + " --out " + out.string(), dir / "io3");
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.stderr_text.find("holds another sweep"), std::string::npos) << other.stderr_text;
}

// Where Slurm is not installed (no sbatch, squeue, scontrol on PATH), `--backend slurm`
// fails at once, says what is missing, and writes nothing.
TEST(SweepCliTest, WithoutSlurmTheSlurmBackendFailsAtOnce) {
  const fs::path dir = TempDir("no_slurm");
  const fs::path empty_path = dir / "empty_path";
  fs::create_directories(empty_path);
  const fs::path out = dir / "sweep";
  const std::string saved = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", empty_path.c_str(), 1);
  const Result r = Trackbed(
      "sweep " + WriteNavigationSweep(dir).string() + " --out " + out.string() + " --backend slurm",
      dir / "io");
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.stderr_text,
            "trackbed sweep: --backend slurm: sbatch, squeue, scontrol not found on PATH; is "
            "Slurm installed here (Debian: slurm-client)? Without Slurm, leave out --backend to "
            "run the cells locally\n");
  EXPECT_FALSE(fs::exists(out));

  // Slurm's options without the Slurm backend are a mistake, not ignored.
  const Result local =
      Trackbed("sweep " + WriteNavigationSweep(dir).string() + " --out " + out.string() + " --wait",
               dir / "io2");
  EXPECT_EQ(local.exit_code, 2);
  EXPECT_NE(local.stderr_text.find("are for --backend slurm"), std::string::npos)
      << local.stderr_text;
  EXPECT_FALSE(fs::exists(out));
}

TEST(SweepCliTest, ACellOverItsTimeLimitIsKilledAndReported) {
  const fs::path dir = TempDir("timeout");
  // The whole corridor route with the camera: tens of seconds, far over 0.5 s.
  std::ofstream(dir / "slow.yaml") << "scenarios: [" << (kSource / "scenes/corridor.yaml").string()
                                   << "]\nseeds: [1]\ntimeout_s: 0.5\n";
  const fs::path out = dir / "sweep";
  const Result r =
      Trackbed("sweep " + (dir / "slow.yaml").string() + " --out " + out.string(), dir / "io");
  EXPECT_EQ(r.exit_code, 1);
  const nlohmann::json cell = CellJson(out, "corridor__seed-1");
  EXPECT_EQ(cell["status"], "timed_out");
  EXPECT_EQ(cell["reason"], "no result within timeout_s = 0.5 s; killed");
  EXPECT_TRUE(cell["exit_code"].is_null());
  EXPECT_NE(Slurp(out / "summary.csv").find(",timed_out,no result within"), std::string::npos);
}

// A sweep's cells run the binary the sweep started with, even when the file is
// replaced while it runs (a rebuild during a long sweep): every cell of one summary comes
// from one build. Until 2026-12-03 the cells started whatever the path then held, and
// failed with "cannot start …" while the linker wrote it.
TEST(SweepCliTest, CellsRunTheBinaryTheSweepStartedWithWhenTheFileIsReplaced) {
  const fs::path dir = TempDir("replaced");
  std::ofstream(dir / "nav.yaml") << "name: nav\n"
                                  << "scenarios: ["
                                  << (kSource / "scenes/nav_paper_left.yaml").string() << "]\n"
                                  << "seeds: [1, 2]\n"
                                  << "set: [\"duration_s=30\"]\n"
                                  << "vary:\n"
                                  << "  - {key: navigation.method, values: [gauss_newton_subgoal, "
                                     "potential_field, dwa]}\n";
  // The copy sits beside the real binary, not in the temporary folder, which may be
  // mounted noexec.
  const fs::path copy = fs::path(TRACKBED_BINARY).parent_path() /
                        ("trackbed_replaced_test_" + std::to_string(getpid()));
  fs::copy_file(TRACKBED_BINARY, copy, fs::copy_options::overwrite_existing);
  fs::permissions(copy, fs::perms::owner_all);
  const fs::path out = dir / "sweep";
  pid_t pid = Spawn({"sweep", (dir / "nav.yaml").string(), "--out", out.string(), "--jobs", "1"},
                    dir / "io", copy.string());
  struct Cleanup {  // on a failed assertion too: no stray sweep, no stray file
    pid_t* pid;
    fs::path file;
    ~Cleanup() {
      if (*pid > 0) {
        kill(*pid, SIGKILL);
        waitpid(*pid, nullptr, 0);
      }
      std::error_code ignored;
      fs::remove(file, ignored);
    }
  } cleanup{&pid, copy};
  // Once the first cell has started, the file becomes a program that fails.
  ASSERT_TRUE(WaitForFile(
      out / "cells" / "nav_paper_left__method-gauss_newton_subgoal__seed-1" / "stderr.txt", pid));
  fs::remove(copy);
  std::ofstream(copy) << "#!/bin/sh\necho 'not the sweep binary' >&2\nexit 3\n";
  fs::permissions(copy, fs::perms::owner_all);
  // Cells start one at a time, each a few seconds long: most start after the swap,
  // which is what this test is about.
  const auto started =
      std::distance(fs::directory_iterator(out / "cells"), fs::directory_iterator{});
  ASSERT_LT(started, 6);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  pid = -1;
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << Slurp(dir / "io" / "err");
  int ok = 0;
  for (const auto& entry : fs::directory_iterator(out / "cells")) {
    const nlohmann::json cell = nlohmann::json::parse(Slurp(entry.path() / "cell.json"));
    EXPECT_EQ(cell["status"], "ok") << entry.path() << ": " << cell.dump();
    ok += cell["status"] == "ok" ? 1 : 0;
  }
  EXPECT_EQ(ok, 6);
}

TEST(SweepCliTest, AnInterruptedSweepResumesToTheSameSummaryAsAnUninterruptedOne) {
  const fs::path dir = TempDir("interrupt");
  // The corridor and the park for 3 simulated seconds, two seeds: about a second a cell.
  const std::string ci = (dir / "short.yaml").string();
  std::ofstream(ci) << "name: short\n"
                    << "scenarios: [" << (kSource / "scenes/corridor.yaml").string() << ", "
                    << (kSource / "scenes/outdoor.yaml").string() << "]\n"
                    << "seeds: [1, 2]\n"
                    << "set: [\"duration_s=3\"]\n"
                    << "timeout_s: 300\n";
  const fs::path whole = dir / "whole", cut = dir / "cut";
  const Result uninterrupted =
      Trackbed("sweep " + ci + " --out " + whole.string() + " --jobs 2", dir / "io1");
  ASSERT_EQ(uninterrupted.exit_code, 0) << uninterrupted.stderr_text;

  // One cell at a time; SIGINT as soon as the second cell has started (its stderr.txt
  // is created when it is launched), i.e. while it runs — it takes about a second.
  const pid_t pid = Spawn({"sweep", ci, "--out", cut.string(), "--jobs", "1"}, dir / "io2");
  ASSERT_TRUE(WaitForFile(cut / "cells" / "corridor__seed-2" / "stderr.txt", pid));
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130) << Slurp(dir / "io2" / "err");
  EXPECT_NE(Slurp(dir / "io2" / "err").find("rerun the same command to resume"), std::string::npos);
  EXPECT_EQ(CellJson(cut, "corridor__seed-1")["status"], "ok");
  const nlohmann::json stopped = CellJson(cut, "corridor__seed-2");
  EXPECT_EQ(stopped["status"], "interrupted");
  EXPECT_FALSE(fs::exists(cut / "cells/corridor__seed-2/run/metrics.json"));
  EXPECT_FALSE(fs::exists(cut / "cells/outdoor__seed-2"));  // never started
  EXPECT_NE(Slurp(cut / "summary.csv").find(",pending,"), std::string::npos);

  const Result resumed =
      Trackbed("sweep " + ci + " --out " + cut.string() + " --jobs 2", dir / "io3");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.stderr_text;
  EXPECT_NE(resumed.stderr_text.find("4 cells, 1 finished already, 3 to run"), std::string::npos)
      << resumed.stderr_text;
  EXPECT_EQ(DeterministicColumns(cut / "summary.csv"), DeterministicColumns(whole / "summary.csv"));
  // The report holds no machine-dependent figure: the same bytes.
  EXPECT_EQ(Slurp(cut / "report.md"), Slurp(whole / "report.md"));
  const std::string report = Slurp(whole / "report.md");
  EXPECT_NE(report.find("## Localization: ATE [m] per estimator"), std::string::npos);
  EXPECT_NE(report.find("plots/ate_corridor.png"), std::string::npos);
  EXPECT_TRUE(fs::exists(whole / "plots/ate_outdoor.png"));
}

// A sweep killed with SIGKILL (which it cannot catch) takes its running cell with it,
// and a rerun resumes. Until 2026-12-04 the cell ran on to its end, orphaned.
TEST(SweepCliTest, ASweepKilledOutrightTakesItsCellsWithItAndResumes) {
  const fs::path dir = TempDir("sigkill");
  // The corridor with its camera for 120 simulated seconds: about ten seconds a cell.
  const std::string sweep = (dir / "long.yaml").string();
  std::ofstream(sweep) << "name: long\n"
                       << "scenarios: [" << (kSource / "scenes/corridor.yaml").string() << "]\n"
                       << "seeds: [1, 2]\n"
                       << "set: [\"duration_s=120\"]\n";
  const fs::path out = dir / "sweep";
  pid_t pid = Spawn({"sweep", sweep, "--out", out.string(), "--jobs", "1"}, dir / "io1");
  const std::string cell_run = (out / "cells" / "corridor__seed-1" / "run").string();
  ASSERT_TRUE(WaitForFile(out / "cells" / "corridor__seed-1" / "stderr.txt", pid));
  ASSERT_TRUE(
      Within(std::chrono::seconds(10), [&] { return !ProcessesMentioning(cell_run).empty(); }));
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  ASSERT_EQ(waitpid(pid, nullptr, 0), pid);
  // The cell dies with it, long before its ten seconds are up.
  EXPECT_TRUE(
      Within(std::chrono::seconds(5), [&] { return ProcessesMentioning(cell_run).empty(); }))
      << "cell still running: pid " << ProcessesMentioning(cell_run).front();
  EXPECT_FALSE(fs::exists(out / "cells" / "corridor__seed-1" / "run" / "metrics.json"));

  const Result resumed =
      Trackbed("sweep " + sweep + " --out " + out.string() + " --jobs 2", dir / "io2");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.stderr_text;
  EXPECT_NE(resumed.stderr_text.find("2 cells, 0 finished already, 2 to run"), std::string::npos)
      << resumed.stderr_text;
  EXPECT_EQ(CellJson(out, "corridor__seed-1")["status"], "ok");
  EXPECT_EQ(CellJson(out, "corridor__seed-2")["status"], "ok");
}

// Runs `trackbed ARGS...` from the source folder on a pseudo-terminal (so that the
// sweep draws its bar) and returns all it wrote there.
std::string OnATerminal(const std::vector<std::string>& args) {
  int master = -1;
  const pid_t pid = forkpty(&master, nullptr, nullptr, nullptr);
  if (pid == 0) {
    if (chdir(TRACKBED_SOURCE_DIR) != 0) _exit(127);
    setenv("TERM", "xterm", 1);
    std::vector<char*> argv{const_cast<char*>(TRACKBED_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(TRACKBED_BINARY, argv.data());
    _exit(127);
  }
  EXPECT_GT(pid, 0);
  std::string out;
  char buf[4096];
  for (ssize_t n; (n = read(master, buf, sizeof(buf))) > 0;) out.append(buf, n);  // EIO at the end
  close(master);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  return out;
}

// "m:ss" at `at` in `s`: its length, or 0.
std::size_t MinutesSecondsAt(const std::string& s, std::size_t at) {
  std::size_t k = at;
  while (k < s.size() && std::isdigit(static_cast<unsigned char>(s[k]))) ++k;
  if (k == at || k + 3 > s.size() || s[k] != ':') return 0;
  if (!std::isdigit(static_cast<unsigned char>(s[k + 1])) ||
      !std::isdigit(static_cast<unsigned char>(s[k + 2])))
    return 0;
  return k + 3 - at;
}

TEST(SweepCliTest, TheBarOnATerminalShowsTheTimeLeft) {
  const fs::path dir = TempDir("bar");
  const fs::path file =
      WriteNavigationSweep(dir, "nav3", "gauss_newton_subgoal, potential_field, dwa");
  const std::string out =
      OnATerminal({"sweep", file.string(), "--out", (dir / "sweep").string(), "--jobs", "1"});
  // Before any cell has finished there is no pace to go by.
  EXPECT_NE(out.find("0/3 cells  0 ok  0 not ok  1 running  "), std::string::npos) << out;
  EXPECT_NE(out.find(" -:-- left"), std::string::npos) << out;
  // One at a time: when the first has finished the bar is drawn again as the second
  // starts, with the time left at the first one's pace.
  const std::string after_first = "] 1/3 cells  1 ok  0 not ok  1 running  ";
  const std::size_t at = out.find(after_first);
  ASSERT_NE(at, std::string::npos) << out;
  const std::size_t elapsed = at + after_first.size();
  const std::size_t elapsed_length = MinutesSecondsAt(out, elapsed);
  ASSERT_GT(elapsed_length, 0u) << out.substr(at, 80);
  ASSERT_EQ(out.substr(elapsed + elapsed_length, 2), "  ") << out.substr(at, 80);
  const std::size_t left = elapsed + elapsed_length + 2;
  const std::size_t left_length = MinutesSecondsAt(out, left);
  ASSERT_GT(left_length, 0u) << out.substr(at, 80);
  EXPECT_EQ(out.substr(left + left_length, 5), " left") << out.substr(at, 80);
}

}  // namespace
