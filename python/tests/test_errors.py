#!/usr/bin/env python3
"""Bad input from Python: clear exceptions carrying the command line's one-line
messages, and no crash."""
import os
import pathlib
import shutil
import tempfile
import unittest

import numpy as np

import trackbed

SOURCE_DIR = pathlib.Path(os.environ.get("TRACKBED_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
CORRIDOR = SOURCE_DIR / "scenes/corridor.yaml"
QUICK = {"duration_s": 0.2, "robot.stereo.enabled": False}


class ErrorsTest(unittest.TestCase):
    def test_wrong_override_key(self):
        with self.assertRaises(trackbed.ScenarioError) as e:
            trackbed.Simulation(CORRIDOR, overrides={"duraton_s": 20})
        self.assertIn("--set duraton_s=20", str(e.exception))
        self.assertIn("duraton_s", str(e.exception))
        self.assertNotIn("\n", str(e.exception))
        self.assertIsInstance(e.exception, ValueError)

    def test_wrong_override_value(self):
        with self.assertRaises(trackbed.ScenarioError) as e:
            trackbed.Simulation(CORRIDOR, overrides={"duration_s": -1})
        self.assertIn("duration_s: must be in (0, 1e6]", str(e.exception))

    def test_bad_override_key_syntax(self):
        with self.assertRaises(ValueError) as e:
            trackbed.Simulation(CORRIDOR, overrides={"a..b": 1})
        self.assertIn("--set", str(e.exception))

    def test_missing_scenario(self):
        with self.assertRaises(trackbed.ScenarioError) as e:
            trackbed.Simulation(SOURCE_DIR / "scenes/no_such_scene.yaml")
        self.assertIn("no_such_scene.yaml: cannot read file", str(e.exception))
        with self.assertRaises(trackbed.ScenarioError):
            trackbed.run(SOURCE_DIR / "scenes/no_such_scene.yaml", out=tempfile.gettempdir())

    def test_step_after_done_and_finish_twice(self):
        sim = trackbed.Simulation(CORRIDOR, overrides=QUICK)
        while not sim.done:
            sim.step(0.2, 0.2)
        with self.assertRaises(RuntimeError) as e:
            sim.step(0.2, 0.2)
        self.assertIn("step: the run is done", str(e.exception))
        sim.finish()
        with self.assertRaises(RuntimeError):
            sim.finish()
        with self.assertRaises(RuntimeError):
            sim.step(0.2, 0.2)
        with self.assertRaises(RuntimeError):
            sim.report_estimate("mine", np.eye(4))

    def test_estimates_that_are_not_rigid_transforms(self):
        sim = trackbed.Simulation(CORRIDOR, overrides=QUICK)
        sim.step(0.2, 0.2)
        scaled = np.eye(4)
        scaled[0, 0] = 2.0
        reflected = np.diag([1.0, 1.0, -1.0, 1.0])
        last_row = np.eye(4)
        last_row[3, 0] = 0.5
        not_finite = np.eye(4)
        not_finite[0, 3] = float("nan")
        for T, reason in ((scaled, "not orthonormal"), (reflected, "reflection"),
                          (last_row, "last row"), (not_finite, "non-finite"),
                          (np.eye(3), "4x4"), ([[1, 0], [0, 1]], "4x4")):
            with self.assertRaises(ValueError) as e:
                sim.report_estimate("mine", T)
            self.assertIn('estimate "mine": not a rigid transform', str(e.exception))
            self.assertIn(reason, str(e.exception))
        for name in ("fused", "ground_truth", "", "my estimate", "../x"):
            with self.assertRaises(ValueError):
                sim.report_estimate(name, np.eye(4))
        sim.report_estimate("mine", np.eye(4))
        with self.assertRaises(ValueError) as e:
            sim.report_estimate("mine", np.eye(4))
        self.assertIn("already reported", str(e.exception))
        sim.step(0.2, 0.2)
        sim.report_estimate("mine", np.eye(4))  # a later time: fine
        with self.assertRaises(ValueError):
            sim.step(float("nan"), 0.2)
        with self.assertRaises(ValueError):
            sim._sim.estimate("nobody")
        metrics = sim.finish()
        self.assertEqual(metrics["estimators"]["mine"]["samples"], 2)

    def test_scenarios_python_cannot_drive(self):
        with self.assertRaises(trackbed.ScenarioError) as e:
            trackbed.Simulation(SOURCE_DIR / "scenes/tr_lab.yaml")
        self.assertIn("teach_repeat.enabled", str(e.exception))
        with self.assertRaises(ValueError) as e:
            trackbed.Simulation(SOURCE_DIR / "scenes/nav_outdoor.yaml")
        self.assertIn("navigation.enabled", str(e.exception))

    def test_no_drive_section_needed(self):
        root = pathlib.Path(tempfile.mkdtemp(prefix="trackbed_py_err_"))
        self.addCleanup(shutil.rmtree, root, ignore_errors=True)
        text = CORRIDOR.read_text()
        lines = text.splitlines()
        start = next(k for k, line in enumerate(lines) if line.startswith("drive:"))
        end = next((k for k in range(start + 1, len(lines))
                    if lines[k] and not lines[k][0].isspace() and not lines[k].startswith("#")),
                   len(lines))
        driveless = root / "driveless.yaml"
        driveless.write_text("\n".join(lines[:start] + lines[end:]) + "\n")
        self.assertNotIn("drive:", driveless.read_text())
        sim = trackbed.Simulation(driveless, overrides=QUICK)
        while not sim.done:
            sim.step(0.1, 0.1)
        self.assertEqual(sim.finish()["status"], "completed")
        # trackbed run still wants one.
        with self.assertRaises(trackbed.ScenarioError) as e:
            trackbed.run(driveless, out=root / "run", overrides=QUICK)
        self.assertIn("drive.waypoints", str(e.exception))
        with self.assertRaises(trackbed.ScenarioError) as e:
            trackbed.Simulation(driveless, overrides={"drive.rate_hz": 0})
        self.assertIn("drive.rate_hz: must be > 0", str(e.exception))

    def test_overrides_must_be_a_dict(self):
        with self.assertRaises(TypeError):
            trackbed.Simulation(CORRIDOR, overrides=["duration_s=1"])


if __name__ == "__main__":
    unittest.main()
