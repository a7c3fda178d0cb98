#!/usr/bin/env python3
"""What recording a run as a ROS 2 bag costs (docs/mcap.md): a run of each scene with
`outputs.mcap=false`, then `trackbed export-mcap` on its folder --repeats times, timed
against the run itself (the process's start, timed on a folder that is not a run's, taken
off); run.mcap's size per simulated minute and the export's wall time per simulated
minute and as a fraction of the run's. A benchmark: it prints figures, it
never fails on them.

    python3 bench/mcap_cost.py [--duration 60] [--repeats 3]
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]


def timed(command):
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def timed_failing(command):
    start = time.perf_counter()
    subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=60.0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--trackbed", default=str(ROOT / "build/apps/trackbed"))
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        for scene in ("corridor", "outdoor"):
            run = pathlib.Path(tmp) / scene
            run_s = timed([args.trackbed, "run", str(ROOT / f"scenes/{scene}.yaml"), "--out",
                           str(run), "--set", f"duration_s={args.duration}",
                           "--set", "outputs.mcap=false"])
            simulated_min = json.loads((run / "metrics.json").read_text())["sim_time_s"] / 60.0
            # The process's start (loading its libraries) timed alone, on a folder that
            # is not a run's, and taken off: what is left is the bag's reading and writing.
            export_s, start_s = [], []
            for _ in range(args.repeats):
                export_s.append(timed([args.trackbed, "export-mcap", str(run)]))
                start_s.append(timed_failing([args.trackbed, "export-mcap", tmp]))
            size_mb = (run / "run.mcap").stat().st_size / 1e6
            e = max(statistics.median(export_s) - statistics.median(start_s), 0.0)
            print(f"{scene:8s} {simulated_min * 60:.0f} simulated s: run.mcap {size_mb:.2f} MB "
                  f"({size_mb / simulated_min:.2f} MB per simulated minute); export "
                  f"{e:.3f} s median of {args.repeats} ({e / simulated_min:.3f} s per simulated "
                  f"minute, {e / run_s:.3f} of the run's {run_s:.1f} s wall time)")


if __name__ == "__main__":
    main()
