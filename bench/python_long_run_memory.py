#!/usr/bin/env python3
"""Peak memory of a long run stepped from Python against the same run by `trackbed run`
(a benchmark: it prints figures, it never fails on them).

Both drive the park (scenes/outdoor.yaml without its objects and walkers, so that
nothing stops the robot; without the camera unless --camera) with the same constant track
speeds, round and round a circle, for each --durations value,
each in a process of its own, and write a run folder. Printed per run: metrics.json's
memory.peak_rss_mb (taken before the plots and the bag are written) and the process's
whole peak resident set (the child's own ru_maxrss, from wait4); the growth from the shortest
to the longest run is the figure a bounded run keeps small. The two ground_truth.tum of
each duration must be identical (the same simulation); the program checks it.

    python3 bench/python_long_run_memory.py [--durations 300 3600] [--camera]

(with a python3 that has numpy, as the module needs: Debian's /usr/bin/python3)
"""
import argparse
import filecmp
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
LEFT_MPS, RIGHT_MPS = 0.4, 0.38

# The child that steps the Simulation: argv = build/python, scene, duration, out, camera.
PYTHON_CHILD = """
import sys
sys.path.insert(0, sys.argv[1])
import trackbed
overrides = {"duration_s": float(sys.argv[3]), "scene.objects": [], "scene.occluders": []}
if sys.argv[5] == "0":
    overrides["robot.stereo.enabled"] = False
sim = trackbed.Simulation(sys.argv[2], overrides=overrides, images=False)
while not sim.done:
    sim.step(left_mps=%r, right_mps=%r)
sim.finish(out=sys.argv[4])
""" % (LEFT_MPS, RIGHT_MPS)


def child_peak_mb(command):
    """Runs `command` and returns its process's largest resident set [MB] (its own
    rusage, from wait4)."""
    child = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)
    if child.returncode != 0:
        raise subprocess.CalledProcessError(child.returncode, command)
    return usage.ru_maxrss / 1024.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--durations", type=float, nargs="+", default=[300.0, 3600.0])
    parser.add_argument("--camera", action="store_true", help="keep the stereo camera on")
    parser.add_argument("--trackbed", default=ROOT / "build/apps/trackbed")
    parser.add_argument("--python-dir", default=ROOT / "build/python")
    parser.add_argument("--scene", default=ROOT / "scenes/outdoor.yaml")
    args = parser.parse_args()
    work = pathlib.Path(tempfile.mkdtemp(prefix="trackbed_py_memory_"))
    camera = "1" if args.camera else "0"
    rows = []
    try:
        for duration in sorted(args.durations):
            script = f"[{{t_s: 0, left_mps: {LEFT_MPS}, right_mps: {RIGHT_MPS}}}]"
            cli = [str(args.trackbed), "run", str(args.scene), "--out", str(work / "cli"),
                   "--no-progress", "--set", f"duration_s={duration}",
                   "--set", "scene.objects=[]", "--set", "scene.occluders=[]",
                   "--set", "drive.mode=script", "--set", f"drive.script={script}"]
            if not args.camera:
                cli += ["--set", "robot.stereo.enabled=false"]
            py = [sys.executable, "-c", PYTHON_CHILD, str(args.python_dir), str(args.scene),
                  str(duration), str(work / "py"), camera]
            for name, command, out in (("trackbed run", cli, "cli"), ("Python", py, "py")):
                shutil.rmtree(work / out, ignore_errors=True)
                whole = child_peak_mb(command)
                metrics = json.loads((work / out / "metrics.json").read_text())
                rows.append((name, duration, metrics["memory"]["peak_rss_mb"], whole,
                             metrics["distance_m"]))
            if not filecmp.cmp(work / "cli/ground_truth.tum", work / "py/ground_truth.tum",
                               shallow=False):
                sys.exit(f"python_long_run_memory: Python simulated another run at {duration} s")
        print(f"park, {'with' if args.camera else 'without'} the camera, constant track speeds")
        for name, duration, peak, whole, distance in rows:
            print(f"  {name:12s} {duration:7.0f} s ({distance:7.1f} m): peak_rss_mb {peak:7.1f} MB, "
                  f"whole process {whole:7.1f} MB")
        for name in ("trackbed run", "Python"):
            mine = [r for r in rows if r[0] == name]
            print(f"  {name:12s} growth from {mine[0][1]:.0f} s to {mine[-1][1]:.0f} s: "
                  f"{mine[-1][2] - mine[0][2]:.1f} MB (peak_rss_mb), "
                  f"{mine[-1][3] - mine[0][3]:.1f} MB (whole process)")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
