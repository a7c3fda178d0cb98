#!/usr/bin/env python3
"""The bias instability as a sum of first-order Gauss-Markov terms (robot/imu_parts.cpp).

One first-order Gauss-Markov term's Allan deviation has a hump near 1.9 times its
correlation time, not a floor. The Allan variance of a sum of independent terms is the
sum of theirs, linear in the terms' variances, so the variances whose sum is flat at a
floor F over a range of averaging times are a linear least-squares fit. This prints,
for correlation times 1, 10, 100 and 1000 s fitted on 200 log-spaced averaging times
over 1-3000 s, each term's standard deviation as a multiple of F
(kFloorMultiples in robot/imu_parts.cpp) and the summed Allan deviation over F.

Usage: python3 scripts/imu_gauss_markov_fit.py
"""
import math

TAUS_C = [1.0, 10.0, 100.0, 1000.0]
LO, HI, N = 1.0, 3000.0, 200


def shape(tau, tau_c):
    """Allan variance of a unit-variance first-order Gauss-Markov process at tau."""
    x = tau / tau_c
    return 2.0 / x - (3.0 - 4.0 * math.exp(-x) + math.exp(-2.0 * x)) / (x * x)


def solve(m, r):
    """Gaussian elimination of the small normal equations m v = r."""
    k = len(r)
    m = [row[:] for row in m]
    r = r[:]
    for i in range(k):
        for j in range(i + 1, k):
            f = m[j][i] / m[i][i]
            for c in range(k):
                m[j][c] -= f * m[i][c]
            r[j] -= f * r[i]
    v = [0.0] * k
    for i in reversed(range(k)):
        v[i] = (r[i] - sum(m[i][c] * v[c] for c in range(i + 1, k))) / m[i][i]
    return v


def main():
    taus = [LO * (HI / LO) ** (j / (N - 1)) for j in range(N)]
    a = [[shape(t, tc) for tc in TAUS_C] for t in taus]
    k = len(TAUS_C)
    m = [[sum(row[p] * row[q] for row in a) for q in range(k)] for p in range(k)]
    r = [sum(row[p] for row in a) for p in range(k)]
    variances = solve(m, r)
    assert all(v > 0 for v in variances), variances
    print("tau_c [s]:", TAUS_C)
    print("std / floor:", ", ".join("%.6f" % math.sqrt(v) for v in variances))
    for t in [1, 3, 10, 30, 100, 300, 1000, 2000, 3000, 10000, 30000]:
        s = math.sqrt(sum(v * shape(t, tc) for v, tc in zip(variances, TAUS_C)))
        print("tau %6g s: Allan deviation / floor %.3f" % (t, s))


if __name__ == "__main__":
    main()
