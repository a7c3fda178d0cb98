#!/usr/bin/env python3
"""What the robot's own shadow does to visual odometry (docs/camera_model.md, "The robot's
own shadow"): scenes/studies/robot_shadow.yaml, a 60 s straight drive with the sun low
behind the robot, so that its shadow lies ahead in the camera's view and moves with it,
with the shadow on and off, per seed and realism profile. Per run: VO's path-length
ratio (VO's path over the true path, both at the camera's frames), its heading error at
the end (VO's yaw minus the true yaw, degrees), its end-point error, the run's aligned
ATE from metrics.json and VO's mean inliers per frame (fusion.csv). A study: it prints a table and writes it as CSV; it never
fails on the figures.

    python3 bench/robot_shadow_study.py [--seeds 1 2 3] [--realism typical ideal]
        [--out DIR] [--set KEY=VALUE ...]
"""
import argparse
import csv
import json
import math
import pathlib
import subprocess

ROOT = pathlib.Path(__file__).resolve().parents[1]


def read_tum(path):
    rows = []
    for line in path.read_text().splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        t, x, y, z, qx, qy, qz, qw = map(float, line.split())
        yaw = math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
        rows.append((t, x, y, z, yaw))
    return rows


def at_times(truth, times):
    """The true pose nearest in time to each of `times` (truth at 100 Hz, frames at 10 Hz)."""
    out, k = [], 0
    for t in times:
        while k + 1 < len(truth) and abs(truth[k + 1][0] - t) <= abs(truth[k][0] - t):
            k += 1
        out.append(truth[k])
    return out


def path_length(rows):
    return sum(math.dist(a[1:4], b[1:4]) for a, b in zip(rows, rows[1:]))


def score(run_dir):
    vo = read_tum(run_dir / "visual_odometry.tum")
    truth = at_times(read_tum(run_dir / "ground_truth.tum"), [r[0] for r in vo])
    heading = math.degrees(math.remainder(vo[-1][4] - truth[-1][4], 2 * math.pi))
    with open(run_dir / "fusion.csv") as f:
        inliers = [float(r["features"]) for r in csv.DictReader(f) if r["features"]]
    metrics = json.loads((run_dir / "metrics.json").read_text())
    vo_metrics = metrics["estimators"]["visual_odometry"]
    return {
        "true_path_m": path_length(truth),
        "path_length_ratio": path_length(vo) / path_length(truth),
        "heading_error_deg": heading,
        "end_error_m": math.dist(vo[-1][1:4], truth[-1][1:4]),
        "ate_m": vo_metrics.get("ate_rmse_m"),
        "mean_inliers": sum(inliers) / len(inliers),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--realism", nargs="+", default=["typical", "ideal"])
    parser.add_argument("--out", default="runs/robot_shadow_study")
    parser.add_argument("--set", action="append", default=[], dest="sets")
    parser.add_argument("--trackbed", default=str(ROOT / "build/apps/trackbed"))
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    rows = []
    for realism in args.realism:
        for seed in args.seeds:
            for shadow in ("false", "true"):
                run_dir = out / f"{realism}_seed{seed}_shadow_{shadow}"
                command = [args.trackbed, "run", str(ROOT / "scenes/studies/robot_shadow.yaml"),
                           "--out", str(run_dir), "--seed", str(seed), "--progress", "none",
                           "--set", f"robot.realism={realism}",
                           "--set", f"scene.appearance.robot_shadow={shadow}"]
                for s in args.sets:
                    command += ["--set", s]
                if not (run_dir / "metrics.json").exists():
                    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
                row = {"realism": realism, "seed": seed, "robot_shadow": shadow}
                row.update(score(run_dir))
                rows.append(row)
                print(f"{realism:8s} seed {seed} shadow {shadow:5s}: path-length ratio "
                      f"{row['path_length_ratio']:.4f}, heading error "
                      f"{row['heading_error_deg']:+.2f} deg, end error {row['end_error_m']:.3f} m "
                      f"over {row['true_path_m']:.2f} m, ATE {row['ate_m']:.3f} m, VO inliers "
                      f"{row['mean_inliers']:.1f}", flush=True)
    with open(out / "robot_shadow_study.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


if __name__ == "__main__":
    main()
