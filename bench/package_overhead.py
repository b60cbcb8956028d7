"""package_overhead: what the Python package costs beside the core it drives, in one
process (a command, not a test; docs/populations.md "Benchmark", docs/reference_case.md
"The package's cost").

    .venv/bin/python bench/package_overhead.py [--grains N] [--label TEXT]

Whichever `tribo` is imported is measured (scripts/bench_package.sh runs this file once
with a revision's package on PYTHONPATH and once with this tree's). Printed: one JSON line.

- grains: N grains of the population benchmark's feed (seed 1, the SI FMI 3.0 FMU, the
  defaults of `tribo population`), each run through the package as a population runs it
  (tribo.populations.feed.run_particle: the thread's CPU time it reports) and through the
  core alone, in the same process: the FMU's library driven by fmpy's FMU3Slave directly
  (instantiate, set the parameters, initialise, doSteps to the horizon, read two outputs,
  free; the thread's CPU time of that). The package's overhead per grain is the
  difference.
- disc: the rolling 1 mm disc (epsilon 1, mu 0.5, placed on 0.3 m of steel at 30 degrees)
  through tribo.run_si with its default rows (every 0.1 ms to the exit), with the end
  alone (record_interval=None, where the package has it), and through the core alone as
  above, to the exit in one step, to every 0.1 ms on the way (what the FMU's
  communication points cost, reading nothing), and to every 0.1 ms reading there the
  outputs tribo.run_si records, one call of the FMU per type into an array (the same run
  and rows as tribo.run_si's): the fastest of 5 each.

Only API that the package has had since its populations is used, so that the same file
measures the package before and after a change.
"""

import argparse
import ctypes
import json
import os
import shutil
import tempfile
import time
import zipfile

from ctypes import byref

import numpy as np
from fmpy.fmi3 import FMU3Slave, fmi3Boolean, fmi3Float64

import tribo
from tribo.fmu import FmuImage
from tribo.fmu.library import raw_getters
from tribo.fmu.names import start_value, to_fmu
from tribo.populations.feed import Feed, run_particle, specs_of

DISC = dict(size=1e-3, epsilon=1.0, mu=0.5, drop_height=0.0, chute_length=0.3, tilt_deg=30.0)
DISC_T_END = 10.0  # tribo.run_si's default horizon: the disc leaves the chute at 0.43 s


class Core:
    """The SI FMU's library loaded once, driven directly through fmpy's FMU3Slave."""

    def __init__(self, image, path):
        self.md = image.model_description()
        self.variables = {v.name: v for v in self.md.modelVariables}
        self.dir = tempfile.mkdtemp(prefix="tribo_bench_")
        with zipfile.ZipFile(path) as z:
            z.extractall(self.dir)
        self.slave = FMU3Slave(guid=self.md.guid, unzipDirectory=self.dir,
                               modelIdentifier=self.md.coSimulation.modelIdentifier,
                               instanceName="core")
        s = self.slave
        self.setters = {"Float64": (s.setFloat64, float), "Int32": (s.setInt32, int),
                        "Int64": (s.setInt64, int), "Enumeration": (s.setInt64, int),
                        "UInt64": (s.setUInt64, int), "Boolean": (s.setBoolean, bool)}
        self.flags = [fmi3Boolean(), fmi3Boolean(), fmi3Boolean(), fmi3Float64()]

    def reads(self, names):
        """A function that reads the variables `names` at once: one call of the FMU per
        type into a preallocated array, no Python object per value (the least an importer
        that keeps the rows can do)."""
        calls = []
        by_type = {}
        for name in names:
            v = self.variables[name]
            by_type.setdefault(v.type, []).append(v.valueReference)
        getters = raw_getters(self.slave.dll, 3)  # C functions that take plain addresses
        for kind, refs in by_type.items():
            _, function, dtype = getters[kind]
            buffer = np.empty(len(refs), dtype)
            calls.append((function, (ctypes.c_uint32 * len(refs))(*refs), len(refs),
                          buffer.ctypes.data, buffer))
        slave = self.slave

        def read():  # on the instance of the run (each run instantiates anew)
            for function, refs, n, address, _ in calls:
                function(slave.component, refs, n, address, n)

        return read

    def run(self, params: dict, t_end: float, interval: float | None = None,
            read=None) -> tuple[float, float]:
        """(the thread's CPU time of one run, the time it ended): doSteps to the horizon, or
        (interval) to each multiple of interval on the way, reading nothing there, or
        calling `read` (Core.reads) at the start and at each point."""
        values = [(self.variables[n], value) for n, value in to_fmu(self.md, params).items()]
        flags = self.flags
        cpu0 = time.thread_time()
        s = self.slave
        s.instantiate()
        for v, value in values:
            setter, kind = self.setters[v.type]
            setter([v.valueReference], [kind(value)])
        s.enterInitializationMode(startTime=0.0, stopTime=t_end)
        s.exitInitializationMode()
        if read:
            read()
        t, k = 0.0, 1
        while True:  # on to the horizon (or the next point) through the work limit's early ends
            to = t_end if interval is None else min(k * interval, t_end)
            status = s.dll.fmi3DoStep(s.component, t, to - t, True, *(byref(f) for f in flags))
            if status > 2:
                raise RuntimeError(f"fmi3DoStep: status {status}")
            if status == 0 and not flags[1].value and not flags[2].value:
                t, k = to, k + 1  # reached the point: its time is `to`
                if read:
                    read()
                if to == t_end:
                    break
            else:  # the run's end (the exit), or cut by the work limit: on from where it stopped
                t = flags[3].value
                if flags[1].value:
                    if read:
                        read()
                    break
        s.getFloat64([self.variables["u"].valueReference, self.variables["x"].valueReference])
        s.terminate()
        s.fmi3FreeInstance(s.component)
        return time.thread_time() - cpu0, t


def to_fmu_outputs(md) -> list[str]:
    """The FMU's names of the outputs tribo.run_si records by default (every scalar one)."""
    return [v.name for v in md.modelVariables if v.causality == "output" and not v.dimensions]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grains", type=int, default=100)
    parser.add_argument("--label", default="")
    args = parser.parse_args()
    path = tribo.find_fmu(3, variant="si")
    image = FmuImage.load(path)
    core = Core(image, path)
    depth = start_value(image.model_description(), "cylinder_length")
    specs = specs_of(Feed(), args.grains + 1, 1, 5.0, {"cylinder_length": depth})
    run_particle(image, specs[0])  # warm: first loads, caches
    core.run(specs[0].params, specs[0].t_end)
    package_s, core_s = [], []
    for spec in specs[1:]:
        core_s.append(core.run(spec.params, spec.t_end)[0])
        package_s.append(run_particle(image, spec).row["cpu_s"])
    package_s, core_s = np.array(package_s), np.array(core_s)

    def fastest(f, n=5):
        times = []
        for _ in range(n):
            cpu0 = time.thread_time()
            f()
            times.append(time.thread_time() - cpu0)
        return min(times)

    read = core.reads(to_fmu_outputs(image.model_description()))
    disc = {"core_s": min(core.run(DISC, DISC_T_END)[0] for _ in range(5)),
            "core_points_s": min(core.run(DISC, DISC_T_END, 1e-4)[0] for _ in range(5)),
            "core_rows_s": min(core.run(DISC, DISC_T_END, 1e-4, read)[0] for _ in range(5)),
            "run_si_s": fastest(lambda: tribo.run_si(**DISC)),
            "rows": len(tribo.run_si(**DISC))}
    try:
        disc["run_si_end_s"] = fastest(lambda: tribo.run_si(record_interval=None, **DISC))
    except TypeError:  # a package without the end-only run
        disc["run_si_end_s"] = None
    print(json.dumps({"label": args.label, "package": os.path.dirname(tribo.__file__),
                      "grains": args.grains,
                      "grain_package_ms": 1e3 * package_s.mean(),
                      "grain_core_ms": 1e3 * core_s.mean(),
                      "grain_overhead_ms": 1e3 * (package_s - core_s).mean(),
                      "grain_overhead_median_ms": 1e3 * np.median(package_s - core_s),
                      "disc": disc}))
    shutil.rmtree(core.dir)


if __name__ == "__main__":
    main()
