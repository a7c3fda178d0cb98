#!/usr/bin/env python3
"""The images a Simulation returns are the cameras' own, as the robot gets them; with a
rectified pair (robot.realism: ideal, where the export needs no rectification) byte for
byte the run folder's KITTI export (outputs.save_images: kitti) of the same seed."""
import json
import os
import pathlib
import shutil
import tempfile
import unittest

import numpy as np

import trackbed

SOURCE_DIR = pathlib.Path(os.environ.get("TRACKBED_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))


class ImagesTest(unittest.TestCase):
    def test_images_are_the_kitti_export(self):
        root = pathlib.Path(tempfile.mkdtemp(prefix="trackbed_py_img_"))
        self.addCleanup(shutil.rmtree, root, ignore_errors=True)
        # Sensor noise on, so that the seed shows in every pixel.
        sim = trackbed.Simulation(SOURCE_DIR / "scenes/outdoor.yaml", seed=5,
                                  overrides={"duration_s": 1.0, "robot.stereo.noise_std": 2.0,
                                             "outputs.save_images": "kitti",
                                             "robot.realism": "ideal"})
        pairs = []
        while not sim.done:
            pairs += sim.step(left_mps=0.3, right_mps=0.25).stereo_pairs
        sim.finish(out=root / "run")
        images = root / "run/images"
        self.assertEqual(len(pairs), 11)
        self.assertEqual(len(list((images / "image_0").glob("*.png"))), 11)
        times = [float(t) for t in (images / "times.txt").read_text().split()]
        for k, (t, left, right) in enumerate(pairs):
            self.assertAlmostEqual(t, times[k], places=6)
            for camera, image in (("image_0", left), ("image_1", right)):
                exported = trackbed.read_image(images / camera / f"{k:06d}.png")
                self.assertEqual(exported.dtype, np.uint8)
                self.assertTrue(np.array_equal(exported, image), f"{camera} frame {k}")
        # Another seed: other noise.
        sim = trackbed.Simulation(SOURCE_DIR / "scenes/outdoor.yaml", seed=6,
                                  overrides={"duration_s": 0.1, "robot.stereo.noise_std": 2.0})
        other = sim.step(0.3, 0.25).stereo[0]
        self.assertFalse(np.array_equal(other, pairs[0][1]))

    def test_under_typical_the_images_are_raw_and_the_export_rectified(self):
        root = pathlib.Path(tempfile.mkdtemp(prefix="trackbed_py_img_typical_"))
        self.addCleanup(shutil.rmtree, root, ignore_errors=True)
        sim = trackbed.Simulation(SOURCE_DIR / "scenes/outdoor.yaml", seed=5,
                                  overrides={"duration_s": 0.3, "outputs.save_images": "kitti"})
        pairs = []
        while not sim.done:
            pairs += sim.step(left_mps=0.3, right_mps=0.25).stereo_pairs
        sim.finish(out=root / "run")
        run = root / "run"
        given = json.loads((run / "stereo_calibration.json").read_text())
        # The given pair is not rectified: its cameras differ.
        self.assertNotEqual((given["fx"], given["cx"]), (given["right"]["fx"], given["right"]["cx"]))
        # The export holds the rectified pair's projection, not the raw left camera's ...
        p0 = [float(x) for x in (run / "images/calib.txt").read_text().split("\n")[0].split()[1:]]
        self.assertNotAlmostEqual(p0[0], given["fx"], places=6)
        # ... and rectified images, which are not the cameras' own.
        self.assertEqual(len(pairs), 4)
        for k, (_, left, right) in enumerate(pairs):
            for camera, image in (("image_0", left), ("image_1", right)):
                exported = trackbed.read_image(run / "images" / camera / f"{k:06d}.png")
                self.assertEqual(exported.shape, image.shape)
                self.assertFalse(np.array_equal(exported, image), f"{camera} frame {k}")


if __name__ == "__main__":
    unittest.main()
