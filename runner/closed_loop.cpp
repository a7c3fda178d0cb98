// The closed loop (see closed_loop.h).
#include "trackbed/runner/closed_loop.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "trackbed/common/skid_steer.h"
#include "trackbed/common/split_mix.h"
#include "trackbed/common/units.h"
#include "trackbed/perception/opencv_views.h"
#include "trackbed/render/camera_exposure.h"
#include "trackbed/render/renderer.h"
#include "trackbed/robot/auto_exposure.h"
#include "trackbed/robot/encoder.h"
#include "trackbed/robot/image_sensor.h"
#include "trackbed/robot/pose_path_carrier.h"
#include "trackbed/robot/tracked_vehicle.h"
#include "trackbed/runner/closed_loop_navigation.h"
#include "trackbed/runner/estimator_scoring.h"
#include "trackbed/runner/localization_options.h"
#include "trackbed/runner/ordered_worker.h"
#include "trackbed/runner/path_driver.h"
#include "trackbed/runner/run_folder.h"
#include "trackbed/runner/wheel_calibration_run.h"
#include "trackbed/sim/sim_clock.h"
#include "trackbed/sim/world.h"

namespace trackbed::runner {
namespace {

// Tasks (encoder samples, gyro samples, stereo frames) the simulation may run ahead of
// the localization stack.
constexpr std::int64_t kMaxTasksAhead = 64;

EstimateSample EstimateAfterEncoders(estimation::LocalizationStack& stack, const RunSample& s,
                                     bool has_camera) {
  stack.AddEncoderSample(s.t_s, s.ticks[0], s.ticks[1]);
  EstimateSample e;
  e.t_s = s.t_s;
  e.wheel_odometry = stack.wheel_odometry();
  e.wheel_odometry_noslip = stack.wheel_odometry_noslip();
  e.fused = stack.fused();
  e.ekf = stack.ekf();
  e.has_camera = has_camera;
  e.slip = stack.slip();
  return e;
}

LocalizationFrame LocalizeStereoFrame(estimation::LocalizationStack& stack, double t_s,
                                      bool blackout, const GrayImage& left,
                                      const GrayImage& right) {
  LocalizationFrame lf;
  lf.t_s = t_s;
  lf.camera_blackout = blackout;
  lf.report = stack.AddStereoFrame(t_s, perception::AsCvMat(left), perception::AsCvMat(right));
  lf.visual_odometry = stack.visual_odometry();
  return lf;
}

// Peak resident set size of this process so far [MB].
double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

// Wall-clock seconds of the main thread's stages.
struct StageTimes {
  double setup_s = 0.0, physics_s = 0.0, control_s = 0.0, sensing_s = 0.0, io_s = 0.0;
};

// Runs `f`, adding its wall-clock time to *seconds.
template <class F>
auto Timed(double* seconds, F&& f) {
  const auto start = std::chrono::steady_clock::now();
  struct Add {
    double* seconds;
    std::chrono::steady_clock::time_point start;
    ~Add() {
      *seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
  } add{seconds, start};
  return f();
}

// The camera's stages after rendering: the sensor model (exposure, gain, noise keyed
// by seed, frame and camera: in electrons when `sensors` are given, else in grey
// levels), then the blackout fault, on a rendered pair.
struct CameraPipeline {
  const robot::StereoRigOptions& stereo;
  const robot::ImageSensor* sensors;  // left, right; null: the grey-level model
  double exposure;                    // light on the sensor relative to the render's
  double gain;                        // analog gain (auto-exposure)
  bool clipped_render;                // exposed before the render's 8 bits clipped
  std::uint64_t noise_seed;
  std::int64_t frame_index;
  bool blackout;

  void Apply(GrayImage* left, GrayImage* right) const {
    const auto frame = static_cast<std::uint64_t>(frame_index);
    if (sensors) {
      sensors[0].Apply(exposure, noise_seed, frame, left, gain, clipped_render);
      sensors[1].Apply(exposure, noise_seed, frame, right, gain, clipped_render);
    } else {
      robot::ApplySensorModel(exposure * gain, stereo.noise_std, noise_seed, frame, 0, left);
      robot::ApplySensorModel(exposure * gain, stereo.noise_std, noise_seed, frame, 1, right);
    }
    if (blackout) {
      std::fill(left->pixels.begin(), left->pixels.end(), 0);
      std::fill(right->pixels.begin(), right->pixels.end(), 0);
    }
  }
};

// The observers, each call's time added to *io_s (they write the run folder).
RunObservers TimedObservers(const RunObservers& o, double* io_s) {
  return CombineObservers(o, o, [io_s](const auto& f, const auto&) -> std::decay_t<decltype(f)> {
    if (!f) return {};
    return [f, io_s](const auto& x) { Timed(io_s, [&] { f(x); }); };
  });
}

// The body's pose `dt_s` later at constant velocity (dt small: a camera's time offset).
render::BodyMotion Advanced(const render::BodyMotion& m, double dt_s) {
  if (dt_s == 0.0) return m;
  render::BodyMotion out = m;
  out.T_world_body = m.PoseAfter(dt_s);
  return out;
}

// The carrier of a pose path: the drive's curve, the robot's weight and footprint.
robot::PosePathOptions PosePathOf(const scenario::Scenario& scenario) {
  const robot::TrackedVehicleOptions& v = scenario.robot.vehicle;
  robot::PosePathOptions o;
  o.waypoints = scenario.drive.waypoints;
  o.closed = scenario.drive.closed;
  o.laps = scenario.drive.laps;
  o.speed_mps = scenario.drive.speed_mps;
  o.body_height_m = v.com_height_m;
  o.footprint_length_m = v.track_contact_length_m;
  o.footprint_width_m = v.track_gauge_m;
  o.mass_kg = v.mass_kg;
  o.stations_per_track =
      v.station_x_m.empty() ? v.road_wheels_per_track : static_cast<int>(v.station_x_m.size());
  return o;
}

// The straight calibration run of `scenario`'s robot, in closed loop.
calibration::VehicleCalibration CalibrateWheels(const scenario::Scenario& scenario) {
  StraightRunFit fit(scenario.robot.encoders.ticks_per_rev, scenario.robot.vehicle.track_gauge_m,
                     scenario.estimation.icr_expansion);
  RunObservers observers;
  observers.on_sample = [&fit](const RunSample& s) { fit.Add(s); };
  const std::string what =
      "the straight calibration run of the robot (robot.imperfections.wheel_calibration: "
      "straight_run; scenes/calibration/straight_line.yaml)";
  try {
    const RunMetrics m = RunClosedLoop(StraightRunScenario(scenario), observers);
    if (!m.completed) throw std::runtime_error("it stopped: " + m.stop_reason);
    return fit.Result();
  } catch (const std::exception& e) {
    throw std::runtime_error(what + ": " + e.what());
  }
}

// The estimators' names a reported estimate may not take: the stack's, and the TUM
// file of ground truth.
constexpr const char* kTakenNames[] = {"wheel_odometry", "wheel_odometry_noslip", "ekf",
                                       "fused",          "visual_odometry",       "ground_truth"};

// Throws std::invalid_argument unless `name` may name a reported estimator.
void CheckEstimatorName(const std::string& name) {
  const auto fail = [&name](const std::string& why) {
    throw std::invalid_argument("estimate \"" + name + "\": " + why);
  };
  if (name.empty()) fail("the name must not be empty");
  for (const char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) fail("the name may hold only letters, digits, '_' and '-'");
  }
  for (const char* taken : kTakenNames) {
    if (name == taken) fail("the name is taken (the built-in estimators' and ground_truth)");
  }
}

// Throws std::invalid_argument unless `T` is a rigid transform: finite, the last row
// 0 0 0 1, the rotation orthonormal (to 1e-6) with determinant +1.
void CheckRigid(const std::string& name, const Eigen::Matrix4d& T) {
  const auto fail = [&name](const std::string& why) {
    throw std::invalid_argument("estimate \"" + name + "\": not a rigid transform: " + why);
  };
  if (!T.allFinite()) fail("it has non-finite entries");
  if (T.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) fail("the last row is not 0 0 0 1");
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (off > 1e-6)
    fail("the rotation is not orthonormal (|R^T R - I| = " + std::to_string(off) + ")");
  if (R.determinant() < 0) fail("the rotation is a reflection (determinant -1)");
}

}  // namespace

// The run's state: what RunClosedLoop's locals were, kept between Steps.
class ClosedLoop::Impl {
 public:
  Impl(const scenario::Scenario& scenario, ClosedLoopOptions options)
      : scenario_(scenario), options_(std::move(options)) {
    scenario_.Validate(drive_source());
    if (options_.commander && scenario_.navigation.enabled) {
      throw std::invalid_argument(
          "navigation.enabled: a run driven by a given commander does not navigate; set it false");
    }
  }

  void Start();
  const StepResult& Step();
  RunMetrics Finish();
  bool done() const { return done_; }
  const estimation::LocalizationStack* localization();
  void ReportEstimate(const std::string& name, const Eigen::Matrix4d& T_world_body);
  // Writes metrics.json saying why the run failed (when there is a folder).
  void RecordFailure(const std::exception& e);
  scenario::DriveSource drive_source() const {
    return options_.commander ? scenario::DriveSource::kExternal : scenario::DriveSource::kScenario;
  }

 private:
  using ImagePair = std::pair<GrayImage, GrayImage>;

  void BuildWorld();
  void BuildCameras();
  void BuildSoftware();
  void BuildSchedule();
  // One physics step and whatever fires in it; true when the commander was called.
  bool StepOnce(StepResult* out);
  bool SampleEncoders(const robot::ChassisState& truth, StepResult* out);
  bool TakeStereoFrame(const robot::ChassisState& truth, StepResult* out);
  ImagePair* FreePair();
  void SubmitFrame(ImagePair* pair, const Eigen::Isometry3d& T_world_body, double t_s,
                   const CameraPipeline& finish, bool finish_on_worker);
  void SampleImu(const robot::ChassisState& truth, StepResult* out);
  void Scan(const robot::ChassisState& truth, StepResult* out);
  // Calls the commander and commands the tracks; false when it ended the run.
  bool Control(const robot::ChassisState& truth, const cv::Mat* left_image);
  void Stop(std::string reason) {
    stop_reason_ = std::move(reason);
    done_ = true;
  }
  RunMetrics Metrics();
  void ReleaseSimulation();

  scenario::Scenario scenario_;
  ClosedLoopOptions options_;
  RobotBuild robot_;
  std::unique_ptr<RunFolderWriter> folder_;
  bool started_ = false, finished_ = false, done_ = false, failed_ = false, time_ran_out_ = false;
  std::string stop_reason_ = "duration reached";
  std::chrono::steady_clock::time_point wall_start_;
  // Wall-clock seconds per stage (metrics.json `timing`), on this thread; the
  // localization stack's own time is the worker's busy time.
  StageTimes times_;
  RunObservers observers_;
  StepResult step_;  // Step()'s result, reused

  std::unique_ptr<sim::World> world_;
  // The tracked vehicle in the physics, or the carrier of a pose path.
  std::unique_ptr<robot::Platform> vehicle_;
  const robot::PosePathCarrier* carrier_ = nullptr;  // vehicle_, when it is one
  std::unique_ptr<robot::Imu> imu_;
  Commander* commander_ = nullptr;
  std::int64_t last_ticks_[2] = {0, 0};
  // Encoder dropouts: the shaft's count at the last sample, and the counts lost so far.
  std::int64_t last_shaft_ticks_[2] = {0, 0}, lost_ticks_[2] = {0, 0};
  std::optional<robot::StereoRig> rig_;
  std::unique_ptr<render::Renderer> renderer_;
  GrayImage left_image_, right_image_;
  std::unique_ptr<render::CameraExposure> exposures_[2];  // left, right
  std::vector<robot::ImageSensor> image_sensors_;         // left, right; or none
  std::optional<robot::AutoExposure> auto_exposure_;      // when on
  std::unique_ptr<estimation::LocalizationStack> stack_;
  EstimatorScoring estimates_;
  double estimation_wall_s_ = 0.0;
  // With the camera on, the localization stack runs on a second thread, fed the same
  // samples in the same order as it would be inline (identical results), while this
  // thread simulates and renders ahead. The worker gets copies of each stereo pair in
  // buffers that come back to `free_pairs_` when the frame's delivery runs here, so no
  // frame allocates images (declared before the worker, which may still hold some when
  // it is destroyed).
  std::vector<std::unique_ptr<ImagePair>> image_pairs_;
  std::vector<ImagePair*> free_pairs_;
  std::unique_ptr<OrderedWorker> worker_;
  std::unique_ptr<robot::RangeSensor> range_sensor_;
  std::uint64_t scan_index_ = 0;
  std::int64_t stereo_index_ = 0;
  double render_wall_s_ = 0.0;
  double sensor_model_wall_s_ = 0.0;       // on this thread
  double sensor_model_on_worker_s_ = 0.0;  // written by the worker, read after Drain()
  std::uint64_t noise_seed_ = 0;
  std::unique_ptr<MetricsAccumulator> metrics_;
  std::unique_ptr<sim::SimClock> clock_;
  std::int64_t encoder_period_ = 1, imu_period_ = 1, camera_period_ = 1, scan_period_ = 1;
  std::int64_t control_period_ = 1, end_step_ = 0;
  Eigen::Vector3d v_at_last_imu_ = Eigen::Vector3d::Zero();
  std::map<std::string, double> reported_t_;  // reported estimator → time of its last estimate
};

void ClosedLoop::Impl::Start() {
  if (started_) throw std::logic_error("ClosedLoop::Start: called twice");
  started_ = true;
  wall_start_ = std::chrono::steady_clock::now();
  RunObservers observers = options_.observers;
  if (!options_.dir.empty()) folder_ = std::make_unique<RunFolderWriter>(scenario_, options_.dir);
  robot_ = options_.robot ? *options_.robot : BuildRunRobot(scenario_);
  if (folder_) {
    folder_->WriteCalibration(scenario_, robot_);
    observers = Chained(folder_->observers(), observers);
  }
  observers_ = TimedObservers(observers, &times_.io_s);
  Timed(&times_.setup_s, [&] {
    BuildWorld();
    BuildSoftware();
    BuildSchedule();
  });
}

void ClosedLoop::Impl::BuildWorld() {
  const scenario::RobotSpec& rs = scenario_.robot;
  world_ = std::make_unique<sim::World>(
      scenario_.scene.world,
      sim::Terrain(scenario_.scene.terrain, split_mix::Stream(scenario_.seed, 0)),
      scenario::SceneObjects(scenario_));
  if (scenario_.CarriedOnPosePath(drive_source())) {
    auto carrier = std::make_unique<robot::PosePathCarrier>(
        PosePathOf(scenario_), &world_->terrain(), robot_.truth.vehicle,
        scenario_.scene.world.gravity_mps2);
    carrier_ = carrier.get();
    vehicle_ = std::move(carrier);
  } else {
    vehicle_ = std::make_unique<robot::TrackedVehicle>(
        rs.vehicle, world_.get(), rs.start.x_m, rs.start.y_m, units::Radians(rs.start.yaw_deg),
        &robot_.truth.vehicle);
  }
  imu_ = std::make_unique<robot::Imu>(rs.imu, scenario_.scene.world.gravity_mps2,
                                      split_mix::Stream(scenario_.seed, 1), &robot_.truth.imu);
  if (rs.stereo.enabled) BuildCameras();
  if (rs.range_sensor.enabled) {
    range_sensor_ =
        std::make_unique<robot::RangeSensor>(rs.range_sensor, split_mix::Stream(scenario_.seed, 4));
  }
  noise_seed_ = split_mix::Stream(scenario_.seed, 3);
  metrics_ = std::make_unique<MetricsAccumulator>(
      rs.vehicle.sprocket_radius_m, rs.vehicle.track_gauge_m, rs.encoders.ticks_per_rev);
}

// The stereo rig as built, one renderer for both cameras, sized for the wider of their
// renders through the lens, and each camera's exposure.
void ClosedLoop::Impl::BuildCameras() {
  const scenario::RobotSpec& rs = scenario_.robot;
  const robot::StereoRigOptions stereo = robot::WithCameraEffectsResolved(rs.stereo, rs.realism);
  rig_.emplace(stereo, *robot_.truth.stereo);
  // Four pixels of margin: what a rolling shutter or blur warp may reach past the edge;
  // the render drawn `supersampling` times as finely.
  const int margin = stereo.distortion->is_zero() && *stereo.rolling_shutter.line_delay_s == 0 &&
                             stereo.exposure_time_s == 0
                         ? 0
                         : 4;
  const geometry::PinholeCamera left = render::Supersampled(
      render::RenderCameraFor(rig_->intrinsics(), margin), stereo.supersampling);
  const geometry::PinholeCamera right = render::Supersampled(
      render::RenderCameraFor(rig_->right_intrinsics(), margin), stereo.supersampling);
  const int w = std::max(left.width_px, right.width_px);
  const int h = std::max(left.height_px, right.height_px);
  renderer_ = std::make_unique<render::Renderer>(
      *world_, scenario_.scene.appearance, scenario_.scene.occluders,
      split_mix::Stream(scenario_.seed, 2), w, h, stereo.near_m, stereo.far_m);
  const double line_delay = *stereo.rolling_shutter.line_delay_s;
  exposures_[0] = std::make_unique<render::CameraExposure>(
      rig_->intrinsics(), render::GrownTo(left, w, h), stereo.exposure_samples, line_delay);
  exposures_[1] = std::make_unique<render::CameraExposure>(
      rig_->right_intrinsics(), render::GrownTo(right, w, h), stereo.exposure_samples, line_delay);
  if (stereo.auto_exposure.enabled) {
    auto_exposure_.emplace(stereo.auto_exposure, stereo.exposure_time_s);
  }
  if (*stereo.photometric.enabled) {
    const std::uint64_t pattern_seed = split_mix::Stream(scenario_.seed, 6);
    for (int camera = 0; camera < 2; ++camera) {
      image_sensors_.emplace_back(stereo.photometric, stereo.width_px, stereo.height_px,
                                  pattern_seed, camera);
    }
  }
}

// The robot software: the localization stack on the robot's own sensors, and the
// commander (the scenario's own unless one was given).
void ClosedLoop::Impl::BuildSoftware() {
  const scenario::RobotSpec& rs = scenario_.robot;
  if (scenario_.estimation.enabled) {
    const calibration::StereoCalibration* given_stereo =
        rig_ && robot_.given.stereo ? &*robot_.given.stereo : nullptr;
    stack_ = std::make_unique<estimation::LocalizationStack>(
        LocalizationOptionsOf(scenario_, robot_.given), given_stereo,
        vehicle_->chassis().T_world_body);
  }
  if (stack_ && rig_) worker_ = std::make_unique<OrderedWorker>();
  if (!options_.commander) {
    if (scenario_.navigation.enabled) {
      options_.commander = std::make_unique<ClosedLoopNavigation>(scenario_, world_->objects(),
                                                                  observers_.on_navigation_step);
    } else if (carrier_) {
      options_.commander = std::make_unique<PathDriver>(scenario_.drive, rs.vehicle.track_gauge_m,
                                                        carrier_->end_time_s());
    } else {
      options_.commander = std::make_unique<PathDriver>(scenario_.drive, rs.vehicle.track_gauge_m);
    }
  }
  commander_ = options_.commander.get();
}

void ClosedLoop::Impl::BuildSchedule() {
  const scenario::RobotSpec& rs = scenario_.robot;
  clock_ = std::make_unique<sim::SimClock>(scenario_.scene.world.physics_step_s);
  encoder_period_ = clock_->StepsPerPeriod(rs.encoders.rate_hz);
  imu_period_ = clock_->StepsPerPeriod(rs.imu.rate_hz);
  camera_period_ = clock_->StepsPerPeriod(rs.stereo.rate_hz);
  scan_period_ = clock_->StepsPerPeriod(rs.range_sensor.rate_hz);
  if (commander_->trigger() == Commander::Trigger::kPeriodic) {
    control_period_ = clock_->StepsPerPeriod(1.0 / commander_->period_s());
  }
  end_step_ = static_cast<std::int64_t>(std::llround(scenario_.duration_s / clock_->step_s()));
  v_at_last_imu_ = vehicle_->chassis().v_world;
}

const StepResult& ClosedLoop::Impl::Step() {
  if (!started_) throw std::logic_error("ClosedLoop::Step: Start() first");
  if (finished_) throw std::logic_error("ClosedLoop::Step: the run is finished");
  StepResult& out = step_;
  out.encoders.clear();  // clear() keeps the capacity: no allocation per step
  out.imu.clear();
  out.scans.clear();
  out.stereo.clear();
  out.stereo_frames = 0;
  while (!done_ && !StepOnce(&out)) {
  }
  out.t_s = clock_->now_s();
  out.T_world_body = vehicle_->chassis().T_world_body;
  return out;
}

bool ClosedLoop::Impl::StepOnce(StepResult* out) {
  const robot::ChassisState truth = vehicle_->chassis();
  if (clock_->Fires(encoder_period_) && !SampleEncoders(truth, out)) return true;
  bool controlled = false;
  if (renderer_ && clock_->Fires(camera_period_)) {
    controlled = commander_->trigger() == Commander::Trigger::kStereoFrame;
    if (!TakeStereoFrame(truth, out)) return true;
  }
  if (clock_->steps() > 0 && clock_->Fires(imu_period_)) SampleImu(truth, out);
  if (range_sensor_ && clock_->Fires(scan_period_)) Scan(truth, out);
  if (clock_->steps() >= end_step_) {
    time_ran_out_ = true;
    done_ = true;
    return true;
  }
  if (commander_->trigger() == Commander::Trigger::kPeriodic && clock_->Fires(control_period_)) {
    controlled = true;
    if (!Control(truth, nullptr)) return true;
  }
  Timed(&times_.physics_s, [&] {
    vehicle_->ApplyForces(clock_->step_s());
    if (vehicle_->needs_physics()) world_->Step();
  });
  clock_->Tick();
  if (vehicle_->stalled()) Stop("stalled");  // a motor at its torque limit that cannot turn
  return controlled;
}

bool ClosedLoop::Impl::SampleEncoders(const robot::ChassisState& truth, StepResult* out) {
  RunSample s;
  s.t_s = clock_->now_s();
  s.chassis = truth;
  const robot::EncoderOptions& encoders = scenario_.robot.encoders;
  for (int side = 0; side < 2; ++side) {
    s.tracks[side] = vehicle_->track(static_cast<robot::Side>(side));
    // In a dropout the count freezes, and what the shaft turns meanwhile is lost.
    const std::int64_t shaft =
        robot::EncoderTicks(s.tracks[side].sprocket_angle_rad, encoders.ticks_per_rev);
    if (encoders.InDropout(side, s.t_s)) lost_ticks_[side] += shaft - last_shaft_ticks_[side];
    last_shaft_ticks_[side] = shaft;
    s.ticks[side] = shaft - lost_ticks_[side];
  }
  const Eigen::Vector3d p = truth.T_world_body.translation();
  const sim::GroundSample g = world_->terrain().Sample(p.x(), p.y());
  s.material = &g.material->name;
  if (!p.allFinite() || !truth.v_world.allFinite()) {
    failed_ = true;
    Stop("simulation diverged: non-finite chassis state at t = " + std::to_string(s.t_s) + " s");
    return false;
  }
  if (p.z() < g.height_m) {
    failed_ = true;
    Stop("simulation diverged: chassis below the terrain at t = " + std::to_string(s.t_s) + " s");
    return false;
  }
  metrics_->Add(s, g.height_m);
  last_ticks_[0] = s.ticks[0];
  last_ticks_[1] = s.ticks[1];
  out->encoders.push_back({s.t_s, {s.ticks[0], s.ticks[1]}});
  const bool has_camera = rig_.has_value();
  if (worker_) {
    worker_->Submit([this, s, has_camera] {
      const EstimateSample e = EstimateAfterEncoders(*stack_, s, has_camera);
      worker_->Deliver([this, s, e]() mutable {
        estimates_.Add(s, e);
        s.estimate = &e;
        if (observers_.on_sample) observers_.on_sample(s);
      });
    });
    worker_->RunDeliveries();
  } else if (stack_) {
    const auto start = std::chrono::steady_clock::now();
    const EstimateSample e = EstimateAfterEncoders(*stack_, s, has_camera);
    estimation_wall_s_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    estimates_.Add(s, e);
    s.estimate = &e;
    if (observers_.on_sample) observers_.on_sample(s);
  } else if (observers_.on_sample) {
    observers_.on_sample(s);
  }
  return true;
}

// A buffer pair for the worker: rendered into here, read there, given back by the
// frame's delivery.
ClosedLoop::Impl::ImagePair* ClosedLoop::Impl::FreePair() {
  if (free_pairs_.empty()) {
    image_pairs_.push_back(std::make_unique<ImagePair>());
    free_pairs_.push_back(image_pairs_.back().get());
  }
  ImagePair* pair = free_pairs_.back();
  free_pairs_.pop_back();
  return pair;
}

bool ClosedLoop::Impl::TakeStereoFrame(const robot::ChassisState& truth, StepResult* out) {
  const scenario::RobotSpec& rs = scenario_.robot;
  const auto render_start = std::chrono::steady_clock::now();
  StereoFrame frame;
  frame.index = stereo_index_++;
  frame.t_s = clock_->now_s();
  // The pair stamped now was exposed `offset` later on the IMU's clock (as built).
  const double offset = robot_.truth.imu.camera_time_offset_s;
  const render::BodyMotion motion =
      Advanced({truth.T_world_body, truth.v_world, truth.omega_world}, offset);
  frame.T_world_left = motion.T_world_body * rig_->T_body_left();
  frame.T_world_right = motion.T_world_body * rig_->T_body_right();
  // Both cameras see the terrain at the detail of the rig's centre.
  const Eigen::Vector2d rig_xy =
      0.5 * (frame.T_world_left.translation() + frame.T_world_right.translation()).head<2>();
  // With the worker, the pair is rendered straight into a buffer that the worker then
  // reads, so the main thread copies no image.
  ImagePair* pair = worker_ ? FreePair() : nullptr;
  GrayImage& left = pair ? pair->first : left_image_;
  GrayImage& right = pair ? pair->second : right_image_;
  // Each image is exposed around the frame's time (an instant by default), for the
  // time the auto-exposure chose if it is on.
  frame.exposure_time_s =
      auto_exposure_ ? auto_exposure_->exposure_time_s() : rs.stereo.exposure_time_s;
  frame.gain = auto_exposure_ ? auto_exposure_->gain() : 1.0;
  // The render shows the scene at `exposure_time_s`; the light scales with the time.
  // With scene lighting the renderer applies it before its output clips (a zone
  // brighter than the exposure holds saturates), else the sensor model does.
  const double light = rs.stereo.exposure *
                       (auto_exposure_ ? frame.exposure_time_s / rs.stereo.exposure_time_s : 1.0);
  if (renderer_->pre_exposed()) renderer_->SetExposure(light);
  exposures_[0]->Render(*renderer_, motion, rig_->T_body_left(), frame.t_s + offset,
                        frame.exposure_time_s, &left, &rig_xy);
  exposures_[1]->Render(*renderer_, motion, rig_->T_body_right(), frame.t_s + offset,
                        frame.exposure_time_s, &right, &rig_xy);
  frame.blackout = rs.stereo.InBlackout(frame.t_s);
  const CameraPipeline finish{rs.stereo,
                              image_sensors_.empty() ? nullptr : image_sensors_.data(),
                              renderer_->pre_exposed() ? 1.0 : light,
                              frame.gain,
                              renderer_->pre_exposed(),
                              noise_seed_,
                              frame.index,
                              frame.blackout};
  // The sensor model is the camera's last stage. When nothing on this thread looks at
  // the images, it runs on the worker, off this thread's critical path; the bytes are
  // the same either way (its noise is keyed by seed, frame and camera).
  const bool image_commander = commander_->trigger() == Commander::Trigger::kStereoFrame;
  const bool finish_on_worker =
      pair && !observers_.on_stereo && !image_commander && !options_.step_images && !auto_exposure_;
  const auto rendered = std::chrono::steady_clock::now();
  render_wall_s_ += std::chrono::duration<double>(rendered - render_start).count();
  if (!finish_on_worker) {
    finish.Apply(&left, &right);
    // The auto-exposure meters the left image for the next frame.
    if (auto_exposure_ && !frame.blackout) {
      auto_exposure_->Update(auto_exposure_->Meter(left), 1.0 / rs.stereo.rate_hz);
    }
    sensor_model_wall_s_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - rendered).count();
  }
  frame.left = &left;
  frame.right = &right;
  frame.rig = &*rig_;
  frame.ticks[0] = last_ticks_[0];
  frame.ticks[1] = last_ticks_[1];
  ++out->stereo_frames;
  if (options_.step_images) out->stereo.push_back({frame.t_s, left, right});
  if (observers_.on_stereo) observers_.on_stereo(frame);
  if (image_commander) {
    const cv::Mat left_mat = perception::AsCvMat(left);
    if (!Control(truth, &left_mat)) return false;
  }
  if (pair) SubmitFrame(pair, truth.T_world_body, frame.t_s, finish, finish_on_worker);
  return true;
}

// Hands a rendered pair to the worker, which owns it until the frame's delivery gives
// it back; the main thread meanwhile renders the next frames into other buffers.
void ClosedLoop::Impl::SubmitFrame(ImagePair* pair, const Eigen::Isometry3d& T_world_body,
                                   double t_s, const CameraPipeline& finish,
                                   bool finish_on_worker) {
  worker_->Submit([this, pair, T_world_body, t_s, finish, finish_on_worker] {
    if (finish_on_worker) {
      const auto start = std::chrono::steady_clock::now();
      finish.Apply(&pair->first, &pair->second);
      sensor_model_on_worker_s_ +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    const LocalizationFrame lf =
        LocalizeStereoFrame(*stack_, t_s, finish.blackout, pair->first, pair->second);
    worker_->Deliver([this, pair, T_world_body, lf] {
      free_pairs_.push_back(pair);
      estimates_.AddFrame(T_world_body, lf);
      if (observers_.on_localization_frame) observers_.on_localization_frame(lf);
    });
  });
  // Bounded look-ahead: the simulation runs at most about two camera periods ahead of
  // the robot software.
  worker_->WaitUntilPendingAtMost(kMaxTasksAhead);
}

void ClosedLoop::Impl::SampleImu(const robot::ChassisState& truth, StepResult* out) {
  const double dt = clock_->step_s();
  const Eigen::Vector3d accel = (truth.v_world - v_at_last_imu_) / (imu_period_ * dt);
  v_at_last_imu_ = truth.v_world;
  const robot::ImuSample sample =
      imu_->Sample(clock_->now_s(), truth.T_world_body.linear(), truth.omega_world, accel);
  out->imu.push_back(sample);
  if (observers_.on_imu) observers_.on_imu(sample);
  if (worker_) {
    worker_->Submit([this, t = sample.t_s, w = sample.gyro_radps, a = sample.accel_mps2] {
      stack_->AddImuSample(t, w, a);
    });
  } else if (stack_) {
    stack_->AddImuSample(sample.t_s, sample.gyro_radps, sample.accel_mps2);
  }
}

void ClosedLoop::Impl::Scan(const robot::ChassisState& truth, StepResult* out) {
  const robot::RangeScanSample scan = Timed(&times_.sensing_s, [&] {
    return range_sensor_->Scan(*world_, truth.T_world_body, clock_->now_s(), scan_index_++);
  });
  out->scans.push_back(scan);
  if (observers_.on_scan) observers_.on_scan(scan);
  commander_->AddScan(scan);
}

bool ClosedLoop::Impl::Control(const robot::ChassisState& truth, const cv::Mat* left_image) {
  ControlInput input;
  input.t_s = clock_->now_s();
  input.T_world_body = truth.T_world_body;
  input.left_image = left_image;
  if (commander_->needs_estimates() && stack_) {
    if (worker_) worker_->Drain();  // the estimates are then the same as inline
    input.estimates = stack_.get();
  }
  const ControlOutput c = Timed(&times_.control_s, [&] { return commander_->Update(input); });
  vehicle_->CommandTrackSpeeds(c.tracks.left_mps, c.tracks.right_mps);
  if (c.stop_reason) {
    Stop(*c.stop_reason);
    return false;
  }
  return true;
}

const estimation::LocalizationStack* ClosedLoop::Impl::localization() {
  if (!started_) throw std::logic_error("ClosedLoop::localization: Start() first");
  if (finished_) throw std::logic_error("ClosedLoop::localization: the run is finished");
  if (worker_) worker_->Drain();  // the stack has then seen every sample taken
  return stack_.get();
}

void ClosedLoop::Impl::ReportEstimate(const std::string& name, const Eigen::Matrix4d& T) {
  if (!started_) throw std::logic_error("ClosedLoop::ReportEstimate: Start() first");
  if (finished_) throw std::logic_error("ClosedLoop::ReportEstimate: the run is finished");
  CheckEstimatorName(name);
  CheckRigid(name, T);
  const double t_s = clock_->now_s();
  const auto [it, first] = reported_t_.try_emplace(name, t_s);
  if (!first) {
    if (!(t_s > it->second)) {
      throw std::invalid_argument("estimate \"" + name + "\": already reported at t = " +
                                  std::to_string(t_s) + " s (one estimate per name and time)");
    }
    it->second = t_s;
  }
  ExternalEstimate e;
  e.name = &it->first;
  e.t_s = t_s;
  e.T_world_body.matrix() = T;
  e.T_world_body_true = vehicle_->chassis().T_world_body;
  estimates_.AddExternal(e);
  if (observers_.on_external_estimate) observers_.on_external_estimate(e);
}

RunMetrics ClosedLoop::Impl::Metrics() {
  if (worker_) {
    worker_->Drain();
    // The sensor model is its own stage, wherever it ran.
    estimation_wall_s_ = worker_->busy_s() - sensor_model_on_worker_s_;
    sensor_model_wall_s_ += sensor_model_on_worker_s_;
  }
  RunMetrics m = metrics_->Metrics();
  m.completed = !failed_;
  m.stereo_frames = stereo_index_;
  m.render_wall_s = render_wall_s_;
  m.sensor_model_wall_s = sensor_model_wall_s_;
  m.estimation_wall_s = estimation_wall_s_;
  m.setup_wall_s = times_.setup_s;
  m.physics_wall_s = times_.physics_s;
  m.control_wall_s = times_.control_s;
  m.sensing_wall_s = times_.sensing_s;
  m.io_wall_s = times_.io_s;
  m.peak_rss_mb = PeakRssMb();
  m.estimators = estimates_.Metrics(m.distance_m);
  m.localization = estimates_.Summary();
  m.stop_reason = stop_reason_;
  commander_->AddMetrics(time_ran_out_, &m);
  m.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
  return m;
}

// Frees the world, the robot, its sensors and software and the scored trajectories
// once the metrics are taken (the worker first: its tasks refer to the rest).
void ClosedLoop::Impl::ReleaseSimulation() {
  worker_.reset();
  stack_.reset();
  estimates_ = EstimatorScoring();
  image_pairs_.clear();
  free_pairs_.clear();
  renderer_.reset();
  range_sensor_.reset();
  imu_.reset();
  carrier_ = nullptr;
  vehicle_.reset();
  world_.reset();
}

RunMetrics ClosedLoop::Impl::Finish() {
  if (!started_) throw std::logic_error("ClosedLoop::Finish: Start() first");
  if (finished_) throw std::logic_error("ClosedLoop::Finish: called twice");
  finished_ = true;
  done_ = true;
  RunMetrics m = Metrics();
  ReleaseSimulation();  // before the plots, so their memory does not add to the world's
  if (folder_) folder_->Close(scenario_, m);
  return m;
}

void ClosedLoop::Impl::RecordFailure(const std::exception& e) {
  done_ = true;
  if (options_.dir.empty()) return;
  RunMetrics m;
  m.completed = false;
  m.stop_reason = std::string("failed: ") + e.what();
  WriteMetricsJson(m, options_.dir);
}

ClosedLoop::ClosedLoop(const scenario::Scenario& scenario, ClosedLoopOptions options)
    : impl_(std::make_unique<Impl>(scenario, std::move(options))) {}

ClosedLoop::~ClosedLoop() = default;

// Each stage leaves a metrics.json that says why, should it throw.
void ClosedLoop::Start() {
  try {
    impl_->Start();
  } catch (const std::exception& e) {
    impl_->RecordFailure(e);
    throw;
  }
}

const StepResult& ClosedLoop::Step() {
  try {
    return impl_->Step();
  } catch (const std::exception& e) {
    impl_->RecordFailure(e);
    throw;
  }
}

bool ClosedLoop::done() const { return impl_->done(); }

RobotBuild BuildRunRobot(const scenario::Scenario& scenario) {
  return BuildRobot(scenario, CalibrateWheels);
}

const estimation::LocalizationStack* ClosedLoop::localization() { return impl_->localization(); }

void ClosedLoop::ReportEstimate(const std::string& name, const Eigen::Matrix4d& T_world_body) {
  impl_->ReportEstimate(name, T_world_body);
}

RunMetrics ClosedLoop::Finish() {
  try {
    return impl_->Finish();
  } catch (const std::exception& e) {
    impl_->RecordFailure(e);
    throw;
  }
}

RunMetrics ClosedLoop::Run() {
  Start();
  while (!done()) Step();
  return Finish();
}

RunMetrics RunClosedLoop(const scenario::Scenario& scenario, const RunObservers& observers) {
  ClosedLoopOptions options;
  options.observers = observers;
  return ClosedLoop(scenario, std::move(options)).Run();
}

}  // namespace trackbed::runner
