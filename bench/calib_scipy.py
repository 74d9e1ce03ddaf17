#!/usr/bin/env python3
"""The same calibration as bench_calib_lm with scipy.optimize.least_squares.

usage: calib_scipy.py SAMPLES.csv REPETITIONS COST(j2|ml)
Residual per sample (one row, as calib/residuals.hpp): the power P of the
radical centre of the three passive circles (J2, eq. 38 with ERRATA), or for
ml P / |dP/dtheta_m| with the gradient by central differences in the readings.
Start: nominal with xa1, ya1, xa2, ya2 at the true (Table 5) values; 11 free.
Prints the median solve time and the largest error against Table 5.
"""
import sys
import time

import numpy as np
from scipy.optimize import least_squares

TRUE = dict(xa1=0, ya1=250, xa2=433, ya2=0.3, xa3=433.5, ya3=499.4, la1=244.1, la2=244.2, la3=243.5,
            lb1=243.8, lb2=244.2, lb3=244.6, dth1=0.01, dth2=-0.01, dth3=0.01)
NAMES = list(TRUE)
FREE = [n for n in NAMES if n not in ("xa1", "ya1", "xa2", "ya2")]


def power(g, th):
    """P for every sample (th: n x 3 readings), eq. 30-33 relative to B1."""
    B = []
    for i in range(3):
        ta = th[:, i] + g[f"dth{i+1}"]
        B.append(np.stack([g[f"xa{i+1}"] + g[f"la{i+1}"] * np.cos(ta),
                           g[f"ya{i+1}"] + g[f"la{i+1}"] * np.sin(ta)], axis=1))
    d2, d3 = B[1] - B[0], B[2] - B[0]
    lb1 = g["lb1"] ** 2
    r2 = 0.5 * ((d2 ** 2).sum(1) + lb1 - g["lb2"] ** 2)
    r3 = 0.5 * ((d3 ** 2).sum(1) + lb1 - g["lb3"] ** 2)
    det = d2[:, 0] * d3[:, 1] - d2[:, 1] * d3[:, 0]
    ux = (r2 * d3[:, 1] - r3 * d2[:, 1]) / det
    uy = (d2[:, 0] * r3 - d3[:, 0] * r2) / det
    return ux * ux + uy * uy - lb1


def main():
    path, reps, cost = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    data = np.genfromtxt(path, delimiter=",", names=True)
    th = np.stack([data["theta_m1"], data["theta_m2"], data["theta_m3"]], axis=1)
    start = dict(TRUE)
    for n in FREE:
        start[n] = 0.0 if n.startswith("dth") else (244.0 if n[0] == "l" else {"xa3": 433.0, "ya3": 500.0}[n])

    def residual(x):
        g = dict(start)
        g.update(zip(FREE, x))
        P = power(g, th)
        if cost == "j2":
            return P
        h = 1e-6
        grad2 = np.zeros_like(P)
        for k in range(3):
            tp, tm = th.copy(), th.copy()
            tp[:, k] += h
            tm[:, k] -= h
            grad2 += ((power(g, tp) - power(g, tm)) / (2 * h)) ** 2
        return P / np.sqrt(grad2)

    x0 = np.array([start[n] for n in FREE])
    times = []
    for _ in range(reps):
        t0 = time.perf_counter()
        sol = least_squares(residual, x0, method="lm", x_scale="jac", ftol=1e-15, xtol=1e-15, gtol=1e-15)
        times.append(time.perf_counter() - t0)
    times.sort()
    est = dict(start)
    est.update(zip(FREE, sol.x))
    err_mm = max(abs(est[n] - TRUE[n]) for n in FREE if not n.startswith("dth"))
    err_rad = max(abs(est[n] - TRUE[n]) for n in FREE if n.startswith("dth"))
    print(f"median_s {times[len(times)//2]:.9g} min_s {times[0]:.9g} max_err_mm {err_mm:.3g} "
          f"max_err_rad {err_rad:.3g} evaluations {sol.nfev} status {sol.status}")


if __name__ == "__main__":
    main()
