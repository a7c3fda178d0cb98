#!/usr/bin/env python3
"""Heading error over a stretch of a run: for each estimator's TUM file in a run folder,
its heading change from T0 to T1 less the truth's (ground_truth.tum), in degrees; and the
gyro alone over the same stretch: imu.csv's z rate integrated, less the truth's change,
raw and (with --standstill S) less the mean rate over the run's first S seconds, where the
robot stood still (drive.start_standstill_s).

    python3 scripts/heading_over_stretch.py RUN_FOLDER T0 T1 [--standstill 10]

Used by docs/results/2026-12-07-stack-outputs.md (a blacked-out stretch of the kilometre
loop). Each pose is the file's last one at or before the time; the heading is the yaw of
the body's x axis, unwrapped along the file.
"""
import argparse
import bisect
import csv
import math
import pathlib


def yaw(qx, qy, qz, qw):
    return math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))


def unwrapped_headings(path):
    times, headings = [], []
    for line in path.read_text().splitlines():
        v = line.split()
        if len(v) != 8:
            continue
        h = yaw(*map(float, v[4:8]))
        if headings:
            h = headings[-1] + math.remainder(h - headings[-1], 2 * math.pi)
        times.append(float(v[0]))
        headings.append(h)
    return times, headings


def at(times, values, t):
    i = bisect.bisect_right(times, t + 1e-9) - 1
    if i < 0:
        raise SystemExit(f"no pose at or before t = {t}")
    return values[i]


def gyro_change(folder, t0, t1, standstill):
    rows = list(csv.DictReader((folder / "imu.csv").open()))
    t = [float(r["t"]) for r in rows]
    w = [float(r["gyro_z_radps"]) for r in rows]
    bias = 0.0
    if standstill > 0:
        still = [wi for ti, wi in zip(t, w) if ti <= standstill]
        bias = sum(still) / len(still)
    raw = corrected = 0.0
    for k in range(1, len(t)):
        if t[k - 1] >= t0 and t[k] <= t1 + 1e-9:
            dt = t[k] - t[k - 1]
            raw += w[k] * dt
            corrected += (w[k] - bias) * dt
    return raw, corrected, bias


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("folder", type=pathlib.Path)
    p.add_argument("t0", type=float)
    p.add_argument("t1", type=float)
    p.add_argument("--standstill", type=float, default=0.0)
    a = p.parse_args()
    tt, th = unwrapped_headings(a.folder / "ground_truth.tum")
    truth = at(tt, th, a.t1) - at(tt, th, a.t0)
    print(f"truth turned {math.degrees(truth):+.3f} deg from {a.t0} to {a.t1} s")
    for f in sorted(a.folder.glob("*.tum")):
        if f.stem == "ground_truth":
            continue
        et, eh = unwrapped_headings(f)
        err = at(et, eh, a.t1) - at(et, eh, a.t0) - truth
        print(f"{f.stem:24s} {math.degrees(err):+8.3f} deg")
    raw, corrected, bias = gyro_change(a.folder, a.t0, a.t1, a.standstill)
    print(f"{'gyro alone (raw)':24s} {math.degrees(raw - truth):+8.3f} deg")
    if a.standstill > 0:
        print(f"{'gyro alone, less bias':24s} {math.degrees(corrected - truth):+8.3f} deg"
              f"  (standstill mean {bias:.3e} rad/s)")


if __name__ == "__main__":
    main()
