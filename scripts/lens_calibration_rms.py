#!/usr/bin/env python3
"""A published lens calibration's accuracy as `robot.imperfections.distortion_calibration_rms_px`.

A calibration tool prints each distortion coefficient's spread (Bouguet's toolbox:
kc_error, about three standard deviations). Those spreads belong to the camera that
was calibrated: how much k2 is pinned down depends on how far from the centre its
image reaches. What carries over to another camera is the calibrated model's error in
pixels over the image. This script finds it, as robot/lens_calibration_error.h models a
calibration: the coefficients' covariance is eps^2 (2M/p) (J^T J)^-1 over a 64 x 48 grid
of the calibrated camera's image, so a coefficient's printed spread sigma_i gives
eps_i = sigma_i / sqrt((2M/p) [(J^T J)^-1]_ii). It prints eps_i per coefficient (k1, k2,
p1, p2) and their geometric mean, the value a profile takes. The grid's points are taken
at their pixel positions: the calibrated camera's own lens would move them by a few per
cent of their radius, and a fitted lens need not be invertible out to the corners, where
the calibration saw no points (the Kinect v2 infrared camera's below is not).

  scripts/lens_calibration_rms.py --size 640 480 --fc 657.5 --cc 303 242 \\
      --kc-error 0.003142 0.012508 1.694e-4 1.675e-4 --sigmas 3      # typical: 0.017
  scripts/lens_calibration_rms.py --size 512 424 --fc 364.457 364.543 --cc 258.422 202.487 \\
      --kc-error 0.0127308 0.0388271 0.0019336 0.0023805 --sigmas 3  # harsh: 0.22
"""
import argparse
import math


def distort(kc, x, y):
    k1, k2, p1, p2 = kc
    r2 = x * x + y * y
    radial = 1 + k1 * r2 + k2 * r2 * r2
    return (x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
            y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y)


def inverse(a):
    """Gauss-Jordan inverse of a small square matrix (lists of lists)."""
    n = len(a)
    m = [row[:] + [1.0 if i == j else 0.0 for j in range(n)] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        pivot = m[c][c]
        m[c] = [v / pivot for v in m[c]]
        for r in range(n):
            if r != c:
                f = m[r][c]
                m[r] = [v - f * w for v, w in zip(m[r], m[c])]
    return [row[n:] for row in m]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", type=int, nargs=2, required=True, metavar=("W", "H"))
    ap.add_argument("--fc", type=float, nargs="+", required=True, help="fx [fy] [px]")
    ap.add_argument("--cc", type=float, nargs=2, required=True, metavar=("CX", "CY"))
    ap.add_argument("--kc-error", type=float, nargs=4, required=True)
    ap.add_argument("--sigmas", type=float, default=1.0,
                    help="how many standard deviations kc-error is (Bouguet: 3)")
    a = ap.parse_args()
    w, h = a.size
    fx = a.fc[0]
    fy = a.fc[1] if len(a.fc) > 1 else fx
    cx, cy = a.cc
    jtj = [[0.0] * 4 for _ in range(4)]
    rows = 0
    for row in range(48):
        for col in range(64):
            u = (col + 0.5) * w / 64 - 0.5
            v = (row + 0.5) * h / 48 - 0.5
            x, y = (u - cx) / fx, (v - cy) / fy
            J = []
            for i in range(4):
                unit = [0.0] * 4
                unit[i] = 1.0  # the model is linear in its coefficients
                d = distort(unit, x, y)
                J.append((fx * (d[0] - x), fy * (d[1] - y)))
            for i in range(4):
                for j in range(4):
                    jtj[i][j] += J[i][0] * J[j][0] + J[i][1] * J[j][1]
            rows += 2
    cov = inverse(jtj)
    eps = [e / a.sigmas / math.sqrt(rows / 4 * cov[i][i]) for i, e in enumerate(a.kc_error)]
    print("eps per coefficient (k1 k2 p1 p2) [px]: " + " ".join(f"{e:.4f}" for e in eps))
    print(f"geometric mean [px]: {math.exp(sum(math.log(e) for e in eps) / 4):.4f}")


if __name__ == "__main__":
    main()
