"""parallel_runs: whether runs cost more CPU two at a time than one after the other, without
Dask (a command, not a test; docs/populations.md, "Benchmark: the map against its core").

    TRIBO_BUILD_DIR=build .venv/bin/python bench/parallel_runs.py [ROUNDS=2]

The 2160 episodes of the map of the benchmark (`scripts/bench_runs_package.sh impact-map`:
10 speeds x 6 angles x 6 orientations x 6 roundnesses, PE on steel) as a task's runs
(batch/executors.py's run_each), each round: one after the other; in tasks of 64 on 2
threads of this process (the GIL switched between them: the context switches counted); in
two halves on 2 processes forked from this one. The CPU of each (this process's and its
children's) and its wall time.
"""

import os
import resource
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import tribo
from tribo.batch.executors import run_each
from tribo.fmu import FmuImage
from tribo.impact.episode import Grid, episode_specs, run_episode

TASK = 64


def used() -> tuple[float, int]:
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime,
            own.ru_nvcsw + own.ru_nivcsw)


def forked(image, halves) -> None:
    pids = []
    for half in halves:
        pid = os.fork()
        if pid == 0:
            run_each(run_episode, image, half)
            os._exit(0)
        pids.append(pid)
    for pid in pids:
        os.waitpid(pid, 0)


def threads(image, tasks) -> None:
    with ThreadPoolExecutor(2) as pool:
        list(pool.map(lambda task: run_each(run_episode, image, task), tasks))


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 2
    image = FmuImage.load(tribo.find_fmu(3, variant="si"))
    grid = Grid.of(speed=np.linspace(0.25, 8, 10), angle_deg=np.linspace(15, 90, 6),
                   phi0_deg=np.linspace(0, 150, 6), epsilon=np.linspace(0.4, 1, 6))
    specs = episode_specs(grid, "PE", "steel", {}, 200.0)
    run_each(run_episode, image, specs[:4])  # the FMU loaded before anything is timed
    tasks = [specs[i:i + TASK] for i in range(0, len(specs), TASK)]
    ways = {"one after the other": lambda: run_each(run_episode, image, specs),
            f"tasks of {TASK} on 2 threads": lambda: threads(image, tasks),
            "two halves on 2 forked processes": lambda: forked(image, [specs[0::2], specs[1::2]])}
    print(f"{len(specs)} episodes; load average {os.getloadavg()[0]:.2f}")
    for r in range(rounds):
        for name, way in ways.items():
            (cpu0, switches0), wall0 = used(), time.perf_counter()
            way()
            (cpu, switches), wall = used(), time.perf_counter()
            print(f"round {r + 1}, {name}: CPU {cpu - cpu0:.2f} s, wall {wall - wall0:.1f} s, "
                  f"{switches - switches0} context switches of this process")


if __name__ == "__main__":
    main()
