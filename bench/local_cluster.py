"""Threads against worker processes for the package's local Dask cluster: the same work
on both, in alternating rounds, wall time from entering the executor (the cluster's
start included) to the last result.

    .venv/bin/python bench/local_cluster.py [--rounds 3] [--workers N] [--particles 100]

Three workloads: a population of the reference case's feed (tribo.population's default:
PE on 0.3 m of steel, seed 1; short runs and a tail of slow ones, which sets the wall
time), the same feed on a 5 cm chute (4x as many particles, each a few tens of
milliseconds: the most Python per unit of FMU work, the worst case for threads), and the
paper's grid as a sweep (epsilon 0.1 ... 1.0, both frictions, tau to 5000, recorded every
time unit: few long runs). Prints the cluster's start time, one line per round and the median of each, then, run
serially, the share of each workload's CPU time spent inside the FMU's doStep, where the
GIL is released (the rest, Python, holds it: threads cannot overlap it); docs/sweeps.md
quotes them.
"""

import argparse
import os
import statistics
import tempfile
import time

import tribo
from tribo.batch.executors import SerialExecutor
from tribo.fmu import instance
from tribo.batch.executors import DaskExecutor, available_cores
from tribo.batch.grid import PAPER_BASE, build_specs
from tribo.batch.sweep import run_sweep
from tribo.fmu import FmuImage
from tribo.fmu.parameters import integer_names
from tribo.populations.feed import Feed
from tribo.populations.runner import prepare_population, run_population


def population(executor, n, chute_length=0.3):
    image = FmuImage.load(tribo.find_fmu(variant="si"))
    feed = Feed(chute={"chute_length": chute_length})
    specs = prepare_population(feed, n, 1, 5.0, image)
    with tempfile.TemporaryDirectory() as out:
        started = time.perf_counter()
        report = run_population(feed, n, 1, 5.0, image, out, executor, progress=False,
                                figure=False, specs=specs)
        wall = time.perf_counter() - started
    assert not report.failed and report.complete, report.failed[:1]
    return wall, float(report.results["cpu_s"].sum())


def short_population(executor, n):
    return population(executor, 4 * n, chute_length=0.05)


def sweep(executor, _n):
    image = FmuImage.load(tribo.find_fmu())
    grid = [("epsilon", [round(0.1 * k, 10) for k in range(1, 11)]), ("mu", [0.1, 1.0])]
    specs = build_specs(grid, PAPER_BASE, integer_names(image.model_description()), 5000.0, 1.0)
    with tempfile.TemporaryDirectory() as out:
        started = time.perf_counter()
        with executor:
            report = run_sweep(specs, image, os.path.join(out, "results.csv"), executor,
                               progress=False)
        wall = time.perf_counter() - started
    assert not report.failed and report.complete, report.failed[:1]
    return wall, float(report.results["cpu_s"].sum())


def fmu_share(work, n) -> float:
    """The share of the runs' CPU time inside fmi3DoStep, run serially in this thread."""
    inside = [0.0]
    original = instance.Instance._do_step3

    def timed(self, t, h):
        started = time.thread_time()
        try:
            return original(self, t, h)
        finally:
            inside[0] += time.thread_time() - started

    instance.Instance._do_step3 = timed
    try:
        _, cpu = work(SerialExecutor(), n)
    finally:
        instance.Instance._do_step3 = original
    return inside[0] / cpu


def start_time(processes: bool, workers: int) -> float:
    """From entering the executor to the first (empty) task's result."""
    started = time.perf_counter()
    with DaskExecutor(workers=workers, processes=processes) as executor:
        executor.client.submit(int).result()
        return time.perf_counter() - started


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--workers", type=int, default=available_cores())
    p.add_argument("--particles", type=int, default=100)
    args = p.parse_args()
    print(f"{available_cores()} cores, {args.workers} workers, load average before: "
          f"{', '.join(f'{x:.2f}' for x in os.getloadavg())}", flush=True)
    for processes in (False, True):
        starts = [start_time(processes, args.workers) for _ in range(3)]
        print(f"start of the local cluster, {'processes' if processes else 'threads'}: median "
              f"{statistics.median(starts):.2f} s of 3", flush=True)
    walls = {}
    for r in range(args.rounds):
        for name, work in (("population", population), ("short runs", short_population),
                           ("sweep", sweep)):
            for processes in (False, True):
                kind = "processes" if processes else "threads"
                wall, cpu = work(DaskExecutor(workers=args.workers, processes=processes),
                                 args.particles)
                walls.setdefault((name, kind), []).append(wall)
                print(f"round {r + 1}: {name:10s} {kind:9s} wall {wall:6.1f} s "
                      f"(CPU of the runs {cpu:.1f} s)", flush=True)
    for (name, kind), w in walls.items():
        print(f"median {name:10s} {kind:9s} {statistics.median(w):6.1f} s over {len(w)} rounds")
    print(f"load average after: {', '.join(f'{x:.2f}' for x in os.getloadavg())}")
    for name, work in (("population", population), ("short runs", short_population),
                       ("sweep", sweep)):
        print(f"{name:10s}: {fmu_share(work, args.particles):.0%} of the runs' CPU inside the "
              f"FMU's doStep", flush=True)


if __name__ == "__main__":
    main()
