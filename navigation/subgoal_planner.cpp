// Sub-goal switching (see subgoal_planner.h for the paper's rule and our extensions).
#include "trackbed/navigation/subgoal_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {
namespace {

using geometry::WrapAngle;

// Candidates whose distances to the goal differ by less than this [m] are a tie.
constexpr double kTieM = 1e-3;

Eigen::Vector2d Direction(double angle_rad) { return {std::cos(angle_rad), std::sin(angle_rad)}; }

double Bearing(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  const Eigen::Vector2d d = to - from;
  return std::atan2(d.y(), d.x());
}

// Distance from point c to the segment [a, b].
double SegmentDistance(const Eigen::Vector2d& c, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((c - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - c).norm();
}

// Rule 5: the obstacle lies beyond the target and the straight way to the target clears
// it, so driving to the target never meets it.
bool BeyondTarget(const Eigen::Vector2d& robot, const Eigen::Vector2d& target,
                  const Circle& obstacle, double robot_radius_m) {
  const Eigen::Vector2d to_target = target - robot;
  const double range = to_target.norm();
  if (range <= 0.0) return true;
  const double along = (obstacle.centre - robot).dot(to_target / range);
  return along >= range &&
         SegmentDistance(obstacle.centre, robot, target) >= obstacle.radius_m + robot_radius_m;
}

// Nearest obstacle (by surface distance) that blocks the robot's heading, skipping those
// for which `skip(k)` holds. Rule 1 (alignment) is checked by the caller.
template <typename Skip>
std::optional<std::size_t> NearestBlocking(const Pose2& pose, const Eigen::Vector2d& target,
                                           const std::vector<Circle>& obstacles,
                                           const std::vector<double>& margins,
                                           const SubgoalOptions& options, Skip skip) {
  const Eigen::Vector2d p(pose.x, pose.y);
  const double d_max = options.safety_radius_m;
  std::optional<std::size_t> best;
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const Circle& o = obstacles[k];
    if (skip(k) || BeyondTarget(p, target, o, options.robot_radius_m)) continue;
    const AvoidanceCone cone = AvoidanceConeOf(p, d_max, o, margins[k]);
    const double distance = (o.centre - p).norm();
    bool blocked = cone.kind == AvoidanceCone::Kind::kEnclosing;
    if (!blocked && distance <= d_max + o.radius_m + margins[k]) {  // the circles meet
      blocked = std::abs(WrapAngle(pose.yaw - cone.direction_rad)) < cone.half_width_rad;
    }
    const double surface = distance - o.radius_m;
    if (blocked && surface < best_distance) {
      best_distance = surface;
      best = k;
    }
  }
  return best;
}

struct Plan {
  Eigen::Vector2d subgoal;
  Eigen::Vector2d edge_point;
  bool left = true;
};

// Rule 3: a candidate is free when its footprint overlaps no obstacle and the straight
// way to it enters no safety circle of an obstacle outside the group (unless the robot is
// inside that circle already).
bool CandidateFree(const Eigen::Vector2d& p, const Eigen::Vector2d& candidate,
                   const std::vector<Circle>& obstacles, const std::vector<double>& margins,
                   const std::vector<bool>& in_group, double robot_radius_m) {
  if (FootprintClearance(candidate, robot_radius_m, obstacles) <= 0.0) return false;
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    if (in_group[k]) continue;
    const double safety = obstacles[k].radius_m + margins[k];
    if ((obstacles[k].centre - p).norm() <= safety) continue;
    if (SegmentDistance(obstacles[k].centre, p, candidate) < safety) return false;
  }
  return true;
}

// Rule 2: the extreme edges of the union of the group's cones, grown from the blocking
// circle's cone; the candidate nearer the goal (rule 3: a free one first).
std::optional<Plan> PlanAround(const Eigen::Vector2d& p, const Eigen::Vector2d& goal,
                               const std::vector<Circle>& obstacles,
                               const std::vector<double>& margins,
                               const std::vector<std::size_t>& group, std::size_t blocking,
                               std::optional<bool> preferred_left, const SubgoalOptions& options,
                               bool* no_way_around) {
  *no_way_around = false;
  const double d_max = options.safety_radius_m;
  const double scale = options.subgoal_scale;
  const AvoidanceCone base = AvoidanceConeOf(p, d_max, obstacles[blocking], margins[blocking]);
  if (base.kind == AvoidanceCone::Kind::kEnclosing) {
    // Inside the physical circle (after a collision): back straight out, away from
    // the centre.
    Eigen::Vector2d away = p - obstacles[blocking].centre;
    away = away.norm() > 1e-9 ? Eigen::Vector2d(away.normalized()) : Eigen::Vector2d(1.0, 0.0);
    return Plan{p + scale * d_max * away, p + d_max * away, true};
  }

  struct Interval {
    double lo, hi, edge_distance;
  };
  std::vector<Interval> intervals;
  for (std::size_t k : group) {
    const AvoidanceCone c = AvoidanceConeOf(p, d_max, obstacles[k], margins[k]);
    if (c.kind == AvoidanceCone::Kind::kEnclosing) continue;
    const double offset = WrapAngle(c.direction_rad - base.direction_rad);
    for (double shift : {-2.0 * M_PI, 0.0, 2.0 * M_PI}) {
      intervals.push_back({offset + shift - c.half_width_rad, offset + shift + c.half_width_rad,
                           c.edge_distance_m});
    }
  }
  double lo = -base.half_width_rad, hi = base.half_width_rad;
  double lo_distance = base.edge_distance_m, hi_distance = base.edge_distance_m;
  for (bool grown = true; grown && hi - lo < 2.0 * M_PI;) {
    grown = false;
    for (const Interval& iv : intervals) {
      if (iv.lo <= hi && iv.hi > hi) {
        hi = iv.hi;
        hi_distance = iv.edge_distance;
        grown = true;
      }
      if (iv.hi >= lo && iv.lo < lo) {
        lo = iv.lo;
        lo_distance = iv.edge_distance;
        grown = true;
      }
    }
  }
  if (hi - lo >= 2.0 * M_PI - 1e-9) {
    *no_way_around = true;
    return std::nullopt;
  }
  const Eigen::Vector2d left_dir = Direction(base.direction_rad + hi);
  const Eigen::Vector2d right_dir = Direction(base.direction_rad + lo);
  // Rule 7: at least scale·d_max along the line (see the header).
  const Plan left{p + scale * std::max(hi_distance, d_max) * left_dir, p + hi_distance * left_dir,
                  true};
  const Plan right{p + scale * std::max(lo_distance, d_max) * right_dir,
                   p + lo_distance * right_dir, false};
  std::vector<bool> in_group(obstacles.size(), false);
  for (std::size_t k : group) in_group[k] = true;
  const bool left_free =
      CandidateFree(p, left.subgoal, obstacles, margins, in_group, options.robot_radius_m);
  const bool right_free =
      CandidateFree(p, right.subgoal, obstacles, margins, in_group, options.robot_radius_m);
  // Rule 8: keep the side already taken around this group while it is free.
  if (preferred_left && (*preferred_left ? left_free : right_free)) {
    return *preferred_left ? left : right;
  }
  if (left_free != right_free) return left_free ? left : right;
  // Eq. (20): the candidate nearer the goal; ties (collinear scenes) go left.
  const double dl = (left.subgoal - goal).norm(), dr = (right.subgoal - goal).norm();
  return dr < dl - kTieM ? right : left;
}

}  // namespace

std::optional<SubgoalPair> TangentSubgoals(const Eigen::Vector2d& robot,
                                           const Eigen::Vector2d& centre, double safety_radius_m,
                                           double scale) {
  const double d = (centre - robot).norm();
  if (!(d > safety_radius_m)) return std::nullopt;
  const double theta1 = Bearing(robot, centre);          // eq. (13)
  const double theta2 = std::asin(safety_radius_m / d);  // tangent ⟂ radius
  const double length = std::sqrt(d * d - safety_radius_m * safety_radius_m);
  SubgoalPair pair;
  pair.left_point = robot + length * Direction(theta1 + theta2);
  pair.right_point = robot + length * Direction(theta1 - theta2);
  pair.left = robot + scale * (pair.left_point - robot);
  pair.right = robot + scale * (pair.right_point - robot);
  return pair;
}

std::optional<SubgoalPair> IntersectionSubgoals(const Eigen::Vector2d& robot,
                                                double robot_circle_radius_m,
                                                const Eigen::Vector2d& centre,
                                                double safety_radius_m, double scale) {
  const double d = (centre - robot).norm();
  const double a = robot_circle_radius_m, s = safety_radius_m;
  if (!(d > 0.0) || !(d < a + s) || !(d > std::abs(a - s))) return std::nullopt;
  // The radical line of the two circles (the paper's line through the intersection
  // points, just before eq. 20) cuts the robot→centre line
  // at distance x from the robot; the intersection points are ±y across it.
  const double x = (d * d + a * a - s * s) / (2.0 * d);
  const double y = std::sqrt(std::max(0.0, a * a - x * x));
  const Eigen::Vector2d u = (centre - robot) / d;
  const Eigen::Vector2d n(-u.y(), u.x());  // left of the robot→centre line
  SubgoalPair pair;
  pair.left_point = robot + x * u + y * n;
  pair.right_point = robot + x * u - y * n;
  pair.left = robot + scale * (pair.left_point - robot);
  pair.right = robot + scale * (pair.right_point - robot);
  return pair;
}

AvoidanceCone AvoidanceConeOf(const Eigen::Vector2d& robot, double robot_circle_radius_m,
                              const Circle& obstacle, double obstacle_margin_m) {
  AvoidanceCone cone;
  const double d = (obstacle.centre - robot).norm();
  const double s = obstacle.radius_m + obstacle_margin_m;
  const double a = robot_circle_radius_m;
  cone.direction_rad = Bearing(robot, obstacle.centre);
  if (d < obstacle.radius_m || d <= 1e-12) {
    cone.kind = AvoidanceCone::Kind::kEnclosing;
    cone.half_width_rad = M_PI;
    return cone;
  }
  if (d > s) {  // outside: tangents, θ2 = asin(s/d)
    cone.kind = AvoidanceCone::Kind::kTangent;
    cone.half_width_rad = std::asin(s / d);
    cone.edge_distance_m = std::sqrt(d * d - s * s);
    return cone;
  }
  if (d < a - s) {  // the obstacle's circle lies inside the robot's: no intersection
    cone.kind = AvoidanceCone::Kind::kHalfPlane;
    cone.half_width_rad = M_PI / 2.0;
    cone.edge_distance_m = a;
    return cone;
  }
  // Inside: the lines to the intersection points, θ4 from the radical line.
  const double x = (d * d + a * a - s * s) / (2.0 * d);
  const double y = std::sqrt(std::max(0.0, a * a - x * x));
  cone.kind = AvoidanceCone::Kind::kIntersection;
  cone.half_width_rad = std::atan2(y, x);
  cone.edge_distance_m = a;
  return cone;
}

bool Blocks(const Pose2& robot, const Circle& obstacle, double safety_radius_m) {
  const Eigen::Vector2d p(robot.x, robot.y);
  const AvoidanceCone cone = AvoidanceConeOf(p, safety_radius_m, obstacle, safety_radius_m);
  if (cone.kind == AvoidanceCone::Kind::kEnclosing) return true;
  if ((obstacle.centre - p).norm() > 2.0 * safety_radius_m + obstacle.radius_m) return false;
  return std::abs(WrapAngle(robot.yaw - cone.direction_rad)) < cone.half_width_rad;
}

std::vector<int> ClusterLabels(const std::vector<Circle>& obstacles,
                               const std::vector<double>& margins_m) {
  const std::size_t n = obstacles.size();
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const double reach =
          obstacles[i].radius_m + margins_m[i] + obstacles[j].radius_m + margins_m[j];
      if ((obstacles[i].centre - obstacles[j].centre).norm() < reach) {
        parent[find(i)] = find(j);
      }
    }
  }
  std::vector<int> labels(n, -1);
  std::vector<int> label_of_root(n, -1);
  int next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = find(i);
    if (label_of_root[r] < 0) label_of_root[r] = next++;
    labels[i] = label_of_root[r];
  }
  return labels;
}

void SubgoalOptions::Validate() const {
  option_check::Positive("safety_radius_m", safety_radius_m);
  if (!(std::isfinite(subgoal_scale) && subgoal_scale >= 1.0)) {
    throw OptionError("subgoal_scale",
                      "must be >= 1 (got " + option_check::Describe(subgoal_scale) + ")");
  }
  option_check::Positive("reached_distance_m", reached_distance_m);
  option_check::InRange("alignment_band_rad", alignment_band_rad, 1e-9, M_PI);
  option_check::InRange("robot_radius_m", robot_radius_m, 0.0, safety_radius_m);
  option_check::NonNegative("goal_margin_m", goal_margin_m);
  option_check::Positive("match_distance_m", match_distance_m);
}

std::vector<double> SafetyMargins(const std::vector<Circle>& obstacles, const Eigen::Vector2d& goal,
                                  const SubgoalOptions& options) {
  std::vector<double> margins(obstacles.size(), options.safety_radius_m);
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const double surface = SurfaceDistance(goal, obstacles[k]);
    if (surface < options.safety_radius_m + options.goal_margin_m) {  // rule 6
      margins[k] = std::min(options.safety_radius_m,
                            std::max(options.robot_radius_m, surface - options.goal_margin_m));
    }
  }
  return margins;
}

SubgoalSwitcher::SubgoalSwitcher(const SubgoalOptions& options, const Pose2& goal)
    : options_(options), goal_(goal) {
  options_.Validate();
}

ActiveTarget SubgoalSwitcher::Update(const Pose2& pose, const std::vector<Circle>& obstacles) {
  const Eigen::Vector2d p(pose.x, pose.y);
  const Eigen::Vector2d goal_xy(goal_.x, goal_.y);
  if (active_ &&
      (Eigen::Vector2d(subgoal_.x, subgoal_.y) - p).norm() <= options_.reached_distance_m) {
    subgoals_.back().reached = true;
    active_ = false;
    group_.clear();
  }

  ActiveTarget out;
  const Eigen::Vector2d target = active_ ? Eigen::Vector2d(subgoal_.x, subgoal_.y) : goal_xy;
  const double range = (target - p).norm();
  const bool aligned = range > 0.0 && std::abs(WrapAngle(Bearing(p, target) - pose.yaw)) <=
                                          options_.alignment_band_rad;
  if (aligned && !obstacles.empty()) {
    const std::vector<double> margins = SafetyMargins(obstacles, goal_xy, options_);
    // Rule 4: membership of the active sub-goal's group, by position (sensed
    // obstacles move a little from scan to scan).
    auto in_group = [&](std::size_t k) {
      return std::any_of(group_.begin(), group_.end(), [&](const Circle& g) {
        return (obstacles[k].centre - g.centre).norm() <= g.radius_m + options_.match_distance_m;
      });
    };
    const std::optional<std::size_t> blocking = NearestBlocking(
        pose, target, obstacles, margins, options_, [&](std::size_t k) { return in_group(k); });
    if (!blocking && !active_) side_group_.clear();  // free way to the goal: forget sides
    if (blocking) {
      out.blocking_obstacle = static_cast<int>(*blocking);
      std::vector<std::size_t> group;
      const std::vector<int> labels =
          options_.cluster_obstacles ? ClusterLabels(obstacles, margins) : std::vector<int>();
      for (std::size_t k = 0; k < obstacles.size(); ++k) {
        const bool same_cluster =
            k == *blocking || (!labels.empty() && labels[k] == labels[*blocking]);
        if ((same_cluster && !BeyondTarget(p, target, obstacles[k], options_.robot_radius_m)) ||
            in_group(k)) {
          group.push_back(k);
        }
      }
      // Rule 8: the side remembered for the group the blocking obstacle belongs to.
      const bool remembered =
          std::any_of(side_group_.begin(), side_group_.end(), [&](const Circle& g) {
            return (obstacles[*blocking].centre - g.centre).norm() <=
                   g.radius_m + options_.match_distance_m;
          });
      bool no_way_around = false;
      const std::optional<Plan> plan = PlanAround(
          p, goal_xy, obstacles, margins, group, *blocking,
          remembered ? std::optional<bool>(side_left_) : std::nullopt, options_, &no_way_around);
      out.no_way_around = no_way_around;
      if (plan) {
        active_ = true;
        subgoal_ = {plan->subgoal.x(), plan->subgoal.y(), Bearing(p, plan->subgoal)};
        group_.clear();
        for (std::size_t k : group) group_.push_back(obstacles[k]);
        if (!remembered) side_group_.clear();
        for (std::size_t k : group) side_group_.push_back(obstacles[k]);
        side_left_ = plan->left;
        SubgoalRecord record;
        record.position = plan->subgoal;
        record.created_from = p;
        record.edge_point = plan->edge_point;
        record.group_size = static_cast<int>(group.size());
        record.left = plan->left;
        subgoals_.push_back(record);
        out.new_subgoal = true;
      }
    }
  }
  out.subgoal_active = active_;
  out.pose = active_ ? subgoal_ : goal_;
  return out;
}

}  // namespace trackbed::navigation
