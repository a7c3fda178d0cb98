#!/usr/bin/env python3
"""Visual odometry's consistency over run folders: per frame with a motion, the
normalised estimation error squared (NEES) of VO's body motion against the ground
truth's between the two frames' exposures (stamp plus the camera–IMU time offset as
built, `ground_truth_calibration.json`), with VO's own covariance
(`vo_covariance.csv`, docs/run_folder.md), no scale factor fitted:

    ε = (ρ, φ) with  T_true = (Exp(φ), ρ) ∘ T_vo   (the body's motion, curr from prev)
    NEES = εᵀ Σ⁻¹ ε,  6 degrees of freedom

Prints, per run folder and over all of them, the frames, the average NEES, its
two-sided 95 % interval for that many frames (χ²(6N)/N, Wilson–Hilferty), the share of
frames beyond the single frame's 95 % bound χ²₆ = 12.59, and the average NEES of the
translation and rotation blocks alone (3 degrees of freedom each).

    python3 scripts/vo_consistency.py runs/corridor_s1 runs/corridor_s2 ...
"""
import bisect
import csv
import json
import math
import pathlib
import statistics
import sys


# Small dense linear algebra on lists (the scripts need no third-party package).
def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(len(b))) for j in range(len(b[0]))]
            for i in range(len(a))]


def transpose(a):
    return [list(r) for r in zip(*a)]


def solve(A, b):
    """A⁻¹b by Gaussian elimination with partial pivoting; None if singular."""
    n = len(A)
    M = [list(A[i]) + [b[i]] for i in range(n)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(M[r][c]))
        if abs(M[p][c]) < 1e-300:
            return None
        M[c], M[p] = M[p], M[c]
        for r in range(c + 1, n):
            f = M[r][c] / M[c][c]
            for k in range(c, n + 1):
                M[r][k] -= f * M[c][k]
    x = [0.0] * n
    for r in range(n - 1, -1, -1):
        x[r] = (M[r][n] - sum(M[r][k] * x[k] for k in range(r + 1, n))) / M[r][r]
    return x


def quadratic(C, e):
    """eᵀC⁻¹e, or None if C is singular."""
    x = solve(C, e)
    return None if x is None else sum(a * b for a, b in zip(e, x))


def pose(R, t):
    return [R[0] + [t[0]], R[1] + [t[1]], R[2] + [t[2]], [0.0, 0.0, 0.0, 1.0]]


def rotation(T):
    return [row[:3] for row in T[:3]]


def translation(T):
    return [T[0][3], T[1][3], T[2][3]]


def inverse(T):
    Rt = transpose(rotation(T))
    t = translation(T)
    return pose(Rt, [-sum(Rt[i][k] * t[k] for k in range(3)) for i in range(3)])


def quat_to_matrix(qx, qy, qz, qw):
    n = math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw)
    w, x, y, z = qw / n, qx / n, qy / n, qz / n
    return [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]


def exp_so3(r):
    angle = math.sqrt(sum(v * v for v in r))
    if angle == 0.0:
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    k = [v / angle for v in r]
    K = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]]
    K2 = matmul(K, K)
    s, c = math.sin(angle), 1.0 - math.cos(angle)
    return [[(1.0 if i == j else 0.0) + s * K[i][j] + c * K2[i][j] for j in range(3)]
            for i in range(3)]


def log_so3(R):
    c = max(-1.0, min(1.0, (R[0][0] + R[1][1] + R[2][2] - 1.0) / 2.0))
    angle = math.acos(c)
    v = [R[2][1] - R[1][2], R[0][2] - R[2][0], R[1][0] - R[0][1]]
    scale = 0.5 if angle < 1e-12 else angle / (2.0 * math.sin(angle))
    return [x * scale for x in v]


def read_truth(folder):
    """Times and 4×4 poses of ground_truth.tum."""
    times, poses = [], []
    with open(folder / "ground_truth.tum") as f:
        for line in f:
            v = line.split()
            if len(v) != 8:
                continue
            times.append(float(v[0]))
            poses.append((quat_to_matrix(*map(float, v[4:8])), [float(x) for x in v[1:4]]))
    return times, poses


def truth_at(times, poses, t):
    """The true pose at t: the sample at t, else interpolated (linear, and on SO(3))."""
    i = bisect.bisect_left(times, t)
    if i < len(times) and abs(times[i] - t) < 1e-7:
        return pose(*poses[i])
    if i == 0 or i >= len(times):
        return None
    (Ra, ta), (Rb, tb) = poses[i - 1], poses[i]
    s = (t - times[i - 1]) / (times[i] - times[i - 1])
    R = matmul(Ra, exp_so3([s * v for v in log_so3(matmul(transpose(Ra), Rb))]))
    return pose(R, [(1 - s) * a + s * b for a, b in zip(ta, tb)])


def exposure_offset(folder):
    """The camera–IMU time offset as built (ground_truth_calibration.json): a frame
    stamped t was exposed at t + offset, so VO measures the motion between exposures."""
    try:
        with open(folder / "ground_truth_calibration.json") as f:
            return float(json.load(f)["imu"]["camera_time_offset_s"])
    except (OSError, KeyError, ValueError):
        return 0.0


def frame_errors(folder):
    """(ε, Σ) per frame with a motion in one run folder."""
    times, poses = read_truth(folder)
    offset = exposure_offset(folder)
    out = []
    prev_t = None
    with open(folder / "vo_covariance.csv") as f:
        for row in csv.DictReader(f):
            t = float(row["t"])
            status = row["vo_status"]
            if status == "not_processed":
                continue
            if status == "ok" and row["x_m"] != "" and prev_t is not None:
                a = truth_at(times, poses, prev_t + offset)
                b = truth_at(times, poses, t + offset)
                if a is not None and b is not None:
                    true_cp = matmul(inverse(b), a)  # the body's motion, curr from prev
                    M = pose(exp_so3([float(row[k]) for k in ("rx_rad", "ry_rad", "rz_rad")]),
                             [float(row[k]) for k in ("x_m", "y_m", "z_m")])  # VO's T_prev_curr
                    E = matmul(true_cp, M)  # true_cp · (VO's curr from prev)⁻¹
                    eps = translation(E) + log_so3(rotation(E))
                    C = [[0.0] * 6 for _ in range(6)]
                    for i in range(6):
                        for j in range(i, 6):
                            C[i][j] = C[j][i] = float(row[f"c{i}{j}"])
                    out.append((eps, C))
            prev_t = t
    return out


def chi2_mean_interval(n, dof=6):
    """Two-sided 95 % interval of the mean of n χ²(dof) draws (Wilson–Hilferty)."""
    k = dof * n
    h = 2.0 / (9.0 * k)
    q = [k * (1 - h + z * math.sqrt(h)) ** 3 for z in (-1.959964, 1.959964)]
    return q[0] / n, q[1] / n


def summarise(name, errors):
    nees, nees_t, nees_r = [], [], []
    for eps, C in errors:
        full = quadratic(C, eps)
        t = quadratic([r[:3] for r in C[:3]], eps[:3])
        r = quadratic([r[3:] for r in C[3:]], eps[3:])
        if full is None or t is None or r is None:
            continue
        nees.append(full)
        nees_t.append(t)
        nees_r.append(r)
    n = len(nees)
    if n == 0:
        print(f"{name}: no frames")
        return
    lo, hi = chi2_mean_interval(n)
    beyond = sum(1 for v in nees if v > 12.592) / n
    print(f"{name}: frames {n}, mean NEES {statistics.fmean(nees):.2f} (95 % interval {lo:.2f}–{hi:.2f}), "
          f"median {statistics.median(nees):.2f}, beyond 12.59: {100 * beyond:.1f} %, "
          f"translation {statistics.fmean(nees_t):.2f}, rotation {statistics.fmean(nees_r):.2f} (of 3)")


def main(argv):
    if not argv:
        print(__doc__)
        return 2
    everything = []
    for arg in argv:
        folder = pathlib.Path(arg)
        errors = frame_errors(folder)
        summarise(folder.name, errors)
        everything += errors
    if len(argv) > 1:
        summarise("all", everything)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
