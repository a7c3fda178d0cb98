#!/usr/bin/env python3
"""The same Python script and seed give byte-identical run folders, but for the
fields that measure the machine (scripts/compare_run_folders.py)."""
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = pathlib.Path(__file__).resolve().parent
SOURCE_DIR = pathlib.Path(os.environ.get("TRACKBED_SOURCE_DIR", HERE.parents[1]))


class DeterminismTest(unittest.TestCase):
    def test_same_script_and_seed_same_folder(self):
        root = pathlib.Path(tempfile.mkdtemp(prefix="trackbed_py_det_"))
        self.addCleanup(shutil.rmtree, root, ignore_errors=True)
        for name in ("a", "b"):
            subprocess.run([sys.executable, "-B", str(HERE / "drive_outdoor.py"),
                            str(root / name / "run"), "--seed", "4", "--duration", "6"],
                           check=True, stdout=subprocess.DEVNULL)
        self.assertTrue((root / "a/run/mine.tum").is_file())
        compare = subprocess.run([sys.executable, "-B",
                                  str(SOURCE_DIR / "scripts/compare_run_folders.py"),
                                  str(root / "a"), str(root / "b")],
                                 capture_output=True, text=True)
        self.assertEqual(compare.returncode, 0, compare.stdout + compare.stderr)


if __name__ == "__main__":
    unittest.main()
