"""dask_tasks: what Dask's tasks cost a population beside its runs, by the number of runs a
task holds (a command, not a test; docs/sweeps.md, "Tasks of several runs").

    TRIBO_BUILD_DIR=build .venv/bin/python bench/dask_tasks.py [N=400] [RUNS_PER_TASK...=1 16]

N grains of the reference feed (seed 1) on the local cluster's 2 threads, once for each
number of runs per task given (in turn, as given: repeat them to alternate), each into a
fresh folder: the process's CPU over the population (the cluster's start not counted), the
runs' own (the sum of their rows' cpu_s) and the rest, which is Dask's and the rows'.
"""

import resource
import shutil
import sys
import tempfile
import time

import distributed  # noqa: F401  (imported before anything is timed)

import tribo
from tribo.batch.executors import DaskExecutor
from tribo.fmu import FmuImage
from tribo.populations.feed import Feed
from tribo.populations.runner import prepare_population, run_population


def process_cpu() -> float:
    used = resource.getrusage(resource.RUSAGE_SELF)
    return used.ru_utime + used.ru_stime


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 400
    sizes = [int(x) for x in sys.argv[2:]] or [1, 16]
    image = FmuImage.load(tribo.find_fmu(3, variant="si"))
    feed = Feed()
    specs = prepare_population(feed, n, 1, 5.0, image)
    for size in sizes:
        folder = tempfile.mkdtemp(prefix="tribo_tasks_")
        with DaskExecutor(workers=2, task_runs=size) as executor:
            cpu0, wall0 = process_cpu(), time.perf_counter()
            report = run_population(feed, n, 1, 5.0, image, folder, executor, progress=False,
                                    figure=False, specs=specs)
            cpu, wall = process_cpu() - cpu0, time.perf_counter() - wall0
        shutil.rmtree(folder)
        runs = report.results["cpu_s"].sum()
        print(f"{n} grains, at most {size} run(s) a task: CPU {cpu:.2f} s, the runs' own "
              f"{runs:.2f} s, the rest {cpu - runs:.2f} s; wall {wall:.1f} s")


if __name__ == "__main__":
    main()
