#!/usr/bin/env python3
"""What recording a run as a ROS 2 bag costs (docs/mcap.md), per scene: a run with
`outputs.mcap=false` and one with `outputs.mcap_images=true` (which also saves the frames
as PNG in camera/), then `trackbed export-mcap` on each folder --repeats times, the
process's start (timed on a folder that is not a run's) taken off. Prints run.mcap's
size and the export's wall time per simulated minute, without and with the images, and
the images' run against the plain run's wall time. A benchmark: it prints figures, it
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


def timed(command, check=True):
    start = time.perf_counter()
    subprocess.run(command, check=check, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=60.0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--trackbed", default=str(ROOT / "build/apps/trackbed"))
    args = parser.parse_args()
    tb = args.trackbed
    with tempfile.TemporaryDirectory() as tmp:
        for scene in ("corridor", "outdoor"):
            runs, wall = {}, {}
            for variant, sets in (("plain", ["outputs.mcap=false"]),
                                  ("images", ["outputs.mcap_images=true"])):
                runs[variant] = pathlib.Path(tmp) / f"{scene}_{variant}"
                command = [tb, "run", str(ROOT / f"scenes/{scene}.yaml"), "--out",
                           str(runs[variant]), "--set", f"duration_s={args.duration}"]
                for s in sets:
                    command += ["--set", s]
                wall[variant] = timed(command)
            minutes = json.loads((runs["plain"] / "metrics.json").read_text())["sim_time_s"] / 60
            start = statistics.median(timed([tb, "export-mcap", tmp], check=False)
                                      for _ in range(args.repeats))
            for variant, run in runs.items():
                export = statistics.median(timed([tb, "export-mcap", str(run)])
                                           for _ in range(args.repeats))
                size = (run / "run.mcap").stat().st_size / 1e6
                print(f"{scene:8s} {variant:6s}: run.mcap {size / minutes:7.2f} MB per simulated "
                      f"minute; export {max(export - start, 0.0) / minutes:.3f} s per simulated "
                      f"minute (median of {args.repeats})")
            print(f"{scene:8s} the run with the images (frames saved and the bag) against the "
                  f"plain run: {wall['images'] / wall['plain']:.3f} of its wall time "
                  f"({wall['images']:.1f} s against {wall['plain']:.1f} s)")


if __name__ == "__main__":
    main()
