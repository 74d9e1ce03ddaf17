# gpm._plots: the plot() of gpm.CalibrationResult and gpm.Simulation
# (matplotlib, Debian's python3-matplotlib from scripts/setup.sh). Pure
# Python carried inside the module like gpm.study (python/CMakeLists.txt,
# python/bind_plots.cpp), which sets `_gpm` to the module being built.
#
# Figures are made on the Agg canvas, never through pyplot: no display is
# needed and no global figure state is touched. plot(path) saves the figure
# (PNG, PDF, SVG by the extension) and returns it; plot() returns it.
import math
import os

DPI = 100                      # the pixels of a saved figure are its size in inches x DPI
CALIBRATION_SIZE = (12.0, 8.0)  # inches: 1200 x 800 px
SIMULATION_SIZE = (12.0, 5.0)   # inches: 1200 x 500 px
ANGLES = ("dth1", "dth2", "dth3")


def _figure(size):
    """A matplotlib Figure on the Agg canvas (headless)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=size, dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def _finish(fig, path):
    if path is not None:
        fig.savefig(os.fspath(path), dpi=DPI)
    return fig


def _reference(result, truth):
    """The geometry the estimate is compared with, and its name: truth (a gpm.Robot or dict) or the start."""
    if truth is None:
        return result.start, "start"
    geometry = truth.geometry if isinstance(truth, _gpm.Robot) else dict(truth)
    unknown = sorted(set(geometry) - set(_gpm.PARAM_NAMES))
    if unknown:
        raise _gpm.InputError(f"truth: unknown parameter {unknown[0]!r}; valid: {' '.join(_gpm.PARAM_NAMES)}")
    return {**result.start, **geometry}, "truth"


def _residuals(axes, result):
    """The normalised residual of each reading with the +-1 and +-3 bands of the model test's sigma."""
    z = result.residuals
    test = result.diagnostics.get("model_test")
    if z is None or not test:
        axes.text(0.5, 0.5, "no residuals: a loaded result or a fit with the motion model", ha="center",
                  transform=axes.transAxes)
    else:
        axes.axhspan(-1, 1, color="tab:green", alpha=0.15, label="within 1 sigma")
        for v in (-3, 3):
            axes.axhline(v, color="tab:red", lw=0.8, ls="--")
        axes.plot(range(len(z)), z, ".", color="tab:blue", ms=5, label="reading")
        axes.legend(loc="upper right", fontsize="small")
        axes.set(title=f"residuals: model test {'passed' if test['passed'] else 'failed'}, "
                       f"chi2/dof {test['chi2_per_dof']:.3g}")
    axes.set(xlabel="sample", ylabel="ML residual / reading 1-sigma")


def calibration(result, path=None, truth=None):
    """Plots the calibration: each estimated parameter's error (against truth, a gpm.Robot or dict of the
    actual parameters, when given; else its change from the start) in units of its stated 1-sigma, with the
    +-1 and +-3 sigma bands; the 1-sigma themselves (um for lengths, urad for offsets); the residual of
    each reading in units of the reading 1-sigma; and the cost J of every LM iteration. Returns the
    matplotlib Figure (1200 x 800 px); saves it to path when given."""
    reference, what = _reference(result, truth)
    names = result.free
    sigma = result.std
    ratio = [(result.geometry[n] - reference[n]) / sigma[n] if sigma[n] > 0 else math.nan for n in names]
    fig = _figure(CALIBRATION_SIZE)
    (a, s), (z, c) = fig.subplots(2, 2)
    _residuals(z, result)
    y = range(len(names))
    a.axvspan(-1, 1, color="tab:green", alpha=0.15, label="within 1 sigma")
    for x in (-3, 3):
        a.axvline(x, color="tab:red", lw=0.8, ls="--")
    a.axvline(0, color="black", lw=0.6)
    a.barh(y, ratio, color=["tab:blue" if abs(r) <= 1 else "tab:orange" if abs(r) <= 3 else "tab:red"
                            for r in ratio])
    a.set_yticks(list(y), names)
    a.invert_yaxis()
    a.set(xlabel=f"(estimate - {what}) / stated 1-sigma",
          title="errors against their 1-sigma" if what == "truth" else "change from the start in 1-sigma units")
    a.legend(loc="lower right", fontsize="small")
    std = [sigma[n] * (1e6 if n in ANGLES else 1e3) for n in names]
    s.barh(y, std, color=["tab:purple" if n in ANGLES else "tab:blue" for n in names])
    s.set_yticks(list(y), names)
    s.invert_yaxis()
    s.set(xlabel="stated 1-sigma (um for lengths, urad for offsets)", title="parameter 1-sigma")
    conv = result.convergence
    if conv["iteration"]:
        costs = [max(v, 1e-300) for v in conv["cost"]]
        c.semilogy(conv["iteration"], costs, color="gray", lw=0.8)
        ok = [(i, v) for i, v, acc in zip(conv["iteration"], costs, conv["accepted"]) if acc]
        no = [(i, v) for i, v, acc in zip(conv["iteration"], costs, conv["accepted"]) if not acc]
        if ok:
            c.semilogy(*zip(*ok), "o", color="tab:blue", label="accepted step")
        if no:
            c.semilogy(*zip(*no), "o", mfc="none", color="tab:red", label="rejected step")
        c.legend(loc="upper right", fontsize="small")
    else:
        c.text(0.5, 0.5, f"{result.diagnostics['method']}: no LM iterations recorded", ha="center",
               transform=c.transAxes)
    c.set(xlabel="LM iteration", ylabel=f"cost J ({result.diagnostics['cost_function']})",
          title=f"convergence: {result.diagnostics['iterations']} iterations")
    return _finish(fig, path)


def simulation(sim, path=None):
    """Plots the run: the commanded and the actual path of the end-effector with the samples and the base
    joints of the actual robot, and the tracking error |actual - commanded| over time. Returns the
    matplotlib Figure (1200 x 500 px); saves it to path when given."""
    import numpy as np
    fig = _figure(SIMULATION_SIZE)
    p, e = fig.subplots(1, 2, width_ratios=(1.0, 1.4))
    traj = sim.trajectory
    if len(traj["t"]):
        p.plot(traj["desired"][:, 0], traj["desired"][:, 1], "--", color="gray", lw=0.8, label="commanded")
        p.plot(traj["actual"][:, 0], traj["actual"][:, 1], color="tab:blue", lw=1.0, label="actual")
    if len(sim.xy):
        p.plot(sim.xy[:, 0], sim.xy[:, 1], ".", color="tab:red", ms=5, label=f"{len(sim.xy)} samples")
    g = sim.actual.geometry
    for i in (1, 2, 3):
        p.plot(g[f"xa{i}"], g[f"ya{i}"], "^", color="black", ms=8)
        p.annotate(f"A{i}", (g[f"xa{i}"], g[f"ya{i}"]), textcoords="offset points", xytext=(6, 4))
    p.set_aspect("equal", adjustable="datalim")
    p.set(xlabel="x (mm)", ylabel="y (mm)", title=f"{sim.name}: the end-effector's path")
    p.legend(loc="lower left", fontsize="small")
    if len(traj["t"]):
        err = np.hypot(*(traj["actual"] - traj["desired"]).T)  # mm
        unit, scale = ("mm", 1.0) if err.max() >= 1.0 else ("um", 1e3)
        e.plot(traj["t"], err * scale, color="tab:blue", lw=0.8)
        e.set(ylabel=f"|actual - commanded| ({unit})")
    e.set(xlabel="time (s)", title=f"tracking over {sim.simulated_s:.1f} s simulated "
                                   f"({sim.sampling_s:.1f} s sampling), max torque {sim.max_torque:.3g} N m")
    return _finish(fig, path)


def _calibration_plot(self, path=None, truth=None):
    return calibration(self, path, truth)


def _simulation_plot(self, path=None):
    return simulation(self, path)


_calibration_plot.__doc__ = calibration.__doc__
_simulation_plot.__doc__ = simulation.__doc__
_gpm.CalibrationResult.plot = _calibration_plot
_gpm.Simulation.plot = _simulation_plot
