// The Python module's simulation (see simulation.h).
#include "simulation.h"

#include <stdlib.h>

#include <cmath>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "trackbed/common/archive.h"
#include "trackbed/runner/run_folder.h"
#include "trackbed/runner/run_scenario.h"

namespace trackbed::python {
namespace {

namespace fs = std::filesystem;

// A fresh, empty folder under the system's temporary folder.
fs::path TemporaryFolder() {
  std::string pattern = (fs::temp_directory_path() / "trackbed_run_XXXXXX").string();
  if (!mkdtemp(pattern.data())) {
    throw std::runtime_error("cannot create a temporary run folder in " +
                             fs::temp_directory_path().string() + ": " +
                             std::generic_category().message(errno));
  }
  return pattern;
}

// Moves the run folder `from` to `to`: renamed when `to` does not exist and is on the
// same file system, else copied over it (replacing an earlier run's files) and removed.
void MoveFolder(const fs::path& from, const fs::path& to) {
  std::error_code error;
  if (!fs::exists(to)) {
    if (to.has_parent_path()) fs::create_directories(to.parent_path());
    fs::rename(from, to, error);
    if (!error) return;
  }
  fs::create_directories(to);
  fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  fs::remove_all(from);
}

}  // namespace

std::vector<scenario::Override> Overrides(const std::vector<std::string>& key_equals_value,
                                          const std::optional<std::uint64_t>& seed) {
  std::vector<scenario::Override> overrides;
  for (const std::string& s : key_equals_value) overrides.push_back(scenario::ParseOverride(s));
  if (seed) overrides.push_back({"seed", std::to_string(*seed)});
  return overrides;
}

Simulation::Simulation(const std::string& scenario_path,
                       const std::vector<scenario::Override>& overrides, const std::string& out,
                       bool images)
    : scenario_(
          scenario::LoadScenario(scenario_path, overrides, scenario::DriveSource::kExternal)) {
  if (scenario_.teach_repeat.enabled) {
    throw scenario::ScenarioError(scenario_path, "teach_repeat.enabled",
                                  "teach & repeat runs two passes of its own: run it with "
                                  "trackbed.run, or set it false to drive from Python");
  }
  if (out.empty()) {
    dir_ = TemporaryFolder();
    temporary_dir_ = true;
  } else {
    dir_ = out;
  }
  runner::ClosedLoopOptions options;
  options.dir = dir_;
  auto commander = std::make_unique<ExternalCommander>(1.0 / scenario_.drive.rate_hz);
  commander_ = commander.get();
  options.commander = std::move(commander);
  options.step_images = images && scenario_.robot.stereo.enabled;
  loop_ = std::make_unique<runner::ClosedLoop>(scenario_, std::move(options));
  loop_->Start();
}

Simulation::~Simulation() {
  loop_.reset();
  std::error_code ignored;
  if (temporary_dir_) fs::remove_all(dir_, ignored);
}

const runner::StepResult& Simulation::Step(double left_mps, double right_mps) {
  if (finished_) throw std::logic_error("step: the run is finished");
  if (loop_->done()) {
    throw std::logic_error("step: the run is done (t = " + std::to_string(t_s_) +
                           " s); call finish()");
  }
  if (!std::isfinite(left_mps) || !std::isfinite(right_mps)) {
    throw std::invalid_argument("step: left_mps and right_mps must be finite (got " +
                                std::to_string(left_mps) + ", " + std::to_string(right_mps) + ")");
  }
  commander_->Set(left_mps, right_mps);
  const runner::StepResult& r = loop_->Step();
  t_s_ = r.t_s;
  return r;
}

std::optional<Eigen::Matrix4d> Simulation::Estimate(const std::string& name) {
  if (finished_) throw std::logic_error("localization: the run is finished");
  const bool camera = scenario_.robot.stereo.enabled;
  const bool known =
      name == "wheel" || name == "wheel_noslip" || name == "ekf" || name == "vo" || name == "fused";
  if (!known) {
    throw std::invalid_argument("localization: no estimator '" + name +
                                "' (known: wheel, wheel_noslip, vo, fused, ekf)");
  }
  const estimation::LocalizationStack* stack = loop_->localization();
  if (!stack || ((name == "vo" || name == "fused") && !camera)) return std::nullopt;
  if (name == "wheel") return stack->wheel_odometry().matrix();
  if (name == "wheel_noslip") return stack->wheel_odometry_noslip().matrix();
  if (name == "ekf") return stack->ekf().matrix();
  if (name == "vo") return stack->visual_odometry().matrix();
  return stack->fused().matrix();
}

void Simulation::ReportEstimate(const std::string& name, const Eigen::Matrix4d& T_world_body) {
  if (finished_) throw std::logic_error("report_estimate: the run is finished");
  loop_->ReportEstimate(name, T_world_body);
}

std::string Simulation::ScenarioJson() const {
  return archive::ToJson(archive::ParseYaml(scenario::ScenarioToYaml(scenario_)));
}

std::string Simulation::Finish(const std::string& out) {
  if (finished_) throw std::logic_error("finish: called twice");
  finished_ = true;
  const runner::RunMetrics m = loop_->Finish();
  if (!out.empty() &&
      fs::absolute(out).lexically_normal() != fs::absolute(dir_).lexically_normal()) {
    MoveFolder(dir_, out);
    temporary_dir_ = false;
  }
  return runner::MetricsJson(m);
}

std::string RunToFolder(const std::string& scenario_path,
                        const std::vector<scenario::Override>& overrides, const std::string& out) {
  if (out.empty()) throw std::invalid_argument("run: out must name the run folder");
  return runner::MetricsJson(
      runner::RunToFolder(scenario::LoadScenario(scenario_path, overrides), out));
}

}  // namespace trackbed::python
