#!/usr/bin/env python3
"""Choose calibration poses, and see how much they are worth.

A notebook as a plain script (cells marked "# %%"): design 30 poses by
optimal experiment design at the nominal geometry, compare their Cramer-Rao
bounds with a circle and a random disc of 30 poses, then check the bound
against calibrations of noisy synthetic readings at the designed poses.

    PYTHONPATH=build/python /usr/bin/python3 examples/design_poses.py
"""
# %%
import numpy as np

import gpm

sigma = 1e-4  # encoder noise, rad
robot = gpm.load_robot()
design = gpm.design(robot, count=30, sigma=sigma, grid_step=10.0)
print(f"designed 30 poses out of {design.candidates} candidates ({design.exchanges} exchanges): "
      f"worst bound {design.bounds['worst_mm']:.4f} mm ({design.bounds['worst_param']})")

# %% The same number of poses on a circle and in a disc about home.
home = robot.home
t = np.linspace(0, 2 * np.pi, 30, endpoint=False)
circle = home + 80 * np.stack([np.cos(t), np.sin(t)], axis=1)
rng = np.random.default_rng(1)
r, a = 80 * np.sqrt(rng.random(30)), 2 * np.pi * rng.random(30)
disc = home + np.stack([r * np.cos(a), r * np.sin(a)], axis=1)
for name, poses in (("circle 80 mm", circle), ("disc 80 mm", disc), ("designed", design.poses)):
    b = gpm.pose_bounds(robot, poses, sigma=sigma)
    print(f"{name:14} worst {b['worst_mm']:.4f} mm ({b['worst_param']}), mean {b['mean_mm']:.4f} mm")

# %% Monte Carlo check: calibrate noisy readings of the designed poses.
truth = gpm.Robot(geometry=dict(xa3=433.5, ya3=499.4, la1=244.1, la2=244.2, la3=243.5, lb1=243.8,
                                lb2=244.2, lb3=244.6, dth1=0.01, dth2=-0.01, dth3=0.01, ya2=0.3))
clean = truth.ik(design.poses)  # noiseless readings, (30, 3)
bound = gpm.crb(truth, readings=clean, sigma=sigma)
estimates = []
for trial in range(40):
    noisy = clean + rng.normal(0.0, sigma, clean.shape)
    start = gpm.Robot(geometry=dict(ya2=0.3))  # nominal, with the known frame
    estimates.append([gpm.calibrate(noisy, start).geometry[n] for n in bound["free"]])
spread = np.std(estimates, axis=0)
print(f"{'param':6} {'CRB':>10} {'spread of 40 calibrations':>26}")
for name, s in zip(bound["free"], spread):
    print(f"{name:6} {bound['std'][name]:10.2e} {s:26.2e}")
ratio = spread / np.array([bound["std"][n] for n in bound["free"]])
print(f"spread / bound: {ratio.min():.2f} .. {ratio.max():.2f} (1 for an efficient estimator)")
assert 0.5 < ratio.min() and ratio.max() < 2.0
