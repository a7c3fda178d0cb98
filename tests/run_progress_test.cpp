// The run's progress: the line's figures, one line per tenth when not on a terminal, the
// bar rewritten in place at most four times a second, nothing with `none`; and
// `trackbed run` under a pseudo-terminal (a bar) and into a file (lines, or none).
#include "trackbed/runner/run_progress.h"

#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"

namespace trackbed::runner {
namespace {

namespace fs = std::filesystem;

TEST(RunProgressTest, FormatsSimulatedTimeRealTimeFactorTimeLeftAndDistance) {
  EXPECT_EQ(FormatProgress({612.0, 3600.0, 4.0, 245.34}),
            "  612.0 / 3600.0 s (17 %)  153x real time  0:00:20 left  245.3 m");
  // 8 h at 10x real time with 7 h left: 0:42:00; from 10 km on in km.
  EXPECT_EQ(FormatProgress({3600.0, 28800.0, 360.0, 12345.0}),
            " 3600.0 / 28800.0 s (12 %)  10x real time  0:42:00 left  12.35 km");
  EXPECT_EQ(FormatProgress({0.0, 150.0, 0.0, 0.0}),
            "    0.0 / 150.0 s (0 %)  ?x real time  ? left  0.0 m");
  // A route that outlasts duration_s never shows more than 100 %, nor time below 0.
  EXPECT_EQ(FormatProgress({150.0, 150.0, 50.0, 60.0}),
            "  150.0 / 150.0 s (100 %)  3x real time  0:00:00 left  60.0 m");
  EXPECT_EQ(ParseProgressMode("lines"), ProgressMode::kLines);
  EXPECT_THROW(ParseProgressMode("auto"), std::invalid_argument);
}

// Feeds `progress` a 100 Hz run of `total_s`, 0.5 m/s along x, 20x real time.
std::string Drive(ProgressMode mode, double total_s, int* lines) {
  char* buf = nullptr;
  std::size_t size = 0;
  std::FILE* out = open_memstream(&buf, &size);
  RunProgress progress(mode, total_s, out);
  for (long k = 0; k <= static_cast<long>(total_s * 100.0); ++k) {
    const double t = 0.01 * static_cast<double>(k);
    progress.Sample(t, Eigen::Vector3d(0.5 * t, 0.0, 0.0), t / 20.0);
  }
  progress.Finish();
  *lines = progress.lines();
  std::fclose(out);
  std::string text(buf, size);
  std::free(buf);
  return text;
}

TEST(RunProgressTest, LinesModePrintsOneLinePerTenth) {
  int lines = 0;
  const std::string text = Drive(ProgressMode::kLines, 300.0, &lines);
  EXPECT_EQ(lines, 10);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 10);
  EXPECT_EQ(text.find('\r'), std::string::npos);
  EXPECT_NE(
      text.find("trackbed run:    30.0 / 300.0 s (10 %)  20x real time  0:00:14 left  15.0 m\n"),
      std::string::npos)
      << text;
  EXPECT_NE(text.find("(100 %)"), std::string::npos);
}

TEST(RunProgressTest, ASecondPassCountsItsTenthsAgain) {
  char* buf = nullptr;
  std::size_t size = 0;
  std::FILE* out = open_memstream(&buf, &size);
  RunProgress progress(ProgressMode::kLines, 100.0, out);
  for (int pass = 0; pass < 2; ++pass) {
    for (int k = 0; k <= 10000; ++k) {
      const double t = 0.01 * k;
      // The second pass starts where the first ended: no jump in distance.
      progress.Sample(t, Eigen::Vector3d(0.5 * t + 50.0 * pass, 0.0, 0.0), 10.0 * pass + t / 10.0);
    }
  }
  progress.Finish();
  std::fclose(out);
  const std::string text(buf, size);
  std::free(buf);
  EXPECT_EQ(progress.lines(), 20);
  EXPECT_NE(text.find("(100 %)  10x real time  0:00:00 left  50.0 m\n"), std::string::npos) << text;
  EXPECT_NE(text.find("(100 %)  10x real time  0:00:00 left  100.0 m\n"), std::string::npos)
      << text;
}

TEST(RunProgressTest, BarIsRewrittenInPlaceAtMostFourTimesASecond) {
  int lines = 0;
  // 300 s at 20x: 15 s of wall time, so 60 rewrites and the first.
  const std::string text = Drive(ProgressMode::kBar, 300.0, &lines);
  EXPECT_EQ(lines, 61);
  EXPECT_EQ(text.find('\n'), std::string::npos);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\r'), 61 + 2);  // and Finish's clearing
  EXPECT_EQ(text.back(), '\r');
  EXPECT_EQ(Drive(ProgressMode::kNone, 300.0, &lines), "");
  EXPECT_EQ(lines, 0);
}

// `trackbed run` of a short scene with ARGS under a pseudo-terminal: everything it wrote.
std::string RunUnderPty(const std::string& args) {
  int master = -1;
  const pid_t pid = forkpty(&master, nullptr, nullptr, nullptr);
  if (pid < 0) throw std::runtime_error("forkpty failed");
  if (pid == 0) {
    const std::string cmd =
        std::string("cd '") + TRACKBED_SOURCE_DIR + "' && exec '" + TRACKBED_BINARY + "' " + args;
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  std::string text;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(master, buf, sizeof(buf));
    if (n <= 0) break;  // EIO once the child has closed the terminal
    text.append(buf, static_cast<std::size_t>(n));
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ::close(master);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << text;
  return text;
}

const char* kShortRun =
    "run scenes/outdoor.yaml --set robot.stereo.enabled=false --set duration_s=20 "
    "--set outputs.mcap=false";

TEST(RunProgressCliTest, BarOnATerminalLinesOrNothingIntoAFile) {
  const fs::path dir = trackbed::testing_cli::FreshTempDir("trackbed_progress_", "cli");
  const std::string tty = RunUnderPty(std::string(kShortRun) + " --out " + (dir / "a").string());
  // The first state of the bar, then the line cleared before the report.
  EXPECT_NE(tty.find("\r    0.0 / 20.0 s (0 %)"), std::string::npos) << tty;
  EXPECT_NE(tty.find("\rduration reached: 20.0 s simulated"), std::string::npos) << tty;
  EXPECT_EQ(tty.find("trackbed run:    2.0 / 20.0 s"), std::string::npos) << tty;

  auto r = trackbed::testing_cli::RunTrackbed(
      std::string(kShortRun) + " --out " + (dir / "b").string(), dir / "io_b");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(r.stderr_text.find('\r'), std::string::npos);
  int progress_lines = 0;
  for (std::size_t at = 0; (at = r.stderr_text.find(" / 20.0 s (", at)) != std::string::npos; ++at)
    ++progress_lines;
  EXPECT_EQ(progress_lines, 10) << r.stderr_text;

  r = trackbed::testing_cli::RunTrackbed(
      std::string(kShortRun) + " --no-progress --out " + (dir / "c").string(), dir / "io_c");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(r.stderr_text.find(" / 20.0 s ("), std::string::npos) << r.stderr_text;
  EXPECT_EQ(std::count(r.stderr_text.begin(), r.stderr_text.end(), '\n'), 1) << r.stderr_text;
}

}  // namespace
}  // namespace trackbed::runner
