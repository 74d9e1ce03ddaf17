#!/usr/bin/env python3
"""gpm.calibrate in a Python loop against scipy.optimize.least_squares.

usage: python_calib_vs_scipy.py SAMPLES.csv [REPETITIONS]
Both solve the same problem in the same process: the ML cost (closure power
P divided by |dP/dtheta_m|) on the same readings, 11 free parameters, start
nominal with xa1, ya1, xa2, ya2 at the true (paper Table 5) values. SciPy's
residual is bench/calib_scipy.py's NumPy formulation (vectorised over the
samples, reading gradient by central differences), solved with
method="lm" to tolerances 1e-15. gpm.calibrate is the whole library call
(identifiability, Ceres LM, covariance), as a notebook user would loop it.
Prints per-calibration times (median and fastest: on a loaded machine the
fastest is the fairer figure), both final errors against Table 5, the largest
difference between the two estimates, and the speed ratios.
"""
import pathlib
import sys
import time

import numpy as np
from scipy.optimize import least_squares

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import calib_scipy  # noqa: E402  (the existing SciPy formulation)
import gpm  # noqa: E402

TRUE, FREE = calib_scipy.TRUE, calib_scipy.FREE
START = dict(TRUE)
START.update({n: 0.0 if n.startswith("dth") else 244.0 if n[0] == "l" else {"xa3": 433.0, "ya3": 500.0}[n]
              for n in FREE})


def scipy_calibrate(th):
    """The ML calibration of bench/calib_scipy.py: returns the estimated geometry dict."""
    def residual(x):
        g = dict(START)
        g.update(zip(FREE, x))
        return calib_scipy.ml(g, th)

    x0 = np.array([START[n] for n in FREE])
    sol = least_squares(residual, x0, method="lm", x_scale="jac", ftol=1e-15, xtol=1e-15, gtol=1e-15)
    est = dict(START)
    est.update(zip(FREE, sol.x))
    return est


def errors(est):
    mm = max(abs(est[n] - TRUE[n]) for n in FREE if not n.startswith("dth"))
    rad = max(abs(est[n] - TRUE[n]) for n in FREE if n.startswith("dth"))
    return mm, rad


def timed(fn, reps):
    times, out = [], None
    for _ in range(reps):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    times.sort()
    return times[len(times) // 2], times[0], out


def main():
    path = sys.argv[1]
    reps = int(sys.argv[2]) if len(sys.argv) > 2 else 100
    readings = gpm.read_samples(path)
    robot = gpm.Robot(geometry=START)
    gm, gn, g = timed(lambda: gpm.calibrate(readings, robot, cost="ml", method="lm").geometry, reps)
    sm, sn, s = timed(lambda: scipy_calibrate(readings), max(5, reps // 10))
    ge, se = errors(g), errors(s)
    diff = max(abs(g[n] - s[n]) for n in FREE)
    print(f"{len(readings)} samples, {len(FREE)} free parameters, ML cost, LM; {reps} gpm and "
          f"{max(5, reps // 10)} scipy repetitions")
    print(f"{'solver':28} {'median ms':>10} {'min ms':>9} {'max err mm':>11} {'max err rad':>12}")
    print(f"{'gpm.calibrate (Ceres LM)':28} {gm * 1e3:10.3f} {gn * 1e3:9.3f} {ge[0]:11.3g} {ge[1]:12.3g}")
    print(f"{'scipy least_squares lm':28} {sm * 1e3:10.3f} {sn * 1e3:9.3f} {se[0]:11.3g} {se[1]:12.3g}")
    print(f"largest difference between the two estimates: {diff:.3g}")
    print(f"ratio scipy / gpm: median {sm / gm:.1f}x, fastest {sn / gn:.1f}x (goal >= 20x)")
    if max(ge[0], se[0]) > 1e-6 or max(ge[1], se[1]) > 1e-8:
        print("accuracy: the solvers did not both reach the true robot", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
