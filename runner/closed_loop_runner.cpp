// The closed-loop runner (see closed_loop_runner.h).
#include "trackbed/runner/closed_loop_runner.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "trackbed/common/split_mix.h"
#include "trackbed/estimation/skid_steer.h"
#include "trackbed/navigation/pure_pursuit.h"
#include "trackbed/robot/encoder.h"
#include "trackbed/robot/range_sensor.h"
#include "trackbed/robot/tracked_vehicle.h"
#include "trackbed/runner/closed_loop_navigation.h"
#include "trackbed/runner/ordered_worker.h"
#include "trackbed/sim/camera_exposure.h"
#include "trackbed/sim/renderer.h"
#include "trackbed/sim/sim_clock.h"
#include "trackbed/sim/world.h"

namespace trackbed::runner {
namespace {

double Yaw(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

// The drive: what the tracks are told, at the drive's rate.
class Driver {
 public:
  Driver(const scenario::DriveSpec& spec, double nominal_gauge_m)
      : spec_(spec), gauge_(nominal_gauge_m) {
    if (spec_.mode == scenario::DriveSpec::Mode::kPath) {
      navigation::PurePursuitOptions o;
      o.speed_mps = spec_.speed_mps;
      o.lookahead_m = spec_.lookahead_m;
      o.goal_tolerance_m = spec_.goal_tolerance_m;
      follower_.emplace(o, spec_.waypoints, spec_.closed, spec_.laps);
    }
  }

  // Returns the track speeds to command; sets *finished when the path is done.
  estimation::TrackSpeeds Update(double t_s, const robot::ChassisState& truth, bool* finished) {
    *finished = false;
    if (follower_) {
      const Eigen::Isometry3d& T = truth.T_world_body;
      const navigation::PurePursuitCommand c =
          follower_->Update({T.translation().x(), T.translation().y(), Yaw(T.linear())});
      *finished = c.finished;
      return estimation::TrackSpeedsFromTwist(c.twist, gauge_);
    }
    while (next_ < spec_.script.size() && spec_.script[next_].t_s <= t_s + 1e-9) ++next_;
    if (next_ == 0) return {};
    const scenario::DriveCommand& c = spec_.script[next_ - 1];
    if (c.track_speeds) return {c.left_mps, c.right_mps};
    return estimation::TrackSpeedsFromTwist({c.v_mps, c.yaw_rate_radps}, gauge_);
  }

 private:
  scenario::DriveSpec spec_;
  double gauge_;
  std::optional<navigation::PurePursuit> follower_;
  std::size_t next_ = 0;
};

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
                                      bool blackout, const sim::GrayImage& left,
                                      const sim::GrayImage& right) {
  const auto as_mat = [](const sim::GrayImage& g) {
    return cv::Mat(g.height, g.width, CV_8UC1, const_cast<std::uint8_t*>(g.pixels.data()));
  };
  LocalizationFrame lf;
  lf.t_s = t_s;
  lf.camera_blackout = blackout;
  lf.report = stack.AddStereoFrame(t_s, as_mat(left), as_mat(right));
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
  double physics_s = 0.0, control_s = 0.0, sensing_s = 0.0, io_s = 0.0;
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
// by seed, frame and camera), then the blackout fault, on a rendered pair.
struct CameraPipeline {
  const robot::StereoRigOptions& stereo;
  std::uint64_t noise_seed;
  std::int64_t frame_index;
  bool blackout;

  void Apply(sim::GrayImage* left, sim::GrayImage* right) const {
    const auto frame = static_cast<std::uint64_t>(frame_index);
    robot::ApplySensorModel(stereo.exposure, stereo.noise_std, noise_seed, frame, 0, left);
    robot::ApplySensorModel(stereo.exposure, stereo.noise_std, noise_seed, frame, 1, right);
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

}  // namespace

RunMetrics RunClosedLoop(const scenario::Scenario& scenario, const RunObservers& given_observers,
                         teach_repeat::Repeater* repeater) {
  scenario.Validate();
  const auto wall_start = std::chrono::steady_clock::now();
  // Wall-clock seconds per stage (metrics.json `timing`), on this thread; the
  // localization stack's own time is the worker's busy time.
  StageTimes times;
  const RunObservers observers = TimedObservers(given_observers, &times.io_s);

  sim::World world(scenario.scene.world,
                   sim::Terrain(scenario.scene.terrain, split_mix::Stream(scenario.seed, 0)),
                   scenario.scene.objects);
  const scenario::RobotSpec& rs = scenario.robot;
  robot::TrackedVehicle vehicle(rs.vehicle, &world, rs.start.x_m, rs.start.y_m,
                                rs.start.yaw_deg * M_PI / 180.0);
  robot::Imu imu(rs.imu, scenario.scene.world.gravity_mps2, split_mix::Stream(scenario.seed, 1));
  std::optional<Driver> driver;  // the drive, unless navigation drives
  if (!scenario.navigation.enabled && !repeater) {
    driver.emplace(scenario.drive, rs.vehicle.track_gauge_m);
  }
  const double gauge_eff_m = scenario.estimation.icr_expansion * rs.vehicle.track_gauge_m;
  std::int64_t last_ticks[2] = {0, 0};
  std::int64_t repeat_features_lost = 0, repeat_features_recovered = 0;
  std::optional<robot::StereoRig> rig;
  std::unique_ptr<sim::Renderer> renderer;
  if (rs.stereo.enabled) {
    rig.emplace(rs.stereo);
    renderer =
        std::make_unique<sim::Renderer>(world, scenario.scene.appearance, scenario.scene.occluders,
                                        split_mix::Stream(scenario.seed, 2), rs.stereo.width_px,
                                        rs.stereo.height_px, rs.stereo.near_m, rs.stereo.far_m);
  }
  sim::GrayImage left_image, right_image;
  sim::CameraExposure exposure(rs.stereo.exposure_time_s, rs.stereo.exposure_samples);
  // The robot software: the localization stack on the robot's own sensors.
  std::unique_ptr<estimation::LocalizationStack> stack;
  EstimatorScoring estimates;
  double estimation_wall_s = 0.0;
  if (scenario.estimation.enabled) {
    estimation::LocalizationOptions lo;
    lo.wheel.sprocket_radius_m = rs.vehicle.sprocket_radius_m;
    lo.wheel.track_gauge_m = rs.vehicle.track_gauge_m;
    lo.wheel.icr_expansion = scenario.estimation.icr_expansion;
    lo.wheel.icr_offset_m = scenario.estimation.icr_offset_m;
    lo.wheel.ticks_per_rev = rs.encoders.ticks_per_rev;
    lo.wheel.slip_decay_time_s = scenario.estimation.slip_decay_time_s;
    lo.wheel.slip_filter_time_s = scenario.estimation.slip_filter_time_s;
    lo.min_inliers_for_slip = scenario.estimation.min_inliers_for_slip;
    lo.fusion_rules_file = scenario.estimation.fusion_rules;
    lo.fusion_weight_rise_time_s = scenario.estimation.fusion_weight_rise_time_s;
    lo.vo_coast_time_s = scenario.estimation.vo_coast_time_s;
    lo.vo.max_translation_per_frame_m = scenario.estimation.vo_max_translation_per_frame_m;
    lo.vo.max_rotation_per_frame_deg = scenario.estimation.vo_max_rotation_per_frame_deg;
    lo.vo.max_acceleration_mps2 = scenario.estimation.vo_max_acceleration_mps2;
    lo.vo.max_angular_acceleration_dps2 = scenario.estimation.vo_max_angular_acceleration_dps2;
    lo.vo.max_rotation_prior_error_deg = scenario.estimation.vo_max_gyro_rotation_error_deg;
    lo.ekf = scenario.estimation.ekf;
    std::optional<perception::StereoCalibration> calibration;
    if (rig) {
      const sim::PinholeIntrinsics& K = rig->intrinsics();
      calibration = perception::StereoCalibration::FromIntrinsics(K.fx, K.fy, K.cx, K.cy,
                                                                  rs.stereo.baseline_m);
    }
    stack = std::make_unique<estimation::LocalizationStack>(
        lo, calibration ? &*calibration : nullptr,
        rig ? rig->T_body_left() : Eigen::Isometry3d::Identity(), vehicle.chassis().T_world_body);
  }
  // With the camera on, the localization stack runs on a second thread, fed the same
  // samples in the same order as it would be inline (identical results), while this
  // thread simulates and renders ahead. The drive does not read the estimates.
  // The worker gets copies of each stereo pair in buffers that come back to
  // `free_pairs` when the frame's delivery runs here, so no frame allocates images
  // (declared before the worker, which may still hold some when it is destroyed).
  using ImagePair = std::pair<sim::GrayImage, sim::GrayImage>;
  std::vector<std::unique_ptr<ImagePair>> image_pairs;
  std::vector<ImagePair*> free_pairs;
  std::unique_ptr<OrderedWorker> worker;
  if (stack && rig) worker = std::make_unique<OrderedWorker>();
  // Closed-loop navigation replaces the drive; it reads the estimates at each control
  // step (the worker is drained first, so they are the same as inline).
  std::unique_ptr<ClosedLoopNavigation> navigator;
  if (scenario.navigation.enabled) navigator = std::make_unique<ClosedLoopNavigation>(scenario);
  std::unique_ptr<robot::RangeSensor> range_sensor;
  if (rs.range_sensor.enabled) {
    range_sensor =
        std::make_unique<robot::RangeSensor>(rs.range_sensor, split_mix::Stream(scenario.seed, 4));
  }
  std::uint64_t scan_index = 0;
  std::int64_t stereo_index = 0;
  double render_wall_s = 0.0;
  double sensor_model_wall_s = 0.0;       // on this thread
  double sensor_model_on_worker_s = 0.0;  // written by the worker, read after Drain()
  const std::uint64_t noise_seed = split_mix::Stream(scenario.seed, 3);
  MetricsAccumulator metrics(rs.vehicle.sprocket_radius_m, rs.vehicle.track_gauge_m,
                             rs.encoders.ticks_per_rev);

  sim::SimClock clock(scenario.scene.world.physics_step_s);
  const std::int64_t encoder_period = clock.StepsPerPeriod(rs.encoders.rate_hz);
  const std::int64_t imu_period = clock.StepsPerPeriod(rs.imu.rate_hz);
  const std::int64_t drive_period = clock.StepsPerPeriod(scenario.drive.rate_hz);
  const std::int64_t camera_period = clock.StepsPerPeriod(rs.stereo.rate_hz);
  const std::int64_t scan_period = clock.StepsPerPeriod(rs.range_sensor.rate_hz);
  const std::int64_t navigation_period =
      navigator ? clock.StepsPerPeriod(1.0 / navigator->period_s()) : 1;
  const auto end_step =
      static_cast<std::int64_t>(std::llround(scenario.duration_s / clock.step_s()));
  const double dt = clock.step_s();

  std::string stop_reason = "duration reached";
  bool time_ran_out = false;
  bool failed = false;
  Eigen::Vector3d v_at_last_imu = vehicle.chassis().v_world;
  for (;;) {
    const robot::ChassisState truth = vehicle.chassis();
    if (clock.Fires(encoder_period)) {
      RunSample s;
      s.t_s = clock.now_s();
      s.chassis = truth;
      for (int side = 0; side < 2; ++side) {
        s.tracks[side] = vehicle.track(static_cast<robot::Side>(side));
        s.ticks[side] =
            robot::EncoderTicks(s.tracks[side].sprocket_angle_rad, rs.encoders.ticks_per_rev);
      }
      const Eigen::Vector3d p = truth.T_world_body.translation();
      const sim::GroundSample g = world.terrain().Sample(p.x(), p.y());
      s.material = &g.material->name;
      if (!p.allFinite() || !truth.v_world.allFinite()) {
        failed = true;
        stop_reason =
            "simulation diverged: non-finite chassis state at t = " + std::to_string(s.t_s) + " s";
        break;
      }
      if (p.z() < g.height_m) {
        failed = true;
        stop_reason =
            "simulation diverged: chassis below the terrain at t = " + std::to_string(s.t_s) + " s";
        break;
      }
      metrics.Add(s, g.height_m);
      last_ticks[0] = s.ticks[0];
      last_ticks[1] = s.ticks[1];
      if (worker) {
        worker->Submit([&, s] {
          const EstimateSample e = EstimateAfterEncoders(*stack, s, rig.has_value());
          worker->Deliver([&, s, e]() mutable {
            estimates.Add(s, e);
            s.estimate = &e;
            if (observers.on_sample) observers.on_sample(s);
          });
        });
        worker->RunDeliveries();
      } else if (stack) {
        const auto start = std::chrono::steady_clock::now();
        const EstimateSample e = EstimateAfterEncoders(*stack, s, rig.has_value());
        estimation_wall_s +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        estimates.Add(s, e);
        s.estimate = &e;
        if (observers.on_sample) observers.on_sample(s);
      } else if (observers.on_sample) {
        observers.on_sample(s);
      }
    }
    if (renderer && clock.Fires(camera_period)) {
      const auto render_start = std::chrono::steady_clock::now();
      StereoFrame frame;
      frame.index = stereo_index++;
      frame.t_s = clock.now_s();
      frame.T_world_left = truth.T_world_body * rig->T_body_left();
      frame.T_world_right = truth.T_world_body * rig->T_body_right();
      // Both cameras see the terrain at the detail of the rig's centre.
      const Eigen::Vector2d rig_xy =
          0.5 * (frame.T_world_left.translation() + frame.T_world_right.translation()).head<2>();
      // With the worker, the pair is rendered straight into a buffer that the worker
      // then reads, so the main thread copies no image.
      ImagePair* pair = nullptr;
      if (worker) {
        if (free_pairs.empty()) {
          image_pairs.push_back(std::make_unique<ImagePair>());
          free_pairs.push_back(image_pairs.back().get());
        }
        pair = free_pairs.back();
        free_pairs.pop_back();
      }
      sim::GrayImage& left = pair ? pair->first : left_image;
      sim::GrayImage& right = pair ? pair->second : right_image;
      // Each image is exposed around the frame's time (an instant by default).
      const sim::BodyMotion motion{truth.T_world_body, truth.v_world, truth.omega_world};
      exposure.Render(*renderer, rig->intrinsics(), motion, rig->T_body_left(), frame.t_s, &left,
                      &rig_xy);
      exposure.Render(*renderer, rig->intrinsics(), motion, rig->T_body_right(), frame.t_s, &right,
                      &rig_xy);
      frame.blackout = rs.stereo.InBlackout(frame.t_s);
      const CameraPipeline finish{rs.stereo, noise_seed, frame.index, frame.blackout};
      // The sensor model is the camera's last stage. When nothing on this thread looks
      // at the images, it runs on the worker, off this thread's critical path; the bytes
      // are the same either way (its noise is keyed by seed, frame and camera).
      const bool finish_on_worker = pair && !observers.on_stereo && !repeater;
      const auto rendered = std::chrono::steady_clock::now();
      render_wall_s += std::chrono::duration<double>(rendered - render_start).count();
      if (!finish_on_worker) {
        finish.Apply(&left, &right);
        sensor_model_wall_s +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - rendered).count();
      }
      frame.left = &left;
      frame.right = &right;
      frame.rig = &*rig;
      frame.ticks[0] = last_ticks[0];
      frame.ticks[1] = last_ticks[1];
      if (observers.on_stereo) observers.on_stereo(frame);
      if (repeater) {
        // Teach & repeat steers from this image alone.
        const cv::Mat left_mat(left.height, left.width, CV_8UC1,
                               const_cast<std::uint8_t*>(left.pixels.data()));
        const teach_repeat::RepeatCommand c =
            Timed(&times.control_s, [&] { return repeater->Update(left_mat, frame.t_s); });
        if (observers.on_repeat_step) observers.on_repeat_step({frame.t_s, c});
        repeat_features_lost = c.features_lost;
        repeat_features_recovered = c.features_recovered;
        const estimation::TrackSpeeds cmd = estimation::TrackSpeedsFromTwist(c.twist, gauge_eff_m);
        vehicle.CommandTrackSpeeds(cmd.left_mps, cmd.right_mps);
        if (c.status != teach_repeat::RepeatStatus::kDriving) {
          stop_reason = std::string("repeat ") + teach_repeat::ToString(c.status);
          break;
        }
      }
      if (pair) {
        // The worker owns the pair until the frame's delivery gives it back; the main
        // thread meanwhile renders the next frames into other buffers.
        const Eigen::Isometry3d T_world_body = truth.T_world_body;
        const double t_s = frame.t_s;
        worker->Submit([&, pair, T_world_body, t_s, finish, finish_on_worker] {
          if (finish_on_worker) {
            const auto start = std::chrono::steady_clock::now();
            finish.Apply(&pair->first, &pair->second);
            sensor_model_on_worker_s +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          }
          const LocalizationFrame lf =
              LocalizeStereoFrame(*stack, t_s, finish.blackout, pair->first, pair->second);
          worker->Deliver([&, pair, T_world_body, lf] {
            free_pairs.push_back(pair);
            estimates.AddFrame(T_world_body, lf);
            if (observers.on_localization_frame) observers.on_localization_frame(lf);
          });
        });
        // Bounded look-ahead: the simulation runs at most about two camera periods ahead
        // of the robot software.
        worker->WaitUntilPendingAtMost(kMaxTasksAhead);
      }
    }
    if (clock.steps() > 0 && clock.Fires(imu_period)) {
      const Eigen::Vector3d accel = (truth.v_world - v_at_last_imu) / (imu_period * dt);
      v_at_last_imu = truth.v_world;
      const robot::ImuSample sample =
          imu.Sample(clock.now_s(), truth.T_world_body.linear(), truth.omega_world, accel);
      if (observers.on_imu) observers.on_imu(sample);
      if (worker) {
        worker->Submit([&, t = sample.t_s, w = sample.gyro_radps] { stack->AddGyroSample(t, w); });
      } else if (stack) {
        stack->AddGyroSample(sample.t_s, sample.gyro_radps);
      }
    }
    if (range_sensor && clock.Fires(scan_period)) {
      const robot::RangeScanSample scan = Timed(&times.sensing_s, [&] {
        return range_sensor->Scan(world, truth.T_world_body, clock.now_s(), scan_index++);
      });
      if (navigator) navigator->AddScan(scan);
    }
    if (clock.steps() >= end_step) {
      time_ran_out = true;
      break;
    }
    if (navigator) {
      if (clock.Fires(navigation_period)) {
        if (worker) worker->Drain();
        const estimation::Pose2 believed =
            scenario.navigation.pose_source == "ground_truth"
                ? estimation::PlanarPose(truth.T_world_body)
                : estimation::PlanarPose(scenario.navigation.pose_source == "fused"
                                             ? stack->fused()
                                             : stack->wheel_odometry());
        const estimation::TrackSpeeds cmd = Timed(&times.control_s, [&] {
          return navigator->Update(clock.now_s(), believed, truth.T_world_body, world.objects());
        });
        if (observers.on_navigation_step) observers.on_navigation_step(navigator->last_entry());
        vehicle.CommandTrackSpeeds(cmd.left_mps, cmd.right_mps);
        if (navigator->finished()) {
          stop_reason = "navigation " + navigator->Metrics(false).status;
          break;
        }
      }
    } else if (driver && clock.Fires(drive_period)) {
      bool finished = false;
      const estimation::TrackSpeeds cmd =
          Timed(&times.control_s, [&] { return driver->Update(clock.now_s(), truth, &finished); });
      vehicle.CommandTrackSpeeds(cmd.left_mps, cmd.right_mps);
      if (finished) {
        stop_reason = "path finished";
        break;
      }
    }
    Timed(&times.physics_s, [&] {
      vehicle.ApplyForces(dt);
      world.Step();
    });
    clock.Tick();
    if (vehicle.stalled()) {  // a motor at its torque limit that cannot turn: a result
      stop_reason = "stalled";
      break;
    }
  }

  if (worker) {
    worker->Drain();
    // The sensor model is its own stage, wherever it ran.
    estimation_wall_s = worker->busy_s() - sensor_model_on_worker_s;
    sensor_model_wall_s += sensor_model_on_worker_s;
  }
  RunMetrics m = metrics.Metrics();
  m.completed = !failed;
  m.stereo_frames = stereo_index;
  m.render_wall_s = render_wall_s;
  m.sensor_model_wall_s = sensor_model_wall_s;
  m.estimation_wall_s = estimation_wall_s;
  m.physics_wall_s = times.physics_s;
  m.control_wall_s = times.control_s;
  m.sensing_wall_s = times.sensing_s;
  m.io_wall_s = times.io_s;
  m.peak_rss_mb = PeakRssMb();
  m.repeat_features_lost = repeat_features_lost;
  m.repeat_features_recovered = repeat_features_recovered;
  m.estimators = estimates.Metrics(m.distance_m);
  m.localization = estimates.Summary();
  m.stop_reason = stop_reason;
  if (navigator) {
    m.navigation_method = scenario.navigation.method;
    m.navigation = navigator->Metrics(time_ran_out);
    m.navigation_subgoals = navigator->subgoals();
  }
  m.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return m;
}

}  // namespace trackbed::runner
