"""gpm.study: a scenario over a population of robots, on this machine's
threads or on a Dask cluster (python/README.md).

    import gpm.study
    pop = gpm.study.population("scenarios/main.yaml", 100)    # local threads
    pop.table        # a pandas DataFrame (a list of dicts without pandas)
    pop.plot("population.png")

    from dask.distributed import Client
    pop = gpm.study.population("scenarios/main.yaml", 100, client=Client("tcp://HOST:8786"))

Robot k takes the seed s_k (the scenario's seed + k, or the seeds given): its
scenario is gpm.population_robot_scenario (the actual geometry and, unless
keep_effects, every effect drawn from the seed) and gpm.run runs it. The same
seeds give the same numbers bit for bit whoever runs them. A robot whose run
fails is a row with its seed and the reason, never dropped.

Carried as text inside the compiled module (python/bind_study.cpp): `_gpm`
is the gpm module itself.
"""

import concurrent.futures
import json
import math
import os
import sys
import time

__all__ = ["population", "Population", "main"]

# Columns that depend on who ran the robot, not on the robot (left out of a
# bit-for-bit comparison: Population.numbers()).
RUN_COLUMNS = ("seconds", "worker")


def _worker_address():
    """The Dask worker running this task, or 'local'."""
    try:
        from distributed import get_worker
        return get_worker().address
    except (ImportError, ValueError):
        return "local"


def _accuracy(summary, which, key):
    """summary["accuracy"][which][key], NaN where the run did not measure it."""
    a = (summary.get("accuracy") or {}).get(which)
    return float("nan") if a is None or a.get(key) is None else a[key]


def _number(v):
    """A number of summary.json (null: not finite) as a float."""
    return float("nan") if v is None else v


def _parameter_columns(row, parameters):
    """err_NAME, std_NAME per estimated parameter; the worst |error| / std; the counts within 1 and 3 of it."""
    worst, worst_name, within1, within3, estimated = 0.0, "", 0, 0, 0
    for name, p in parameters.items():
        err = _number(p.get("estimated")) - _number(p.get("actual"))
        std = _number(p.get("std"))
        row["err_" + name], row["std_" + name] = err, std
        if not std > 0:
            continue
        ratio = abs(err) / std
        estimated += 1
        within1 += ratio <= 1.0
        within3 += ratio <= 3.0
        if ratio >= worst:
            worst, worst_name = ratio, name
    row.update(estimated=estimated, within_1_sigma=within1, within_3_sigma=within3, worst_param=worst_name,
               worst_sigma_ratio=worst)


def robot_row(seed, summary, failure=None):
    """One robot's row from gpm.run's summary (or its failure): flat, for a table."""
    row = {"seed": int(seed), "failed": failure is not None, "failure": failure or ""}
    if summary is None:
        return row
    pos = summary.get("positioning_um") or {}
    mt = summary.get("model_test") or {}
    row.update(
        verdict=summary.get("verdict", ""),
        robot_time_s=_number(summary.get("robot_time_s")),
        positioning_rms_um=_number(pos.get("rms")),
        positioning_max_um=_number(pos.get("max")),
        stated_sigma_rms_um=_number(pos.get("stated_sigma_rms")),
        normalised_rms=_number(pos.get("normalised_rms")),
        carried_sigma_rms_um=_number(pos.get("carried_sigma_rms")),
        positioning_bound_um=_number(pos.get("bound_rms")),
        nominal_static_rms_um=_accuracy(summary, "nominal", "static_rms_um"),
        calibrated_static_rms_um=_accuracy(summary, "calibrated", "static_rms_um"),
        calibrated_path_rms_um=_accuracy(summary, "calibrated", "path_rms_um"),
        floor_static_rms_um=_accuracy(summary, "actual", "static_rms_um"),
        plan_deviation_mm=_number(summary.get("plan_deviation_mm")),
        model_test_passed=mt.get("passed"),
        chi2_per_dof=_number(mt.get("chi2")) / _number(mt.get("dof")) if mt.get("dof") else float("nan"),
    )
    row["floor_ratio"] = row["calibrated_static_rms_um"] / row["floor_static_rms_um"] \
        if row["floor_static_rms_um"] > 0 else float("nan")
    ci = (summary.get("floor_ratio") or {}).get("ci95") or [None, None]
    row["floor_ratio_ci95_lo"], row["floor_ratio_ci95_hi"] = _number(ci[0]), _number(ci[1])
    _parameter_columns(row, summary.get("parameters") or {})
    mon = summary.get("monitor")
    if mon:
        row.update(monitor_s=_number(mon.get("duration_s")), monitor_alarms=mon.get("alarms"),
                   monitor_false_alarms=mon.get("false_alarms"))
    return row


def run_robot(text, seed, base_dir):
    """Runs robot `seed` (its scenario text) through gpm.run: its row. Any error is the row's failure."""
    t0 = time.perf_counter()
    try:
        row = robot_row(seed, _gpm.run(text, base_dir=base_dir))
    except Exception as e:  # gpm.InputError, gpm.SimError, gpm.Error: the robot failed, the study goes on
        row = robot_row(seed, None, f"{type(e).__name__}: {e}")
    row["seconds"] = time.perf_counter() - t0
    row["worker"] = _worker_address()
    return row


def _progress_line(row, done, total):
    """The progress line of a finished robot (as `gpm study population` prints it)."""
    if row["failed"]:
        what = f"failed: {row['failure']}"
    else:
        mt = row.get("model_test_passed")
        what = (f"positioning {row['positioning_rms_um']:.2f} um RMS (stated 1-sigma {row['stated_sigma_rms_um']:.2f}),"
                f" worst parameter {row['worst_sigma_ratio']:.1f} sigma ({row['worst_param']}), model test "
                f"{'-' if mt is None else 'passes' if mt else 'fails'}")
    return f"  [{done}/{total}] robot {row['seed']}: {what} ({row.get('seconds', 0):.1f} s, {row.get('worker', '')})"


def _run_local(jobs, threads, report):
    """Runs the jobs (text, seed, base_dir) on `threads` threads of this process (1: one after the other)."""
    if threads == 1:
        for job in jobs:
            report(run_robot(*job))
        return
    with concurrent.futures.ThreadPoolExecutor(max_workers=threads) as pool:
        futures = [pool.submit(run_robot, *job) for job in jobs]
        for f in concurrent.futures.as_completed(futures):
            report(f.result())


def _run_dask(jobs, client, retries, report):
    """Runs the jobs on the client's cluster; a task that failed outright (a lost worker too often) is a failed
    row. Returns the seeds run more than once (their worker was lost, or the task was retried)."""
    from distributed import as_completed
    texts, seeds, bases = (list(x) for x in zip(*jobs))
    futures = client.map(run_robot, texts, seeds, bases, pure=False, retries=retries,
                         key=[f"gpm-robot-{s}-{os.getpid()}-{time.monotonic_ns()}" for s in seeds])
    seed_of = {f.key: s for f, s in zip(futures, seeds)}
    for f in as_completed(futures):
        try:
            row = f.result()
        except Exception as e:  # KilledWorker, CancelledError, a worker that cannot import gpm
            row = robot_row(seed_of[f.key], None, f"{type(e).__name__}: {e}")
            row.update(seconds=float("nan"), worker="")
        report(row)

    def lost_workers(dask_scheduler, keys):  # runs on the scheduler (pickled by value: no gpm there)
        return {k: dask_scheduler.tasks[k].suspicious for k in keys if k in dask_scheduler.tasks}

    retried = set()
    try:
        lost = client.run_on_scheduler(lost_workers, keys=list(seed_of))
        retried |= {seed_of[k] for k, n in lost.items() if n > 0}
    except Exception:  # a scheduler that keeps no such record: none known
        pass
    return sorted(retried)


def _whole(value, name, lo, hi, none_ok=False):
    """value as an int within lo .. hi; gpm.InputTypeError (a TypeError) for a non-integer,
    gpm.InputError (a ValueError) out of range, each naming the keyword `name` and the valid values."""
    if value is None and none_ok:
        return None
    if isinstance(value, bool) or not hasattr(value, "__index__"):
        raise _gpm.InputTypeError(f"{name}: expected an integer from {lo} to {hi}, got {type(value).__name__}")
    value = value.__index__()
    if not lo <= value <= hi:
        raise _gpm.InputError(f"{name}: must be an integer from {lo} to {hi}, got {value}")
    return value


def _seeds(scenario, count, seeds):
    """The robots' seeds (given, or the scenario's seed + 0 .. count - 1); checks the scenario file whole."""
    first = _gpm.scenario_seed(scenario)
    if seeds is not None:
        if isinstance(seeds, (str, bytes)) or not hasattr(seeds, "__iter__"):
            raise _gpm.InputTypeError(f"seeds: expected a list of distinct integers >= 0, got {type(seeds).__name__}")
        seeds = [_whole(s, "seeds", 0, 2**53) for s in seeds]
        if not seeds or len(set(seeds)) != len(seeds):
            raise _gpm.InputError(f"seeds: expected distinct integers >= 0, got {seeds}")
        return seeds
    return [first + k for k in range(_whole(count, "count", 1, 100000))]


def population(scenario, count=None, client=None, seeds=None, keep_effects=False, threads=None, retries=2,
               progress=True):
    """Runs `scenario` over a population of robots: a Population (its .table, .plot(), .failed, .retried).

    scenario: a scenario file. count: robots, seeds scenario seed + 0 .. count - 1; or seeds: these robots.
    keep_effects: the scenario's effects for every robot (only the geometry varies), else drawn per robot.
    client: a dask.distributed.Client: the robots run on its cluster (the workers need `import gpm` and
    the files the scenario names, at the same paths); retries: times a task is run again after an error.
    Without a client: `threads` threads of this process (default: the CPU count; 1: one after the other).
    progress: one line per robot on stderr as it finishes.
    """
    scenario = os.path.abspath(os.fspath(scenario))
    seeds = _seeds(scenario, count, seeds)
    threads = _whole(threads, "threads", 1, 64, none_ok=True)
    retries = _whole(retries, "retries", 0, 100)
    base_dir = os.path.dirname(scenario)
    jobs = [(_gpm.population_robot_scenario(scenario, s, keep_effects), s, base_dir) for s in seeds]
    rows, t0 = [], time.perf_counter()
    where = f"the Dask cluster of {client.scheduler.address}" if client is not None else \
        f"{threads or os.cpu_count()} local thread(s)"
    if progress:
        print(f"population study: {len(seeds)} robots of {scenario} on {where}", file=sys.stderr, flush=True)

    def report(row):
        rows.append(row)
        if progress:
            print(_progress_line(row, len(rows), len(jobs)), file=sys.stderr, flush=True)

    if client is not None:
        retried = _run_dask(jobs, client, retries, report)
    else:
        _run_local(jobs, threads or os.cpu_count() or 1, report)
        retried = []
    order = {s: k for k, s in enumerate(seeds)}
    rows.sort(key=lambda r: order[r["seed"]])
    pop = Population(scenario, rows, time.perf_counter() - t0, retried, {s: j[0] for s, j in zip(seeds, jobs)})
    if progress:
        print(pop.summary_line(), file=sys.stderr, flush=True)
    return pop


def _normal_coverage(k):
    """P(|Z| <= k) for a standard normal Z."""
    return math.erf(k / math.sqrt(2.0))


def _median(values):
    v = sorted(x for x in values if x == x)
    if not v:
        return float("nan")
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


class Population:
    """The result of gpm.study.population: one row per robot, in seed order."""

    def __init__(self, scenario, rows, seconds, retried, texts):
        self.scenario = scenario
        self.rows = rows          # list of dicts, one per robot
        self.seconds = seconds    # wall time of the study
        self.retried = retried    # seeds run more than once (a lost worker, a retried task)
        self.texts = texts        # seed -> its scenario text (gpm.run re-runs it alone)

    @property
    def table(self):
        """The rows as a pandas DataFrame (a list of dicts when pandas is not installed)."""
        try:
            import pandas
        except ImportError:
            return list(self.rows)
        return pandas.DataFrame(self.rows)

    @property
    def failed(self):
        """The rows of the robots whose run failed (seed and failure)."""
        return [r for r in self.rows if r["failed"]]

    def numbers(self):
        """Every row without the columns of who ran it (seconds, worker): equal bit for bit for equal seeds."""
        return [{k: v for k, v in r.items() if k not in RUN_COLUMNS} for r in self.rows]

    def sigma_ratios(self):
        """|estimated - actual| / stated 1-sigma of every estimated parameter of every robot that ran."""
        out = []
        for r in self.rows:
            for k, err in r.items():
                if k.startswith("err_"):
                    std = r["std_" + k[4:]]
                    if std == std and std > 0:
                        out.append(abs(err) / std)
        return out

    def summary(self):
        """Figures over the robots that ran: positioning median and worst, coverage of the stated 1-sigma."""
        ok = [r for r in self.rows if not r["failed"]]
        ratios = self.sigma_ratios()
        return {
            "robots": len(self.rows), "failed": len(self.rows) - len(ok), "retried": list(self.retried),
            "positioning_median_um": _median(r["positioning_rms_um"] for r in ok),
            "positioning_worst_um": max((r["positioning_rms_um"] for r in ok), default=float("nan")),
            "coverage_1_sigma": sum(x <= 1.0 for x in ratios) / len(ratios) if ratios else float("nan"),
            "coverage_1_sigma_normal": _normal_coverage(1.0),
            "coverage_3_sigma": sum(x <= 3.0 for x in ratios) / len(ratios) if ratios else float("nan"),
            "robot_time_median_s": _median(r["robot_time_s"] for r in ok),
            "plan_deviation_worst_mm": max((d for d in (r.get("plan_deviation_mm", float("nan")) for r in ok)
                                            if d == d), default=float("nan")),
            "seconds": self.seconds,
            "robots_per_minute": 60.0 * len(self.rows) / self.seconds if self.seconds > 0 else float("nan"),
        }

    def __repr__(self):
        s = self.summary()
        return (f"<gpm.study.Population {s['robots']} robots ({s['failed']} failed): positioning median "
                f"{s['positioning_median_um']:.3g} um, worst {s['positioning_worst_um']:.3g} um; within the stated "
                f"1-sigma {100 * s['coverage_1_sigma']:.0f}% (normal 68%); {s['seconds']:.1f} s>")

    def summary_line(self):
        """One line: robots, failures, retries, time and throughput, accuracy, coverage of the stated 1-sigma."""
        s = self.summary()
        retried = f", retried: robots {s['retried']}" if s["retried"] else ""
        return (f"{s['robots']} robots ({s['failed']} failed{retried}) in {s['seconds']:.1f} s "
                f"({s['robots_per_minute']:.2f} robots/min): positioning median {s['positioning_median_um']:.2f} um "
                f"RMS, worst {s['positioning_worst_um']:.2f} um; parameters within their stated 1-sigma "
                f"{100 * s['coverage_1_sigma']:.0f}% (normal: 68%), within 3 sigma {100 * s['coverage_3_sigma']:.0f}%")

    def plot(self, path=None):
        """A matplotlib Figure: the accuracy distribution, the coverage of the stated 1-sigma and the robot
        time; saved to path (PNG, PDF, SVG by its extension) when given."""
        from matplotlib.figure import Figure
        ok = [r for r in self.rows if not r["failed"]]
        fig = Figure(figsize=(13, 4), layout="constrained")
        a, c, t = fig.subplots(1, 3)
        a.hist([r["positioning_rms_um"] for r in ok], bins=max(5, min(30, len(ok))), color="tab:blue")
        a.set(title="accuracy after calibration", xlabel="positioning error RMS over the disc (um)", ylabel="robots")
        ratios = sorted(self.sigma_ratios())
        ks = [0.05 * i for i in range(81)]
        if ratios:
            c.plot(ks, [sum(x <= k for x in ratios) / len(ratios) for k in ks], label="population")
        c.plot(ks, [_normal_coverage(k) for k in ks], "--", color="gray", label="normal (honest 1-sigma)")
        c.axvline(1.0, color="tab:red", lw=0.8)
        c.set(title="coverage of the stated 1-sigma", xlabel="|error| / stated 1-sigma",
              ylabel="fraction of parameters within", ylim=(0, 1.02))
        c.legend(loc="lower right")
        t.hist([r["robot_time_s"] for r in ok], bins=max(5, min(30, len(ok))), color="tab:green")
        t.set(title="robot time", xlabel="robot time of the main procedure (s)", ylabel="robots")
        if path is not None:
            fig.savefig(os.fspath(path), dpi=110)
        return fig

    def write(self, out_dir):
        """Writes population.json (summary and rows), population.csv, population.png and robot_SEED.yaml."""
        os.makedirs(out_dir, exist_ok=True)
        with open(os.path.join(out_dir, "population.json"), "w") as f:
            json.dump({"scenario": self.scenario, "summary": self.summary(), "robots": self.rows}, f, indent=2)
        columns = list(dict.fromkeys(k for r in self.rows for k in r))
        with open(os.path.join(out_dir, "population.csv"), "w") as f:
            f.write(",".join(columns) + "\n")
            for r in self.rows:
                f.write(",".join(_csv_cell(r.get(k, "")) for k in columns) + "\n")
        for seed, text in self.texts.items():
            with open(os.path.join(out_dir, f"robot_{seed}.yaml"), "w") as f:
                f.write(text)
        self.plot(os.path.join(out_dir, "population.png"))


def _csv_cell(v):
    """One CSV cell: a float in its exact shortest form, text quoted where it must be."""
    if isinstance(v, float):
        return repr(v)
    s = str(v)
    return '"' + s.replace('"', '""') + '"' if any(ch in s for ch in ',"\n') else s


def main(argv=None):
    """`gpm study population SCENARIO -o DIR --scheduler ADDRESS ...` (app/cmd_study.cpp runs this): exit code."""
    import argparse
    p = argparse.ArgumentParser(prog="gpm study population")
    p.add_argument("scenario")
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--count", type=int, default=30)
    p.add_argument("--seeds")
    p.add_argument("--keep-effects", action="store_true")
    p.add_argument("--scheduler", required=True)
    p.add_argument("--retries", type=int, default=2)
    a = p.parse_args(argv)
    try:
        from distributed import Client
    except ImportError:
        print("gpm: error: --scheduler: the Dask scheduler needs python3-distributed (scripts/setup.sh)",
              file=sys.stderr)
        return 2
    try:
        seeds = None if a.seeds is None else [int(s) for s in a.seeds.split(",")]
        _seeds(os.path.abspath(a.scenario), a.count, seeds)  # bad input before connecting
        with Client(a.scheduler, timeout="20s") as client:
            pop = population(a.scenario, a.count, client=client, seeds=seeds, keep_effects=a.keep_effects,
                             retries=a.retries)
    except (ValueError, _gpm.InputError) as e:
        print(f"gpm: error: {e}", file=sys.stderr)
        return 2
    except OSError as e:  # the scheduler cannot be reached
        print(f"gpm: error: --scheduler {a.scheduler}: {e}", file=sys.stderr)
        return 1
    pop.write(a.output)
    print(pop.summary_line())
    print(f"-> {a.output}/population.json, population.csv, population.png, robot_SEED.yaml")
    return 0
