#!/usr/bin/env python3
"""The Gymnasium-style wrapper: reset/step, the reward hook, the episode's end."""
import os
import pathlib
import shutil
import tempfile
import unittest

import trackbed.gym

SOURCE_DIR = pathlib.Path(os.environ.get("TRACKBED_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))


class GymTest(unittest.TestCase):
    def test_episodes(self):
        root = pathlib.Path(tempfile.mkdtemp(prefix="trackbed_py_gym_"))
        self.addCleanup(shutil.rmtree, root, ignore_errors=True)
        # Reward: progress along x since the last step, from ground truth.
        last_x = {}

        def reward(obs, action, sim):
            x = obs.ground_truth[0, 3]
            r = x - last_x.get("x", x)
            last_x["x"] = x
            return r

        env = trackbed.gym.TrackbedEnv(SOURCE_DIR / "scenes/corridor.yaml", seed=3,
                                       overrides={"duration_s": 1.0,
                                                  "robot.stereo.enabled": False},
                                       reward=reward, out=root)
        episodes = []
        for _ in range(2):
            last_x.clear()
            obs, info = env.reset()
            total, steps, done = 0.0, 0, False
            while not done:
                obs, r, terminated, truncated, info = env.step((0.3, 0.3))
                total += r
                steps += 1
                done = terminated or truncated
            self.assertTrue(truncated)
            self.assertFalse(terminated)
            episodes.append((info["seed"] if "seed" in info else None, total, steps,
                             info["metrics"]["distance_m"]))
        self.assertEqual(steps, 20)  # 1 s at 20 Hz after reset's first step
        # Driving straight along the corridor at 0.3 m/s earns about the distance.
        self.assertGreater(episodes[0][1], 0.2)
        self.assertAlmostEqual(episodes[0][1], episodes[0][3], delta=0.05)
        self.assertTrue((root / "episode_0000/metrics.json").is_file())
        self.assertTrue((root / "episode_0001/metrics.json").is_file())
        self.assertEqual(env.sim.seed, 4)  # the second episode counted up
        with self.assertRaises(RuntimeError):
            env.step((0.3, 0.3))


if __name__ == "__main__":
    unittest.main()
