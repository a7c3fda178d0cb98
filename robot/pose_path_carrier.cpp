// A body on a scripted path (see pose_path_carrier.h).
#include "trackbed/robot/pose_path_carrier.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

namespace trackbed::robot {
namespace {

// Arc length between the curve's samples [m]: fine enough that the polyline through
// them departs from the curve by micrometres on a road's bends (s²/8R: 0.3 µm at 50 m).
constexpr double kSampleSpacingM = 0.05;
// Step of the finite differences that give the body's velocities [m of path].
constexpr double kDifferenceStepM = 0.01;

// Point at parameter u ∈ [0, 1] of the centripetal Catmull–Rom segment from p1 to p2
// (Barry and Goldman's pyramid; knots spaced by the square root of the chord).
Eigen::Vector2d CatmullRom(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                           const Eigen::Vector2d& p2, const Eigen::Vector2d& p3, double u) {
  const double t0 = 0.0;
  const double t1 = t0 + std::sqrt((p1 - p0).norm());
  const double t2 = t1 + std::sqrt((p2 - p1).norm());
  const double t3 = t2 + std::sqrt((p3 - p2).norm());
  const double t = t1 + u * (t2 - t1);
  const auto lerp = [t](const Eigen::Vector2d& a, const Eigen::Vector2d& b, double ta,
                        double tb) -> Eigen::Vector2d {
    return ((tb - t) * a + (t - ta) * b) / (tb - ta);
  };
  const Eigen::Vector2d a1 = lerp(p0, p1, t0, t1);
  const Eigen::Vector2d a2 = lerp(p1, p2, t1, t2);
  const Eigen::Vector2d a3 = lerp(p2, p3, t2, t3);
  const Eigen::Vector2d b1 = lerp(a1, a2, t0, t2);
  const Eigen::Vector2d b2 = lerp(a2, a3, t1, t3);
  return lerp(b1, b2, t1, t2);
}

// The curve's control points: the waypoints with one more at each end — the ends
// mirrored (an open curve leaves its ends straight on) or the waypoints wrapped (closed).
std::vector<Eigen::Vector2d> ControlPoints(const std::vector<Eigen::Vector2d>& w, bool closed) {
  const std::size_t n = w.size();
  std::vector<Eigen::Vector2d> c;
  c.reserve(n + 3);
  c.push_back(closed ? w[n - 1] : Eigen::Vector2d(2.0 * w[0] - w[1]));
  c.insert(c.end(), w.begin(), w.end());
  if (closed) {
    c.push_back(w[0]);
    c.push_back(w[1]);
  } else {
    c.push_back(2.0 * w[n - 1] - w[n - 2]);
  }
  return c;
}

void CheckOptions(const PosePathOptions& o) {
  const std::size_t n = o.waypoints.size();
  if (n < 2) throw std::invalid_argument("pose path: needs at least 2 waypoints");
  for (std::size_t k = 0; k < n; ++k) {
    if (!o.waypoints[k].allFinite()) {
      throw std::invalid_argument("pose path: waypoint " + std::to_string(k) + " is not finite");
    }
    const std::size_t next = k + 1 < n ? k + 1 : 0;
    if ((next != 0 || o.closed) && (o.waypoints[next] - o.waypoints[k]).norm() < 1e-6) {
      throw std::invalid_argument("pose path: waypoints " + std::to_string(k) + " and " +
                                  std::to_string(next) + " coincide");
    }
  }
  if (!(o.speed_mps > 0.0 && std::isfinite(o.speed_mps))) {
    throw std::invalid_argument("pose path: the speed must be > 0");
  }
  if (o.laps < 1) throw std::invalid_argument("pose path: laps must be >= 1");
  if (!(o.footprint_length_m > 0.0 && o.footprint_width_m > 0.0)) {
    throw std::invalid_argument("pose path: the footprint must be > 0 in length and width");
  }
}

}  // namespace

PosePathCarrier::PosePathCarrier(const PosePathOptions& options, const sim::Terrain* terrain,
                                 const calibration::VehicleCalibration& tracks, double gravity_mps2)
    : terrain_(terrain),
      closed_(options.closed),
      laps_(options.closed ? options.laps : 1),
      speed_mps_(options.speed_mps),
      body_height_m_(options.body_height_m),
      half_length_m_(0.5 * options.footprint_length_m),
      half_width_m_(0.5 * options.footprint_width_m),
      load_n_(0.5 * options.mass_kg * gravity_mps2),
      stations_(options.stations_per_track),
      gauge_m_(tracks.track_gauge_m),
      sprocket_radius_m_{tracks.sprocket_radius_left_m, tracks.sprocket_radius_right_m} {
  CheckOptions(options);
  const std::vector<Eigen::Vector2d> c = ControlPoints(options.waypoints, closed_);
  const std::size_t segments = options.waypoints.size() - (closed_ ? 0 : 1);
  samples_.push_back({0.0, c[1], 0.0});
  for (std::size_t k = 0; k < segments; ++k) {
    const int pieces =
        std::max(16, static_cast<int>(std::ceil((c[k + 2] - c[k + 1]).norm() / kSampleSpacingM)));
    for (int i = 1; i <= pieces; ++i) {
      const Eigen::Vector2d p =
          CatmullRom(c[k], c[k + 1], c[k + 2], c[k + 3], static_cast<double>(i) / pieces);
      samples_.push_back({samples_.back().s_m + (p - samples_.back().p).norm(), p, 0.0});
    }
  }
  // Headings by central differences (one-sided at an open curve's ends), unwrapped.
  const std::size_t n = samples_.size();
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t before = k > 0 ? k - 1 : (closed_ ? n - 2 : 0);
    std::size_t after = k + 1 < n ? k + 1 : (closed_ ? 1 : n - 1);
    const Eigen::Vector2d d = samples_[after].p - samples_[before].p;
    double h = std::atan2(d.y(), d.x());
    if (k > 0) h += 2.0 * M_PI * std::round((samples_[k - 1].heading_rad - h) / (2.0 * M_PI));
    samples_[k].heading_rad = h;
  }
  lap_length_m_ = samples_.back().s_m;
  for (TrackState& t : tracks_) {
    t.normal_load_n = load_n_;
    t.stations_in_contact = stations_;
  }
  state_ = StateAt(0.0);
}

void PosePathCarrier::Interpolate(double s_m, Eigen::Vector2d* p, double* heading_rad) const {
  const auto after = std::upper_bound(samples_.begin(), samples_.end(), s_m,
                                      [](double s, const Sample& x) { return s < x.s_m; });
  const std::size_t i = std::clamp<std::size_t>(after - samples_.begin(), 1, samples_.size() - 1);
  const Sample& a = samples_[i - 1];
  const Sample& b = samples_[i];
  const double w = std::clamp((s_m - a.s_m) / (b.s_m - a.s_m), 0.0, 1.0);
  *p = (1.0 - w) * a.p + w * b.p;
  *heading_rad = (1.0 - w) * a.heading_rad + w * b.heading_rad;
}

Eigen::Isometry3d PosePathCarrier::PoseOnGround(const Eigen::Vector2d& p,
                                                double heading_rad) const {
  const Eigen::Vector2d f(std::cos(heading_rad), std::sin(heading_rad));
  const Eigen::Vector2d l(-f.y(), f.x());
  const auto height = [this](const Eigen::Vector2d& q) { return terrain_->Height(q.x(), q.y()); };
  const double front = height(p + half_length_m_ * f), back = height(p - half_length_m_ * f);
  const double left = height(p + half_width_m_ * l), right = height(p - half_width_m_ * l);
  const Eigen::Vector3d x =
      Eigen::Vector3d(f.x(), f.y(), (front - back) / (2.0 * half_length_m_)).normalized();
  const Eigen::Vector3d y_up(l.x(), l.y(), (left - right) / (2.0 * half_width_m_));
  const Eigen::Vector3d z = x.cross(y_up).normalized();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = z.cross(x);
  T.linear().col(2) = z;
  const double ground = 0.25 * (front + back + left + right);
  T.translation() = Eigen::Vector3d(p.x(), p.y(), ground) + body_height_m_ * z;
  return T;
}

Eigen::Isometry3d PosePathCarrier::PoseAt(double s_m) const {
  const double s = std::clamp(s_m, 0.0, length_m());
  const double lap = closed_ ? std::min(std::floor(s / lap_length_m_), laps_ - 1.0) : 0.0;
  Eigen::Vector2d p;
  double heading = 0.0;
  Interpolate(s - lap * lap_length_m_, &p, &heading);
  return PoseOnGround(p, heading);
}

ChassisState PosePathCarrier::StateAt(double s_m) const {
  const double s = std::clamp(s_m, 0.0, length_m());
  ChassisState state;
  state.T_world_body = PoseAt(s);
  if (s >= length_m()) return state;  // standing at the end
  // Velocities by a difference over the next centimetre of path (the last one before
  // the end), at the set speed.
  const double a = std::min(s, length_m() - kDifferenceStepM);
  const Eigen::Isometry3d T0 = PoseAt(a), T1 = PoseAt(a + kDifferenceStepM);
  const double dt = kDifferenceStepM / speed_mps_;
  state.v_world = (T1.translation() - T0.translation()) / dt;
  const Eigen::AngleAxisd turn(T1.linear() * T0.linear().transpose());
  state.omega_world = turn.angle() / dt * turn.axis();
  return state;
}

void PosePathCarrier::ApplyForces(double dt_s) {
  const double s_before = std::min(speed_mps_ * t_s_, length_m());
  t_s_ += dt_s;
  const double s_after = std::min(speed_mps_ * t_s_, length_m());
  state_ = StateAt(s_after);
  // Tracks without slip: each side's speed over the ground is the body's forward speed
  // less (left) or plus (right) its yaw rate times half the gauge, taken at the middle
  // of the step's stretch of path and held for the time it took (the last step may
  // reach the end early).
  const ChassisState mid = StateAt(0.5 * (s_before + s_after));
  const Eigen::Matrix3d R = mid.T_world_body.linear();
  const double v = (R.transpose() * mid.v_world).x();
  const double yaw_rate = (R.transpose() * mid.omega_world).z();
  const double moving_s = (s_after - s_before) / speed_mps_;
  const bool moving = s_after < length_m();
  for (int side = 0; side < 2; ++side) {
    const double speed = v + (side == kLeft ? -0.5 : 0.5) * gauge_m_ * yaw_rate;
    TrackState& t = tracks_[side];
    t.track_speed_mps = moving ? speed : 0.0;
    t.ground_speed_mps = t.track_speed_mps;
    t.sprocket_speed_radps = t.track_speed_mps / sprocket_radius_m_[side];
    t.sprocket_angle_rad += speed * moving_s / sprocket_radius_m_[side];
  }
}

}  // namespace trackbed::robot
