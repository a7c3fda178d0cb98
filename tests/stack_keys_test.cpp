// Every key of the scenario's `navigation` and `teach_repeat` sections reaches what a
// run builds from it: each scalar key, set alone by a `--set` override to a value of
// its own, is found in the options the runner builds (the navigators', the kinematic
// simulation's, the scan clustering's, the teach pass's and both repeaters'), read
// back through the same key lists, or in the section the runner reads it from. And the
// sections' enumerations name their values when given another.
#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "scenario_key_walk.h"
#include "trackbed/common/archive.h"
#include "trackbed/common/units.h"
#include "trackbed/navigation/navigator_factory.h"
#include "trackbed/navigation/pure_pursuit.h"
#include "trackbed/runner/closed_loop_navigation.h"
#include "trackbed/runner/navigation_scenario.h"
#include "trackbed/runner/path_driver.h"
#include "trackbed/runner/teach_repeat_run.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::scenario {
namespace {

using archive::Node;

// Valid as it is, with the stereo camera on so that teach & repeat may be enabled.
constexpr char kBase[] =
    "drive:\n  waypoints: [[0, 0], [5, 0]]\nrobot:\n  stereo:\n    enabled: true\n";

Scenario Parse(const std::vector<Override>& overrides) {
  return ParseScenario(kBase, "test.yaml", overrides);
}

// The message ParseScenario throws for one override (empty when it does not throw).
std::string ErrorOf(const std::string& key, const std::string& value) {
  try {
    Parse({{key, value}});
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

// The sections as a run sees them: the scenario's own, with every part the runner
// builds options from replaced by the options it builds, written through their key
// lists. A key the runner drops, or builds from elsewhere, shows its default there.
Node RunView(const Scenario& s) {
  Node root = Node::Map();
  Node nav = archive::Write(s.navigation);
  const navigation::NavigatorOptions built = runner::NavigatorOptionsOf(s);
  const Node built_node = archive::Write(built);
  for (const auto& [key, value] : built_node.entries()) nav.Set(key, value);
  const navigation::KinematicSimulationOptions kinematic = runner::KinematicOptionsOf(s);
  nav.Set("kinematic", archive::Write(kinematic));
  nav.Set("clustering", archive::Write(runner::ClusteringOptionsOf(s)));
  nav.Set("safety_radius_m", archive::Write(built.subgoal.safety_radius_m));
  // Every method keeps the one footprint clear.
  EXPECT_EQ(built.potential_field.robot_radius_m, built.subgoal.robot_radius_m);
  EXPECT_EQ(built.dwa.robot_radius_m, built.subgoal.robot_radius_m);
  nav.Set("footprint_radius_m", archive::Write(built.subgoal.robot_radius_m));
  if (s.navigation.mode == NavigationSpec::Mode::kKinematic) {  // the simulation's robot too
    EXPECT_EQ(kinematic.footprint_radius_m, built.subgoal.robot_radius_m);
    EXPECT_EQ(kinematic.drive.wheel_radius_m, built.setup.drive.wheel_radius_m);
    EXPECT_EQ(kinematic.drive.wheel_separation_m, built.setup.drive.wheel_separation_m);
    EXPECT_EQ(kinematic.drive.max_wheel_speed_radps, built.setup.drive.max_wheel_speed_radps);
  }
  EXPECT_EQ(kinematic.control_period_s, built.setup.control_period_s);
  root.Set("navigation", nav);

  const TeachRepeatSpec& tr = s.teach_repeat;
  Node teach = archive::Write(tr);
  const teach_repeat::MilestoneBuilderOptions milestones = runner::MilestoneBuilderOptionsOf(tr);
  EXPECT_EQ(milestones.mode, tr.method);
  teach.Set("milestones", archive::Write(milestones));
  const teach_repeat::FunnelLaneOptions lane = runner::FunnelLaneOptionsOf(tr);
  const teach_repeat::Localizer3dOptions localizer = runner::Localizer3dOptionsOf(tr);
  teach.Set("funnel_lane", archive::Write(lane));
  teach.Set("localizer_3d", archive::Write(localizer));
  teach.Set("max_milestone_overrun", archive::Write(lane.max_milestone_overrun));
  teach.Set("repeat_speed_mps", archive::Write(lane.forward_speed_mps));
  EXPECT_EQ(localizer.forward_speed_mps, lane.forward_speed_mps);
  EXPECT_EQ(lane.turn_rate_radps, units::Radians(tr.repeat_turn_rate_deg_s));
  EXPECT_EQ(localizer.max_yaw_rate_radps, units::Radians(tr.repeat_turn_rate_deg_s));
  root.Set("teach_repeat", teach);
  return root;
}

// The names an enumeration key accepts, from the message for a name it does not (empty
// for a key that takes any string).
std::vector<std::string> AllowedNames(const std::string& key) {
  const std::string error = ErrorOf(key, "no_such_name");
  const std::string head = "must be one of ";
  const std::size_t begin = error.find(head);
  if (begin == std::string::npos) return {};
  const std::string list =
      error.substr(begin + head.size(), error.find(" (got") - begin - head.size());
  std::vector<std::string> names;
  for (std::size_t at = 0; at <= list.size();) {
    const std::size_t comma = std::min(list.find(", ", at), list.size());
    names.push_back(list.substr(at, comma - at));
    at = comma + 2;
  }
  return names;
}

// Values of the key's type other than `now`, to try in order until one is valid: a
// number's or a bool's from key_walk::OtherValues (numbers smallest first: some are
// capped by another key, d_max caps the clustering's wall spacing), an enumeration's
// other names, else a free string (teach_repeat.map).
std::vector<std::string> OtherValues(const std::string& key, const Node& now) {
  if (now.tag() != Node::Tag::kString && now.tag() != Node::Tag::kPlain) {
    std::vector<std::string> values = key_walk::OtherValues(now);
    if (now.tag() == Node::Tag::kFloat) {
      std::sort(values.begin(), values.end(), [](const std::string& a, const std::string& b) {
        return *archive::ParseDouble(a) < *archive::ParseDouble(b);
      });
    }
    return values;
  }
  std::vector<std::string> names;
  for (const std::string& name : AllowedNames(key)) {
    if (name != now.text()) names.push_back(name);
  }
  if (names.empty()) names.push_back("some_" + key);
  return names;
}

// The scenario with `key` set to the first of `values` that is valid, and that value.
std::optional<std::pair<Scenario, std::string>> WithOtherValue(
    const std::string& key, const std::vector<std::string>& values) {
  for (const std::string& value : values) {
    try {
      return std::make_pair(Parse({{key, value}}), value);
    } catch (const ScenarioError&) {
    }
  }
  return std::nullopt;
}

// The keys whose built values a key changes besides its own: in closed loop the drive is
// the tracked robot's and the footprint covers its hull; d_max bounds the clustering's
// wall spacing.
bool DependsOn(const std::string& other, const std::string& key) {
  if (key == "navigation.mode") {
    for (const char* k :
         {"wheel_radius_m", "wheel_separation_m", "max_wheel_speed_radps", "footprint_radius_m"}) {
      if (other == std::string("navigation.") + k) return true;
    }
  }
  return key == "navigation.safety_radius_m" && other == "navigation.clustering.wall_spacing_m";
}

TEST(StackKeysTest, EveryKeyReachesWhatTheRunBuilds) {
  const Scenario base = Parse({});
  std::vector<key_walk::ScalarKey> leaves;
  const Node written = archive::Write(base);
  for (const char* section : {"navigation", "teach_repeat"}) {
    key_walk::CollectScalarKeys(*written.Find(section), section, &leaves);
  }
  ASSERT_GT(leaves.size(), 120u);  // the sections' structs are all visited
  for (const auto& [key, now] : leaves) {
    const std::vector<std::string> values = OtherValues(key, now);
    const std::optional<std::pair<Scenario, std::string>> set = WithOtherValue(key, values);
    SCOPED_TRACE(key);
    if (!set) {
      ADD_FAILURE() << "no value other than " << now.text() << " is valid";
      continue;
    }
    const auto& [s_value, value] = *set;
    const Scenario* s = &s_value;
    const Node view = RunView(*s);
    const Node* got = key_walk::NodeAt(view, key);
    ASSERT_NE(got, nullptr);
    EXPECT_EQ(got->text(), value);
    // Nothing else moved: the run's view of the default scenario with this key set.
    const Node before = RunView(base);
    std::vector<key_walk::ScalarKey> all, all_before;
    key_walk::CollectScalarKeys(view, "", &all);
    key_walk::CollectScalarKeys(before, "", &all_before);
    ASSERT_EQ(all.size(), all_before.size());
    for (std::size_t m = 0; m < all.size(); ++m) {
      if (all[m].path == key || DependsOn(all[m].path, key)) continue;
      EXPECT_EQ(all[m].value.text(), all_before[m].value.text()) << all[m].path;
    }
  }
}

TEST(StackKeysTest, EnumerationsNameTheirValues) {
  const std::pair<const char*, const char*> kCases[] = {
      {"navigation.method", "gauss_newton_subgoal, potential_field, dwa"},
      {"navigation.mode", "kinematic, closed_loop"},
      {"navigation.field",
       "none, random, paper_left, paper_right, u_trap, narrow_gap, goal_beside_wall, "
       "narrow_corridor"},
      {"navigation.pose_source", "fused, wheel_odometry, ground_truth"},
      {"teach_repeat.method", "2d, 3d"},
      {"teach_repeat.milestones.interval_unit", "images, distance"},
      {"teach_repeat.funnel_lane.switch_error", "mean_absolute, mean_outward"},
  };
  for (const auto& [key, names] : kCases) {
    EXPECT_EQ(ErrorOf(key, "teleport"), std::string("--set ") + key + "=teleport: " + key +
                                            ": must be one of " + names + " (got 'teleport')");
  }
  EXPECT_EQ(Parse({{"navigation.method", "dwa"}}).navigation.method,
            navigation::NavigationMethod::kDwa);
  EXPECT_EQ(Parse({{"navigation.field", "u_trap"}}).navigation.field,
            NavigationSpec::Field::kUTrap);
  EXPECT_EQ(Parse({{"navigation.pose_source", "wheel_odometry"}}).navigation.pose_source,
            NavigationSpec::PoseSource::kWheelOdometry);
  EXPECT_EQ(Parse({{"teach_repeat.method", "3d"}}).teach_repeat.method,
            teach_repeat::TeachMode::k3d);
}

TEST(StackKeysTest, DerivedFieldsAreNotKeys) {
  // The footprint, d_max, the repeat speeds and the teach mode have one key each, at
  // the section's level; the structs they reach do not list them again.
  const Node written = archive::Write(Parse({}));
  for (const char* key :
       {"navigation.subgoal.safety_radius_m", "navigation.subgoal.robot_radius_m",
        "navigation.potential_field.robot_radius_m", "navigation.dwa.robot_radius_m",
        "navigation.kinematic.footprint_radius_m", "navigation.kinematic.drive",
        "navigation.kinematic.control_period_s", "navigation.kinematic.criteria",
        "teach_repeat.milestones.mode", "teach_repeat.funnel_lane.forward_speed_mps",
        "teach_repeat.funnel_lane.turn_rate_radps",
        "teach_repeat.funnel_lane.max_milestone_overrun",
        "teach_repeat.localizer_3d.forward_speed_mps",
        "teach_repeat.localizer_3d.max_yaw_rate_radps"}) {
    EXPECT_EQ(key_walk::NodeAt(written, key), nullptr) << key;
  }
  // In closed loop the drive is the tracked robot's and the footprint covers the hull.
  const Scenario s = Parse({{"navigation.mode", "closed_loop"},
                            {"navigation.wheel_radius_m", "0.3"},
                            {"navigation.footprint_radius_m", "0.1"}});
  const navigation::NavigatorOptions o = runner::NavigatorOptionsOf(s);
  EXPECT_EQ(o.setup.drive.wheel_radius_m, s.robot.vehicle.sprocket_radius_m);
  EXPECT_EQ(o.setup.drive.max_wheel_speed_radps,
            s.navigation.max_speed_mps / s.robot.vehicle.sprocket_radius_m);
  EXPECT_EQ(o.dwa.robot_radius_m, 0.5 * s.robot.vehicle.hull_size_m.head<2>().norm());
  EXPECT_EQ(
      runner::ClusteringOptionsOf(Parse({{"navigation.safety_radius_m", "0.7"}})).wall_spacing_m,
      0.7);
}

// The drive's path follower takes the `drive` section's pursuit keys as they are: each,
// set alone to a valid other value, is the follower's option (PathDriver builds its
// PurePursuit from DriveSpec::pursuit).
TEST(StackKeysTest, DriveKeysReachThePathFollower) {
  const Node defaults = archive::Write(navigation::PurePursuitOptions{});
  ASSERT_EQ(defaults.size(), 5u);
  for (const auto& [name, now] : defaults.entries()) {
    const std::string key = "drive." + name;
    SCOPED_TRACE(key);
    const std::optional<std::pair<Scenario, std::string>> set =
        WithOtherValue(key, key_walk::OtherValues(now));
    ASSERT_TRUE(set.has_value());
    const Node built = archive::Write(set->first.drive.pursuit);
    EXPECT_EQ(built.Find(name)->text(), set->second);
    for (const auto& [other, value] : built.entries()) {
      if (other != name) {
        EXPECT_EQ(value.text(), defaults.Find(other)->text()) << other;
      }
    }
  }
}

// drive.start_standstill_s: the tracks at zero for its length, then the script on a clock
// started at its end; the run lasts duration_s plus it when the scenario drives, not when
// a commander from outside or kinematic navigation does.
TEST(StackKeysTest, TheStartStandstillHoldsTheTracksAndLengthensTheRun) {
  Scenario s = Parse({{"drive.start_standstill_s", "2"}, {"duration_s", "30"}});
  s.drive.mode = DriveSpec::Mode::kScript;
  s.drive.script.resize(2);
  s.drive.script[0].v_mps = 0.3;
  s.drive.script[1].t_s = 1.0;
  s.drive.script[1].v_mps = 0.5;
  runner::PathDriver driver(s.drive, 0.5);
  runner::ControlInput in;
  in.t_s = 1.5;
  EXPECT_EQ(driver.Update(in).tracks.left_mps, 0.0);
  in.t_s = 2.5;  // 0.5 s into the script: its first command
  EXPECT_DOUBLE_EQ(driver.Update(in).tracks.left_mps, 0.3);
  in.t_s = 3.0;  // 1 s into the script: its second
  EXPECT_DOUBLE_EQ(driver.Update(in).tracks.left_mps, 0.5);
  EXPECT_EQ(s.RunDuration(DriveSource::kScenario), 32.0);
  EXPECT_EQ(s.RunDuration(DriveSource::kExternal), 30.0);
  s.navigation.enabled = true;  // kinematic: no stack to take a bias
  EXPECT_EQ(s.RunDuration(DriveSource::kScenario), 30.0);
  s.navigation.mode = scenario::NavigationSpec::Mode::kClosedLoop;
  EXPECT_EQ(s.RunDuration(DriveSource::kScenario), 32.0);
}

// Closed-loop navigation starts after drive.start_standstill_s: the tracks at zero and
// nothing logged before it, the navigator driving from its end, and the time limit
// duration_s plus it.
TEST(StackKeysTest, ClosedLoopNavigationStartsAfterTheStandstill) {
  Scenario s = Parse({{"drive.start_standstill_s", "2"},
                      {"duration_s", "30"},
                      {"navigation.enabled", "true"},
                      {"navigation.mode", "closed_loop"},
                      {"navigation.pose_source", "ground_truth"},
                      {"robot.range_sensor.enabled", "true"},
                      {"navigation.goal", "{x_m: 5, y_m: 0, yaw_deg: 0}"}});
  runner::ClosedLoopNavigation nav(s, {}, {}, {});
  runner::ControlInput in;
  in.t_s = 1.9;
  runner::ControlOutput out = nav.Update(in);
  EXPECT_EQ(out.tracks.left_mps, 0.0);
  EXPECT_EQ(out.tracks.right_mps, 0.0);
  EXPECT_FALSE(out.stop_reason);
  in.t_s = 2.0;  // the navigator's first step: toward the goal 5 m ahead
  out = nav.Update(in);
  EXPECT_GT(out.tracks.left_mps, 0.0);
  EXPECT_EQ(nav.last_entry().t_s, 2.0);
  EXPECT_EQ(nav.Metrics(true).duration_s, 2.0);
}

}  // namespace
}  // namespace trackbed::scenario
