// The closed loop (see closed_loop.h).
#include "trackbed/runner/closed_loop.h"

#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "trackbed/perception/opencv_views.h"
#include "trackbed/runner/closed_loop_navigation.h"
#include "trackbed/runner/estimator_scoring.h"
#include "trackbed/runner/localization_options.h"
#include "trackbed/runner/ordered_worker.h"
#include "trackbed/runner/path_driver.h"
#include "trackbed/runner/plant.h"
#include "trackbed/runner/reported_estimates.h"
#include "trackbed/runner/run_folder.h"
#include "trackbed/runner/stage_times.h"
#include "trackbed/runner/wheel_calibration_run.h"
#include "trackbed/sim/sim_clock.h"

namespace trackbed::runner {
namespace {

// Tasks (encoder samples, gyro samples, stereo frames) the simulation may run ahead of
// the localization stack.
constexpr std::int64_t kMaxTasksAhead = 64;

// Steps of the clock between a sensor's samples, between a periodic commander's calls;
// the step at which the duration is reached.
struct Schedule {
  std::int64_t encoders = 1, imu = 1, camera = 1, scan = 1, control = 1, end_step = 0;
};

EstimateSample EstimateAfterEncoders(estimation::LocalizationStack& stack, const RunSample& s,
                                     bool has_camera) {
  stack.AddEncoderSample(s.t_s, s.ticks[0], s.ticks[1]);
  EstimateSample e;
  e.t_s = s.t_s;
  e.wheel_odometry = stack.wheel_odometry();
  e.wheel_odometry_noslip = stack.wheel_odometry_noslip();
  e.fused = stack.fused();
  e.fused_ham2012 = stack.fused_ham2012();
  e.ekf = stack.ekf();
  e.has_camera = has_camera;
  e.slip = stack.slip();
  e.covariances = stack.pose_covariances();
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
  HeldSizes held_sizes();
  const estimation::LocalizationStack* localization();
  void ReportEstimate(const std::string& name, const Eigen::Matrix4d& T_world_body);
  // Runs `f`; should it throw, writes a metrics.json that says why (when there is a
  // folder) and rethrows.
  template <class F>
  decltype(auto) Recorded(F&& f) {
    try {
      return f();
    } catch (const std::exception& e) {
      RecordFailure(e);
      throw;
    }
  }
  // Whether a commander was given from outside (BuildSoftware later sets the scenario's
  // own in options_.commander).
  scenario::DriveSource drive_source() const { return drive_source_; }

 private:
  using ImagePair = std::pair<GrayImage, GrayImage>;

  void BuildSoftware();
  void BuildSchedule();
  // One physics step and whatever fires in it; true when the commander was called.
  bool StepOnce(StepResult* out);
  bool SampleEncoders(const robot::ChassisState& truth, StepResult* out);
  bool TakeStereoFrame(const robot::ChassisState& truth, StepResult* out);
  ImagePair* FreePair();
  void SubmitFrame(ImagePair* pair, const Eigen::Isometry3d& T_world_body,
                   const robot::StereoCapture& capture, bool develop_on_worker);
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
  void RecordFailure(const std::exception& e);

  scenario::Scenario scenario_;
  ClosedLoopOptions options_;
  scenario::DriveSource drive_source_ =
      options_.commander ? scenario::DriveSource::kExternal : scenario::DriveSource::kScenario;
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

  std::optional<Plant> plant_;  // the world and the robot in it
  Commander* commander_ = nullptr;
  std::unique_ptr<estimation::LocalizationStack> stack_;
  EstimatorScoring estimates_;
  // With the camera on, the localization stack runs on a second thread, fed the same
  // samples in the same order as it would be inline (identical results), while this
  // thread simulates and renders ahead. The worker gets copies of each stereo pair in
  // buffers that come back to `free_pairs_` when the frame's delivery runs here, so no
  // frame allocates images (declared before the worker, which may still hold some when
  // it is destroyed).
  std::vector<std::unique_ptr<ImagePair>> image_pairs_;
  std::vector<ImagePair*> free_pairs_;
  std::unique_ptr<OrderedWorker> worker_;
  std::uint64_t scan_index_ = 0;
  double sensor_model_on_worker_s_ = 0.0;  // written by the worker, read after Drain()
  std::unique_ptr<MetricsAccumulator> metrics_;
  std::unique_ptr<sim::SimClock> clock_;
  Schedule schedule_;
  Eigen::Vector3d v_at_last_imu_ = Eigen::Vector3d::Zero();
  ReportedEstimates reported_;
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
    plant_.emplace(BuildPlant(scenario_, robot_, scenario_.CarriedOnPosePath(drive_source()),
                              options_.track_marks));
    const scenario::RobotSpec& rs = scenario_.robot;
    metrics_ = std::make_unique<MetricsAccumulator>(
        rs.vehicle.sprocket_radius_m, rs.vehicle.track_gauge_m, rs.encoders.ticks_per_rev);
    BuildSoftware();
    BuildSchedule();
  });
}

// The robot software: the localization stack on the robot's own sensors, and the
// commander (the scenario's own unless one was given).
void ClosedLoop::Impl::BuildSoftware() {
  const scenario::RobotSpec& rs = scenario_.robot;
  if (scenario_.estimation.enabled) {
    const calibration::StereoCalibration* given_stereo =
        plant_->camera && robot_.given.stereo ? &*robot_.given.stereo : nullptr;
    stack_ = std::make_unique<estimation::LocalizationStack>(
        LocalizationOptionsOf(scenario_, robot_.given), given_stereo,
        plant_->vehicle->chassis().T_world_body);
    estimates_ = EstimatorScoring(scenario_.estimation.localization.localization_lost);
  }
  if (stack_ && plant_->camera) worker_ = std::make_unique<OrderedWorker>();
  if (!options_.commander) {
    if (scenario_.navigation.enabled) {
      options_.commander = std::make_unique<ClosedLoopNavigation>(
          scenario_, plant_->world->objects(), plant_->world->mesh_solids(),
          observers_.on_navigation_step);
    } else if (plant_->carrier) {
      options_.commander = std::make_unique<PathDriver>(scenario_.drive, rs.vehicle.track_gauge_m,
                                                        plant_->carrier->end_time_s());
    } else {
      options_.commander = std::make_unique<PathDriver>(scenario_.drive, rs.vehicle.track_gauge_m);
    }
  }
  commander_ = options_.commander.get();
}

void ClosedLoop::Impl::BuildSchedule() {
  const scenario::RobotSpec& rs = scenario_.robot;
  clock_ = std::make_unique<sim::SimClock>(scenario_.scene.world.physics_step_s);
  schedule_.encoders = clock_->StepsPerPeriod(rs.encoders.rate_hz);
  schedule_.imu = clock_->StepsPerPeriod(rs.imu.rate_hz);
  schedule_.camera = clock_->StepsPerPeriod(rs.stereo.rate_hz);
  schedule_.scan = clock_->StepsPerPeriod(rs.range_sensor.rate_hz);
  if (commander_->trigger() == Commander::Trigger::kPeriodic) {
    schedule_.control = clock_->StepsPerPeriod(1.0 / commander_->period_s());
  }
  schedule_.end_step = static_cast<std::int64_t>(
      std::llround(scenario_.RunDuration(drive_source()) / clock_->step_s()));
  v_at_last_imu_ = plant_->vehicle->chassis().v_world;
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
  out.T_world_body = plant_->vehicle->chassis().T_world_body;
  return out;
}

bool ClosedLoop::Impl::StepOnce(StepResult* out) {
  const robot::ChassisState truth = plant_->vehicle->chassis();
  if (clock_->Fires(schedule_.encoders) && !SampleEncoders(truth, out)) return true;
  bool controlled = false;
  if (plant_->camera && clock_->Fires(schedule_.camera)) {
    controlled = commander_->trigger() == Commander::Trigger::kStereoFrame;
    if (!TakeStereoFrame(truth, out)) return true;
  }
  if (clock_->steps() > 0 && clock_->Fires(schedule_.imu)) SampleImu(truth, out);
  if (plant_->range_sensor && clock_->Fires(schedule_.scan)) Scan(truth, out);
  if (clock_->steps() >= schedule_.end_step) {
    time_ran_out_ = true;
    done_ = true;
    return true;
  }
  if (commander_->trigger() == Commander::Trigger::kPeriodic && clock_->Fires(schedule_.control)) {
    controlled = true;
    if (!Control(truth, nullptr)) return true;
  }
  Timed(&times_.physics_s, [&] {
    plant_->vehicle->ApplyForces(clock_->step_s());
    if (plant_->vehicle->needs_physics()) plant_->world->Step();
  });
  clock_->Tick();
  if (plant_->vehicle->stalled()) Stop("stalled");  // a motor at its torque limit that cannot turn
  return controlled;
}

bool ClosedLoop::Impl::SampleEncoders(const robot::ChassisState& truth, StepResult* out) {
  RunSample s;
  s.t_s = clock_->now_s();
  s.chassis = truth;
  s.tracks[0] = plant_->vehicle->track(robot::Side::kLeft);
  s.tracks[1] = plant_->vehicle->track(robot::Side::kRight);
  const std::array<std::int64_t, 2> ticks = plant_->encoders->Sample(
      s.t_s, {s.tracks[0].sprocket_angle_rad, s.tracks[1].sprocket_angle_rad});
  s.ticks[0] = ticks[0];
  s.ticks[1] = ticks[1];
  const Eigen::Vector3d p = truth.T_world_body.translation();
  const sim::GroundSample g = plant_->world->terrain().Sample(p.x(), p.y());
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
  out->encoders.push_back({s.t_s, {s.ticks[0], s.ticks[1]}});
  const bool has_camera = plant_->camera != nullptr;
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
    const EstimateSample e =
        Timed(&times_.estimation_s, [&] { return EstimateAfterEncoders(*stack_, s, has_camera); });
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
  robot::StereoCamera& camera = *plant_->camera;
  // With the worker, the pair is rendered straight into a buffer that the worker then
  // reads, so the main thread copies no image.
  ImagePair* pair = worker_ ? FreePair() : nullptr;
  const robot::StereoCapture capture = Timed(&times_.render_s, [&] {
    return camera.Expose(clock_->now_s(), {truth.T_world_body, truth.v_world, truth.omega_world},
                         pair ? &pair->first : nullptr, pair ? &pair->second : nullptr);
  });
  // The sensor model is the camera's last stage. When nothing on this thread looks at
  // the images, it runs on the worker, off this thread's critical path; the bytes are
  // the same either way (its noise is keyed by seed, frame and camera).
  const bool image_commander = commander_->trigger() == Commander::Trigger::kStereoFrame;
  const bool develop_on_worker = pair && !observers_.on_stereo && !image_commander &&
                                 !options_.step_images && !camera.has_auto_exposure();
  if (!develop_on_worker) Timed(&times_.sensor_model_s, [&] { camera.Finish(capture); });
  StereoFrame frame;
  frame.index = capture.index;
  frame.t_s = capture.t_s;
  frame.left = capture.left;
  frame.right = capture.right;
  frame.T_world_left = capture.T_world_left;
  frame.T_world_right = capture.T_world_right;
  frame.rig = &camera.rig();
  frame.blackout = capture.blackout;
  frame.exposure_time_s = capture.exposure_time_s;
  frame.gain = capture.gain;
  frame.ticks[0] = plant_->encoders->counts()[0];
  frame.ticks[1] = plant_->encoders->counts()[1];
  ++out->stereo_frames;
  if (options_.step_images) out->stereo.push_back({frame.t_s, *frame.left, *frame.right});
  if (observers_.on_stereo) observers_.on_stereo(frame);
  if (image_commander) {
    const cv::Mat left_mat = perception::AsCvMat(*frame.left);
    if (!Control(truth, &left_mat)) return false;
  }
  if (pair) SubmitFrame(pair, truth.T_world_body, capture, develop_on_worker);
  return true;
}

// Hands a rendered pair to the worker, which owns it until the frame's delivery gives
// it back; the main thread meanwhile renders the next frames into other buffers.
void ClosedLoop::Impl::SubmitFrame(ImagePair* pair, const Eigen::Isometry3d& T_world_body,
                                   const robot::StereoCapture& capture, bool develop_on_worker) {
  const robot::StereoCamera* camera = plant_->camera.get();
  worker_->Submit([this, pair, T_world_body, capture, camera, develop_on_worker] {
    if (develop_on_worker) Timed(&sensor_model_on_worker_s_, [&] { camera->Develop(capture); });
    const LocalizationFrame lf =
        LocalizeStereoFrame(*stack_, capture.t_s, capture.blackout, pair->first, pair->second);
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
  const Eigen::Vector3d accel = (truth.v_world - v_at_last_imu_) / (schedule_.imu * dt);
  v_at_last_imu_ = truth.v_world;
  const robot::ImuSample sample =
      plant_->imu->Sample(clock_->now_s(), truth.T_world_body.linear(), truth.omega_world, accel);
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
    return plant_->range_sensor->Scan(*plant_->world, truth.T_world_body, clock_->now_s(),
                                      scan_index_++);
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
  plant_->vehicle->CommandTrackSpeeds(c.tracks.left_mps, c.tracks.right_mps);
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

HeldSizes ClosedLoop::Impl::held_sizes() {
  if (!started_ || finished_) throw std::logic_error("ClosedLoop::held_sizes: not running");
  if (worker_) worker_->Drain();  // the scores are then up to date
  HeldSizes h;
  h.scoring_window_poses = estimates_.window_size();
  if (metrics_) h.icr_fit_groups = metrics_->icr_fit_groups();
  if (folder_) {
    h.plot_points = folder_->plot_points();
    h.largest_plot_series = folder_->largest_plot_series();
  }
  return h;
}

void ClosedLoop::Impl::ReportEstimate(const std::string& name, const Eigen::Matrix4d& T) {
  if (!started_) throw std::logic_error("ClosedLoop::ReportEstimate: Start() first");
  if (finished_) throw std::logic_error("ClosedLoop::ReportEstimate: the run is finished");
  const ExternalEstimate e =
      reported_.Accept(name, T, clock_->now_s(), plant_->vehicle->chassis().T_world_body);
  estimates_.AddExternal(e);
  if (observers_.on_external_estimate) observers_.on_external_estimate(e);
}

RunMetrics ClosedLoop::Impl::Metrics() {
  if (worker_) {
    worker_->Drain();
    // The sensor model is its own stage, wherever it ran.
    times_.estimation_s = worker_->busy_s() - sensor_model_on_worker_s_;
    times_.sensor_model_s += sensor_model_on_worker_s_;
  }
  RunMetrics m = metrics_->Metrics();
  m.completed = !failed_;
  m.stereo_frames = plant_->camera ? plant_->camera->frames() : 0;
  times_.WriteTo(&m);
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
  plant_.reset();
}

RunMetrics ClosedLoop::Impl::Finish() {
  if (!started_) throw std::logic_error("ClosedLoop::Finish: Start() first");
  if (finished_) throw std::logic_error("ClosedLoop::Finish: called twice");
  finished_ = true;
  done_ = true;
  RunMetrics m = Metrics();
  if (const sim::TrackMarks* marks = plant_->track_marks.get()) {
    m.track_marks.emplace();
    for (int side = 0; side < 2; ++side) {
      m.track_marks->points_held += marks->size(side);
      m.track_marks->points_recorded += marks->recorded(side);
    }
    m.track_marks->bound_mb = static_cast<double>(marks->capacity_bytes()) / (1 << 20);
  }
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
  impl_->Recorded([this] { impl_->Start(); });
}

const StepResult& ClosedLoop::Step() {
  return impl_->Recorded([this]() -> const StepResult& { return impl_->Step(); });
}

bool ClosedLoop::done() const { return impl_->done(); }

RobotBuild BuildRunRobot(const scenario::Scenario& scenario) {
  return BuildRobot(scenario, CalibrateWheels);
}

const estimation::LocalizationStack* ClosedLoop::localization() { return impl_->localization(); }

HeldSizes ClosedLoop::held_sizes() { return impl_->held_sizes(); }

void ClosedLoop::ReportEstimate(const std::string& name, const Eigen::Matrix4d& T_world_body) {
  impl_->ReportEstimate(name, T_world_body);
}

RunMetrics ClosedLoop::Finish() {
  return impl_->Recorded([this] { return impl_->Finish(); });
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
