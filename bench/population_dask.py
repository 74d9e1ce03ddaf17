"""Benchmark of gpm.run and gpm.study.population (python/bind_run.cpp, python/study.py).

1. One robot of a scenario (default scenarios/main.yaml, the main job): its
   CPU time by stage (the stages gpm.run reports), and its wall time.
2. A small population study on a Dask LocalCluster of one worker process,
   then of two (one thread each, 127.0.0.1), in this one run: the speed
   ratio 2 workers / 1 worker and the throughput in robots per minute, with
   the check that both give the same numbers bit for bit.
3. The same robots on a plain process pool of one, then two processes (no
   Dask), and a pure-Python arithmetic loop run twice in one process, then
   once in each of two at once: what this machine gives two processes at
   all, the ceiling of the ratio in 2 (a virtual machine's two cores need not
   give two processes twice the speed of one).

    PYTHONPATH=build/python /usr/bin/python3 bench/population_dask.py [--scenario S] [--study-scenario S]
        [--count N] [--one-robot]

--one-robot measures part 1 only (the CPU of one robot, which a shared
machine leaves measurable; parts 2 and 3 need a quiet one).

The machine is shared: run it on a quiet one (the ratio is only as good as
the second core is free).
"""
import argparse
import collections
import os
import pathlib
import tempfile
import time

import gpm
import gpm.study

ROOT = pathlib.Path(__file__).resolve().parents[1]


def cpu_by_stage(scenario, seed=None):
    """(rows of (stage, cpu s, wall s), total cpu s, total wall s) of one gpm.run of scenario."""
    marks = []

    def stage(name):
        marks.append((name, time.process_time(), time.perf_counter()))

    c0, w0 = time.process_time(), time.perf_counter()
    marks.append(("parsing the scenario", c0, w0))
    gpm.run(scenario, progress=stage, seed=seed)
    c1, w1 = time.process_time(), time.perf_counter()
    marks.append(("end", c1, w1))
    rows = [(a[0], b[1] - a[1], b[2] - a[2]) for a, b in zip(marks, marks[1:])]
    return rows, c1 - c0, w1 - w0


def study_seconds(scenario, count, workers, local_dir):
    """(wall s, Population) of a study of count robots on a LocalCluster of `workers` processes."""
    from distributed import Client, LocalCluster
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None, local_directory=local_dir) as cluster, Client(cluster) as client:
        client.wait_for_workers(workers)
        t0 = time.perf_counter()
        pop = gpm.study.population(scenario, count, client=client, progress=False)
        return time.perf_counter() - t0, pop


def where_the_time_went(rows):
    """(sum of the robots' own seconds, seconds the busiest worker ran robots, seconds the least busy one did) of
    a study's rows (each robot's wall seconds and worker)."""
    busy = collections.Counter()
    for r in rows:
        busy[r.get("worker", "")] += r["seconds"]
    return sum(busy.values()), max(busy.values()), min(busy.values())


def _run_robot(job):
    """One robot of the study as gpm.study.population's tasks run it (a task of the plain process pool)."""
    import gpm.study as st
    return st.run_robot(*job)


def _import_gpm(_):
    """Imports gpm in a pool process (what a Dask worker has done before its first task)."""
    import gpm.study as st
    return st.__name__


def plain_pool_seconds(scenario, count, workers):
    """(wall s, sum of the robots' own seconds) of the study's count robots (the same scenario texts and seeds
    gpm.study.population gives its tasks, each through the same gpm.study.run_robot) on a plain process pool of
    `workers` processes, no Dask, each process as cold as a fresh Dask worker (gpm imported, no robot run): what
    this machine's cores give two processes at all (the ceiling of the Dask ratio)."""
    import concurrent.futures
    import multiprocessing
    scenario = os.path.abspath(scenario)
    first = gpm.scenario_seed(scenario)
    jobs = [(gpm.population_robot_scenario(scenario, first + k, False), first + k, os.path.dirname(scenario))
            for k in range(count)]
    ctx = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(max_workers=workers, mp_context=ctx) as pool:
        list(pool.map(_import_gpm, range(workers)))  # start every process first
        t0 = time.perf_counter()
        rows = list(pool.map(_run_robot, jobs))
        return time.perf_counter() - t0, sum(r["seconds"] for r in rows)


def _spin(n):
    """Wall s of n iterations of a pure-Python arithmetic loop (no memory, no I/O, no library)."""
    t0 = time.perf_counter()
    x = 0
    for i in range(n):
        x += i * i
    return time.perf_counter() - t0


def spin_ratio(n=30_000_000, repeats=3):
    """Median over repeats of (two loops of n one after the other) / (the same two loops in two processes at
    once): what two processes that only compute get from this machine's cores, whatever the program."""
    import concurrent.futures
    import multiprocessing
    import statistics
    ratios = []
    ctx = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(max_workers=2, mp_context=ctx) as pool:
        list(pool.map(_spin, [1000, 1000]))  # both processes started
        for _ in range(repeats):
            t0 = time.perf_counter()
            list(pool.map(_spin, [n], chunksize=1))
            list(pool.map(_spin, [n], chunksize=1))
            serial = time.perf_counter() - t0
            t0 = time.perf_counter()
            list(pool.map(_spin, [n, n], chunksize=1))
            ratios.append(serial / (time.perf_counter() - t0))
    return statistics.median(ratios), min(ratios), max(ratios)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenario", default=str(ROOT / "scenarios" / "main.yaml"), help="the one robot of part 1")
    p.add_argument("--study-scenario", default=str(ROOT / "tests" / "fixtures" / "population_small.yaml"))
    p.add_argument("--count", type=int, default=20, help="robots of the study (part 2)")
    p.add_argument("--one-robot", action="store_true", help="part 1 only: one robot's CPU by stage")
    a = p.parse_args()

    print("load average at the start: {:.1f} {:.1f} {:.1f} ({} cores)".format(*os.getloadavg(), os.cpu_count()))
    rows, cpu, wall = cpu_by_stage(a.scenario)
    print(f"one robot of {os.path.relpath(a.scenario, ROOT)}: {cpu:.2f} s CPU, {wall:.2f} s wall")
    print(f"  {'stage':<58} {'CPU s':>7} {'wall s':>7}")
    for name, c, w in rows:
        print(f"  {name:<58} {c:7.2f} {w:7.2f}")
    # A study's worker runs robot after robot of one data sheet: the pose
    # design is made once per process (run/sampling_design.cpp).
    rows2, cpu2, wall2 = cpu_by_stage(a.scenario, seed=12345)
    print(f"the next robot in the same process (another seed, the design remembered): {cpu2:.2f} s CPU, "
          f"{wall2:.2f} s wall")
    for name, c, w in rows2:
        print(f"  {name:<58} {c:7.2f} {w:7.2f}")
    print(f"throughput of one core at that CPU: {60 / cpu2:.1f} robots per minute (a study of n workers on n free "
          f"cores: n times that, less what part 2 measures)")
    if a.one_robot:
        return

    with tempfile.TemporaryDirectory(prefix="gpm-bench-dask-") as d:
        t1, one = study_seconds(a.study_scenario, a.count, 1, d)
        t2, two = study_seconds(a.study_scenario, a.count, 2, d)
    p1, ps1 = plain_pool_seconds(a.study_scenario, a.count, 1)
    p2, ps2 = plain_pool_seconds(a.study_scenario, a.count, 2)
    spin, spin_lo, spin_hi = spin_ratio()
    same = repr(one.numbers()) == repr(two.numbers())
    print(f"study of {a.count} robots of {os.path.relpath(a.study_scenario, ROOT)} on a Dask LocalCluster:")
    print(f"  1 worker:  {t1:7.1f} s  {60 * a.count / t1:6.2f} robots/min")
    print(f"  2 workers: {t2:7.1f} s  {60 * a.count / t2:6.2f} robots/min")
    print(f"  speed ratio 2 workers / 1 worker: {t1 / t2:.2f}; same numbers bit for bit: {same}")
    s1, _, _ = where_the_time_went(one.rows)
    s2, hi, lo = where_the_time_went(two.rows)
    print(f"  where the ratio goes: the robots' own seconds {s1:.1f} one at a time, {s2:.1f} two at once "
          f"({s2 / s1:.2f}x: the cores slower when both run); the two workers ran robots for {hi:.1f} and {lo:.1f} s "
          f"(the less busy one idle {hi - lo:.1f} s at the end); the rest ({t2 - hi:.1f} s of {t2:.1f}) Dask's own")
    print(f"  failed robots: {len(one.failed)} and {len(two.failed)}")
    print(f"the same robots on a plain process pool (no Dask), the machine's own ceiling: 1 process {p1:.1f} s, "
          f"2 processes {p2:.1f} s: {p1 / p2:.2f}; Dask reaches {(t1 / t2) / (p1 / p2):.0%} of it; the robots' own "
          f"seconds {ps1:.1f} one at a time, {ps2:.1f} two at once ({ps2 / ps1:.2f}x)")
    print(f"a pure CPU loop, two at once against one after the other (what the cores give two processes that "
          f"only compute): {spin:.2f} (from {spin_lo:.2f} to {spin_hi:.2f} over 3 repeats)")
    print("load average at the end: {:.1f} {:.1f} {:.1f}".format(*os.getloadavg()))


if __name__ == "__main__":
    main()
