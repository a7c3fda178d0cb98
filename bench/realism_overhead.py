#!/usr/bin/env python3
"""What the robot as built and its given calibration cost in speed: the outdoor park
under `robot.realism=ideal` and `typical`, each run --repeats times interleaved, by the
real-time factor metrics.json reports (ClosedLoop::Start to the metrics: the straight
calibration run, the rectification of each frame and the IMU correction included). A
benchmark: it prints figures and their ratio, it never fails on them.

    python3 bench/realism_overhead.py [--duration 30] [--repeats 5]
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]


def run(trackbed_bin, realism, duration, out):
    subprocess.run([str(trackbed_bin), "run", str(ROOT / "scenes/outdoor.yaml"), "--out", str(out),
                    "--set", f"duration_s={duration}", "--set", f"robot.realism={realism}"],
                   check=True, stdout=subprocess.DEVNULL)
    return json.loads((out / "metrics.json").read_text())["real_time_factor"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=30.0)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--trackbed", default=str(ROOT / "build/apps/trackbed"))
    args = parser.parse_args()
    rtf = {"ideal": [], "typical": []}
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(args.repeats):
            for realism in rtf:
                rtf[realism].append(run(args.trackbed, realism, args.duration,
                                        pathlib.Path(tmp) / f"{realism}_{k}"))
    for realism, values in rtf.items():
        print(f"{realism:8s} real-time factor: median {statistics.median(values):.2f}, "
              f"max {max(values):.2f} ({', '.join(f'{v:.2f}' for v in values)})")
    ratios = [t / i for i, t in zip(rtf["ideal"], rtf["typical"])]
    print(f"typical / ideal, pair by pair: median {statistics.median(ratios):.3f} "
          f"({', '.join(f'{r:.3f}' for r in ratios)}); of the medians "
          f"{statistics.median(rtf['typical']) / statistics.median(rtf['ideal']):.3f}")


if __name__ == "__main__":
    main()
