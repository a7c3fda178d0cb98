#!/usr/bin/env python3
"""The outdoor scene driven from Python by a proportional controller on ground truth,
with the user's own estimate scored in metrics.json beside the built-in ones."""
import json
import math
import pathlib
import shutil
import sys
import tempfile
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import drive_outdoor  # noqa: E402


class SimulationTest(unittest.TestCase):
    def setUp(self):
        self.dir = pathlib.Path(tempfile.mkdtemp(prefix="trackbed_py_sim_"))
        self.addCleanup(shutil.rmtree, self.dir, ignore_errors=True)

    def test_own_controller_and_estimate_are_scored(self):
        out = self.dir / "run"
        metrics = drive_outdoor.drive(out, seed=1, duration_s=15.0)
        self.assertEqual(metrics["status"], "completed")
        self.assertEqual(metrics["stop_reason"], "duration reached")
        # The controller drove the loop: 0.4 m/s for 15 s, less the turns.
        self.assertGreater(metrics["distance_m"], 4.5)
        self.assertLess(metrics["distance_m"], 6.5)
        on_disk = json.loads((out / "metrics.json").read_text())
        self.assertEqual(on_disk["estimators"], metrics["estimators"])
        mine = on_disk["estimators"]["mine"]
        # One estimate per step: 15 s at the drive's 20 Hz, and the end.
        self.assertEqual(mine["samples"], 301)
        # Dead reckoning over ~5 m of grass: within 0.25 m of the true path.
        self.assertLess(mine["ate_rmse_m"], 0.25)
        self.assertLess(mine["final_error_m"], 0.5)
        for builtin in ("wheel_odometry", "fused", "visual_odometry", "ekf"):
            self.assertIn(builtin, on_disk["estimators"])
        self.assertTrue((out / "mine.tum").is_file())
        self.assertEqual(len((out / "mine.tum").read_text().splitlines()), 301)
        self.assertTrue((out / "trajectories.png").is_file())

    def test_observation_and_localization(self):
        import trackbed
        sim = trackbed.Simulation(drive_outdoor.SOURCE_DIR / "scenes/outdoor.yaml", seed=3,
                                  overrides={"duration_s": 1, "robot.range_sensor.enabled": True})
        self.assertAlmostEqual(sim.control_period_s, 0.05)
        first = sim.step(left_mps=0.3, right_mps=0.3)
        self.assertEqual(first.stereo[0].dtype.name, "uint8")
        self.assertEqual(first.stereo[0].shape, (480, 640))
        self.assertEqual(first.stereo_t, 0.0)
        self.assertEqual(first.ground_truth.shape, (4, 4))
        self.assertEqual(first.range_scan.ndim, 1)
        frames, last = 1, first
        while not sim.done:
            last = sim.step(left_mps=0.3, right_mps=0.3)
            frames += len(last.stereo_pairs)
            self.assertEqual(last.imu.shape[1], 7)
        self.assertEqual(frames, 11)  # t = 0, 0.1, ..., 1 s at the camera's 10 Hz
        self.assertAlmostEqual(last.t, 1.0)
        self.assertGreater(last.encoders[0], 0)
        fused = sim.localization.fused()
        self.assertEqual(fused.shape, (4, 4))
        # 0.3 m in 1 s: the estimate is within a few centimetres of the truth.
        self.assertLess(math.dist(fused[:2, 3], last.ground_truth[:2, 3]), 0.05)
        self.assertIsNotNone(sim.localization.wheel())
        self.assertIsNotNone(sim.localization.vo())
        self.assertIsNotNone(sim.localization.ekf())
        metrics = sim.finish()
        self.assertEqual(metrics["stereo_frames"], 11)

    def test_run_is_trackbed_run(self):
        import trackbed
        out = self.dir / "corridor"
        metrics = trackbed.run(drive_outdoor.SOURCE_DIR / "scenes/corridor.yaml", out=out,
                               seed=2, overrides={"duration_s": 2,
                                                  "robot.stereo.enabled": False})
        self.assertEqual(metrics["status"], "completed")
        self.assertGreater(metrics["distance_m"], 0.5)
        on_disk = json.loads((out / "metrics.json").read_text())
        self.assertEqual(on_disk["distance_m"], metrics["distance_m"])
        self.assertIn("seed: 2", (out / "scenario.yaml").read_text())


if __name__ == "__main__":
    unittest.main()
