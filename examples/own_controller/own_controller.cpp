// A user's own stack in trackbed's closed loop, from C++: a Commander that steers
// towards the scenario's waypoints with a proportional heading controller on the
// built-in fused estimate, and an estimator of its own — dead reckoning from encoder
// counts and gyro rates, fed by the loop's observers — whose estimate is scored
// beside the built-in ones (metrics.json `estimators.own`).
//
//   own_controller SCENARIO.yaml OUT_DIR [DURATION_S]
//
// Prints every estimator's error; exits 1 when the run did not complete or the own
// estimate strayed more than 0.5 m (RMS) from the true path, 2 on bad input.
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/runner/closed_loop.h"
#include "trackbed/runner/commander.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace {

using trackbed::runner::Commander;
using trackbed::runner::ControlInput;
using trackbed::runner::ControlOutput;

// Steers towards the next waypoint (closed loop) at a constant speed, from the
// localization stack's fused estimate.
class WaypointCommander : public Commander {
 public:
  WaypointCommander(std::vector<Eigen::Vector2d> waypoints, double half_gauge_m)
      : waypoints_(std::move(waypoints)), half_gauge_m_(half_gauge_m) {}

  double period_s() const override { return 0.05; }
  bool needs_estimates() const override { return true; }

  ControlOutput Update(const ControlInput& input) override {
    const Eigen::Isometry3d T =
        input.estimates ? input.estimates->fused() : input.T_world_body;  // no stack: truth
    const Eigen::Vector2d p = T.translation().head<2>();
    while ((waypoints_[next_] - p).norm() < 0.6) next_ = (next_ + 1) % waypoints_.size();
    const Eigen::Vector2d to = waypoints_[next_] - p;
    const double yaw = std::atan2(T.linear()(1, 0), T.linear()(0, 0));
    const double error = std::remainder(std::atan2(to.y(), to.x()) - yaw, 2 * M_PI);
    const double v = 0.4, w = 2.0 * error;
    ControlOutput out;
    out.tracks = {v - w * half_gauge_m_, v + w * half_gauge_m_};
    return out;
  }

 private:
  std::vector<Eigen::Vector2d> waypoints_;
  double half_gauge_m_;
  std::size_t next_ = 1;
};

// Dead reckoning: encoder distance along the heading integrated from the gyro.
class DeadReckoning {
 public:
  explicit DeadReckoning(const trackbed::scenario::Scenario& s)
      : x_(s.robot.start.x_m),
        y_(s.robot.start.y_m),
        yaw_(s.robot.start.yaw_deg * M_PI / 180.0),
        m_per_tick_(2 * M_PI * s.robot.vehicle.sprocket_radius_m / s.robot.encoders.ticks_per_rev) {
  }

  // The loop's observers feed it while the run goes.
  trackbed::runner::RunObservers Observers() {
    trackbed::runner::RunObservers o;
    o.on_imu = [this](const trackbed::robot::ImuSample& s) {
      if (imu_t_ >= 0) yaw_ += s.gyro_radps.z() * (s.t_s - imu_t_);
      imu_t_ = s.t_s;
    };
    o.on_sample = [this](const trackbed::runner::RunSample& s) {
      if (has_ticks_) {
        const double d = m_per_tick_ * 0.5 *
                         static_cast<double>((s.ticks[0] - ticks_[0]) + (s.ticks[1] - ticks_[1]));
        x_ += d * std::cos(yaw_);
        y_ += d * std::sin(yaw_);
      }
      ticks_[0] = s.ticks[0];
      ticks_[1] = s.ticks[1];
      has_ticks_ = true;
    };
    return o;
  }

  Eigen::Matrix4d T_world_body() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.rotate(Eigen::AngleAxisd(yaw_, Eigen::Vector3d::UnitZ()));
    T.translation() = Eigen::Vector3d(x_, y_, 0.0);
    return T.matrix();
  }

 private:
  double x_, y_, yaw_, m_per_tick_;
  double imu_t_ = -1.0;
  long long ticks_[2] = {0, 0};
  bool has_ticks_ = false;
};

int Run(const std::string& scenario_path, const std::string& out, const std::string& duration) {
  namespace tb = trackbed;
  // Driven by our own commander: the scenario needs no `drive` section.
  const tb::scenario::Scenario s = tb::scenario::LoadScenario(
      scenario_path, {{"duration_s", duration}}, tb::scenario::DriveSource::kExternal);
  std::vector<Eigen::Vector2d> waypoints = s.drive.waypoints;
  if (waypoints.size() < 2) waypoints = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  DeadReckoning own(s);
  tb::runner::ClosedLoopOptions options;
  options.dir = out;
  options.commander =
      std::make_unique<WaypointCommander>(waypoints, 0.5 * s.robot.vehicle.track_gauge_m);
  options.observers = own.Observers();
  tb::runner::ClosedLoop loop(s, std::move(options));
  loop.Start();
  while (!loop.done()) {
    loop.Step();
    loop.ReportEstimate("own", own.T_world_body());
  }
  const tb::runner::RunMetrics m = loop.Finish();
  std::printf("%s after %.1f s, %.2f m driven; run folder %s\n", m.stop_reason.c_str(),
              m.sim_time_s, m.distance_m, out.c_str());
  for (const auto& [name, e] : m.estimators) {
    std::printf("%-22s ATE %.3f m, final error %.3f m\n", name.c_str(), e.ate_rmse_m,
                e.final_error_m);
  }
  const auto it = m.estimators.find("own");
  return m.completed && it != m.estimators.end() && it->second.ate_rmse_m < 0.5 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: own_controller SCENARIO.yaml OUT_DIR [DURATION_S]\n");
    return 2;
  }
  try {
    return Run(argv[1], argv[2], argc == 4 ? argv[3] : "20");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "own_controller: %s\n", e.what());
    return 2;
  }
}
