// Slip and ICR expansion per terrain material: runs the calibration scenes
// (scenes/calibration/straight_line.yaml and icr_turns.yaml) on flat ground of
// every built-in material and prints a Markdown table.
//
//   material_slip_table [SOURCE_DIR]
#include <cstdio>
#include <exception>
#include <string>

#include "trackbed/scenes/closed_loop_runner.h"
#include "trackbed/scenes/scenario_yaml.h"
#include "trackbed/sim/terrain_material.h"

namespace {

double Mean(double a, double b) { return (a + b) / 2.0; }

}  // namespace

int main(int argc, char** argv) {
  using namespace trackbed;
  const std::string root = argc > 1 ? argv[1] : TRACKBED_SOURCE_DIR;
  try {
    std::printf(
        "| material | straight: mean slip ratio (%%) | straight: mean abs slip velocity (m/s) | "
        "straight: encoder distance error (%%) | turns: mean abs slip ratio (%%) | turns: chi "
        "|\n|---|---|---|---|---|---|\n");
    for (const sim::TerrainMaterial& material : sim::BuiltinMaterials()) {
      const std::vector<scenes::Override> ground = {
          {"scene.terrain.default_material", material.name}};
      const scenes::RunMetrics s = scenes::RunClosedLoop(
          scenes::LoadScenario(root + "/scenes/calibration/straight_line.yaml", ground));
      const scenes::RunMetrics t = scenes::RunClosedLoop(
          scenes::LoadScenario(root + "/scenes/calibration/icr_turns.yaml", ground));
      std::printf("| %s | %.3f | %.4f | %+.3f | %.2f | %.3f |\n", material.name.c_str(),
                  100.0 * Mean(s.slip[0].mean_ratio(), s.slip[1].mean_ratio()),
                  Mean(s.slip[0].mean_abs_velocity_mps(), s.slip[1].mean_abs_velocity_mps()),
                  100.0 * (s.encoder_distance_m - s.distance_m) / s.distance_m,
                  100.0 * Mean(t.slip[0].mean_abs_ratio(), t.slip[1].mean_abs_ratio()), t.icr.chi);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "material_slip_table: %s\n", e.what());
    return 1;
  }
  return 0;
}
