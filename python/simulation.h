// The Python module's simulation, in plain C++: a closed-loop run driven one control
// period at a time with track speeds from outside (an ExternalCommander), its run
// folder written to a temporary folder and moved where finish() says. The bindings
// (module.cpp) only convert to and from Python.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "trackbed/runner/closed_loop.h"
#include "trackbed/runner/commander.h"
#include "trackbed/scenario/scenario.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::python {

/// A commander whose track speeds are set from outside before each call.
class ExternalCommander : public runner::Commander {
 public:
  explicit ExternalCommander(double period_s) : period_s_(period_s) {}
  double period_s() const override { return period_s_; }
  runner::ControlOutput Update(const runner::ControlInput& /*input*/) override {
    runner::ControlOutput out;
    out.tracks = tracks_;
    return out;
  }
  void Set(double left_mps, double right_mps) { tracks_ = {left_mps, right_mps}; }

 private:
  double period_s_;
  kinematics::TrackSpeeds tracks_;
};

/// The overrides of a run: `key=value` texts (ParseOverride), then the seed if given.
std::vector<scenario::Override> Overrides(const std::vector<std::string>& key_equals_value,
                                          const std::optional<std::uint64_t>& seed);

/// One run driven from outside. Not copyable.
class Simulation {
 public:
  /// Loads the scenario (DriveSource::kExternal: no `drive` section needed; the control
  /// period is 1 / drive.rate_hz), starts the run, writing its folder into `out` or,
  /// when `out` is empty, into a fresh temporary folder. `images`: Step() returns the
  /// stereo pairs. Throws scenario::ScenarioError for a bad scenario or override, and
  /// for teach & repeat (two passes: run those with trackbed run).
  Simulation(const std::string& scenario_path, const std::vector<scenario::Override>& overrides,
             const std::string& out, bool images);
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;
  /// Removes the temporary folder of a run never finished into `out`.
  ~Simulation();

  bool done() const { return finished_ || loop_->done(); }
  bool finished() const { return finished_; }
  /// Commands the tracks for one control period and simulates it. Throws
  /// std::invalid_argument for non-finite speeds, std::logic_error once done().
  const runner::StepResult& Step(double left_mps, double right_mps);
  /// The stack's estimate `name` (wheel, wheel_noslip, vo, fused, ekf) now; none when
  /// estimation is off or the estimator needs the camera and it is off. Throws
  /// std::invalid_argument for an unknown name.
  std::optional<Eigen::Matrix4d> Estimate(const std::string& name);
  /// runner::ClosedLoop::ReportEstimate.
  void ReportEstimate(const std::string& name, const Eigen::Matrix4d& T_world_body);
  /// Ends the run: writes plots and metrics.json, moves the folder to `out` when given
  /// (files of an earlier run there are replaced), and returns metrics.json's text.
  std::string Finish(const std::string& out);

  const scenario::Scenario& scenario() const { return scenario_; }
  /// The resolved scenario (every key, defaults included) as JSON text.
  std::string ScenarioJson() const;
  /// The loop's time: the end of the last step [s].
  double t_s() const { return t_s_; }

 private:
  scenario::Scenario scenario_;
  std::filesystem::path dir_;
  bool temporary_dir_ = false;
  ExternalCommander* commander_ = nullptr;  // owned by loop_
  std::unique_ptr<runner::ClosedLoop> loop_;
  bool finished_ = false;
  double t_s_ = 0.0;
};

/// `trackbed run`: runs the scenario into `out` and returns metrics.json's text.
std::string RunToFolder(const std::string& scenario_path,
                        const std::vector<scenario::Override>& overrides, const std::string& out);

}  // namespace trackbed::python
