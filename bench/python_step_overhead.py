#!/usr/bin/env python3
"""What stepping a run from Python costs against `trackbed run`, measured in one run
of this program (a benchmark: it prints figures, it never fails on them).

Both drive the outdoor scene (camera, range-free, the whole localization stack) with
the same constant track speeds for the same simulated time and write a run folder:
`trackbed run` with a one-command drive script, Python by calling sim.step() with
those speeds and an empty callback on each observation. Their ground_truth.tum must
be identical (the same simulation, so the same work); the program checks it. Each
configuration runs --repeats times, interleaved; the fastest run of each counts, by wall
time and by CPU time (user + system, all threads: less disturbed by other load on the
machine), end to end (the process or the Simulation, start to finish) and in the loop
(metrics.json's wall_time_s, from ClosedLoop::Start to the metrics: the stepping itself,
without the program's start or the plots).

    PYTHONPATH=build/python python3 bench/python_step_overhead.py [--duration 30]
"""
import argparse
import filecmp
import json
import pathlib
import resource
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
LEFT_MPS, RIGHT_MPS = 0.4, 0.38


def cpu_s(who):
    usage = resource.getrusage(who)
    return usage.ru_utime + usage.ru_stime


def run_cli(trackbed_bin, scene, duration, out):
    script = f"[{{t_s: 0, left_mps: {LEFT_MPS}, right_mps: {RIGHT_MPS}}}]"
    command = [str(trackbed_bin), "run", str(scene), "--out", str(out),
               "--set", f"duration_s={duration}", "--set", "drive.mode=script",
               "--set", f"drive.script={script}"]
    start, cpu = time.perf_counter(), cpu_s(resource.RUSAGE_CHILDREN)
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall, cpu = time.perf_counter() - start, cpu_s(resource.RUSAGE_CHILDREN) - cpu
    return wall, cpu, json.loads((out / "metrics.json").read_text())["wall_time_s"]


def run_python(trackbed, scene, duration, out, images):
    def callback(obs):
        pass

    start, cpu = time.perf_counter(), cpu_s(resource.RUSAGE_SELF)
    sim = trackbed.Simulation(scene, overrides={"duration_s": duration}, images=images)
    while not sim.done:
        callback(sim.step(left_mps=LEFT_MPS, right_mps=RIGHT_MPS))
    loop_s = sim.finish(out=out)["wall_time_s"]
    return time.perf_counter() - start, cpu_s(resource.RUSAGE_SELF) - cpu, loop_s


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=30.0, help="simulated seconds")
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--trackbed", default=ROOT / "build/apps/trackbed")
    parser.add_argument("--scene", default=ROOT / "scenes/outdoor.yaml")
    args = parser.parse_args()
    sys.path.insert(0, str(ROOT / "build/python"))
    import trackbed

    work = pathlib.Path(tempfile.mkdtemp(prefix="trackbed_py_bench_"))
    try:
        times = {"trackbed run": [], "Python, images": [], "Python, no images": []}
        for k in range(args.repeats):
            times["trackbed run"].append(
                run_cli(args.trackbed, args.scene, args.duration, work / f"cli{k}"))
            times["Python, images"].append(
                run_python(trackbed, args.scene, args.duration, work / f"py{k}", True))
            times["Python, no images"].append(
                run_python(trackbed, args.scene, args.duration, work / f"pyn{k}", False))
        for name in ("py0", "pyn0"):
            if not filecmp.cmp(work / "cli0/ground_truth.tum", work / name / "ground_truth.tum",
                               shallow=False):
                sys.exit(f"python_step_overhead: {name} simulated another run than trackbed run")
        cli = [min(t[k] for t in times["trackbed run"]) for k in range(3)]
        print(f"outdoor scene, {args.duration:g} s simulated, best of {args.repeats}; "
              "ratio: time / trackbed run's time")
        for name, runs in times.items():
            wall, cpu, loop = (min(t[k] for t in runs) for k in range(3))
            print(f"  {name:18s} end to end: wall {wall:6.2f} s (ratio {wall / cli[0]:.3f}), "
                  f"CPU {cpu:6.2f} s (ratio {cpu / cli[1]:.3f}); in the loop: wall "
                  f"{loop:6.2f} s ({args.duration / loop:5.2f}x real time, ratio "
                  f"{loop / cli[2]:.3f})")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
