// The terramechanics report: per built-in material, the traction coefficient the
// shipped robot gets, steady slip driving straight, and the ICR expansion χ in
// turns in place and on two arcs; then slip against grade on dry sand. Runs the
// calibration scenes (scenes/calibration/straight_line.yaml, icr_turns.yaml) on
// flat ground of each material and prints Markdown tables.
//
//   material_slip_table [SOURCE_DIR]
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "trackbed/common/units.h"
#include "trackbed/estimation/icr_calibration.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "trackbed/sim/terrain_material.h"

namespace {

using namespace trackbed;

double Mean(double a, double b) { return (a + b) / 2.0; }

// (c A + W tan φ) / W for the whole robot: both tracks' contact area, its weight.
double TractionCoefficient(const sim::TerrainMaterial& m, const robot::TrackedVehicleOptions& v) {
  const double area = 2.0 * v.track_contact_length_m * v.track_width_m;
  const double weight = v.mass_kg * 9.81;
  return (m.cohesion_pa * area + weight * std::tan(units::Radians(m.friction_angle_deg))) / weight;
}

// χ fitted separately in each scripted segment of icr_turns.yaml (10 s each:
// in place both ways, then arcs of 1.25 m and 2.5 m radius), skipping each
// segment's first 2 s of transient. Also returns the run's stop reason.
std::vector<double> SegmentChi(const scenario::Scenario& s, std::string* stop_reason) {
  std::vector<std::vector<estimation::IcrSample>> segments(4);
  const double r = s.robot.vehicle.sprocket_radius_m, b = s.robot.vehicle.track_gauge_m;
  runner::RunObservers obs;
  obs.on_sample = [&](const runner::RunSample& x) {
    const auto k = static_cast<std::size_t>(x.t_s / 10.0);
    if (k >= segments.size() || x.t_s - 10.0 * k < 2.0) return;
    segments[k].push_back(
        {r * (x.tracks[1].sprocket_speed_radps - x.tracks[0].sprocket_speed_radps) / b,
         x.chassis.omega_world.z()});
  };
  *stop_reason = runner::RunClosedLoop(s, obs).stop_reason;
  std::vector<double> chi;
  for (const auto& seg : segments) {
    const estimation::IcrFit fit = estimation::FitIcrExpansion(seg);
    chi.push_back(fit.samples_used > 100 ? fit.chi : std::nan(""));
  }
  return chi;
}

void MaterialTable(const std::string& root) {
  std::printf(
      "| material | traction coefficient | straight: mean slip ratio (%%) | straight: encoder "
      "distance error (%%) | chi in place (turning left, right) | chi arc 1.25 m | chi arc 2.5 m | "
      "turns |\n|---|---|---|---|---|---|---|---|\n");
  for (const sim::TerrainMaterial& material : sim::BuiltinMaterials()) {
    const std::vector<scenario::Override> ground = {
        {"scene.terrain.default_material", material.name}};
    const scenario::Scenario straight =
        scenario::LoadScenario(root + "/scenes/calibration/straight_line.yaml", ground);
    const runner::RunMetrics s = runner::RunClosedLoop(straight);
    std::string stop;
    const std::vector<double> chi = SegmentChi(
        scenario::LoadScenario(root + "/scenes/calibration/icr_turns.yaml", ground), &stop);
    std::printf("| %s | %.2f | %.3f | %+.3f | %.3f, %.3f | %.3f | %.3f | %s |\n",
                material.name.c_str(), TractionCoefficient(material, straight.robot.vehicle),
                100.0 * Mean(s.slip[0].mean_ratio(), s.slip[1].mean_ratio()),
                100.0 * (s.encoder_distance_m - s.distance_m) / s.distance_m, chi[0], chi[1],
                chi[2], chi[3], stop.c_str());
  }
}

// Steady slip climbing dry sand at 0.4 m/s: both tracks, 8–24 s of the run.
void GradeTable(const std::string& root) {
  std::printf("\n| dry sand, uphill | tan θ | steady slip ratio (%%) |\n|---|---|---|\n");
  for (double deg : {0.0, 5.0, 10.0, 15.0, 20.0}) {
    const double slope = std::tan(units::Radians(deg));
    const scenario::Scenario s =
        scenario::LoadScenario(root + "/scenes/calibration/straight_line.yaml",
                               {{"scene.terrain.default_material", "dry_sand"},
                                {"scene.terrain.roughness.slope_x", std::to_string(slope)}});
    double sum = 0.0;
    int n = 0;
    runner::RunObservers obs;
    obs.on_sample = [&](const runner::RunSample& x) {
      if (x.t_s < 8.0 || x.t_s > 24.0) return;
      for (const robot::TrackState& t : x.tracks) {
        sum += (t.track_speed_mps - t.ground_speed_mps) / t.track_speed_mps;
        ++n;
      }
    };
    const runner::RunMetrics m = runner::RunClosedLoop(s, obs);
    std::printf("| %.0f° | %.4f | %.2f%s |\n", deg, slope, 100.0 * sum / n,
                m.stop_reason == "stalled" ? " (stalled)" : "");
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string root = argc > 1 ? argv[1] : TRACKBED_SOURCE_DIR;
  try {
    MaterialTable(root);
    GradeTable(root);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "material_slip_table: %s\n", e.what());
    return 1;
  }
  return 0;
}
