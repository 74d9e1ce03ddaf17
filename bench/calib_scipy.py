#!/usr/bin/env python3
"""The same calibration as bench_calib_lm with scipy.optimize.least_squares.

usage: calib_scipy.py SAMPLES.csv REPETITIONS COST(j1|j2|j3|ml)
Residuals per sample as calib/residuals.hpp: for j2 one row, the power P of
the radical centre of the three passive circles (eq. 38 with the squares of
eq. 32 restored); for j3 the same in the decoupled variables l_ac = l_a cos
dth, l_as = l_a sin dth (eq. 41-43, mapped back by eq. 44 with atan2); for j1
six rows (|O - B_i| - l_b^i) (O - B_i) / |O - B_i| (eq. 36); for ml
P / |dP/dtheta_m| with the gradient by central differences in the readings.
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


def elbows(g, th, decoupled=False):
    """B_i for every sample (th: n x 3 readings), eq. 30 (or eq. 41 when decoupled:
    the la and dth entries hold l_ac and l_as)."""
    B = []
    for i in range(3):
        if decoupled:
            c, s = np.cos(th[:, i]), np.sin(th[:, i])
            lac, las = g[f"la{i+1}"], g[f"dth{i+1}"]
            B.append(np.stack([g[f"xa{i+1}"] + lac * c - las * s, g[f"ya{i+1}"] + lac * s + las * c], axis=1))
        else:
            ta = th[:, i] + g[f"dth{i+1}"]
            B.append(np.stack([g[f"xa{i+1}"] + g[f"la{i+1}"] * np.cos(ta),
                               g[f"ya{i+1}"] + g[f"la{i+1}"] * np.sin(ta)], axis=1))
    return B


def centre(g, B):
    """Radical centre O (n x 2) relative to B1 (eq. 32-33) and its power P."""
    d2, d3 = B[1] - B[0], B[2] - B[0]
    lb1 = g["lb1"] ** 2
    r2 = 0.5 * ((d2 ** 2).sum(1) + lb1 - g["lb2"] ** 2)
    r3 = 0.5 * ((d3 ** 2).sum(1) + lb1 - g["lb3"] ** 2)
    det = d2[:, 0] * d3[:, 1] - d2[:, 1] * d3[:, 0]
    ux = (r2 * d3[:, 1] - r3 * d2[:, 1]) / det
    uy = (d2[:, 0] * r3 - d3[:, 0] * r2) / det
    return B[0] + np.stack([ux, uy], axis=1), ux * ux + uy * uy - lb1


def power(g, th, decoupled=False):
    """P for every sample."""
    return centre(g, elbows(g, th, decoupled))[1]


def e1(g, th):
    """The six E1 rows of every sample, flattened (eq. 36 with atan2, eq. 34)."""
    B = elbows(g, th)
    O, _ = centre(g, B)
    rows = []
    for i in range(3):
        w = O - B[i]
        n = np.sqrt((w ** 2).sum(1))
        rows.append(((n - g[f"lb{i+1}"]) / n)[:, None] * w)
    return np.concatenate(rows, axis=1).ravel()


def ml(g, th):
    """The ML residual: the closure power over the norm of its gradient with
    respect to the readings (central differences)."""
    P = power(g, th)
    h = 1e-6
    grad2 = np.zeros_like(P)
    for k in range(3):
        tp, tm = th.copy(), th.copy()
        tp[:, k] += h
        tm[:, k] -= h
        grad2 += ((power(g, tp) - power(g, tm)) / (2 * h)) ** 2
    return P / np.sqrt(grad2)


def main():
    path, reps, cost = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    data = np.genfromtxt(path, delimiter=",", names=True)
    th = np.stack([data["theta_m1"], data["theta_m2"], data["theta_m3"]], axis=1)
    start = dict(TRUE)
    for n in FREE:
        start[n] = 0.0 if n.startswith("dth") else (244.0 if n[0] == "l" else {"xa3": 433.0, "ya3": 500.0}[n])
    if cost == "j3":  # l_ac = l_a cos dth, l_as = l_a sin dth in the la, dth entries
        for i in range(1, 4):
            la, dth = start[f"la{i}"], start[f"dth{i}"]
            start[f"la{i}"], start[f"dth{i}"] = la * np.cos(dth), la * np.sin(dth)

    def residual(x):
        g = dict(start)
        g.update(zip(FREE, x))
        if cost == "j1":
            return e1(g, th)
        if cost in ("j2", "j3"):
            return power(g, th, cost == "j3")
        return ml(g, th)

    x0 = np.array([start[n] for n in FREE])
    times = []
    for _ in range(reps):
        t0 = time.perf_counter()
        sol = least_squares(residual, x0, method="lm", x_scale="jac", ftol=1e-15, xtol=1e-15, gtol=1e-15)
        times.append(time.perf_counter() - t0)
    times.sort()
    est = dict(start)
    est.update(zip(FREE, sol.x))
    if cost == "j3":  # eq. 44: l_a = hypot(l_ac, l_as), dth = atan2(l_as, l_ac)
        for i in range(1, 4):
            lac, las = est[f"la{i}"], est[f"dth{i}"]
            est[f"la{i}"], est[f"dth{i}"] = np.hypot(lac, las), np.arctan2(las, lac)
    err_mm = max(abs(est[n] - TRUE[n]) for n in FREE if not n.startswith("dth"))
    err_rad = max(abs(est[n] - TRUE[n]) for n in FREE if n.startswith("dth"))
    print(f"median_s {times[len(times)//2]:.9g} min_s {times[0]:.9g} max_err_mm {err_mm:.3g} "
          f"max_err_rad {err_rad:.3g} evaluations {sol.nfev} status {sol.status}")


if __name__ == "__main__":
    main()
