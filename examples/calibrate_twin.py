#!/usr/bin/env python3
"""Calibrate the digital twin from its own encoder readings.

A notebook as a plain script (cells marked "# %%"): simulate a scenario whose
actual robot differs from the controller's model by a seeded perturbation,
calibrate the model from the sampled readings, and compare both the model
and the calibrated robot with the actual one.

    PYTHONPATH=build/python /usr/bin/python3 examples/calibrate_twin.py [SCENARIO.yaml [PLOT.png]]
"""
# %%
import pathlib
import sys

import numpy as np

import gpm

scenario = sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(gpm.scenarios_dir()) / "procedure_disc_stopgo.yaml"
run = gpm.simulate(scenario)
print(f"{scenario}: {len(run.readings)} samples, {run.simulated_s:.2f} s simulated, "
      f"largest loop gap {run.max_violation_m * 1e6:.3f} um")

# %% Calibrate the controller's model from the readings (ML cost, Ceres LM).
result = gpm.calibrate(run.readings, run.controller, true_xy=run.xy)
d = result.diagnostics
print(f"calibrated {len(result.free)} parameters: J = {d['cost']:.3g}, {d['iterations']} iterations, "
      f"{d['seconds'] * 1e3:.1f} ms, kmrmse {d['kmrmse_mm']:.4f} mm")

# %% Parameter errors against the actual robot, before and after.
actual, model = run.actual.geometry, run.controller.geometry
print(f"{'param':6} {'model error':>12} {'calibrated error':>17} {'1-sigma':>10}")
for name in result.free:
    unit = "rad" if name.startswith("dth") else "mm"
    print(f"{name:6} {model[name] - actual[name]:12.2e} {result.geometry[name] - actual[name]:17.2e} "
          f"{result.std[name]:10.2e} {unit}")

# %% What it means at the end-effector: fk of the readings by each model.
err_model = np.linalg.norm(run.controller.fk(run.readings) - run.xy, axis=1)
err_calib = np.linalg.norm(result.robot.fk(run.readings) - run.xy, axis=1)
print(f"end-effector error over the samples: model {err_model.max():.4f} mm, calibrated {err_calib.max():.4f} mm")
assert err_calib.max() < err_model.max(), "calibration did not improve the model"

# %% The result in a few lines, and its picture: each parameter's error in units
# of its stated 1-sigma, the 1-sigma, the cost of each LM iteration (a notebook
# shows the returned Figure; a second argument saves it as a PNG).
print(result)
figure = result.plot(sys.argv[2] if len(sys.argv) > 2 else None, truth=run.actual)
