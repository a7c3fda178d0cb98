// The straight calibration run that gives the wheel odometry its sprocket radii, as
// one calibrates a real robot (Borenstein & Feng 1996, UMBmark's Ed and a surveyed
// distance): drive straight on a hard floor, survey where the robot ended, divide by
// what the encoders counted. The run is scenes/calibration/straight_line.yaml with
// the robot under calibration; `trackbed run` on that file (with the same robot keys)
// repeats it, and its vehicle_calibration.json is the result (docs/calibration.md).
#pragma once

#include "trackbed/common/robot_calibration.h"
#include "trackbed/runner/run_sample.h"
#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

/// scenes/calibration/straight_line.yaml with `scenario`'s robot as built (its realism,
/// imperfections and as_built_seed; no camera, no range sensor) and no estimation: 10 m
/// at 0.4 m/s on a flat hard floor, 25 s.
scenario::Scenario StraightRunScenario(const scenario::Scenario& scenario);

/// Fits each track's effective sprocket radius to a straight run's encoder counts and
/// surveyed end pose (ground truth, exactly). With θ_l, θ_r the sprocket angles, s the
/// path length (the chord D over the arc of heading change Δψ: s = D·(Δψ/2)/sin(Δψ/2))
/// and B_eff = χ·B the effective gauge, the radii solve r_l·θ_l + r_r·θ_r = 2s (the
/// distance) and r_r·θ_r − r_l·θ_l = Δψ·B_eff (the heading change).
class StraightRunFit {
 public:
  StraightRunFit(int ticks_per_rev, double track_gauge_m, double icr_expansion);
  void Add(const RunSample& sample);
  /// The fitted calibration (gauge and χ as given). Throws std::runtime_error when the
  /// run drove less than 1 m.
  calibration::VehicleCalibration Result() const;

 private:
  int ticks_per_rev_;
  double gauge_m_, chi_;
  bool has_first_ = false;
  RunSample first_, last_;
};

}  // namespace trackbed::runner
